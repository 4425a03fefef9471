//! Lines for the user on standard output ([`out!`]) and standard error ([`note!`]), in place of
//! `println!` and `eprintln!`, which panic where the stream cannot be written. A reader that has
//! gone (`sweepffd autorig … | head -1`) ends the process as a shell's SIGPIPE would, with status
//! 128 + 13 = [`BROKEN_PIPE`]; any other failure to write (a full disk behind a redirect) with
//! [`IO_ERROR`]. Either way the temporary file of any write in progress is removed and its target
//! keeps its old bytes, as on SIGINT; an output file already written stays.

use std::fmt::Arguments;
use std::io::{self, Write};

use sweepffd::atomic_file::exit_removing_temporaries;

/// The exit status where the reader of standard output or standard error has gone.
pub const BROKEN_PIPE: i32 = 141;
/// The exit status where standard output or standard error cannot be written otherwise
/// (sysexits' EX_IOERR).
pub const IO_ERROR: i32 = 74;

/// Writes `line` and a newline to standard output.
pub fn line_out(line: Arguments) {
    end_if_failed(writeln!(io::stdout().lock(), "{line}"));
}

/// Writes `line` and a newline to standard error.
pub fn line_err(line: Arguments) {
    end_if_failed(writeln!(io::stderr().lock(), "{line}"));
}

fn end_if_failed(written: io::Result<()>) {
    match written {
        Ok(()) => {}
        Err(error) if error.kind() == io::ErrorKind::BrokenPipe => exit_removing_temporaries(BROKEN_PIPE),
        // Nothing is left to report to.
        Err(_) => exit_removing_temporaries(IO_ERROR),
    }
}

/// `println!` that ends the process quietly where standard output cannot be written.
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::console::line_out(format_args!($($arg)*))
    };
}

/// `eprintln!` that ends the process quietly where standard error cannot be written.
macro_rules! note {
    ($($arg:tt)*) => {
        $crate::console::line_err(format_args!($($arg)*))
    };
}
