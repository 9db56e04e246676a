//! What the lean path and the batch cost per scene, beside the generic solve, on two classes
//! of seeded free bodies hit at two contacts, Newton and Poisson each:
//!
//! * **Example-3-class** ([`example_3_class`]): the paper's Example 3 with its first
//!   coefficient and its velocity's y varied — well conditioned, every scene on the lean route;
//! * **random boxes** ([`random_boxes`]): boxes of random size and mass, random points inside,
//!   random normals and velocities, cond G ≤ 100 — many too nearly dependent for the lean route.
//!
//! Per class, ns per scene:
//!
//! * **generic**: [`crate::impact::solve::Impact`] reassembled and solved for both models,
//!   every output (frames, contact velocities, energies), one scene after another;
//! * **lean**: [`crate::impact::lean::Lean`] built and solved for both models, impulses and
//!   twist only, one scene after another, on the scenes the lean route accepts;
//! * **batch, accepted**: [`crate::impact::batch::solve_both`] over those same scenes;
//! * **lean or generic**: every scene one by one, `Lean` where its route accepts the scene and
//!   `Impact` (impulses and twist read from its outcome) where not — what a caller without the
//!   batch writes;
//! * **batch**: [`crate::impact::batch::solve_both`] over every scene, which does the same.

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

/// One class of scenes, ns per scene (both models).
#[derive(Clone, Debug, PartialEq)]
pub struct ClassBench {
    /// The class's name.
    pub class: &'static str,
    /// Scenes in the class.
    pub scenes: usize,
    /// Of which the lean route accepted.
    pub lean_routed: usize,
    /// Generic, every output, every scene.
    pub generic_ns: f64,
    /// Lean, impulses and twist, one accepted scene at a time.
    pub lean_ns: f64,
    /// The batch over the accepted scenes only: the same scenes as `lean_ns`.
    pub batch_accepted_ns: f64,
    /// Every scene one by one, lean where accepted, generic where not.
    pub fallback_ns: f64,
    /// The batch over every scene (the refused by the generic route, once per model).
    pub batch_ns: f64,
}

/// The measured costs (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct LeanBench {
    /// f64 lanes the batch used on this machine ([`batch::width`]).
    pub lanes: usize,
    /// Example-3-class, then random boxes.
    pub classes: Vec<ClassBench>,
}

/// A uniform draw in [lo, hi).
fn uniform(rng: &mut Seeded, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * (rng.next() >> 11) as f64 / (1u64 << 53) as f64
}

/// `count` Example-3-class scenes (module docs): Example 3 (m = 1, J = (12, 1.6, 12),
/// contacts at y = −2 and 4 with normal x) with k₁ = 0.0 … 0.9 and v_y = 0 … 6 in turn.
pub fn example_3_class(count: usize) -> Vec<Problem<f64>> {
    (0..count)
        .filter_map(|i| {
            let body = RigidBody::principal(1.0, Vec3::new(12.0, 1.6, 12.0));
            let velocity = Screw::new(
                Vec3::new(0.0, 0.0, 0.4),
                Vec3::new(3.0, (i % 7) as f64, 0.0),
            );
            let x = Vec3::new(1.0, 0.0, 0.0);
            let contacts = vec![
                Contact::new(Vec3::new(0.0, -2.0, 0.0), x, (i % 10) as f64 / 10.0),
                Contact::new(Vec3::new(0.0, 4.0, 0.0), x, 0.2),
            ];
            Problem::new(body, velocity, contacts).ok()
        })
        .collect()
}

/// A unit vector of uniformly random direction (rejection from the cube).
fn direction(rng: &mut Seeded) -> Vec3<f64> {
    loop {
        let v = Vec3::new(
            uniform(rng, -1.0, 1.0),
            uniform(rng, -1.0, 1.0),
            uniform(rng, -1.0, 1.0),
        );
        let n = v.norm();
        if n > 0.1 && n <= 1.0 {
            return v / n;
        }
    }
}

