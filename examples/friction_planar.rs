//! The planar frictional solve in f64 against the frictionless one, on the friction bench's
//! seeded scenes (`inertance::tools::friction_bench`: 1–3 contacts, μ = 1/2, Poisson's law).
//!
//! * `cargo run --release --example friction_planar` — per scene, ns per frictional solve and
//!   per frictionless assemble + Poisson solve, measured one after the other, and their ratio;
//!   then the ratio of the medians (what `inertance bench` prints) and the median ratio.
//! * `… -- --dump` — every scene's f64 outputs (impulses along the stacked axes, velocities
//!   after, the twist, the works, the end of s, the segments' modes), in full precision: run it
//!   before and after a change and compare.
//! * `… -- --loop N [--frictionless]` — N passes over the scenes and nothing printed, for
//!   instruction counts:
//!   `valgrind --tool=callgrind target/release/examples/friction_planar --loop 20`
//!
//! The frictional solves run on one kept [`PlanarFrictionWork`], as the bench times them;
//! `--one-off` makes `--dump` and `--loop` call `solve_frictional` afresh for every scene
//! instead (the two dumps are identical).

use std::time::Duration;

use inertance::impact::friction::{
    Frictional, Hypothesis, PlanarFrictionWork, Restitution, solve_frictional,
};
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::tools::friction_bench::{PLANAR_GOAL, planar_scenes, time_planar};
use inertance::{Problem, Scalar};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let problems: Vec<Problem<f64>> = planar_scenes(24)
        .iter()
        .map(|s| s.problem::<f64>().expect("the bench's scenes are valid"))
        .collect();
    let one_off = args.iter().any(|a| a == "--one-off");
    let mut work = PlanarFrictionWork::new();
    if let Some(at) = args.iter().position(|a| a == "--loop") {
        let passes: usize = args[at + 1].parse().expect("--loop N");
        if args.iter().any(|a| a == "--frictionless") {
            let mut out = Outcome::default();
            for _ in 0..passes {
                for p in &problems {
                    let mut impact = Impact::assemble(std::hint::black_box(p)).expect("assembles");
                    impact.solve(Model::Poisson, &mut out).expect("solves");
                }
            }
        } else if one_off {
            for _ in 0..passes {
                for p in &problems {
                    let p = std::hint::black_box(p);
                    std::hint::black_box(
                        solve_frictional(p, Restitution::Poisson, 0.0).expect("solves"),
                    );
                }
            }
        } else {
            for _ in 0..passes {
                for p in &problems {
                    let p = std::hint::black_box(p);
                    let f = work
                        .solve_into(p, Restitution::Poisson, Hypothesis::Simultaneous, 0.0)
                        .expect("solves");
                    std::hint::black_box(f);
                }
            }
        }
        return;
    }
    if args.iter().any(|a| a == "--dump") {
        for (k, p) in problems.iter().enumerate() {
            let f: Frictional<f64> = match one_off {
                true => solve_frictional(p, Restitution::Poisson, 0.0).expect("solves"),
                false => work
                    .solve_into(p, Restitution::Poisson, Hypothesis::Simultaneous, 0.0)
                    .expect("solves")
                    .clone(),
            };
            let fmt = |xs: &[f64]| {
                xs.iter()
                    .map(|x| format!("{x:e}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            let modes: Vec<String> = f
                .segments
                .iter()
                .map(|s| {
                    let m: Vec<&str> = s.modes.iter().map(|m| m.name()).collect();
                    format!("[{}]", m.join(","))
                })
                .collect();
            println!(
                "scene {k}: impulses {} | after {} | twist {} | wc {} | wr {} | friction {:e} | end {:e} | {}",
                fmt(&f.impulses),
                fmt(&f.after),
                fmt(f.velocity.as_slice()),
                fmt(&f.work_compression),
                fmt(&f.work_restitution),
                f.friction_dissipation,
                f.end.to_f64(),
                modes.join(" ")
            );
        }
        return;
    }
    let budget = Duration::from_millis(40);
    let (mut fr, mut free, mut ratios) = (vec![], vec![], vec![]);
    for (k, p) in problems.iter().enumerate() {
        let (a, b) = time_planar(p, budget).expect("times");
        println!(
            "scene {k:2} ({} contacts): frictional {a:8.0} ns, frictionless {b:6.0} ns, {:5.1}×",
            p.contacts().len(),
            a / b
        );
        fr.push(a);
        free.push(b);
        ratios.push(a / b);
    }
    let (a, b) = (median(fr), median(free));
    println!(
        "planar friction f64 ÷ frictionless f64: {:.1}× (medians {a:.0} ns ÷ {b:.0} ns; median \
         ratio {:.1}×; goal ≤ {PLANAR_GOAL}×)",
        a / b,
        median(ratios)
    );
}
