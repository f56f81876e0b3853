//! The page's drag-latency measurement, natively: 1000 drag updates (move + warm re-solve +
//! encoded path + encoded comb) of point 30 of the 100-point closed star the browser test
//! uses, per scheme. `cargo run --release --example drag_latency` in `web/`.

use std::time::Instant;

use kappa::Scheme;
use kappa_web::Session;

fn star(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            let r = if i % 2 == 0 { 250.0 } else { 225.0 };
            (450.0 + r * th.cos(), 300.0 + r * th.sin())
        })
        .collect()
}

fn main() {
    const UPDATES: usize = 1000;
    for (name, scheme) in [
        ("kappa", Scheme::Kappa),
        ("ek-cubic", Scheme::EkCubic),
        ("ek-trig", Scheme::EkTrig),
    ] {
        let mut s = Session::new(scheme);
        for (x, y) in star(100) {
            s.add_point(x, y);
        }
        s.set_closed(true);
        s.fill_comb(50.0, 0.75, 3.0, 8, 0.0);
        let scale = s.comb_scale();
        let (bx, by) = (
            s.editor().unwrap().doc().points[30].x,
            s.editor().unwrap().doc().points[30].y,
        );
        let mut times = Vec::with_capacity(UPDATES);
        let mut iterations = 0;
        let mut errors = 0;
        let start = Instant::now();
        for k in 1..=UPDATES {
            let off = 1.25 * ((k % 8) as f64 / 4.0 - 1.0);
            let t0 = Instant::now();
            errors += s.drag_point(30, bx + off, by - off);
            s.fill_path();
            s.fill_comb(50.0, 0.75, 3.0, 8, scale);
            times.push(t0.elapsed().as_secs_f64() * 1e3);
            iterations += s.last_change().iterations;
        }
        let total = start.elapsed().as_secs_f64() * 1e3;
        times.sort_by(f64::total_cmp);
        // The parts alone: re-solve, path, comb.
        let mut part = [0.0f64; 3];
        for k in 1..=UPDATES {
            let off = 1.25 * ((k % 8) as f64 / 4.0 - 1.0);
            let t0 = Instant::now();
            s.drag_point(30, bx + off, by - off);
            let t1 = Instant::now();
            s.fill_path();
            let t2 = Instant::now();
            s.fill_comb(50.0, 0.75, 3.0, 8, scale);
            let t3 = Instant::now();
            part[0] += (t1 - t0).as_secs_f64() * 1e3 / UPDATES as f64;
            part[1] += (t2 - t1).as_secs_f64() * 1e3 / UPDATES as f64;
            part[2] += (t3 - t2).as_secs_f64() * 1e3 / UPDATES as f64;
        }
        println!(
            "{name}: re-solve {:.4} ms, path {:.4} ms, comb {:.4} ms (means)",
            part[0], part[1], part[2]
        );
        println!(
            "{name}: mean {:.4} ms, p50 {:.4} ms, p95 {:.4} ms over {UPDATES} updates \
             ({:.2} iterations/update, {errors} errors)",
            total / UPDATES as f64,
            times[UPDATES / 2],
            times[UPDATES * 95 / 100],
            iterations as f64 / UPDATES as f64
        );
    }
}