/// cond₂ G of a free body in principal axes hit at two contacts: g_ij = n_i·n_j/m +
/// (r_i × n_i)·J⁻¹(r_j × n_j) (eq. 12), its eigenvalues from trace and determinant.
fn cond_g(body: &RigidBody<f64>, contacts: &[Contact<f64>]) -> f64 {
    let crate::mechanics::body::Inertia::Principal(j) = &body.inertia else {
        return f64::INFINITY;
    };
    let mu: Vec<Vec3<f64>> = contacts.iter().map(|c| c.point.cross(&c.normal)).collect();
    let g = |a: usize, b: usize| {
        contacts[a].normal.dot(&contacts[b].normal) / body.mass
            + (0..3).map(|k| mu[a][k] * mu[b][k] / j[k]).sum::<f64>()
    };
    let (t, det) = (g(0, 0) + g(1, 1), g(0, 0) * g(1, 1) - g(0, 1) * g(0, 1));
    let root = (t * t - 4.0 * det).max(0.0).sqrt();
    (t + root) / (t - root)
}

/// `count` random boxes (module docs), seeded: half-edges in [0.05, 1], m in [0.5, 5],
/// J = m/3 (b² + c², a² + c², a² + b²), two points uniform inside, unit normals of uniform
/// direction, ω and v_C uniform in [−3, 3]³, k^N and k^P uniform in [0, 1]; scenes with
/// cond G > 100 are drawn again. Everything is written in the box's principal frame, so its
/// pose in the world is a rotation of the points, normals and velocity, which are uniform
/// already.
pub fn random_boxes(count: usize, seed: u64) -> Vec<Problem<f64>> {
    let mut rng = Seeded(seed);
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let half: [f64; 3] = std::array::from_fn(|_| uniform(&mut rng, 0.05, 1.0));
        let mass = uniform(&mut rng, 0.5, 5.0);
        let [a, b, c] = half.map(|h| h * h);
        let body = RigidBody::principal(mass, Vec3::new(b + c, a + c, a + b) * (mass / 3.0));
        let mut v3 = |lo: f64, hi: f64| {
            Vec3::new(
                uniform(&mut rng, lo, hi),
                uniform(&mut rng, lo, hi),
                uniform(&mut rng, lo, hi),
            )
        };
        let velocity = Screw::new(v3(-3.0, 3.0), v3(-3.0, 3.0));
        let contacts: Vec<Contact<f64>> = (0..2)
            .map(|_| {
                let p = Vec3::from_fn(|k, _| uniform(&mut rng, -half[k], half[k]));
                let n = direction(&mut rng);
                let (kn, kp) = (uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0));
                Contact::new(p, n, kn).with_coefficients(kn, kp)
            })
            .collect();
        if cond_g(&body, &contacts) <= 100.0
            && let Ok(p) = Problem::new(body, velocity, contacts)
        {
            out.push(p);
        }
    }
    out
}

/// The scenes of `problems` as structure of arrays.
fn gather<'p>(problems: impl Iterator<Item = &'p Problem<f64>>) -> Scenes<2> {
    let mut scenes = Scenes::<2>::default();
    for p in problems {
        // Every problem here is a free body in principal axes with two contacts.
        let _ = scenes.push(p);
    }
    scenes
}

