//! What the lean path and the batch cost per scene, beside the generic solve: seeded random
//! free bodies hit at two contacts, Newton and Poisson each.
//!
//! * **generic**: [`crate::impact::solve::Impact`] reassembled and solved for both models,
//!   every output (frames, contact velocities, energies), one scene after another;
//! * **lean**: [`crate::impact::lean::Lean`] built and solved for both models, impulses and
//!   twist only, one scene after another;
//! * **batch**: [`crate::impact::batch::solve_both`] over all the scenes at once (structure of
//!   arrays, f64 lanes), the same outputs as lean.
//!
//! Scenes the lean route refuses (too nearly dependent contacts) are counted; the batch
//! solves those by the generic route, lean-one-by-one skips them.

use std::hint::black_box;
use std::time::Duration;

use serde_json::{Value as Json, json};

use crate::impact::batch::{self, Outcomes, Scenes};
use crate::impact::lean::Lean;
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::mechanics::body::RigidBody;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Vec3};
use crate::tools::bench::{Seeded, time_three};

/// The measured costs, ns per scene (both models).
#[derive(Clone, Debug, PartialEq)]
pub struct LeanBench {
    /// Scenes in the batch.
    pub scenes: usize,
    /// Of which the lean route accepted.
    pub lean_routed: usize,
    /// Generic, every output.
    pub generic_ns: f64,
    /// Lean, impulses and twist, one scene at a time.
    pub lean_ns: f64,
    /// The batch, impulses and twist (every scene; those the lean route refuses by the generic
    /// route, twice: once per model).
    pub batch_ns: f64,
    /// The batch over the scenes the lean route accepts only: the same scenes as `lean_ns`.
    pub batch_accepted_ns: f64,
}

/// A uniform draw in [lo, hi).
fn uniform(rng: &mut Seeded, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * (rng.next() >> 11) as f64 / (1u64 << 53) as f64
}

/// A random free body hit at two contacts (normals with n_z = 1, so never zero).
fn scene(rng: &mut Seeded) -> Option<Problem<f64>> {
    let mut v3 = |lo: f64, hi: f64| {
        Vec3::new(
            uniform(rng, lo, hi),
            uniform(rng, lo, hi),
            uniform(rng, lo, hi),
        )
    };
    let body = RigidBody::principal(v3(0.5, 5.0)[0], v3(0.5, 5.0));
    let velocity = Screw::new(v3(-3.0, 3.0), v3(-3.0, 3.0));
    let contacts = (0..2)
        .map(|_| {
            let (p, mut n, k) = (v3(-2.0, 2.0), v3(-1.0, 1.0), v3(0.0, 1.0));
            n[2] = 1.0;
            Contact::new(p, n, k[0]).with_coefficients(k[0], k[1])
        })
        .collect();
    Problem::new(body, velocity, contacts).ok()
}

/// Run it: 256 scenes (64 with `quick`).
pub fn run(quick: bool) -> LeanBench {
    let budget = Duration::from_millis(if quick { 20 } else { 200 });
    let mut rng = Seeded(0x1ea2_ba7c);
    let count = if quick { 64 } else { 256 };
    let problems: Vec<Problem<f64>> = std::iter::from_fn(|| Some(scene(&mut rng)))
        .flatten()
        .take(count)
        .collect();
    let lean: Vec<&Problem<f64>> = problems
        .iter()
        .filter(|p| Lean::<f64, 2>::new(p).is_ok())
        .collect();
    let gather = |ps: &mut dyn Iterator<Item = &Problem<f64>>| {
        let mut scenes = Scenes::<2>::default();
        for p in ps {
            scenes
                .push(p)
                .expect("free bodies in principal axes, two contacts");
        }
        scenes
    };
    let scenes = gather(&mut problems.iter());
    let accepted = gather(&mut lean.iter().copied());
    let per = |ns: f64, n: usize| ns / n.max(1) as f64;
    let (mut impact, mut a, mut b) = (
        Impact::assemble(&problems[0]).expect("a valid problem assembles"),
        Outcome::default(),
        Outcome::default(),
    );
    let generic = time_three(budget, || -> Result<(), ()> {
        for p in &problems {
            impact.reassemble(black_box(p)).map_err(|_| ())?;
            // A singular G (never seen here) is skipped, not timed apart.
            let _ = impact.solve(Model::Newton, &mut a);
            let _ = impact.solve(Model::Poisson, &mut b);
        }
        Ok(())
    })
    .unwrap_or(f64::NAN);
    let single = time_three(budget, || -> Result<(), ()> {
        for p in &lean {
            let l = Lean::<f64, 2>::new(black_box(p)).map_err(|_| ())?;
            black_box(l.solve(Model::Newton).map_err(|_| ())?);
            black_box(l.solve(Model::Poisson).map_err(|_| ())?);
        }
        Ok(())
    })
    .unwrap_or(f64::NAN);
    let (mut n, mut q) = (Outcomes::default(), Outcomes::default());
    let batched = time_three(budget, || {
        batch::solve_both(black_box(&scenes), &mut n, &mut q)
    })
    .unwrap_or(f64::NAN);
    let batched_accepted = time_three(budget, || {
        batch::solve_both(black_box(&accepted), &mut n, &mut q)
    })
    .unwrap_or(f64::NAN);
    LeanBench {
        scenes: problems.len(),
        lean_routed: lean.len(),
        generic_ns: per(generic, problems.len()),
        lean_ns: per(single, lean.len()),
        batch_ns: per(batched, problems.len()),
        batch_accepted_ns: per(batched_accepted, lean.len()),
    }
}

impl LeanBench {
    /// The readable table.
    pub fn to_text(&self) -> String {
        let row = |name: &str, ns: f64| {
            format!("| {name} | {ns:.0} ns | {:.2}× |\n", ns / self.generic_ns)
        };
        format!(
            "\nLean path and batch ({} seeded free bodies with two contacts, Newton + Poisson; {} take the lean route, the batch solves the rest by the generic one):\n\n| path | time per scene | ÷ generic |\n|---|---|---|\n{}{}{}{}",
            self.scenes,
            self.lean_routed,
            row("generic f64, every output", self.generic_ns),
            row(
                "lean f64, impulses + twist, one scene at a time",
                self.lean_ns
            ),
            row(
                "batch f64 (impact::batch), impulses + twist, every scene",
                self.batch_ns
            ),
            row(
                "batch f64, the scenes the lean route accepts",
                self.batch_accepted_ns
            ),
        )
    }

    /// The JSON report.
    pub fn to_json(&self) -> Json {
        let num = |x: f64| {
            serde_json::Number::from_f64(x)
                .map(Json::Number)
                .unwrap_or(Json::Null)
        };
        json!({
            "scenes": self.scenes,
            "lean_routed": self.lean_routed,
            "ns_per_scene_generic": num(self.generic_ns),
            "ns_per_scene_lean": num(self.lean_ns),
            "ns_per_scene_batch": num(self.batch_ns),
            "ns_per_scene_batch_accepted": num(self.batch_accepted_ns),
        })
    }
}
