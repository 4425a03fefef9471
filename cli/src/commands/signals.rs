//! SIGINT and SIGTERM: the temporary file of any write in progress is removed (its target
//! keeps its old bytes) and the process exits with the shell's status for the signal, 128 + its
//! number (130 for SIGINT, 143 for SIGTERM). SIGKILL cannot be caught.

use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;
use sweepffd::atomic_file::exit_removing_temporaries;

/// Starts a thread that waits for SIGINT or SIGTERM and then exits the process through
/// [`exit_removing_temporaries`].
pub fn install() -> std::io::Result<()> {
    let mut signals = Signals::new([SIGINT, SIGTERM])?;
    std::thread::Builder::new().name("signals".to_string()).spawn(move || {
        if let Some(signal) = signals.forever().next() {
            exit_removing_temporaries(128 + signal);
        }
    })?;
    Ok(())
}
