//! The spatial frictional solve in f64 on the ball-in-corner class (issue 29, item 3): a
//! spinning ball thrown into a floor and walls, Newton's law — `examples/ball-in-corner.toml`
//! (floor and wall, μ = 0.3, k = 0.6) and seeded variants of it: random velocity and spin,
//! μ ∈ [0.1, 1], k ∈ [0, 1], 1–3 contacts (the floor, a wall facing −x, a wall facing −y).
//!
//! * `cargo run --release --example friction_spatial` — per scene, µs per solve at the
//!   tolerance 10⁻⁸ (the goal's) and at the friction bench's, ε^(2/3) ≈ 3.7·10⁻¹¹; then the
//!   medians over the scenes (the goal: ≤ 30 µs at 10⁻⁸).
//! * `… -- --dump` — every scene's f64 outputs at both tolerances (impulses along the stacked
//!   axes, velocities after, the twist, the works, the friction dissipation, the end of s, the
//!   error estimate, the segments' modes), in full precision: run it before and after a change
//!   and compare with `cmp`.
//! * `… -- --reference` — per scene and tolerance, the f64 run's error against the
//!   double-double run at 10⁻¹⁴ (impulse vectors and twist, each relative to its group's
//!   largest entry, as the bench's), beside the run's own estimate (relative likewise).
//! * `… -- --stats` — per scene and tolerance, what the integration cost
//!   ([`inertance::impact::friction::spatial::Stats`]: steps accepted and rejected, events,
//!   stops).
//! * `… -- --loop N [--tight]` — N passes over the scenes at 10⁻⁸ (at the bench's tolerance
//!   with `--tight`) and nothing printed, for instruction counts:
//!   `valgrind --tool=callgrind target/release/examples/friction_spatial --loop 20`

use std::time::Instant;

use inertance::Problem;
use inertance::impact::friction::spatial::{self, Stats};
use inertance::impact::friction::{Blocks, Frictional, Restitution, solve_frictional};
use inertance::impact::mechanism::Mechanism;
use inertance::scalar::dd::DoubleDouble;
use inertance::scene::Scene;
use inertance::scene::pipeline::friction_tolerance;
use inertance::tools::ball_in_corner::{self, GOAL_TOL, GOAL_US};
use inertance::tools::friction_bench::{outputs, relative};

/// The double-double reference's tolerance: 10³ times below the bench's (its own ε^(2/3),
/// 10⁻²¹, takes more than the step budget through the stick exits of this class).
const REFERENCE_TOL: f64 = 1e-14;

/// Random variants after the example scene.
const VARIANTS: usize = 23;

/// The class's scenes ([`inertance::tools::ball_in_corner`]).
fn scenes() -> Vec<(Scene, Problem<f64>)> {
    ball_in_corner::scenes(VARIANTS)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// µs per solve of `p` at `tol`: the median of five timed batches of about 20 ms each.
fn time(p: &Problem<f64>, tol: f64) -> f64 {
    let solve = || {
        std::hint::black_box(
            solve_frictional(std::hint::black_box(p), Restitution::Newton, tol).expect("solves"),
        );
    };
    let start = Instant::now();
    solve();
    let once = start.elapsed().as_secs_f64();
    let reps = ((0.02 / once.max(1e-7)) as usize).max(1);
    let samples = (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..reps {
                solve();
            }
            start.elapsed().as_secs_f64() * 1e6 / reps as f64
        })
        .collect();
    median(samples)
}

