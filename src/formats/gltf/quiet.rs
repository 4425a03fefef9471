//! Catching a panic without printing it: the last guard around the `gltf` crate.
//!
//! The reader checks what the `gltf` crate (1.4) is known to panic on before calling it, but a
//! panic it did not foresee must still become an error, and its message must not reach the
//! user's terminal. A panic hook installed once wraps the hook in place then and stays silent
//! while the panicking thread is inside [`catch_quietly`]; panics of other threads, and of
//! this thread outside the guard, go to the wrapped hook as before.

use std::cell::Cell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;

thread_local! {
    /// Whether this thread is inside [`catch_quietly`].
    static QUIET: Cell<bool> = const { Cell::new(false) };
}

/// Installs the silencing hook, once per process.
static INSTALL: Once = Once::new();

/// Runs `f`, turning a panic into `Err` without the panic hook printing anything for this
/// thread. Nested calls are fine; the flag is restored on the way out.
pub(super) fn catch_quietly<R>(f: impl FnOnce() -> R) -> std::thread::Result<R> {
    INSTALL.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    let outer = QUIET.with(|q| q.replace(true));
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(outer));
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_err_and_the_flag_is_restored() {
        let result = catch_quietly(|| -> u8 { panic!("hidden") });
        assert!(result.is_err());
        assert!(!QUIET.with(Cell::get));
        assert_eq!(catch_quietly(|| catch_quietly(|| 3).unwrap()).unwrap(), 3);
        assert!(!QUIET.with(Cell::get));
    }
}
