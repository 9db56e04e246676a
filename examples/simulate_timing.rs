//! Runs a simulation scene many times (for profiling the event loop):
//! `cargo run --release --example simulate_timing -- examples/simulate/slender-block.toml 50`.
use inertance::scene::SimulationScene;
use inertance::simulate::simulate;

fn main() {
    let mut args = std::env::args().skip(1);
    let file = args
        .next()
        .unwrap_or_else(|| "examples/simulate/slender-block.toml".into());
    let runs: usize = args.next().and_then(|n| n.parse().ok()).unwrap_or(50);
    let scene = SimulationScene::load(std::path::Path::new(&file)).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(2)
    });
    let start = std::time::Instant::now();
    let mut impacts = 0;
    for _ in 0..runs {
        match simulate(&scene.setup) {
            Ok(sim) => impacts += sim.impacts.len(),
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(3)
            }
        }
    }
    let per = start.elapsed().as_secs_f64() / runs as f64;
    println!(
        "{file}: {:.3} ms per run, {} impacts per run",
        per * 1e3,
        impacts / runs
    );
}
