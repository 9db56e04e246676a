//! The ball-in-corner class of spatial frictional impacts (issue 29, item 3): a spinning ball
//! thrown into a floor and walls under Newton's law — `examples/ball-in-corner.toml` (floor
//! and wall, μ = 0.3, k = 0.6) and seeded variants of it: random velocity and spin,
//! μ ∈ [0.1, 1], k ∈ [0, 1], 1–3 contacts (the floor, a wall facing −x, a wall facing −y).
//! `examples/friction_spatial.rs` profiles it; `inertance bench` times it against the goal
//! ([`crate::tools::goals`]).

use std::time::Duration;

use crate::impact::friction::{Restitution, solve_frictional};
use crate::impact::problem::Problem;
use crate::scene::Scene;
use crate::scene::pipeline::friction_tolerance;
use crate::tools::bench::{Seeded, time_three};

/// The goal's tolerance.
pub const GOAL_TOL: f64 = 1e-8;

/// The goal of issue 29, item 3: µs per solve at [`GOAL_TOL`].
pub const GOAL_US: f64 = 30.0;

/// The ball-in-corner scene with `n` contacts (1: the floor; 2: and the wall facing −x; 3: and
/// one facing −y), the ball's velocity and spin, and each contact's (μ, k).
fn ball(n: usize, velocity: [String; 3], spin: [String; 3], laws: &[(String, String)]) -> String {
    let mut text = format!(
        "name = \"ball in corner\"\n[body]\nshape = {{ sphere = 0.1 }}\nmass = 0.5\n\
         velocity = [{}]\nangular_velocity = [{}]\n",
        velocity.join(", "),
        spin.join(", ")
    );
    let walls = [
        ("floor", "[0, 0, 1]"),
        ("wall", "[-1, 0, 0]"),
        ("side", "[0, -1, 0]"),
    ];
    for (name, normal) in &walls[..n] {
        text += &format!("[[obstacle]]\nname = \"{name}\"\nnormal = {normal}\n");
    }
    for ((name, _), (mu, k)) in walls[..n].iter().zip(laws) {
        text += &format!("[[contact]]\nobstacle = \"{name}\"\nk = {k}\nmu = {mu}\n");
    }
    text + "[solve]\nmodels = [\"newton\"]\n"
}

/// The example scene, then `variants` seeded variants whose f64 solve succeeds at both
/// [`GOAL_TOL`] and the friction bench's tolerance ε^(2/3).
pub fn scenes(variants: usize) -> Vec<(Scene, Problem<f64>)> {
    let s = |x: &str| x.to_string();
    let example = ball(
        2,
        [s("2"), s("1"), s("-3")],
        [s("3"), s("-4"), s("10")],
        &[(s("0.3"), s("0.6")), (s("0.3"), s("0.6"))],
    );
    let mut texts = vec![example];
    let mut rng = Seeded(0xba11_c0de);
    let mut out = Vec::new();
    let mut tries = 0;
    while out.len() < 1 + variants && tries < 50 * variants.max(1) {
        tries += 1;
        if texts.is_empty() {
            let n = 1 + tries % 3;
            let velocity = [
                rng.decimal(1, 3),
                if n == 3 {
                    rng.decimal(1, 3)
                } else {
                    rng.decimal(-2, 2)
                },
                rng.decimal(-4, -1),
            ];
            let spin = [
                rng.decimal(-12, 12),
                rng.decimal(-12, 12),
                rng.decimal(-12, 12),
            ];
            // μ drawn in tenths of [1, 10]: [0.1, 1]
            let laws: Vec<(String, String)> = (0..n)
                .map(|_| {
                    let mu = rng.decimal(1, 10);
                    let k = rng.decimal(0, 1);
                    let mu = mu
                        .parse::<f64>()
                        .map_or(mu.clone(), |x| format!("{}", x / 10.0));
                    (mu, k)
                })
                .collect();
            texts.push(ball(n, velocity, spin, &laws));
        }
        let Some(text) = texts.pop() else { continue };
        let Ok(scene) = Scene::parse(&text, "ball-in-corner") else {
            continue;
        };
        let Ok(p) = scene.problem::<f64>() else {
            continue;
        };
        let solves = [GOAL_TOL, friction_tolerance::<f64>()]
            .iter()
            .all(|&tol| solve_frictional(&p, Restitution::Newton, tol).is_ok());
        if solves {
            out.push((scene, p));
        }
    }
    out
}

/// The median over the class's scenes (the example and `variants` more) of each scene's µs per
/// f64 solve at [`GOAL_TOL`] (the middle of three timed runs of at least `budget`); `None`
/// when no scene solves.
pub fn median_us(variants: usize, budget: Duration) -> Option<f64> {
    let mut times: Vec<f64> = scenes(variants)
        .iter()
        .filter_map(|(_, p)| {
            time_three(budget, || {
                solve_frictional(std::hint::black_box(p), Restitution::Newton, GOAL_TOL).map(|_| ())
            })
            .ok()
        })
        .map(|ns| ns / 1e3)
        .collect();
    times.sort_by(f64::total_cmp);
    times.get(times.len() / 2).copied()
}
