//! The solver's tuning constants, in one place: one module per part of the solver, each
//! constant with what it trades and, where it was tuned, how it was measured (on the paper
//! drawings, the grid walks and whole-pixel samples of `tests/integer_input.rs` and
//! `examples/walks.rs`, and the bear's instruction count). The parts import them from here.
//!
//! Changing one changes results: check the paper drawings' convergence histograms
//! (`examples/convergence`), the golden images and the bear's count (see
//! `docs/performance.md`) before and after.

/// The nonlinear system ([`super`](crate::solver)): regularisation and the line search.
pub(crate) mod system {
    /// Regularization of the squared doubled triangle area, in normalized coordinates (drawing
    /// size 1): keeps the area differentiable for straight stretches while far below any real
    /// area (a triangle with sides 1e-10 has a squared doubled area ≈ 1e-40).
    pub(crate) const EPS_GRAM: f64 = 1e-60;

    /// Bounds for λ during the line search (it must stay strictly inside (0, 1)).
    pub(crate) const LAMBDA_MIN: f64 = 1e-12;
}

/// Cold solves ([`super::cascade`]): classic starts, the homes and budgets of the continuations in
/// the shapes.
pub(crate) mod cascade {
    /// Iterations of the classic loop used to start Newton from a cold start, one attempt each.
    pub(crate) const CLASSIC_STARTS: [usize; 3] = [3, 1, 12];

    /// Classic iterations that start the first solve of a continuation.
    pub(crate) const CLASSIC_START: usize = 3;

    /// Iteration budget of each direct attempt before the next strategy is tried.
    pub(crate) const ATTEMPT_BUDGET: usize = 30;

    /// Shape parameters where the solver converges most reliably (measured on the drawings of
    /// the εκ paper), the starts of the continuation fallbacks, tried in this order.
    pub(crate) const A_HOMES: [f64; 4] = [0.85, 0.75, 0.95, 0.7];

    /// The same for trigonometric segments, plus a start below the usual targets: their
    /// solution branches coming from large `a` can fold just above `a = 0.65` (a peak moving
    /// into a segment end), where the branch coming from small `a` (peak at the end) goes on.
    pub(crate) const A_HOMES_TRIG: [f64; 4] = [0.85, 0.75, 0.95, 0.6];

    /// Iterations of one continuation from a home of [`A_HOMES`]. Uncapped, the first home
    /// could spend the whole budget creeping along a fold in small steps (1 900 iterations on
    /// the 16-point whole-pixel lemniscate), and the fallbacks after it never ran. With 600,
    /// κ solved two more whole-pixel samples than with 900, but not the 30-point sine
    /// `(10i, 50 sin 0.3i)`, which takes 1 814 iterations through the first home.
    pub(crate) const HOME_BUDGET: usize = 900;

    /// The fine continuation in the shapes, between the homes: from `a = 0.75`, with short
    /// first steps, a Newton budget of 100 a step and no step below 1e-3. Dense whole-pixel
    /// samples fold on the homes' long, cheap steps and converge on these: with the capped
    /// homes it raised κ on the whole-pixel samples of `tests/integer_input.rs` from 62 to 70
    /// of 84 (sines of 16–48 points, lemniscates of 8–24, the 24-point circle of radius 120).
    /// Its home is solved through the continuation out of nudged inflections where it does not
    /// solve directly: the lemniscate's crossing is an inflection through an input point with
    /// collinear neighbours at every shape, and the branch from the nudged home then reaches
    /// `a = 2/3`, which took κ from 70 to 74 (four lemniscates), with the same 11 983 of
    /// 11 993 grid walks (seeds 7, 11, 3). It runs after the first two homes: after all four,
    /// their 3 600 iterations left it about 310 of the 4 000 budget; moved up, it took κ to 75
    /// (the 48-point spiral of radius 120) with the same walks.
    /// Started from `a = 0.85` it solved one more sample, but three fewer grid walks; from 0.8
    /// (with the nudged home) five fewer samples and two fewer walks; steps down to 1e-4, two
    /// fewer samples and four fewer walks.
    pub(crate) const FINE: Descent = Descent {
        home: 0.75,
        first_step: 0.02,
        min_step: 1e-3,
        step_budget: 100,
        budget: FINE_BUDGET,
        nudge_home: true,
    };

