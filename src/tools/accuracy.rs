//! The accuracy contract ([`crate::analysis::accuracy`]) measured over a corpus, per scalar
//! type and per output: the largest ratio error/bound, which `inertance bench` reports and
//! `tests/accuracy_contract.rs` asserts to be at most 1.
//!
//! The corpus is the hard cases of `tests/hard_cases/` and seeded random scenes whose mass,
//! lengths and moments of inertia span 10^±12 ([`ratio_scenes`]). Each scene is solved in the
//! units [`crate::scene::scale`] chooses for it (constrained scenes as written) — the units
//! every float command solves in, and the bounds are unit-free — exactly, then in each float
//! type, and every float outcome is measured against the exact one.

use std::path::Path;

use crate::analysis::accuracy::{Check, Conditioning, Output, measure};
use crate::impact::solve::{Impact, Outcome};
use crate::scalar::dd::DoubleDouble;
use crate::scalar::{Exact, Scalar};
use crate::scene::Scene;
use crate::scene::pipeline::prepare;
use crate::tools::bench::Seeded;

/// One float solve of one model measured against the exact one.
#[derive(Clone, Debug)]
pub struct Measurement {
    /// The scene's name and the model.
    pub case: String,
    /// cond₂ G.
    pub cond: f64,
    /// Per output, in [`Output::ALL`] order; `None` when the type declared G singular.
    pub checks: Option<[Check; 5]>,
}

/// One scalar type over the corpus.
#[derive(Clone, Debug)]
pub struct ContractRow {
    /// The scalar's name.
    pub scalar: &'static str,
    /// Every measurement.
    pub measurements: Vec<Measurement>,
}

impl ContractRow {
    /// The largest ratio error/bound of `output` over the solves, and its case.
    pub fn worst(&self, output: Output) -> (f64, &str) {
        let k = Output::ALL.iter().position(|o| *o == output).unwrap_or(0);
        self.measurements
            .iter()
            .filter_map(|m| m.checks.map(|c| (c[k].ratio(), m.case.as_str())))
            .fold((0.0, ""), |a, b| if b.0 > a.0 { b } else { a })
    }

    /// How many solves the type declared singular, and the smallest cond₂ G among them.
    pub fn declared_singular(&self) -> (usize, f64) {
        self.measurements
            .iter()
            .filter(|m| m.checks.is_none())
            .fold((0, f64::INFINITY), |(k, c), m| (k + 1, c.min(m.cond)))
    }
}

/// The scene in the units float solves use (as written when it is not scaled).
fn in_solver_units(scene: &Scene) -> Scene {
    crate::scene::scale::scale(scene).map_or_else(|| scene.clone(), |(s, _)| s)
}

/// An exactly solved scene: its impact, conditioning and each model's outcome.
struct Reference {
    name: String,
    scene: Scene,
    conditioning: Conditioning,
    outcomes: Vec<(crate::impact::restitution::Model, Outcome<Exact>)>,
    impact: Impact<Exact>,
}

/// Solve `scene` exactly; `None` when G is singular or the scene has no simultaneous solve.
fn reference(scene: &Scene) -> Option<Reference> {
    let scene = in_solver_units(scene);
    let problem = prepare::<Exact>(&scene).ok()?;
    let mut impact = Impact::assemble(&problem).ok()?;
    let conditioning = Conditioning::of(&mut impact)?;
    let mut outcomes = Vec::new();
    for &m in &scene.models {
        let mut out = Outcome::default();
        impact.solve(m, &mut out).ok()?;
        outcomes.push((m, out));
    }
    Some(Reference {
        name: scene.name.clone(),
        scene,
        conditioning,
        outcomes,
        impact,
    })
}

/// Every model of `r` solved in `T` and measured; nothing when the scene cannot be read
/// into `T`.
fn measure_in<T: Scalar>(r: &Reference, into: &mut Vec<Measurement>) {
    let Ok(problem) = prepare::<T>(&r.scene) else {
        return;
    };
    let Ok(mut impact) = Impact::assemble(&problem) else {
        return;
    };
    for (model, exact) in &r.outcomes {
        let mut out = Outcome::default();
        let checks = match impact.solve(*model, &mut out) {
            Ok(()) => measure(&r.impact, &r.conditioning, *model, exact, &impact, &out),
            Err(_) => None,
        };
        into.push(Measurement {
            case: format!("{} {}", r.name, model.name()),
            cond: r.conditioning.cond,
            checks,
        });
    }
}

