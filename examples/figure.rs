//! Render the paper-style figure of a built-in drawing: `cargo run --example figure -- bear`.
use kappa::{builtin_design, gallery::paper_figure, Design};

fn main() {
    let name = std::env::args().nth(1).unwrap_or_else(|| "bear".into());
    let design =
        Design::from_json(builtin_design(&name).expect("unknown drawing")).expect("valid JSON");
    let image = paper_figure(&design, 360).expect("figure");
    let out = format!("target/{name}.png");
    image.save_png(&out).expect("write PNG");
    println!("wrote {out}");
}
