//! The CPU paths' data parallelism: rayon's parallel iterators with the feature `parallel`, and
//! the same names over std's sequential iterators without it, so that every CPU loop is written
//! once (`use crate::parallel::prelude::*;`) and an embedder that does not want a thread pool
//! gets the same results on the calling thread.

/// `par_chunks`, `par_chunks_mut`, `par_iter`, `par_iter_mut` and `into_par_iter`.
pub mod prelude {
    #[cfg(feature = "parallel")]
    pub use rayon::prelude::*;

    #[cfg(not(feature = "parallel"))]
    pub use super::sequential::{IntoParallelIterator, ParallelSlice, ParallelSliceMut};
}

/// Sequential stand-ins for rayon's slice and range adaptors, with rayon's names.
#[cfg(not(feature = "parallel"))]
mod sequential {
    use std::ops::Range;

    /// Shared-slice iterators, run in order on the calling thread.
    pub trait ParallelSlice<T> {
        /// Chunks of `size` elements (the last may be shorter).
        fn par_chunks(&self, size: usize) -> std::slice::Chunks<'_, T>;
        /// Every element.
        fn par_iter(&self) -> std::slice::Iter<'_, T>;
    }

    impl<T> ParallelSlice<T> for [T] {
        fn par_chunks(&self, size: usize) -> std::slice::Chunks<'_, T> {
            self.chunks(size)
        }

        fn par_iter(&self) -> std::slice::Iter<'_, T> {
            self.iter()
        }
    }

    /// Mutable-slice iterators, run in order on the calling thread.
    pub trait ParallelSliceMut<T> {
        /// Chunks of `size` elements (the last may be shorter).
        fn par_chunks_mut(&mut self, size: usize) -> std::slice::ChunksMut<'_, T>;
        /// Every element.
        fn par_iter_mut(&mut self) -> std::slice::IterMut<'_, T>;
    }

    impl<T> ParallelSliceMut<T> for [T] {
        fn par_chunks_mut(&mut self, size: usize) -> std::slice::ChunksMut<'_, T> {
            self.chunks_mut(size)
        }

        fn par_iter_mut(&mut self) -> std::slice::IterMut<'_, T> {
            self.iter_mut()
        }
    }

    /// Ranges of indices, run in order on the calling thread.
    pub trait IntoParallelIterator {
        /// The iterator.
        type Iter: Iterator;
        /// The range as an iterator.
        fn into_par_iter(self) -> Self::Iter;
    }

    impl IntoParallelIterator for Range<usize> {
        type Iter = Range<usize>;

        fn into_par_iter(self) -> Range<usize> {
            self
        }
    }

    impl IntoParallelIterator for Range<u32> {
        type Iter = Range<u32>;

        fn into_par_iter(self) -> Range<u32> {
            self
        }
    }
}

/// Threads the CPU paths use: rayon's pool with `parallel`, else 1.
pub fn thread_count() -> usize {
    #[cfg(feature = "parallel")]
    return rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    1
}

/// Runs `a` and `b`, on two threads with the feature `parallel` (rayon's `join`), else one after
/// the other, and returns both results.
pub fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
where
    A: FnOnce() -> RA + Send,
    B: FnOnce() -> RB + Send,
    RA: Send,
    RB: Send,
{
    #[cfg(feature = "parallel")]
    return rayon::join(a, b);
    #[cfg(not(feature = "parallel"))]
    (a(), b())
}