    /// Iterations of the [`FINE`] continuation.
    pub(crate) const FINE_BUDGET: usize = 2000;

    /// One continuation in the shape parameters: its home, its steps and its budget.
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct Descent {
        pub(crate) home: f64,
        pub(crate) first_step: f64,
        pub(crate) min_step: f64,
        pub(crate) step_budget: usize,
        pub(crate) budget: usize,
        /// Whether a home that does not solve directly is solved by the continuation out of
        /// nudged inflections ([`crate::solver::Workspace::nudge_continuation`]).
        pub(crate) nudge_home: bool,
    }

    impl Descent {
        /// A continuation from `home` with the long, cheap steps that suit most input.
        pub(crate) const fn coarse(home: f64) -> Descent {
            Descent {
                home,
                first_step: 0.25,
                min_step: MIN_STEP,
                step_budget: STEP_BUDGET,
                budget: HOME_BUDGET,
                nudge_home: false,
            }
        }
    }

    /// Newton budget of one continuation step.
    pub(crate) const STEP_BUDGET: usize = 16;

    /// Smallest continuation step in the homotopy parameter before an attempt is given up.
    pub(crate) const MIN_STEP: f64 = 1e-6;
}

/// The convergence measure ([`super::check`]).
pub(crate) mod check {
    /// Rounding floor of the dimensionless (G2 and peak) residuals times the local segment
    /// length, in normalized coordinates: 64 ulps of a unit coordinate.
    pub(crate) const ROUNDING_FLOOR: f64 = 64.0 * f64::EPSILON;

    /// The largest rounding floor granted to a near-degenerate joint (see
    /// [`crate::solver::Workspace::check_row`]): its relative |κ| mismatch still has to be below
    /// this.
    pub(crate) const MAX_FLOOR: f64 = 1e-6;

    /// The largest rounding floor granted to a row made of a ratio near 1 (see
    /// [`crate::solver::Workspace::check_scales`]): `1 - λ` carries a relative error of about `ε/(1
    /// - λ)`, which this caps where `1 - λ` is as small as
    /// [`LAMBDA_MIN`](super::system::LAMBDA_MIN) allows.
    pub(crate) const RATIO_FLOOR: f64 = 1e-3;

    /// A segment counts as shrinking towards its input point when `1 - λ_{j-1}` and `λ_j` are
    /// both below this: its rows get the floors of [`RATIO_FLOOR`]'s doc. (A single ratio near
    /// 1 is a curve heading elsewhere: relaxing its rows there measured worse window
    /// re-solves.)
    pub(crate) const RATIO_NEAR_ONE: f64 = 1e-4;

    /// The largest sine of the control polygon's turn at a segment still counted as shrinking
    /// towards its point (see [`crate::solver::check::Joint::turn_within`]): the polygon of a
    /// segment collapsing at an inflection turns by `O(1 - λ)` (see
    /// [`crate::solver::check::Joint::collapsed`]); a segment shrinking at a real corner is a curve
    /// heading to another solution.
    pub(crate) const STRAIGHTISH: f64 = 1e-4;
}

/// The classic loop ([`super::classic`]).
pub(crate) mod classic {
    /// Least cosine between the last two classic steps for
    /// [`crate::solver::Workspace::extrapolate`].
    pub(crate) const EXTRAPOLATE_COSINE: f64 = 0.9;
}

/// The condensed linear solve ([`super::condense`]).
pub(crate) mod condense {
    /// Most condensed unknowns in a block's stencil: four blocks of `D + 1` (3D: 16).
    pub(crate) const BACK_MAX: usize = 16;

    /// Smallest pivot magnitude accepted when eliminating `t_j` (the rows are scaled to O(1)); a
    /// smaller one is clamped, which keeps the step finite at a degenerate peak.
    pub(crate) const MIN_PIVOT: f64 = 1e-14;
}

