//! What friction costs: the frictional solve ([`crate::impact::friction`]) timed beside the
//! frictionless one, on seeded random scenes, per scalar type.
//!
//! * **Planar** scenes (bodies moving in the xy-plane, 1–3 contacts in it, μ = 1/2 at every
//!   contact, Poisson's law): the exact event-by-event solve in rationals, and the same solve in
//!   f64 and double-double, with their relative error against the exact result (impulses and
//!   twist, each relative to its group's largest entry); beside them the frictionless
//!   assemble + Poisson solve of the same scene in f64.
//! * **Spatial** scenes (1–2 contacts anywhere, μ = 1/2, Poisson): the adaptive integration in
//!   f64 (tolerance ε^(2/3)) and double-double, the f64 run's error estimate, and its actual
//!   error against the double-double run.

use std::time::Duration;

use serde_json::{Value as Json, json};

use crate::impact::friction::{
    Frictional, Hypothesis, PlanarFrictionWork, Restitution, solve_frictional,
};
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::scalar::dd::DoubleDouble;
use crate::scalar::{Exact, Scalar};
use crate::scene::Scene;
use crate::scene::pipeline::friction_tolerance;
use crate::tools::bench::{Seeded, time_three};

/// One group of scenes: medians over the scenes of per-scene medians.
#[derive(Clone, Debug, Default)]
pub struct FrictionGroup {
    /// Scenes solved.
    pub scenes: usize,
    /// ns per frictional solve, per scalar: (name, ns).
    pub ns: Vec<(&'static str, f64)>,
    /// Median relative error per float scalar against the reference: (name, error).
    pub error: Vec<(&'static str, f64)>,
    /// ns per frictionless assemble + Poisson solve (f64), for comparison.
    pub frictionless_f64_ns: f64,
    /// Spatial: the median f64 error estimate (relative, like the errors).
    pub estimate: Option<f64>,
}

/// The friction bench.
#[derive(Clone, Debug, Default)]
pub struct FrictionBench {
    /// Planar scenes, exact reference.
    pub planar: FrictionGroup,
    /// Spatial scenes, double-double reference.
    pub spatial: FrictionGroup,
    /// The ball-in-corner class at the goal's tolerance 10⁻⁸: the median over its scenes of µs
    /// per f64 solve ([`crate::tools::ball_in_corner`]), and how many scenes.
    pub ball_in_corner: (Option<f64>, usize),
}

/// The seed of the scenes.
const SEED: u64 = 0xf71c_7105;

/// The goal of issue 29 for the planar frictional solve in f64: at most this many times the
/// frictionless solve of the same scene.
pub const PLANAR_GOAL: f64 = 5.0;

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// A random scene: planar (xy-plane) or spatial, `n` contacts, μ = 1/2, Poisson's law.
fn scene(rng: &mut Seeded, n: usize, planar: bool) -> Option<Scene> {
    let z = |rng: &mut Seeded, lo, hi| {
        if planar {
            "0".to_string()
        } else {
            rng.decimal(lo, hi)
        }
    };
    let mut text = format!(
        "[body]\nmass = {}\ninertia = [{}, {}, {}]\nvelocity = [{}, {}, {}]\nangular_velocity = [{}, {}, {}]\n",
        rng.decimal(1, 5),
        rng.decimal(1, 5),
        rng.decimal(1, 5),
        rng.decimal(1, 5),
        rng.decimal(-2, 2),
        rng.decimal(-3, -1),
        z(rng, -1, 1),
        z(rng, -1, 1),
        z(rng, -1, 1),
        rng.decimal(-1, 1),
    );
    for _ in 0..n {
        // Contacts below the centre, normals pointing down-ish: the body lands on them.
        text += &format!(
            "[[contact]]\npoint = [{}, {}, {}]\nnormal = [{}, -1, {}]\nk = {}\nmu = 0.5\n",
            rng.decimal(-2, 2),
            rng.decimal(-2, -1),
            z(rng, -1, 1),
            rng.decimal(-1, 1),
            z(rng, -1, 1),
            rng.decimal(0, 1),
        );
    }
    text += "[solve]\nrestitution = \"poisson\"\n";
    Scene::parse(&text, "generated").ok()
}

/// Impulse vectors (each contact's normal then tangential components) and twist of a result,
/// as f64: what the bench and `examples/friction_spatial` compare against a reference.
pub fn outputs<T: Scalar>(f: &Frictional<T>) -> (Vec<f64>, Vec<f64>) {
    let mut impulses = Vec::new();
    for i in 0..f.blocks.contacts() {
        let (n, t) = f.impulse_vectors(i);
        impulses.extend(n.iter().chain(t.iter()).map(|x| x.to_f64()));
    }
    let twist = f.velocity.as_slice().iter().map(|x| x.to_f64()).collect();
    (impulses, twist)
}

/// The largest error of `x` against `y`, relative to the largest entry of `y` (one group of
/// outputs: the impulse vectors, or the twist).
pub fn relative(x: &[f64], y: &[f64]) -> f64 {
    let scale = y
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    x.iter()
        .zip(y)
        .fold(0.0f64, |m, (p, q)| m.max((p - q).abs() / scale))
}

/// The largest error of `a` against `e`, per group relative to the group's largest entry.
fn relative_error(a: &(Vec<f64>, Vec<f64>), e: &(Vec<f64>, Vec<f64>)) -> f64 {
    relative(&a.0, &e.0).max(relative(&a.1, &e.1))
}

/// The bench's planar scenes: the first `count` from its seed (1, 2, 3 contacts in turn) whose
/// frictional solve succeeds in f64, with their contact counts — what
/// `examples/friction_planar.rs` times and profiles.
pub fn planar_scenes(count: usize) -> Vec<Scene> {
    let mut rng = Seeded(SEED);
    let mut out = Vec::new();
    let mut tries = 0;
    while out.len() < count && tries < 50 * count {
        tries += 1;
        let Some(s) = scene(&mut rng, 1 + tries % 3, true) else {
            continue;
        };
        let solves = s.problem::<f64>().is_ok_and(|p| {
            solve_frictional(&p, Restitution::Poisson, friction_tolerance::<f64>()).is_ok()
        });
        if solves {
            out.push(s);
        }
    }
    out
}

/// ns per frictional solve (Poisson, f64) and per frictionless assemble + Poisson solve of the
/// same scene, measured one after the other.
pub fn time_planar(p: &Problem<f64>, budget: Duration) -> Option<(f64, f64)> {
    Some((time_friction(p, budget)?, time_frictionless(p, budget)?))
}

/// ns per frictional solve on a kept [`PlanarFrictionWork`], refilled at every solve as the
/// frictionless baseline's `Impact` is.
fn time_friction<T: Scalar>(p: &Problem<T>, budget: Duration) -> Option<f64> {
    let mut work = PlanarFrictionWork::new();
    time_three(budget, || {
        work.solve_into(
            std::hint::black_box(p),
            Restitution::Poisson,
            Hypothesis::Simultaneous,
            friction_tolerance::<T>(),
        )
        .map(|_| ())
    })
    .ok()
}

fn time_frictionless(p: &Problem<f64>, budget: Duration) -> Option<f64> {
    let mut impact = Impact::assemble(p).ok()?;
    let mut out = Outcome::default();
    time_three(budget, || {
        impact.reassemble(std::hint::black_box(p))?;
        impact.solve(Model::Poisson, &mut out)
    })
    .ok()
}

/// Run the friction bench (`quick`: fewer scenes, shorter budgets).
pub fn run(quick: bool) -> FrictionBench {
    let count = if quick { 6 } else { 24 };
    let budget = Duration::from_millis(if quick { 4 } else { 40 });
    let mut rng = Seeded(SEED);
    let variants = if quick { 5 } else { 23 };
    FrictionBench {
        planar: group(&mut rng, count, budget, true),
        spatial: group(&mut rng, count, budget, false),
        ball_in_corner: (
            crate::tools::ball_in_corner::median_us(variants, budget),
            1 + variants,
        ),
    }
}

fn group(rng: &mut Seeded, count: usize, budget: Duration, planar: bool) -> FrictionGroup {
    let (mut exact_ns, mut f64_ns, mut dd_ns, mut free_ns) = (vec![], vec![], vec![], vec![]);
    let (mut f64_err, mut dd_err, mut estimates) = (vec![], vec![], vec![]);
    let mut tries = 0;
    while f64_ns.len() < count && tries < 50 * count {
        tries += 1;
        let n = if planar { 1 + tries % 3 } else { 1 + tries % 2 };
        let Some(s) = scene(rng, n, planar) else {
            continue;
        };
        let (Ok(pf), Ok(pd)) = (s.problem::<f64>(), s.problem::<DoubleDouble>()) else {
            continue;
        };
        let (Ok(f), Ok(d)) = (
            solve_frictional(&pf, Restitution::Poisson, friction_tolerance::<f64>()),
            solve_frictional(
                &pd,
                Restitution::Poisson,
                friction_tolerance::<DoubleDouble>(),
            ),
        ) else {
            continue;
        };
        let reference = if planar {
            let Some(e) = s
                .problem::<Exact>()
                .ok()
                .and_then(|p| solve_frictional(&p, Restitution::Poisson, 0.0).ok())
            else {
                continue;
            };
            let Some(t) = s
                .problem::<Exact>()
                .ok()
                .and_then(|p| time_friction(&p, budget))
            else {
                continue;
            };
            exact_ns.push(t);
            dd_err.push(relative_error(&outputs(&d), &outputs(&e)));
            outputs(&e)
        } else {
            let scale = outputs(&d).0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            estimates.push(f.error_estimate.unwrap_or(f64::NAN) / scale.max(f64::MIN_POSITIVE));
            outputs(&d)
        };
        f64_err.push(relative_error(&outputs(&f), &reference));
        let (Some(tf), Some(td), Some(t0)) = (
            time_friction(&pf, budget),
            time_friction(&pd, budget),
            time_frictionless(&pf, budget),
        ) else {
            continue;
        };
        f64_ns.push(tf);
        dd_ns.push(td);
        free_ns.push(t0);
    }
    let mut ns = Vec::new();
    let mut error = vec![("f64", median(f64_err))];
    if planar {
        ns.push(("exact", median(exact_ns)));
        error.push(("double-double", median(dd_err)));
    }
    ns.push(("f64", median(f64_ns.clone())));
    ns.push(("double-double", median(dd_ns)));
    FrictionGroup {
        scenes: f64_ns.len(),
        ns,
        error,
        frictionless_f64_ns: median(free_ns),
        estimate: (!planar).then(|| median(estimates)),
    }
}

fn fmt_ns(ns: f64) -> String {
    if ns >= 1e6 {
        format!("{:.2} ms", ns / 1e6)
    } else if ns >= 1e3 {
        format!("{:.1} µs", ns / 1e3)
    } else {
        format!("{ns:.0} ns")
    }
}

impl FrictionGroup {
    /// ns per frictional f64 solve ÷ ns per frictionless f64 solve, both measured in this run
    /// (the ratio of the medians).
    pub fn f64_ratio(&self) -> f64 {
        self.ns
            .iter()
            .find(|(n, _)| *n == "f64")
            .map_or(f64::NAN, |(_, t)| *t)
            / self.frictionless_f64_ns
    }
}

impl FrictionBench {
    /// The readable table.
    pub fn to_text(&self) -> String {
        let mut s =
            String::from("\nFriction (μ = 1/2 at every contact, Poisson; medians per solve):\n");
        for (name, g, reference) in [
            ("planar, exact events", &self.planar, "exact"),
            ("spatial, RK5(4)", &self.spatial, "double-double"),
        ] {
            let times: Vec<String> =
                g.ns.iter()
                    .map(|(n, t)| format!("{n} {}", fmt_ns(*t)))
                    .collect();
            let errors: Vec<String> = g
                .error
                .iter()
                .map(|(n, e)| format!("{n} {e:.1e}"))
                .collect();
            s += &format!(
                "  {name} ({} scenes): {}; frictionless f64 {} ({:.0}× cheaper than frictional f64); error vs {reference}: {}{}\n",
                g.scenes,
                times.join(", "),
                fmt_ns(g.frictionless_f64_ns),
                g.f64_ratio(),
                errors.join(", "),
                g.estimate
                    .map(|e| format!(" (f64 error estimate {e:.1e})"))
                    .unwrap_or_default()
            );
        }
        s += &format!(
            "  planar friction f64 ÷ frictionless f64: {:.1}× (goal ≤ {PLANAR_GOAL}×)\n",
            self.planar.f64_ratio()
        );
        s
    }

    /// The JSON object.
    pub fn to_json(&self) -> Json {
        let group = |g: &FrictionGroup| {
            json!({
                "scenes": g.scenes,
                "ns_per_solve": g.ns.iter().map(|(n, t)| (n.to_string(), json!(t))).collect::<serde_json::Map<_, _>>(),
                "median_relative_error": g.error.iter().map(|(n, e)| (n.to_string(), json!(e))).collect::<serde_json::Map<_, _>>(),
                "frictionless_f64_ns_per_solve": g.frictionless_f64_ns,
                "f64_error_estimate": g.estimate,
                "f64_over_frictionless": g.f64_ratio(),
            })
        };
        json!({
            "planar": group(&self.planar),
            "spatial": group(&self.spatial),
            "planar_goal_f64_over_frictionless": PLANAR_GOAL,
            "ball_in_corner": {
                "scenes": self.ball_in_corner.1,
                "tolerance": crate::tools::ball_in_corner::GOAL_TOL,
                "median_us_per_f64_solve": self.ball_in_corner.0,
                "goal_us": crate::tools::ball_in_corner::GOAL_US,
            },
        })
    }
}