/// Time one class (module docs).
fn class(name: &'static str, problems: &[Problem<f64>], budget: Duration) -> ClassBench {
    let lean: Vec<&Problem<f64>> = problems
        .iter()
        .filter(|p| Lean::<f64, 2>::new(p).is_ok())
        .collect();
    let scenes = gather(problems.iter());
    let accepted = gather(lean.iter().copied());
    let per = |ns: f64, n: usize| ns / n.max(1) as f64;
    let nothing = ClassBench {
        class: name,
        scenes: problems.len(),
        lean_routed: lean.len(),
        generic_ns: f64::NAN,
        lean_ns: f64::NAN,
        batch_accepted_ns: f64::NAN,
        fallback_ns: f64::NAN,
        batch_ns: f64::NAN,
    };
    // Both classes are drawn nonsingular: the first scene assembles.
    let Some(Ok(mut impact)) = problems.first().map(Impact::assemble) else {
        return nothing;
    };
    let (mut a, mut b) = (Outcome::default(), Outcome::default());
    let generic = time_three(budget, || -> Result<(), ()> {
        for p in problems {
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
    let fallback = time_three(budget, || -> Result<(), ()> {
        for p in problems {
            match Lean::<f64, 2>::new(black_box(p)) {
                Ok(l) => {
                    black_box(l.solve(Model::Newton).map_err(|_| ())?);
                    black_box(l.solve(Model::Poisson).map_err(|_| ())?);
                }
                Err(_) => {
                    impact.reassemble(p).map_err(|_| ())?;
                    for (model, o) in [(Model::Newton, &mut a), (Model::Poisson, &mut b)] {
                        let _ = impact.solve(model, o);
                        black_box((&o.impulses_hat, &o.velocity));
                    }
                }
            }
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
    ClassBench {
        class: name,
        scenes: problems.len(),
        lean_routed: lean.len(),
        generic_ns: per(generic, problems.len()),
        lean_ns: per(single, lean.len()),
        batch_accepted_ns: per(batched_accepted, lean.len()),
        fallback_ns: per(fallback, problems.len()),
        batch_ns: per(batched, problems.len()),
    }
}

/// Run it: 256 scenes per class (64 with `quick`).
pub fn run(quick: bool) -> LeanBench {
    let budget = Duration::from_millis(if quick { 20 } else { 200 });
    let count = if quick { 64 } else { 256 };
    LeanBench {
        lanes: batch::width(),
        classes: vec![
            class("Example-3-class", &example_3_class(count), budget),
            class(
                "random boxes, cond G ≤ 100",
                &random_boxes(count, 0x1ea2_ba7c),
                budget,
            ),
        ],
    }
}

impl LeanBench {
    /// The readable table.
    pub fn to_text(&self) -> String {
        let mut s = format!(
            "\nLean path and batch (seeded free bodies with two contacts, Newton + Poisson; the batch in {} f64 lanes):\n\n| scenes | lean route | generic, every output | lean, one by one | batch, same scenes | lean ÷ batch | lean or generic, one by one | batch, every scene | ÷ |\n|---|---|---|---|---|---|---|---|---|\n",
            self.lanes
        );
        for c in &self.classes {
            s += &format!(
                "| {} ({}) | {} | {:.1} ns | {:.1} ns | {:.1} ns | {:.2}× | {:.1} ns | {:.1} ns | {:.2}× |\n",
                c.class,
                c.scenes,
                c.lean_routed,
                c.generic_ns,
                c.lean_ns,
                c.batch_accepted_ns,
                c.lean_ns / c.batch_accepted_ns,
                c.fallback_ns,
                c.batch_ns,
                c.fallback_ns / c.batch_ns,
            );
        }
        s
    }

    /// The JSON report.
    pub fn to_json(&self) -> Json {
        let num = |x: f64| {
            serde_json::Number::from_f64(x)
                .map(Json::Number)
                .unwrap_or(Json::Null)
        };
        let classes: Vec<Json> = self
            .classes
            .iter()
            .map(|c| {
                json!({
                    "class": c.class,
                    "scenes": c.scenes,
                    "lean_routed": c.lean_routed,
                    "ns_per_scene_generic": num(c.generic_ns),
                    "ns_per_scene_lean": num(c.lean_ns),
                    "ns_per_scene_batch_accepted": num(c.batch_accepted_ns),
                    "ns_per_scene_lean_or_generic": num(c.fallback_ns),
                    "ns_per_scene_batch": num(c.batch_ns),
                })
            })
            .collect();
        json!({ "lanes": self.lanes, "classes": classes })
    }
}
