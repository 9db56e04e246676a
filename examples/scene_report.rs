//! Read a scene file and print its JSON report — what `inertance solve SCENE --json` prints,
//! from the library: the scene is read exactly as written, solved in the scalar chosen, and
//! reported in the paper's units.
//!
//! `cargo run --example scene_report -- [SCENE.toml] [--exact]` (default: the paper's
//! Example 3, `examples/planar-bar.toml`)

use std::path::PathBuf;

use inertance::Exact;
use inertance::scene::Scene;
use inertance::scene::pipeline;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    run(&args, &mut std::io::stdout())
}

/// Read the scene named in `args` (or Example 3) and print its report to `out`.
pub fn run(
    args: &[String],
    out: &mut impl std::io::Write,
) -> Result<(), Box<dyn std::error::Error>> {
    let exact = args.iter().any(|a| a == "--exact");
    let path = args
        .iter()
        .find(|a| !a.starts_with("--"))
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/planar-bar.toml")
        });
    let scene = Scene::load(&path)?;
    let solved = if exact {
        pipeline::run::<Exact>(&scene, None)?
    } else {
        pipeline::run::<f64>(&scene, None)?
    };
    writeln!(
        out,
        "{}",
        serde_json::to_string_pretty(&solved.report.to_json())?
    )?;
    Ok(())
}
