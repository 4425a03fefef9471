//! Progress bars for work that takes more than a moment, silenced by `--quiet` (and drawn
//! only when stderr is a terminal).

use indicatif::{ProgressBar, ProgressStyle};

/// Below this many vertices work finishes too fast for a bar to help.
const MIN_VERTICES: usize = 200_000;

/// A bar over `len` vertices labelled `label`, hidden when quiet or when the work is small.
pub fn vertex_bar(len: usize, label: &'static str, quiet: bool) -> ProgressBar {
    if quiet || len < MIN_VERTICES {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len as u64).with_message(label);
    bar.set_style(
        ProgressStyle::with_template("{msg:>8} [{bar:40}] {pos}/{len} vertices ({eta})")
            .expect("a fixed template parses")
            .progress_chars("=> "),
    );
    bar
}
