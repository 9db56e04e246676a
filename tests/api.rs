//! The public API: `Problem::new` refuses every input without physical meaning with the field
//! and the reason; `solve` speaks the paper's units for any normal length, exactly in
//! rationals; the lower-level `Impact` cannot be handed a problem other than its own.

mod common;

use common::*;
use inertance::impact::solve::{Impact, Outcome};
use inertance::scalar::{int, ratio};
use inertance::{
    Contact, Exact, Field, InvalidProblem, Joint, Model, Problem, Reason, RigidBody, Scalar, Screw,
    Solution, Vec3, solve,
};
use proptest::prelude::*;

fn v(x: f64, y: f64, z: f64) -> Vec3<f64> {
    Vec3::new(x, y, z)
}

/// Example 3 in f64, the starting point every refusal below changes one value of.
fn parts() -> (RigidBody<f64>, Screw<f64>, Vec<Contact<f64>>) {
    let body = RigidBody::principal(1.0, v(12.0, 1.6, 12.0));
    let twist = Screw::new(v(0.0, 0.0, 0.4), v(3.0, 2.0, 0.0));
    let contacts = vec![
        Contact::new(v(0.0, -2.0, 0.0), v(1.0, 0.0, 0.0), 0.3),
        Contact::new(v(0.0, 4.0, 0.0), v(1.0, 0.0, 0.0), 0.2),
    ];
    (body, twist, contacts)
}

/// The error for Example 3 with one change.
fn refusal(
    change: impl FnOnce(&mut RigidBody<f64>, &mut Screw<f64>, &mut Vec<Contact<f64>>),
) -> InvalidProblem {
    let (mut body, mut twist, mut contacts) = parts();
    change(&mut body, &mut twist, &mut contacts);
    Problem::new(body, twist, contacts).expect_err("the change makes the problem invalid")
}

/// Set the principal moment J_k of Example 3's body.
fn moment(body: &mut RigidBody<f64>, k: usize, x: f64) {
    let mut j = Vec3::new(12.0, 1.6, 12.0);
    j[k] = x;
    body.inertia = j.into();
}

fn is(e: InvalidProblem, field: Field, reason: Reason) {
    assert_eq!((e.field, e.reason), (field, reason));
}

#[test]
fn example_3_as_given_is_valid() {
    let (body, twist, contacts) = parts();
    assert!(Problem::new(body, twist, contacts).is_ok());
}

#[test]
fn body_values_without_physical_meaning_are_refused() {
    is(
        refusal(|b, _, _| b.mass = 0.0),
        Field::Mass,
        Reason::NotPositive,
    );
    is(
        refusal(|b, _, _| b.mass = -2.0),
        Field::Mass,
        Reason::NotPositive,
    );
    is(
        refusal(|b, _, _| b.mass = f64::NAN),
        Field::Mass,
        Reason::NotFinite,
    );
    is(
        refusal(|b, _, _| b.mass = f64::INFINITY),
        Field::Mass,
        Reason::NotFinite,
    );
    is(
        refusal(|b, _, _| moment(b, 1, -1.6)),
        Field::Inertia(1),
        Reason::NotPositive,
    );
    is(
        refusal(|b, _, _| moment(b, 2, 0.0)),
        Field::Inertia(2),
        Reason::NotPositive,
    );
    is(
        refusal(|b, _, _| moment(b, 0, f64::NAN)),
        Field::Inertia(0),
        Reason::NotFinite,
    );
    is(
        refusal(|_, t, _| t.0[2] = f64::NAN),
        Field::AngularVelocity(2),
        Reason::NotFinite,
    );
    is(
        refusal(|_, t, _| t.0[4] = f64::NEG_INFINITY),
        Field::Velocity(1),
        Reason::NotFinite,
    );
}

