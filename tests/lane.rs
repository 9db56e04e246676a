//! The small-N float lane of `Impact` (`impact::solve`'s `lane` module): a free body in
//! principal axes hit at 2 to 4 contacts, assembled and solved with N a constant.
//!
//! * Its formulas, run in exact rationals through `Impact::assemble_in_lane`, give every
//!   quantity of the general code exactly — frames, velocities before impact, responses,
//!   Ĝ and the tangential inertances, Δ̂, T⁰, and every output of both models.
//! * In f64 it is taken exactly where it should be (and nowhere else), and its outputs keep
//!   the accuracy contract against the exact solve of the same rounded problem (every
//!   output: `tests/accuracy_contract.rs` runs through it too, since it is the route floats
//!   take on such problems).
//! * Outputs asked for are bit for bit those of every output, through the lane as through
//!   the general code (`tests/outputs.rs` covers all 64 subsets; here, on lane problems).

mod common;

use common::*;
use inertance::analysis::accuracy::{Bounds, Conditioning};
use inertance::impact::outputs::Outputs;
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, Scalar};
use num_traits::Zero;
use proptest::prelude::*;

/// Both models' outcomes of `impact`.
fn outcomes<T: Scalar>(impact: &mut Impact<T>) -> Option<[Outcome<T>; 2]> {
    let mut outs = [Outcome::default(), Outcome::default()];
    impact.solve(Model::Newton, &mut outs[0]).ok()?;
    impact.solve(Model::Poisson, &mut outs[1]).ok()?;
    Some(outs)
}

/// The lane in exact rationals against the general code: every assembled quantity and
/// every output equal, exactly.
fn lane_is_the_general_code(p: &Problem<Exact>) {
    let mut general = Impact::assemble(p).expect("a valid problem assembles");
    assert_eq!(general.lane(), None, "exact types take the general code");
    let Some(mut lane) = Impact::assemble_in_lane(p) else {
        // Outside the lane: N outside 2..=4, or a singular G (then the general code says so).
        let n = p.contacts().len();
        assert!(
            !(2..=4).contains(&n) || general.singular(),
            "lane refused N = {n}"
        );
        return;
    };
    assert_eq!(lane.lane(), Some(p.contacts().len()));
    assert_eq!(lane.frames(), general.frames());
    assert_eq!(lane.before_hat(), general.before_hat());
    assert_eq!(lane.responses(), general.responses());
    assert_eq!(lane.g_hat(), general.g_hat());
    assert_eq!(lane.g_yx_hat(), general.g_yx_hat());
    assert_eq!(lane.g_zx_hat(), general.g_zx_hat());
    assert_eq!(lane.det_hat(), general.det_hat());
    assert_eq!(lane.rank(), general.rank());
    assert_eq!(lane.kinetic_before(), general.kinetic_before());
    assert_eq!(outcomes(&mut lane), outcomes(&mut general));
}

/// A free body with two contacts at heights `y1`, `y2` with normal x (Example 3's shape).
fn two_contacts(y1: f64, y2: f64) -> Problem<f64> {
    let contact = |y: f64, k: f64| {
        Contact::new(Vec3::new(0.0, y, 0.0), Vec3::new(1.0, 0.0, 0.0), k)
            .with_tangent(Vec3::new(0.0, 1.0, 0.0))
    };
    Problem::new(
        RigidBody::principal(1.0, Vec3::new(12.0, 1.6, 12.0)),
        Screw::new(Vec3::new(0.0, 0.0, 0.4), Vec3::new(3.0, 2.0, 0.0)),
        vec![contact(y1, 0.3), contact(y2, 0.2)],
    )
    .expect("valid")
}