/// The contract measured on `scenes` in f32, f64 and double-double.
pub fn run(scenes: &[Scene]) -> Vec<ContractRow> {
    let refs: Vec<Reference> = scenes.iter().filter_map(reference).collect();
    let mut rows = vec![
        ContractRow {
            scalar: f32::NAME,
            measurements: Vec::new(),
        },
        ContractRow {
            scalar: f64::NAME,
            measurements: Vec::new(),
        },
        ContractRow {
            scalar: DoubleDouble::NAME,
            measurements: Vec::new(),
        },
    ];
    for r in &refs {
        measure_in::<f32>(r, &mut rows[0].measurements);
        measure_in::<f64>(r, &mut rows[1].measurements);
        measure_in::<DoubleDouble>(r, &mut rows[2].measurements);
    }
    rows
}

/// The hard cases in `dir` (`*.toml`, sorted), as scenes.
pub fn hard_cases(dir: &Path) -> Vec<Scene> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files.iter().filter_map(|f| Scene::load(f).ok()).collect()
}

/// `count` seeded random free-body scenes spanning ratios of 10^±12: a mass 10^a kg
/// (a ∈ [−12, 12]), a length unit 10^b m (b ∈ [−12, 12]), radii of gyration 10^t times it per
/// axis (t ∈ [−6, 6] each, so J/(m L²) spans 10^±12 and the moments differ by up to 10¹²),
/// contact points at 10^s times the length unit (s ∈ [−3, 3] per contact), 1–4 contacts,
/// random normals, velocities 10^d (d ∈ [−3, 3]) in those units. Every number a short decimal,
/// so the exact solve is the reference. Many such scenes have a large cond G; a type that
/// cannot resolve it declares G singular.
pub fn ratio_scenes(count: usize, seed: u64) -> Vec<Scene> {
    let mut rng = Seeded(seed);
    let mut pick = |lo: i64, hi: i64| lo + (rng.next() % (hi - lo + 1) as u64) as i64;
    let mut scenes = Vec::with_capacity(count);
    let mut attempt = 0;
    while scenes.len() < count && attempt < 100 * count {
        attempt += 1;
        let (a, b, d) = (pick(-12, 12), pick(-12, 12), pick(-3, 3));
        let digits = |p: &mut dyn FnMut(i64, i64) -> i64| format!("{}.{}", p(1, 9), p(0, 9));
        let num = |p: &mut dyn FnMut(i64, i64) -> i64, e: i64| {
            let sign = if p(0, 1) == 0 { "" } else { "-" };
            format!("\"{sign}{}e{e}\"", digits(p))
        };
        let mass = format!("\"{}e{a}\"", digits(&mut pick));
        let inertia: Vec<String> = (0..3)
            .map(|_| {
                let t = pick(-6, 6);
                // J = m (ρ 10^(b+t))², written as one decimal.
                let rho = pick(10, 99);
                format!("\"{}e{}\"", rho * rho, a + 2 * (b + t) - 2)
            })
            .collect();
        let v: Vec<String> = (0..3).map(|_| num(&mut pick, b + d)).collect();
        let w: Vec<String> = (0..3).map(|_| num(&mut pick, d)).collect();
        let mut text = format!(
            "name = \"ratios-{}\"\n[body]\nmass = {mass}\ninertia = [{}]\nvelocity = [{}]\nangular_velocity = [{}]\n",
            scenes.len(),
            inertia.join(", "),
            v.join(", "),
            w.join(", ")
        );
        for _ in 0..pick(1, 4) {
            let s = pick(-3, 3);
            let p: Vec<String> = (0..3).map(|_| num(&mut pick, b + s)).collect();
            let n: Vec<String> = (0..3).map(|_| pick(-4, 4).to_string()).collect();
            if n.iter().all(|x| x == "0") {
                continue;
            }
            text += &format!(
                "[[contact]]\npoint = [{}]\nnormal = [{}]\nk_newton = 0.{}\nk_poisson = 0.{}\n",
                p.join(", "),
                n.join(", "),
                pick(0, 9),
                pick(0, 9)
            );
        }
        if let Ok(scene) = Scene::parse(&text, "generated")
            && !scene.contacts.is_empty()
        {
            scenes.push(scene);
        }
    }
    scenes
}
