//! Fork–join for the work on long curves (two halves side by side), and the threads of a
//! batch of curves ([`each_worker`]).
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

/// How many threads [`each_worker`] can use: rayon's pool size with the `parallel` feature
/// (the global pool, or the pool the caller runs on), 1 without it.
#[inline]
pub(crate) fn threads() -> usize {
    #[cfg(feature = "parallel")]
    {
        rayon::current_num_threads().max(1)
    }
    #[cfg(not(feature = "parallel"))]
    {
        1
    }
}

/// Run `work` on each of `workers`: the first on the calling thread, the others as tasks
/// on rayon's pool, all at once; returns when every one has finished. Without the
/// `parallel` feature, or with one worker, one after the other on the calling thread.
///
/// The calling thread does not wait for the pool to pick the tasks up: work shared through
/// a counter (as [`crate::batch`] does) is drained by whoever is running.
pub(crate) fn each_worker<W: Send>(workers: &mut [W], work: impl Fn(&mut W) + Sync) {
    #[cfg(feature = "parallel")]
    if let Some((first, rest)) = workers.split_first_mut() {
        if !rest.is_empty() {
            let work = &work;
            rayon::in_place_scope(|s| {
                for w in rest {
                    s.spawn(move |_| work(w));
                }
                work(first);
            });
            return;
        }
    }
    for w in workers {
        work(w);
    }
}
