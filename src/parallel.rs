//! Fork–join for the work on long curves: two halves side by side.
//!
//! With the `parallel` feature (on by default) [`join`] runs its two closures on rayon's
//! thread pool; without it, with a pool of one thread, or where threads are unavailable (as
//! in WebAssembly) one after the other. The callers split their work the same way in every
//! case, so the results are identical.

/// Run `a` and `b`, possibly in parallel, and return both results.
#[inline]
pub(crate) fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
where
    A: FnOnce() -> RA + Send,
    B: FnOnce() -> RB + Send,
    RA: Send,
    RB: Send,
{
    #[cfg(feature = "parallel")]
    {
        // A pool of one thread (one core, or `RAYON_NUM_THREADS=1`) would only add the
        // hand-over to it.
        if rayon::current_num_threads() > 1 {
            rayon::join(a, b)
        } else {
            (a(), b())
        }
    }
    #[cfg(not(feature = "parallel"))]
    {
        (a(), b())
    }
}
