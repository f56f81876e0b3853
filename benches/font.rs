//! A whole CFF font through `kappa font`, end to end: every drawn glyph of the vendored EB
//! Garamond 12 Regular (3 057 of its 3 080 glyphs) drafted as κ-curves with extremum tangents
//! held, written as TrueType and as a UFO. Prints the wall time, the glyphs within the
//! tolerance, the fallbacks, the slowest glyphs and the time per 2 000 glyphs.
//!
//! Run with `cargo bench --all-features --bench font` (one run, about 2 minutes on two
//! cores; `KAPPA_BENCH_FONT=path` for another font, `KAPPA_BENCH_RUNS=n` for more runs).

use std::process::Command;
use std::time::Instant;

fn main() {
    let font = std::env::var("KAPPA_BENCH_FONT").unwrap_or_else(|_| {
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/fonts/EBGaramond12-Regular.otf"
        )
        .to_owned()
    });
    let runs: usize = std::env::var("KAPPA_BENCH_RUNS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    let out = std::env::temp_dir().join(format!("kappa-bench-font-{}", std::process::id()));
    std::fs::create_dir_all(&out).expect("a scratch folder");
    println!("kappa font --font {font} (TTF + UFO), {runs} run(s)");
    for run in 0..runs {
        let start = Instant::now();
        let output = Command::new(env!("CARGO_BIN_EXE_kappa"))
            .arg("font")
            .arg("--font")
            .arg(&font)
            .arg("--out")
            .arg(out.join("font.ttf"))
            .arg("--out")
            .arg(out.join("font.ufo"))
            .output()
            .expect("kappa runs");
        let wall = start.elapsed().as_secs_f64();
        assert!(
            output.status.success(),
            "kappa font failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
        let report: serde_json::Value =
            serde_json::from_slice(&output.stdout).expect("a JSON report");
        let glyphs = report["glyphs"].as_array().expect("glyphs");
        let mut seconds: Vec<(f64, &str)> = glyphs
            .iter()
            .map(|g| {
                (
                    g["seconds"].as_f64().unwrap_or(0.0),
                    g["name"].as_str().unwrap_or("?"),
                )
            })
            .collect();
        seconds.sort_by(|a, b| b.0.total_cmp(&a.0));
        let over = seconds.iter().filter(|s| s.0 > 1.0).count();
        let cpu: f64 = seconds.iter().map(|s| s.0).sum();
        let n = glyphs.len();
        println!(
            "run {run}: {n} glyphs in {wall:.1} s wall ({:.1} s per 2 000 glyphs; drafting \
             {cpu:.1} s summed over the glyphs), {} within the tolerance, {} fallbacks, \
             {over} glyphs over 1 s",
            wall * 2000.0 / n as f64,
            report["within_tolerance"],
            report["fallback_glyphs"],
        );
        let slowest: Vec<String> = seconds
            .iter()
            .take(5)
            .map(|(s, name)| format!("{name} {s:.2} s"))
            .collect();
        println!("  slowest: {}", slowest.join(", "));
    }
    std::fs::remove_dir_all(&out).ok();
}