/// The linear system of a Newton step ([`super::linear`]).
pub(crate) mod linear {
    /// Systems up to this order are solved densely (a few small closed curves are the common
    /// case in drawings; the bordered solve only pays off above that).
    pub(crate) const DENSE_ORDER: usize = 24;
}

/// Newton steps, chord steps and the line search ([`super::newton`]).
pub(crate) mod newton {
    /// Within this factor of the tolerance, full Newton steps are taken without the line search's
    /// decrease test (the merit is at rounding noise there for very large curves).
    pub(crate) const QUADRATIC_REGION: f64 = 1e3;

    /// Chord steps (warm re-solves) must shrink the merit by this factor or Newton takes over.
    pub(crate) const CHORD_CONTRACTION: f64 = 1e-2;

    /// Chord steps after a Newton step (with its factors) must shrink the merit by this
    /// factor: only where the Jacobian hardly changes any more, so they cannot lead Newton
    /// astray.
    pub(crate) const NEWTON_CHORD_CONTRACTION: f64 = 1e-4;

    /// The same for the near-solution chord steps of shorter curves ([`NEWTON_CHORD_NEAR`]):
    /// there a Newton step costs only a few chord steps, and one chord step that contracts the
    /// merit a thousandfold is still the cheaper way on (2.6 % of the bear's κ instructions
    /// against `1e-4`; its εκ solve takes the same steps).
    pub(crate) const NEAR_CHORD_CONTRACTION: f64 = 1e-3;

    /// Chord steps follow every Newton step on curves with at least this many segments, where
    /// assembling and factoring dominate (a chord step costs about a quarter of a Newton step
    /// there). Shorter curves take them only near the solution ([`NEWTON_CHORD_NEAR`]): from
    /// farther away the saving is small, and the different path through the iterations can
    /// end on another solution branch.
    pub(crate) const NEWTON_CHORD_MIN_BLOCKS: usize = 256;

    /// Shorter curves follow a Newton step with chord steps once the step has brought the
    /// residual below this (relative to the drawing size). That close, the chord steps (each
    /// must contract the merit by [`NEAR_CHORD_CONTRACTION`], or Newton takes over again)
    /// reach the solution Newton would, and the assembly and factorization of the last Newton
    /// step or two are saved: 10 % of the bear's κ instructions, 14 % of its εκ ones. With the
    /// extrapolated classic start, 3e-5 measured best on the bear (1e-4, 3e-4 and 1e-5 more
    /// instructions) and on the 109 drawing curves (fewer iterations for every scheme).
    pub(crate) const NEWTON_CHORD_NEAR: f64 = 3e-5;

    /// At most this many chord steps per warm re-solve.
    pub(crate) const MAX_CHORD: usize = 12;

    /// A full Newton step that leaves more than this fraction of the merit is followed by a trial
    /// of the same step again (kept if it lowers the merit further). Where the Newton model
    /// undershoots, as on a stiff curve whose peak heads for a segment end while its λ shrinks
    /// by a near-constant factor per step, this takes two steps' progress for one factorization.
    /// Measured on the bear: 0.25 and 0.1 the same, 0.5 and 0.05 worse; doubling again more
    /// than once gained nothing.
    pub(crate) const EXPAND_RATIO: f64 = 0.25;

    /// A Newton step that lands `t` within this of an end of `[0, 1]` is taken in full, `t`
    /// clamped to the end: a peak forced to a segment end is reached in one step, not approached
    /// at the rate of the step-to-bound factor.
    pub(crate) const T_LANDING: f64 = 1e-9;

    /// How close to its bound the partner of a held ratio must be (see
    /// [`pinned`](crate::solver::newton)).
    pub(crate) const PARTNER: f64 = 1e-6;
}

/// The continuation out of nudged inflections ([`super::nudge`]).
pub(crate) mod nudge {
    /// Sine of the angle `p_{j-1} p_j p_{j+1}` below which a point counts as collinear with its
    /// neighbours. Whole-pixel input is collinear exactly; the near-collinear band converges
    /// without a nudge (the sweeps of `tests/collinear.rs`).
    pub(crate) const COLLINEAR: f64 = 1e-9;

