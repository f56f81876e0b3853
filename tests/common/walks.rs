//! Clicks on whole pixels: random walks on an integer grid, and whole-pixel samples of
//! smooth curves, as a designer who snaps to the grid would click them. Shared by
//! `tests/integer_input.rs` and `examples/walks.rs` (which includes this file by its path).

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

/// Whole-pixel samples of smooth curves: for 6, 8, 12, 16, 24, 32 and 48 points and radii 20,
/// 50 and 120, a closed circle, a closed lemniscate of Bernoulli, an open spiral of two turns
/// and an open sine, each point rounded to a whole pixel. Each comes with its name.
pub fn pixel_samples() -> Vec<(String, Vec<Point>, bool)> {
    let mut cases = Vec::new();
    let tau = std::f64::consts::TAU;
    let px = |x: f64, y: f64| Point::new(x.round(), y.round());
    for n in [6, 8, 12, 16, 24, 32, 48] {
        for r in [20.0, 50.0, 120.0] {
            let at = |i: usize| i as f64 / n as f64 * tau;
            let circle = (0..n)
                .map(|i| px(300.0 + r * at(i).cos(), 300.0 + r * at(i).sin()))
                .collect();
            let lemniscate = (0..n)
                .map(|i| {
                    let t = at(i);
                    let d = 1.0 + t.sin().powi(2);
                    px(
                        300.0 + 2.0 * r * t.cos() / d,
                        300.0 + 2.0 * r * t.sin() * t.cos() / d,
                    )
                })
                .collect();
            let spiral = (0..n)
                .map(|i| {
                    let t = 2.0 * at(i);
                    let rr = r * (0.2 + t / 6.0);
                    px(300.0 + rr * t.cos(), 300.0 + rr * t.sin())
                })
                .collect();
            let sine = (0..n)
                .map(|i| {
                    let x = i as f64 * 400.0 / n as f64;
                    px(100.0 + x, 300.0 + r * (x / 60.0).sin())
                })
                .collect();
            let name = |what: &str| format!("{what} n = {n}, r = {r}");
            cases.push((name("circle"), circle, true));
            cases.push((name("lemniscate"), lemniscate, true));
            cases.push((name("spiral"), spiral, false));
            cases.push((name("sine"), sine, false));
        }
    }
    cases
}