#[test]
fn contact_values_without_physical_meaning_are_refused() {
    is(
        refusal(|_, _, c| c.clear()),
        Field::Contacts,
        Reason::NoContacts,
    );
    is(
        refusal(|_, _, c| c[1].normal = v(0.0, 0.0, 0.0)),
        Field::Normal(1),
        Reason::ZeroVector,
    );
    is(
        refusal(|_, _, c| c[0].normal[1] = f64::NAN),
        Field::Normal(0),
        Reason::NotFinite,
    );
    is(
        refusal(|_, _, c| c[1].point[2] = f64::INFINITY),
        Field::Point(1),
        Reason::NotFinite,
    );
    is(
        refusal(|_, _, c| c[0].k_newton = 3.0),
        Field::KNewton(0),
        Reason::OutsideUnitInterval,
    );
    is(
        refusal(|_, _, c| c[1].k_poisson = -2.0),
        Field::KPoisson(1),
        Reason::OutsideUnitInterval,
    );
    is(
        refusal(|_, _, c| c[1].k_newton = f64::NAN),
        Field::KNewton(1),
        Reason::NotFinite,
    );
    is(
        refusal(|_, _, c| c[0].tangent = Some(v(0.0, 0.0, 0.0))),
        Field::Tangent(0),
        Reason::ZeroVector,
    );
    is(
        refusal(|_, _, c| c[1].tangent = Some(v(1.0, 1.0, 0.0))),
        Field::Tangent(1),
        Reason::NotPerpendicular { dot: 1.0 },
    );
    // The bounds themselves are allowed: k = 0 (plastic) and k = 1 (elastic).
    let (body, twist, mut contacts) = parts();
    contacts[0] = contacts[0].clone().with_coefficients(0.0, 1.0);
    assert!(Problem::new(body, twist, contacts).is_ok());
}

#[test]
fn messages_name_the_key_as_in_scene_files() {
    let e = refusal(|_, _, c| c[1].k_poisson = -2.0);
    assert_eq!(
        e.to_string(),
        "contact[1].k_poisson must lie in [0, 1] (0: plastic, 1: elastic)"
    );
    let e = refusal(|b, _, _| moment(b, 1, -1.0));
    assert_eq!(e.to_string(), "body.inertia[1] must be positive");
}

#[test]
fn inconsistent_constraints_are_refused() {
    let (body, twist, contacts) = parts();
    let p = Problem::new(body, twist, contacts).unwrap();
    // A hinge about z through C: v_C⁰ = (3, 2, 0) is not a rotation about it.
    let hinge = Joint::Revolute {
        point: v(0.0, 0.0, 0.0),
        axis: v(0.0, 0.0, 1.0),
    };
    let e = p.clone().with_joints(&[hinge]).unwrap_err();
    assert_eq!(e.field, Field::Constraints);
    assert!(matches!(e.reason, Reason::Constraint(_)), "{e}");
    // No free screw at all: the body cannot move.
    let e = p.with_constraints(Vec::new(), None).unwrap_err();
    assert_eq!(e.field, Field::Constraints);
}

/// Example 3 exactly, with contact 1's normal of length `s` (s·x).
fn example_3_scaled(s: i64) -> Problem<Exact> {
    let q = ratio::<Exact>;
    let e = |x, y, z| Vec3::new(q(x, 1), q(y, 1), q(z, 1));
    let body = RigidBody::principal(q(1, 1), Vec3::new(q(12, 1), q(8, 5), q(12, 1)));
    let twist = Screw::new(e(0, 0, 0), e(3, 2, 0));
    let twist = Screw::new(Vec3::new(q(0, 1), q(0, 1), q(2, 5)), twist.bottom());
    let contacts = vec![
        Contact::new(e(0, -2, 0), e(s, 0, 0), q(3, 10)),
        Contact::new(e(0, 4, 0), e(s, 0, 0), q(1, 5)),
    ];
    valid(body, twist, contacts)
}

