//! The lean path of a system (`impact::lean_system`): the impulses and the twist after impact
//! of a system solved again and again, checked against the general solve.
//!
//! - Exactly: in rationals it gives the general solve's impulses and twist, equal, on the
//!   chains of `tools::chain`, the system examples and 60 seeded random systems (free systems
//!   and joint trees), under Newton and Poisson.
//! - In f64: on the same random systems, in the units float solves use, every impulse and
//!   twist within the accuracy contract's bounds for the general solve
//!   (`analysis::accuracy::Bounds`), which takes the same operations (module docs).
//! - Its refusals: a loop of joints, a system of another shape, nearly dependent contacts.

use inertance::Scalar;
use inertance::analysis::accuracy::{Bounds, Conditioning, Contracted};
use inertance::impact::lean_system::{LeanSystem, LeanSystemError};
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::constraint::Joint;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Screws, Vec3};
use inertance::mechanics::system::{Pair, System, SystemBody, SystemJoint, SystemScrew};
use inertance::scalar::Exact;
use inertance::scene::Scene;
use inertance::scene::scale::system::scale_system;
use inertance::tools::accuracy::{system_examples, system_scenes};
use inertance::tools::chain::Chain;
use num_traits::{One, Zero};

const MODELS: [Model; 2] = [Model::Newton, Model::Poisson];

/// Every scene the exact and accuracy checks run on, in solver units.
fn scenes() -> Vec<Scene> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut all = system_examples(&dir);
    all.extend(system_scenes(60, 24));
    all.iter()
        .map(|s| scale_system(s).map_or_else(|| s.clone(), |(s, _)| s))
        .collect()
}

/// Lean and general agree exactly on `system`; whether the lean path accepted it.
fn agree_exactly(name: &str, system: &System<Exact>) -> bool {
    let Ok(mut lean) = LeanSystem::new(system) else {
        return false;
    };
    let Ok(mut impact) = Impact::assemble(system) else {
        return false;
    };
    let mut accepted = false;
    for model in MODELS {
        let mut out = Outcome::default();
        let general = impact.solve(model, &mut out);
        match lean.solve(system, model) {
            Ok(()) => {
                assert!(general.is_ok(), "{name}: the general solve refused");
                assert_eq!(
                    lean.impulses_hat(),
                    &out.impulses_hat[..],
                    "{name} {model:?}"
                );
                assert_eq!(lean.velocity(), &out.velocity, "{name} {model:?}");
                accepted = true;
            }
            Err(LeanSystemError::Singular { .. }) => {
                // Exactly, only where G is singular: a pivot d_k = 0.
                let delta = impact.det_hat().clone();
                assert!(delta.is_zero(), "{name}: refused with Δ̂ = {delta}");
            }
            Err(e) => panic!("{name}: {e}"),
        }
    }
    accepted
}

#[test]
fn exactly_the_general_solves_impulses_and_twist() {
    for n in [1, 2, 3, 6] {
        let chain = Chain::<Exact>::new(n);
        assert!(agree_exactly(&format!("chain {n}"), &chain.system()));
    }
    let mut accepted = 0;
    let all = scenes();
    for scene in &all {
        let system = scene.system::<Exact>().expect("an exact system");
        accepted += usize::from(agree_exactly(&scene.name, &system));
    }
    assert!(accepted >= 50, "{accepted} of {} systems solved", all.len());
}

