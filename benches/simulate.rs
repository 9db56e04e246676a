//! The cost of a simulated run (`simulate::simulate`): the whole event loop — integration,
//! gap tracking, every impact solved by its law, persistent contact, the samples — on a setup
//! read once, f64, at the scenes' own tolerances (10⁻¹⁰).
//!
//! * `simulate/bouncing-ball`: to the accumulation of its impacts (3 impacts, then Zeno);
//! * `simulate/housner-block`: Housner's block rocking to rest (19 landings, unilateral law
//!   with friction);
//! * `simulate/slender-block-10s`: a slender block rocking for 10 s (17 landings);
//! * `simulate/tumbling-box`: a box tumbling to rest (34 impacts, friction, flat landings).
//!
//! Before timing, each run's impacts and steps are printed, so the rates (impacts and steps per
//! second) follow from criterion's time per run. `cargo bench --bench simulate`.

use std::hint::black_box;
use std::time::Duration;

use criterion::Criterion;
use inertance::scene::SimulationScene;
use inertance::simulate::simulate;

fn main() {
    let mut c = Criterion::default()
        .configure_from_args()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(20);
    let mut g = c.benchmark_group("simulate");
    for (name, file) in [
        ("bouncing-ball", "bouncing-ball"),
        ("housner-block", "rocking-block"),
        ("slender-block-10s", "slender-block"),
        ("tumbling-box", "tumbling-box"),
    ] {
        let scene = SimulationScene::load(std::path::Path::new(&format!(
            "examples/simulate/{file}.toml"
        )))
        .expect("loads");
        let sim = simulate(&scene.setup).expect("runs");
        eprintln!(
            "simulate/{name}: {} impacts, {} steps ({} rejected), {} s simulated",
            sim.impacts.len(),
            sim.steps.0,
            sim.steps.1,
            sim.t_end
        );
        g.bench_function(name, |b| {
            b.iter(|| simulate(black_box(&scene.setup)).expect("runs"))
        });
    }
    g.finish();
    c.final_summary();
}