#[test]
fn a_normal_of_length_two_gives_the_impulse_in_newton_seconds() {
    // The paper's values (Example 3, §7): P₁ = 329/90 N s, P₂ = 89/450 N s, Δ = 3 kg⁻².
    for s in [1, 2, 7] {
        let newton = solve(&example_3_scaled(s), Model::Newton).unwrap();
        assert_eq!(
            newton.impulses[0].value(),
            Some(ratio(329, 90)),
            "|n| = {s}"
        );
        assert_eq!(
            newton.impulses[1].value(),
            Some(ratio(89, 450)),
            "|n| = {s}"
        );
        assert_eq!(newton.det, ratio(3, 1), "|n| = {s}");
        assert_eq!(newton.inertances[1].value(), Some(ratio(1, 3)));
        assert_eq!(
            newton.contact_velocities[0][0].value(),
            Some(ratio(-57, 50))
        );
    }
    // The f64 path agrees (one rounding per operation on small numbers).
    let float = Problem::new(parts().0, parts().1, {
        let mut c = parts().2;
        c[0].normal = v(2.0, 0.0, 0.0);
        c
    })
    .unwrap();
    let newton = solve(&float, Model::Newton).unwrap();
    assert!((newton.impulses[0].value().unwrap() - 329.0 / 90.0).abs() < 1e-14);
    assert!((newton.det - 3.0).abs() < 1e-14);
}

/// Every output of a solution as exact text (canonical q·√r), for comparing two solutions.
fn texts(s: &Solution<Exact>) -> Vec<String> {
    let mut out = vec![s.det.exact_text().unwrap()];
    let surd = |x: &inertance::Surd<Exact>| x.exact_text().unwrap();
    out.extend(s.impulses.iter().map(surd));
    out.extend(s.compression_impulses.iter().map(surd));
    out.extend(s.inertances.iter().map(surd));
    for v in s
        .contact_velocities
        .iter()
        .chain(&s.contact_velocities_before)
    {
        out.push(surd(&v[0]));
    }
    out.extend(s.twist.0.iter().map(|x| x.exact_text().unwrap()));
    out.push(s.lost_velocity_energy.exact_text().unwrap());
    out.push(s.kinetic_energy_loss.exact_text().unwrap());
    out
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Scaling a normal by s > 0 changes nothing physical: impulses, normal velocities, G and
    /// Δ are equal exactly (as canonical q·√r), for normals of irrational length.
    #[test]
    fn physical_units_do_not_depend_on_the_normal_length(p in problem(3), s in positive(9, 4)) {
        let Ok(original) = solve(&p, Model::Poisson) else { return Ok(()) };
        let scaled = map_contacts(p, |c| c.normal *= s.clone());
        let scaled = solve(&scaled, Model::Poisson).expect("scaling keeps G regular");
        prop_assert_eq!(texts(&original), texts(&scaled));
    }

    /// The impulses satisfy the law in physical units: Newton's v_ix = −k_i v_ix⁰ (eq. 14),
    /// and the momentum balance m (v_C − v_C⁰) = −Σ P_i n_i/|n_i| (eq. 10), checked in f64
    /// from the exact solution's values.
    #[test]
    fn the_solution_satisfies_newtons_law_and_the_momentum_balance(p in problem(3)) {
        let Ok(s) = solve(&p, Model::Newton) else { return Ok(()) };
        for (i, c) in p.contacts().iter().enumerate() {
            let (after, before) = (&s.contact_velocities[i][0], &s.contact_velocities_before[i][0]);
            // Same radicand √|n_i|² on both sides: compare the rational coefficients.
            prop_assert_eq!(after.coeff.clone(), -c.k_newton.clone() * &before.coeff);
        }
        let dv = s.twist.bottom() - p.velocity().bottom();
        for k in 0..3 {
            let mut balance = p.body().mass.to_f64() * dv[k].to_f64();
            for (pi, c) in s.impulses.iter().zip(p.contacts()) {
                let n = c.normal.map(|x| x.to_f64());
                balance += pi.to_f64() * n[k] / n.norm();
            }
            let scale = s.impulses.iter().map(|x| x.to_f64().abs()).sum::<f64>() + 1.0;
            prop_assert!(balance.abs() <= 1e-12 * scale, "component {}: {}", k, balance);
        }
    }

    /// An impact reassembled for another problem answers exactly as a fresh one: the buffer
    /// reuse carries nothing over, whatever the sizes.
    #[test]
    fn reassembling_equals_a_fresh_assembly(a in problem(4), b in problem(4)) {
        let Ok(mut reused) = Impact::assemble(&a) else { return Ok(()) };
        let _ = reused.solution(Model::Newton);
        reused.reassemble(&b).unwrap();
        let fresh = Impact::assemble(&b).unwrap();
        prop_assert_eq!(reused.g_hat(), fresh.g_hat());
        prop_assert_eq!(reused.det_hat(), fresh.det_hat());
        let (mut x, mut y) = (Outcome::default(), Outcome::default());
        let (rx, ry) = (reused.solve(Model::Poisson, &mut x), fresh.clone().solve(Model::Poisson, &mut y));
        prop_assert_eq!(rx, ry);
        prop_assert_eq!(x, y);
    }
}