    /// Sine below which a point off its neighbours' line is still nudged (further to its own
    /// side, then followed back to the input): the band next to the collinear case where the
    /// κ solve can stall (at sines of 6e-9 on the lemniscate of `tests/inflection.rs`; the
    /// wave's sweeps converge directly down to 1e-7 of its size). Dense samples of a smooth
    /// curve have points at sines of 1e-4 where it is nearly straight, and ordinary solves.
    pub(crate) const NEAR: f64 = 1e-6;

    /// Ratios `1 - λ_{j-1}`, `λ_j` below which a nudged point's segment counts as collapsing
    /// onto it, and each step of the path first shrinks it with the nudge.
    pub(crate) const PREDICT: f64 = 0.1;

    /// The first nudge, as a fraction of the distance to the nearer neighbour: on the 8-point
    /// lemniscate (κ) nudges of 1e-3 and 1e-4 of it converged cold, 2e-5 did not.
    pub(crate) const NUDGE: f64 = 1e-2;

    /// The last nudge of the path, as a fraction of the tolerance: the polish then starts
    /// within the tolerance of the input.
    pub(crate) const END: f64 = 1e-2;

    /// Iterations for one sign: the nudged input's cold cascade and the path back. The point
    /// continuation runs after this and solves most hairpin walks: with 1 000, 4 fewer of the
    /// 11 993 grid walks of seeds 7, 11 and 3 converged (κ and εκ-trig) than with 700, and 400
    /// lost two whole-pixel lemniscates.
    pub(crate) const BUDGET: usize = 700;

    /// Newton budget of one step along the path (as in the point continuation).
    pub(crate) const STEP_BUDGET: usize = 100;

    /// Smallest step in `s` (a quarter of a decade of nudge, about) before a sign is given up.
    pub(crate) const MIN_STEP: f64 = 0.02;
}

/// Finishing a collapse ([`super::collapse`]).
pub(crate) mod collapse {
    /// A block counts as collapsing when both its ratios `1 - λ_{j-1}` and `λ_j` are below
    /// this (the failing lemniscates' crossing blocks were at 1e-5 to 1e-12; the blocks near
    /// 0.02–0.05 there were no collapse but other solutions' joints).
    pub(crate) const COLLAPSING: f64 = 1e-4;

    /// The factor a round moves a collapsing block by towards its limit: 1e-3 solved the four
    /// lemniscates in one round each.
    pub(crate) const SHRINK: f64 = 1e-3;

    /// Rounds of shrinking and Newton.
    pub(crate) const ROUNDS: usize = 3;

    /// Newton budget of one round (the rounds that converged took 5–78 iterations).
    pub(crate) const ROUND_BUDGET: usize = 100;
}

/// Root solves for the peak parameters ([`super::peak`]).
pub(crate) mod peak {
    /// Accuracy of `t` in the classic loop's root solve: Newton refines it afterwards, so the
    /// start-up iterations need not resolve it to the last digit.
    pub(crate) const PEAK_T_TOLERANCE: f64 = 1e-10;

    /// Accuracy of `t` for quadratic segments, whose peak is the root of a cubic: to rounding.
    pub(crate) const QUADRATIC_PEAK_TOLERANCE: f64 = 1e-14;

    /// The same in the classic iterations that start the first Newton attempt of a cold solve.
    /// The root solve stops once a Newton correction is below this, after applying it, so where
    /// it converges quadratically `t` is still accurate to about the square of this; where it
    /// does not, Newton refines `t` anyway: a start needs no more. (1e-8 in place of the full
    /// tolerance took 13 % off the bear's εκ solve, 1e-2 in place of 1e-8 a further 10 %, at a
    /// few more Newton and chord steps. The fallback attempts keep the tighter tolerances: on
    /// hostile input their path is sensitive to every digit of the start.)
    pub(crate) const START_PEAK_T_TOLERANCE: f64 = 1e-2;

    /// The same for curves of [`NEWTON_CHORD_MIN_BLOCKS`](super::newton::NEWTON_CHORD_MIN_BLOCKS)
    /// segments or more: their re-solves after a small move work at the rounding floor of thousands
    /// of rows, and a smooth 2 000-point loop started from the looser tolerance's solution stopped
    /// at 1.6 times the tolerance.
    pub(crate) const LONG_START_PEAK_T_TOLERANCE: f64 = 1e-8;

