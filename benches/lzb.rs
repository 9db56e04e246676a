//! The LZB multiple-impact law's cost per solve (`impact::multiple::solve_lzb`): the whole
//! integration — G, the adaptive Runge–Kutta steps, the events, every output — on a mechanism
//! prepared once, f64.
//!
//! * `lzb/cradle-3`: Newton's cradle of three balls (`examples/cradle-3-lzb.toml`, a system);
//! * `lzb/bar-two-supports`: a bar landing flat on two supports (one body), at K₂/K₁ = 1 and 10
//!   (the unequal stiffnesses take more steps: the stiff contact's impact is shorter).
//!
//! `cargo bench --bench lzb`; `inertance bench --scene examples/cradle-3-lzb.toml` times the
//! same solve without criterion.

use std::hint::black_box;
use std::time::Duration;

use criterion::Criterion;
use inertance::impact::multiple::solve_lzb;
use inertance::scene::Scene;
use inertance::scene::lzb::contact_laws;
use inertance::scene::pipeline::{friction_tolerance, prepare};

fn main() {
    let mut c = Criterion::default()
        .configure_from_args()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(20);
    let tolerance = friction_tolerance::<f64>();
    let mut g = c.benchmark_group("lzb");
    let cradle = Scene::load(std::path::Path::new("examples/cradle-3-lzb.toml")).expect("loads");
    let system = cradle.system::<f64>().expect("a system");
    let laws = contact_laws(&cradle).expect("valid laws");
    g.bench_function("cradle-3", |b| {
        b.iter(|| solve_lzb(black_box(&system), &laws, tolerance).expect("ends"))
    });
    let bar =
        Scene::load(std::path::Path::new("examples/bar-two-supports-lzb.toml")).expect("loads");
    let problem = prepare::<f64>(&bar).expect("prepares");
    for ratio in [1.0, 10.0] {
        let mut laws = contact_laws(&bar).expect("valid laws");
        laws[1].stiffness *= ratio;
        g.bench_function(format!("bar-two-supports/ratio-{ratio}"), |b| {
            b.iter(|| solve_lzb(black_box(&problem), &laws, tolerance).expect("ends"))
        });
    }
    g.finish();
    c.final_summary();
}
