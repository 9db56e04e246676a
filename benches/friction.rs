//! The planar frictional solve beside the frictionless one, on the friction bench's seeded
//! planar scenes (`tools::friction_bench::planar_scenes`: 1–3 contacts, μ = 1/2, Poisson's law):
//!
//! * `friction-planar/frictional-f64`: the planar solve on each of the 24 scenes, event by
//!   event, on a kept `PlanarFrictionWork` (one iteration solves all 24);
//! * `friction-planar/frictional-f64-one-off`: the same through `solve_frictional`, which
//!   builds and drops its workspace and report at every call;
//! * `friction-planar/frictionless-f64`: assemble + Poisson solve of the same 24 scenes on a
//!   kept `Impact`, as `inertance bench` times it;
//! * `friction-planar/frictional-exact`: the same frictional solves in exact rationals.
//!
//! It ends by printing issue 29's ratio, frictional f64 ÷ frictionless f64, timed scene by scene
//! back to back in this run (`tools::friction_bench::time_planar`, the ratio of the medians
//! over the scenes, as `inertance bench` prints it), against its goal.
//!
//! `cargo bench --bench friction`

use std::hint::black_box;
use std::time::Duration;

use criterion::Criterion;
use inertance::impact::friction::{Hypothesis, PlanarFrictionWork, Restitution, solve_frictional};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::scalar::Exact;
use inertance::tools::friction_bench::{PLANAR_GOAL, planar_scenes, time_planar};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let mut c = Criterion::default()
        .configure_from_args()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(20);
    let scenes = planar_scenes(24);
    let f64s: Vec<Problem<f64>> = scenes.iter().map(|s| s.problem().expect("valid")).collect();
    let exact: Vec<Problem<Exact>> = scenes.iter().map(|s| s.problem().expect("valid")).collect();
    let mut g = c.benchmark_group("friction-planar");
    let mut work = PlanarFrictionWork::new();
    g.bench_function("frictional-f64", |b| {
        b.iter(|| {
            for p in &f64s {
                let f = work
                    .solve_into(
                        black_box(p),
                        Restitution::Poisson,
                        Hypothesis::Simultaneous,
                        0.0,
                    )
                    .expect("solves");
                black_box(f);
            }
        })
    });
    g.bench_function("frictional-f64-one-off", |b| {
        b.iter(|| {
            for p in &f64s {
                black_box(
                    solve_frictional(black_box(p), Restitution::Poisson, 0.0).expect("solves"),
                );
            }
        })
    });
    let mut impact = Impact::assemble(&f64s[0]).expect("assembles");
    let mut out = Outcome::default();
    g.bench_function("frictionless-f64", |b| {
        b.iter(|| {
            for p in &f64s {
                impact.reassemble(black_box(p)).expect("assembles");
                impact.solve(Model::Poisson, &mut out).expect("solves");
            }
        })
    });
    g.bench_function("frictional-exact", |b| {
        b.iter(|| {
            for p in &exact {
                black_box(
                    solve_frictional(black_box(p), Restitution::Poisson, 0.0).expect("solves"),
                );
            }
        })
    });
    g.finish();
    c.final_summary();
    let (mut frictional, mut frictionless) = (Vec::new(), Vec::new());
    for p in &f64s {
        let (a, b) = time_planar(p, Duration::from_millis(40)).expect("times");
        frictional.push(a);
        frictionless.push(b);
    }
    let (a, b) = (median(frictional), median(frictionless));
    println!(
        "planar friction f64 ÷ frictionless f64: {:.1}× ({a:.0} ns ÷ {b:.0} ns, medians over {} \
         scenes, this run; goal ≤ {PLANAR_GOAL}×)",
        a / b,
        f64s.len()
    );
}
