//! Random walks on an integer grid, the clicks of a designer who snaps to whole pixels:
//! shared by `tests/integer_input.rs` and `examples/walks.rs` (which includes this file by
//! its path).

use kurbo::Point;

/// A deterministic pseudo-random generator (64-bit LCG) for rate tests.
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `count` random walks of 4–40 points from the origin, steps of up to 5 units each way
/// (never zero), in the order drawn: the even ones open, the odd ones closed, except that a
/// closed walk whose last point is its first is left out.
pub fn grid_walks(rng: &mut Lcg, count: usize) -> Vec<(Vec<Point>, bool)> {
    let mut walks = Vec::new();
    for k in 0..count {
        let n = 4 + (rng.next() * 37.0) as usize;
        let mut p = vec![Point::ZERO];
        while p.len() < n {
            let mut step = || ((rng.next() * 11.0) as i32 - 5) as f64;
            let (dx, dy) = (step(), step());
            if (dx, dy) != (0.0, 0.0) {
                let last = p[p.len() - 1];
                p.push(Point::new(last.x + dx, last.y + dy));
            }
        }
        if k % 2 == 0 {
            walks.push((p, false));
        } else if p[0] != p[n - 1] {
            walks.push((p, true));
        }
    }
    walks
}