    /// Iteration cap of the 1-D root solve for `t` in the classic loop.
    pub(crate) const ROOT_ITERATIONS: usize = 60;
}

/// The continuation in the input points ([`super::points`]).
pub(crate) mod points {
    /// The jitter of a home: each coordinate of a free point moves by up to this fraction of
    /// the distance to its nearer neighbour.
    pub(crate) const JITTER: f64 = 0.125;

    /// Homes tried at most; in practice the iteration cap ends the search first.
    pub(crate) const HOMES: u64 = 30;

    /// Iterations for one jittered home: its cold solve and the path back to the input.
    pub(crate) const HOME_BUDGET: usize = 300;

    /// Iterations for the smoothed home, tried first: dense samples of smooth curves need
    /// more of them (the 35-point sine of docs/curves.md, εκ a = 0.72: 1 621) than the
    /// hairpins of grid walks, which the jittered homes solve.
    pub(crate) const SMOOTHED_BUDGET: usize = 600;

    /// Newton budget of one step along the path: steps are long (a quarter of the way at
    /// first), and on the grid walks 16 (the shape continuation's budget) or 40 iterations
    /// lost curves that 100 (a warm re-solve's budget) found.
    pub(crate) const STEP_BUDGET: usize = 100;

    /// Smallest step in `s` before a home is given up: a home that needs finer steps is
    /// cheaper to replace than to follow.
    pub(crate) const MIN_STEP: f64 = 1e-3;
}

/// The split (two-thread) linear solve ([`super::split`]).
pub(crate) mod split {
    /// Curves of this many blocks or more are solved in two halves (see
    /// [`Split`](crate::solver::split::Split)).
    pub(crate) const SPLIT_MIN_BLOCKS: usize = 2048;
}

/// Prescribed tangents ([`super::tangent`]).
pub(crate) mod tangent {
    /// The smallest step of [`crate::solver::Workspace::tangent_continuation`] (a fraction of each
    /// turn). Where the directions cannot be turned further in steps of this size, the tangents
    /// have usually left the range where a solution exists (the constrained point would have to
    /// leave its segment): measured on the alphabets of DejaVu Sans and EB Garamond, stopping at
    /// 1/128 instead of 1e-6 keeps the same tangents and drafts in a third of the time.
    pub(crate) const TANGENT_MIN_STEP: f64 = 1.0 / 128.0;
}

/// Window re-solves of local edits ([`super::window`]).
pub(crate) mod window {
    /// Blocks of the window on either side of the moved ones: at the window's edge the solution
    /// moves about `7^-7 ≈ 1e-6` times as much as at the moved point (jagged loops), so the
    /// outer blocks' linearization errs by about the square of that.
    pub(crate) const HALF: usize = 7;

    /// Most consecutive blocks an edit may move for a window re-solve.
    pub(crate) const MAX_MOVED: usize = 3;

    /// Curves with fewer blocks are re-solved globally (a window would cover most of them).
    pub(crate) const WINDOW_MIN_BLOCKS: usize = 32;

    /// A chord step must shrink the window's residual by this factor or better; otherwise the
    /// Jacobian is assembled and factored anew.
    pub(crate) const CHORD_RATE: f64 = 0.1;

    /// Chord steps on the whole curve after the window's (where the outer blocks' linearization
    /// is not accurate enough), and the factor by which each must shrink the residual.
    pub(crate) const MAX_FULL: usize = 6;

    pub(crate) const FULL_RATE: f64 = 0.25;

    /// Newton steps on the window before the global steps take over.
    pub(crate) const MAX_NEWTON: usize = 8;

    /// Steps on the window (chord and Newton) before the global steps take over.
    pub(crate) const MAX_STEPS: usize = 16;

    /// A window Newton step halved below this fraction gives up (the global steps take over).
    pub(crate) const MIN_DAMPING: f64 = 1.0 / 64.0;
}