#[test]
fn a_singular_problem_is_an_error_not_a_number() {
    // Two identical contacts: G = [[g, g], [g, g]], Δ = 0.
    let c = Contact::new(v(0.0, 1.0, 0.0), v(1.0, 0.0, 0.0), 0.5);
    let p = Problem::new(parts().0, parts().1, vec![c.clone(), c]).unwrap();
    let e = solve(&p, Model::Newton).unwrap_err();
    assert_eq!(
        e,
        inertance::SolveError::Singular {
            rank: 1,
            contacts: 2,
            rounded: true
        }
    );
}

#[test]
fn a_constrained_problem_reports_its_constraint_impulses() {
    // Example 5's shape: a bar hinged about z through (0, −1, 0), struck at two points.
    let q = ratio::<Exact>;
    let zero = || q(0, 1);
    let body = RigidBody::principal(q(1, 1), Vec3::new(q(1, 3), q(1, 12), q(1, 3)));
    let hinge = Joint::Revolute {
        point: Vec3::new(zero(), q(-1, 1), zero()),
        axis: Vec3::new(zero(), zero(), q(1, 1)),
    };
    let twist = hinge.free_screws().remove(0);
    let contacts = vec![Contact::new(
        Vec3::new(zero(), q(1, 2), zero()),
        Vec3::new(int(1), zero(), zero()),
        q(1, 2),
    )];
    let p = valid(body, twist, contacts).with_joints(&[hinge]).unwrap();
    let s = solve(&p, Model::Newton).unwrap();
    // A hinge holds five constraint screws (6 − 1 free), each with its multiplier.
    assert_eq!(s.constraint_impulses.len(), 5);
    // The twist after impact stays a rotation about the hinge: ω_z alone, v_C = ω × (C − O).
    let (w, vc) = (s.twist.top(), s.twist.bottom());
    assert_eq!((w[0].clone(), w[1].clone()), (zero(), zero()));
    assert_eq!(vc[0], -w[2].clone());
}

#[test]
fn the_unilateral_law_is_one_call_too() {
    // Example 3 pitching at ω_z = 0.7: the simultaneous P₂ = −119/225 pulls; the unilateral law
    // lets A₂ separate: P₁ = (1 + k₁) v_1x⁰ / g₁₁ = 1.3·4.4·3/4 = 429/100, P₂ = 0.
    let q = ratio::<Exact>;
    let e = |x, y, z| Vec3::new(q(x, 1), q(y, 1), q(z, 1));
    let body = RigidBody::principal(q(1, 1), Vec3::new(q(12, 1), q(8, 5), q(12, 1)));
    let twist = Screw::new(Vec3::new(q(0, 1), q(0, 1), q(7, 10)), e(3, 2, 0));
    let contacts = vec![
        Contact::new(e(0, -2, 0), e(1, 0, 0), q(3, 10)),
        Contact::new(e(0, 4, 0), e(1, 0, 0), q(1, 5)),
    ];
    let p = valid(body, twist, contacts);
    let simultaneous = solve(&p, Model::Newton).unwrap();
    assert_eq!(simultaneous.impulses[1].value(), Some(q(-119, 225)));
    let unilateral = inertance::solve_unilateral(&p, Model::Newton).unwrap();
    assert_eq!(unilateral.impulses[0].value(), Some(q(429, 100)));
    assert_eq!(unilateral.impulses[1].value(), Some(q(0, 1)));
}