#[test]
fn in_f64_every_impulse_and_twist_meets_the_general_solves_bound() {
    let (mut solved, mut refused, mut worst) = (0, 0, 0.0f64);
    for scene in &scenes() {
        let exact = scene.system::<Exact>().expect("an exact system");
        let float = scene.system::<f64>().expect("an f64 system");
        let Ok(mut impact) = Impact::assemble(&exact) else {
            continue;
        };
        let Some(cond) = Conditioning::of(&mut impact) else {
            continue;
        };
        let mut lean = LeanSystem::new(&float).expect("trees and free systems");
        for model in MODELS {
            let mut out = Outcome::default();
            if impact.solve(model, &mut out).is_err() {
                continue;
            }
            if let Err(e) = lean.solve(&float, model) {
                // Refused only near a singular G: τ = 2⁻²⁰ on the squared sine of the angle
                // between wrenches asks cond G ≳ 10⁶ (module docs).
                assert!(
                    matches!(e, LeanSystemError::Singular { .. }) && cond.cond > 1e5,
                    "{}: {e} at cond G = {:e}",
                    scene.name,
                    cond.cond
                );
                refused += 1;
                continue;
            }
            let bounds = Bounds::of(&impact, &cond, model, &out, f64::epsilon_f64());
            // ‖δP‖₂ of the physical impulses P_i = P̂_i |n_i|.
            let mut diff2 = Exact::zero();
            for (i, c) in exact.contacts().iter().enumerate() {
                let p = Exact::from(lean.impulses_hat()[i].exact_value().expect("finite"));
                let d = p - &out.impulses_hat[i];
                let n2: Exact = c.normal.iter().map(|x| x * x).sum();
                diff2 += &d * &d * n2;
            }
            let impulses = diff2.to_f64().sqrt();
            // ‖δv‖_M.
            let mut dv = <System<Exact> as Contracted>::exact::<f64>(lean.velocity())
                .expect("a finite twist");
            dv.add_scaled(&-Exact::one(), &out.velocity);
            let twist = (2.0 * exact.kinetic_energy(&dv).to_f64()).sqrt();
            for (what, error, bound) in [
                ("impulses", impulses, bounds.impulses),
                ("twist", twist, bounds.twist),
            ] {
                assert!(
                    error <= bound,
                    "{} {model:?}: {what} error {error:e} > bound {bound:e}",
                    scene.name
                );
                if bound > 0.0 {
                    worst = worst.max(error / bound);
                }
            }
            solved += 1;
        }
    }
    println!(
        "largest error/bound of the lean path in f64: {worst:.3e} over {solved} solves \
         ({refused} refused near a singular G)"
    );
    assert!(solved >= 80, "{solved} solves measured");
}

/// Two bars hinged to the ground and to each other, and a third body hinged to both: a loop.
#[test]
fn a_loop_of_joints_is_refused() {
    let bar = |x: f64| SystemBody {
        body: RigidBody::principal(1.0, Vec3::new(0.1, 0.1, 0.1)),
        centre: Vec3::new(x, 0.0, 0.0),
    };
    let hinge = |x: f64, first: usize, second: Option<usize>| SystemJoint {
        joint: Joint::Revolute {
            point: Vec3::new(x, 0.0, 0.0),
            axis: Vec3::new(0.0, 0.0, 1.0),
        },
        pair: Pair { first, second },
    };
    let system = System::new(
        vec![bar(0.5), bar(1.5)],
        SystemScrew::zeros(2),
        vec![Contact::new(
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, -1.0, 0.0),
            0.5,
        )],
        vec![Pair {
            first: 1,
            second: None,
        }],
        vec![
            hinge(0.0, 0, None),
            hinge(1.0, 1, Some(0)),
            hinge(2.0, 1, None),
        ],
    )
    .expect("a valid system");
    assert_eq!(
        LeanSystem::new(&system).map(|_| ()),
        Err(LeanSystemError::NotTree)
    );
}

#[test]
fn a_system_of_another_shape_is_refused() {
    let (two, three) = (Chain::<f64>::new(2).system(), Chain::<f64>::new(3).system());
    let mut lean = LeanSystem::new(&two).expect("a chain");
    assert_eq!(
        lean.solve(&three, Model::Newton),
        Err(LeanSystemError::Shape { what: "bodies" })
    );
    lean.solve(&two, Model::Newton).expect("its own shape");
}

/// One free body struck at two points 10⁻⁹ m apart with the same normal: G is singular to
/// 10⁻¹⁸ relative, so the lean path leaves it to the general solve.
#[test]
fn nearly_dependent_contacts_are_refused() {
    let contact = |x: f64| Contact::new(Vec3::new(x, 0.0, -0.5), Vec3::new(0.0, 0.0, -1.0), 0.5);
    let system = System::new(
        vec![SystemBody {
            body: RigidBody::principal(1.0, Vec3::new(0.1, 0.2, 0.3)),
            centre: Vec3::zeros(),
        }],
        SystemScrew(vec![Screw::new(
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -1.0),
        )]),
        vec![contact(0.25), contact(0.25 + 1e-9)],
        vec![
            Pair {
                first: 0,
                second: None,
            };
            2
        ],
        Vec::new(),
    )
    .expect("a valid system");
    let mut lean = LeanSystem::new(&system).expect("a free body");
    assert!(matches!(
        lean.solve(&system, Model::Newton),
        Err(LeanSystemError::Singular { pivot: 1 })
    ));
}