fn fmt(xs: &[f64]) -> String {
    xs.iter()
        .map(|x| format!("{x:e}"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn dump(k: usize, tol: f64, f: &Frictional<f64>) {
    let modes: Vec<String> = f
        .segments
        .iter()
        .map(|s| {
            let m: Vec<&str> = s.modes.iter().map(|m| m.name()).collect();
            format!("{:e}..{:e} [{}]", s.from, s.to, m.join(","))
        })
        .collect();
    let verdicts: Vec<String> = f.verdicts.iter().map(|v| format!("{v:?}")).collect();
    println!(
        "scene {k} tol {tol:e}: impulses {} | after {} | twist {} | wc {} | wr {} | friction {:e} \
         | end {:e} | estimate {:e} | {} | {}",
        fmt(&f.impulses),
        fmt(&f.after),
        fmt(f.velocity.as_slice()),
        fmt(&f.work_compression),
        fmt(&f.work_restitution),
        f.friction_dissipation,
        f.end,
        f.error_estimate.unwrap_or(f64::NAN),
        modes.join(" "),
        verdicts.join(" ")
    );
}

fn reference(scenes: &[(Scene, Problem<f64>)]) {
    let tight = friction_tolerance::<f64>();
    let (mut worst_goal, mut worst_tight) = (0.0f64, 0.0f64);
    for (k, (scene, p)) in scenes.iter().enumerate() {
        let dd: Problem<DoubleDouble> = scene.problem().expect("the scene reads in double-double");
        let Ok(d) = solve_frictional(&dd, Restitution::Newton, REFERENCE_TOL) else {
            println!("scene {k:2}: the double-double run fails");
            continue;
        };
        let e = outputs(&d);
        let mut line = format!("scene {k:2} ({} contacts):", p.contacts().len());
        for tol in [GOAL_TOL, tight] {
            let f = solve_frictional(p, Restitution::Newton, tol).expect("solves");
            let o = outputs(&f);
            let err = relative(&o.0, &e.0).max(relative(&o.1, &e.1));
            let scale = e.0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let est = f.error_estimate.unwrap_or(f64::NAN) / scale.max(f64::MIN_POSITIVE);
            line += &format!("  tol {tol:.1e}: error {err:.1e} (estimate {est:.1e})");
            if tol == GOAL_TOL {
                worst_goal = worst_goal.max(err);
            } else {
                worst_tight = worst_tight.max(err);
            }
        }
        println!("{line}");
    }
    println!(
        "largest error against double-double: {worst_goal:.1e} at tol {GOAL_TOL:e}, \
         {worst_tight:.1e} at tol {tight:.1e}"
    );
}

/// What the integration of `p` at `tol` cost.
fn stats(p: &Problem<f64>, tol: f64) -> Stats {
    let frames: Vec<_> = (0..p.contacts().len())
        .map(|i| p.frame(i, true).expect("a validated problem's tangents"))
        .collect();
    spatial::integrate(p, Blocks::spatial(p, &frames), Restitution::Newton, tol)
        .expect("solves")
        .1
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scenes = scenes();
    let problems: Vec<&Problem<f64>> = scenes.iter().map(|(_, p)| p).collect();
    let tight = friction_tolerance::<f64>();
    if let Some(at) = args.iter().position(|a| a == "--loop") {
        let passes: usize = args[at + 1].parse().expect("--loop N");
        let tol = if args.iter().any(|a| a == "--tight") {
            tight
        } else {
            GOAL_TOL
        };
        for _ in 0..passes {
            for p in &problems {
                std::hint::black_box(
                    solve_frictional(std::hint::black_box(*p), Restitution::Newton, tol)
                        .expect("solves"),
                );
            }
        }
        return;
    }
    if args.iter().any(|a| a == "--dump") {
        for (k, p) in problems.iter().enumerate() {
            for tol in [GOAL_TOL, tight] {
                dump(
                    k,
                    tol,
                    &solve_frictional(*p, Restitution::Newton, tol).expect("solves"),
                );
            }
        }
        return;
    }
    if args.iter().any(|a| a == "--stats") {
        for (k, p) in problems.iter().enumerate() {
            for tol in [GOAL_TOL, tight] {
                let s = stats(p, tol);
                println!(
                    "scene {k:2} ({} contacts) tol {tol:.1e}: {} accepted, {} rejected, {} events, {} stops",
                    p.contacts().len(),
                    s.accepted,
                    s.rejected,
                    s.events,
                    s.stops
                );
            }
        }
        return;
    }
    if args.iter().any(|a| a == "--reference") {
        reference(&scenes);
        return;
    }
    let (mut goal, mut bench) = (vec![], vec![]);
    for (k, p) in problems.iter().enumerate() {
        let (a, b) = (time(p, GOAL_TOL), time(p, tight));
        println!(
            "scene {k:2} ({} contacts): {a:8.1} µs at tol {GOAL_TOL:e}, {b:8.1} µs at tol {tight:.1e}",
            p.contacts().len()
        );
        goal.push(a);
        bench.push(b);
    }
    println!(
        "ball in corner, {} scenes: median {:.1} µs per solve at tol {GOAL_TOL:e} (goal ≤ \
         {GOAL_US} µs), {:.1} µs at tol {tight:.1e}",
        problems.len(),
        median(goal),
        median(bench)
    );
}