/// The f64 lane against the exact solve of the rounded problem: impulses and twist within
/// the contract's bounds (`analysis::accuracy::Bounds`), both models.
fn float_lane_within_contract(p: &Problem<Exact>) {
    let float = convert::<f64>(p);
    let mut impact = Impact::assemble(&float).expect("assembles");
    if impact.lane().is_none() {
        return; // outside the lane (N, or G ill conditioned): the general code's tests
    }
    let exact = exact_of(&float);
    let mut general = Impact::assemble(&exact).expect("assembles");
    let (Some(got), Some(want)) = (outcomes(&mut impact), outcomes(&mut general)) else {
        panic!("the lane solved a G the exact solve calls singular");
    };
    let cond = Conditioning::of(&mut general).expect("nonsingular");
    for (k, model) in Model::ALL.into_iter().enumerate() {
        let bounds = Bounds::of(&general, &cond, model, &want[k], f64::EPSILON);
        let mut diff2 = Exact::zero();
        for (i, c) in exact.contacts().iter().enumerate() {
            let n2: Exact = c.normal.iter().map(|x| x * x).sum();
            let d = Exact::from(got[k].impulses_hat[i].exact_value().unwrap())
                - &want[k].impulses_hat[i];
            diff2 += &d * &d * &n2;
        }
        let mut dv = Screw::<Exact>::zero();
        for j in 0..6 {
            dv.0[j] =
                Exact::from(got[k].velocity.0[j].exact_value().unwrap()) - &want[k].velocity.0[j];
        }
        let twist = (2.0 * exact.body().kinetic_energy(&dv).to_f64()).sqrt();
        let impulses = diff2.to_f64().sqrt();
        assert!(
            impulses <= bounds.impulses,
            "{model:?} impulses: {impulses:e} > {:e}",
            bounds.impulses
        );
        assert!(
            twist <= bounds.twist,
            "{model:?} twist: {twist:e} > {:e}",
            bounds.twist
        );
    }
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 160,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn exact_lane_is_the_general_code(p in problem(5)) {
        lane_is_the_general_code(&p);
    }

    #[test]
    fn f64_lane_keeps_the_contract(p in problem(4)) {
        float_lane_within_contract(&p);
    }

    /// Asking for fewer outputs changes no bit of those asked for, through the lane.
    #[test]
    fn outputs_asked_for_are_bit_for_bit_every_output(p in problem(4), bits in 0u32..64) {
        let float = convert::<f64>(&p);
        let asked = Outputs::subsets().nth(bits as usize).unwrap();
        let (Ok(mut all), Ok(mut some)) =
            (Impact::assemble(&float), Impact::assemble_for(&float, asked)) else {
            return Ok(());
        };
        prop_assert_eq!(all.lane(), some.lane());
        let (Some(a), Some(s)) = (outcomes(&mut all), outcomes(&mut some)) else {
            return Ok(());
        };
        for (a, s) in a.iter().zip(&s) {
            if asked.contains(Outputs::IMPULSES) {
                prop_assert_eq!(&a.impulses_hat, &s.impulses_hat);
                prop_assert_eq!(&a.compression_hat, &s.compression_hat);
            }
            if asked.contains(Outputs::TWIST) {
                prop_assert_eq!(&a.velocity, &s.velocity);
            }
            if asked.contains(Outputs::ENERGIES) {
                prop_assert_eq!(a.lost_velocity_energy.to_bits(), s.lost_velocity_energy.to_bits());
                prop_assert_eq!(a.kinetic_energy_loss.to_bits(), s.kinetic_energy_loss.to_bits());
            }
            if asked.contains(Outputs::NORMAL_VELOCITIES | Outputs::TANGENTIAL) {
                prop_assert_eq!(&a.after_hat, &s.after_hat);
            }
        }
    }
}

#[test]
fn example_3_takes_the_lane_in_floats() {
    let p = two_contacts(-2.0, 4.0);
    assert_eq!(Impact::assemble(&p).unwrap().lane(), Some(2));
    let dd = Impact::assemble(&convert::<inertance::scalar::dd::DoubleDouble>(&exact_of(
        &p,
    )));
    assert_eq!(dd.unwrap().lane(), Some(2));
    float_lane_within_contract(&exact_of(&p));
}

#[test]
fn nearly_coincident_contacts_take_the_general_code() {
    // cos of the angle between the two wrenches in the metric of W is near 1: the route test
    // sends G to the orthogonalised wrenches, which the lane does not do.
    let p = two_contacts(-2.0, -2.0 + 1e-6);
    let impact = Impact::assemble(&p).unwrap();
    assert_eq!(impact.lane(), None);
    assert_eq!(
        impact.route(),
        inertance::impact::route::Route::OrthogonalWrenches
    );
}

#[test]
fn outside_the_lane_the_general_code_builds() {
    // A full inertia tensor, a constrained body, one contact, five contacts.
    let base = two_contacts(-2.0, 4.0);
    let tensor = Problem::new(
        RigidBody::with_tensor(1.0, [[12.0, 1.0, 0.0], [1.0, 1.6, 0.0], [0.0, 0.0, 12.0]]),
        base.velocity().clone(),
        base.contacts().to_vec(),
    )
    .unwrap();
    assert_eq!(Impact::assemble(&tensor).unwrap().lane(), None);
    let one = Problem::new(
        base.body().clone(),
        base.velocity().clone(),
        base.contacts()[..1].to_vec(),
    )
    .unwrap();
    assert_eq!(Impact::assemble(&one).unwrap().lane(), None);
    let five: Vec<Contact<f64>> = (0..5)
        .map(|i| {
            let a = i as f64;
            Contact::new(
                Vec3::new(a - 2.0, 0.5 * a, 1.0),
                Vec3::new(0.1 * a, 0.2, 1.0),
                0.5,
            )
        })
        .collect();
    let five = Problem::new(base.body().clone(), base.velocity().clone(), five).unwrap();
    assert_eq!(Impact::assemble(&five).unwrap().lane(), None);
}
