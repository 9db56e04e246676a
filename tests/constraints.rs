//! Constrained bodies (§9–11), exact property tests: D = I is the free body; the momentum
//! balance M({v} − {v⁰}) = −Σ P_i {E_ix} + U q holds exactly; Dᵀ η U = 0 for every joint
//! shorthand; the energy identity (eq. 97) holds.

mod common;

use common::*;
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome, SolveError};
use inertance::mechanics::body::Mobility;
use inertance::mechanics::constraint::{Constrained, Joint};
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, int};
use num_traits::{One, Zero};
use proptest::prelude::*;

/// A body with 1–2 joints (kept when their free screws are independent), an allowed twist
/// v⁰ = D ξ⁰, and 1–3 contacts.
fn constrained_problem() -> impl Strategy<Value = (Problem<Exact>, Vec<Screw<Exact>>)> {
    (
        problem(3),
        prop::collection::vec(joint(), 1..=2),
        prop::collection::vec(rational(4, 3), 6),
    )
        .prop_map(|(p, joints, xi)| {
            let free: Vec<Screw<Exact>> = joints.iter().flat_map(Joint::free_screws).collect();
            let mut v0 = Screw::zero();
            for (s, x) in free.iter().zip(&xi) {
                v0.add_scaled(x, s);
            }
            let (body, _, contacts) = p.into_parts();
            (valid(body, v0, contacts), free)
        })
}

/// A constrained solve: the constraints, the assembled impact, both models' outcomes.
type Solved = (Constrained<Exact>, Impact<Exact>, Vec<Outcome<Exact>>);

/// Solve both models with the constrained mobility; `None` when the joints are dependent or
/// G is singular (more contacts than the body can answer independently).
fn solve(p: &Problem<Exact>, free: Vec<Screw<Exact>>) -> Option<Solved> {
    let c = Constrained::new(p.body(), free, None).ok()?;
    let held = p
        .clone()
        .with_constrained(c.clone())
        .expect("v⁰ = D ξ⁰ by construction");
    let mut impact = Impact::assemble(&held).unwrap();
    let mut outs = Vec::new();
    for m in Model::ALL {
        let mut out = Outcome::default();
        match impact.solve(m, &mut out) {
            Err(SolveError::Singular { .. }) => return None,
            other => other.unwrap(),
        }
        let mut dv = out.velocity.clone();
        dv.add_scaled(&-Exact::one(), p.velocity());
        c.impulses_into(
            &dv,
            out.impulses_hat
                .iter()
                .zip(impact.frames().iter().map(|f| &f.axes[0])),
            &mut out.constraint_impulses,
        );
        outs.push(out);
    }
    Some((c, impact, outs))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// Every direction free (D = I): exactly the free-body result, and no constraint impulse.
    #[test]
    fn all_directions_free_is_the_free_body(p in problem(3)) {
        let free: Vec<Screw<Exact>> = (0..6).map(|k| {
            let mut s = Screw::zero();
            s.0[k] = Exact::one();
            s
        }).collect();
        let mut free_impact = Impact::assemble(&p).unwrap();
        let Some((c, impact, outs)) = solve(&p, free) else { return Ok(()) };
        prop_assert!(c.blocked.is_empty());
        prop_assert_eq!(impact.g_hat(), free_impact.g_hat());
        for (m, out) in Model::ALL.iter().zip(&outs) {
            let mut free_out = Outcome::default();
            free_impact.solve(*m, &mut free_out).unwrap();
            prop_assert_eq!(&out.impulses_hat, &free_out.impulses_hat);
            prop_assert_eq!(&out.velocity, &free_out.velocity);
            prop_assert!(out.constraint_impulses.is_empty());
        }
    }

    /// eq. 76: M({v} − {v⁰}) = −Σ P_i {E_ix} + U q, exactly, with q from the solver; and the
    /// velocity after impact is allowed by the constraints.
    #[test]
    fn momentum_balance_with_constraint_impulses((p, free) in constrained_problem()) {
        let Some((c, impact, outs)) = solve(&p, free) else { return Ok(()) };
        for out in &outs {
            let mut dv = out.velocity.clone();
            dv.add_scaled(&-Exact::one(), p.velocity());
            let lhs = p.body().momentum(&dv);
            let mut rhs = Screw::zero();
            for (pi, f) in out.impulses_hat.iter().zip(impact.frames()) {
                rhs.add_scaled(&-pi.clone(), &f.axes[0]);
            }
            for (qa, ua) in out.constraint_impulses.iter().zip(&c.blocked) {
                rhs.add_scaled(qa, ua);
            }
            prop_assert_eq!(lhs, rhs);
            prop_assert!(c.check_allowed(&out.velocity).is_ok());
        }
    }

    /// The orthogonalised-wrench route (floats' route for constrained bodies; the metric ηW
    /// is only semidefinite here) gives the normal equations' outcome exactly, constraint
    /// impulses included.
    #[test]
    fn orthogonalised_wrenches_give_the_constrained_outcome((p, free) in constrained_problem()) {
        let Some((_, mut impact, outs)) = solve(&p, free) else { return Ok(()) };
        for (m, expected) in Model::ALL.iter().zip(&outs) {
            let mut out = Outcome::default();
            impact.solve_orthogonal(*m, &mut out).expect("G is regular");
            prop_assert_eq!(&out, expected);
        }
    }

    /// eq. 82 for every joint shorthand: Dᵀ η U = 0, and dim D + dim U = 6.
    #[test]
    fn joints_give_reciprocal_screws(b in body(), joints in prop::collection::vec(joint(), 1..=3)) {
        let free: Vec<Screw<Exact>> = joints.iter().flat_map(Joint::free_screws).collect();
        let Ok(c) = Constrained::new(&b, free, None) else { return Ok(()) };
        prop_assert_eq!(c.free.len() + c.blocked.len(), 6);
        for d in &c.free {
            for u in &c.blocked {
                prop_assert!(d.reciprocal(u).is_zero());
            }
        }
    }

    /// eq. 97 (with E_p from the velocity change and ΔE_c from the kinetic energies), and
    /// Newton's law at every contact, for constrained bodies.
    #[test]
    fn constrained_energy_identity_and_newton_law((p, free) in constrained_problem()) {
        let Some((_, impact, outs)) = solve(&p, free) else { return Ok(()) };
        for out in &outs {
            prop_assert_eq!(out.kinetic_energy_loss.clone(), impact.impulse_work(out) - &out.lost_velocity_energy);
        }
        for (i, c) in p.contacts().iter().enumerate() {
            let after = impact.frames()[i].axes[0].reciprocal(&outs[0].velocity);
            prop_assert_eq!(after, -(c.k_newton.clone() * &impact.before_hat()[i][0]));
        }
    }

    /// The constrained response is W = D M_red⁻¹ Dᵀ η: symmetric in the inertance sense,
    /// {a}ᵀ η W {b} = {b}ᵀ η W {a}, and W{E} lies in the span of D.
    #[test]
    fn constrained_mobility_is_symmetric((p, free) in constrained_problem(), a in vec3(3, 2), n in direction()) {
        let Ok(c) = Constrained::new(p.body(), free, None) else { return Ok(()) };
        let e1 = Screw::axis(&a, &n);
        let e2 = Screw::axis(&n, &Vec3::new(int(1), int(-1), int(2)));
        prop_assert_eq!(e1.reciprocal(&c.response(&e2)), e2.reciprocal(&c.response(&e1)));
        prop_assert!(c.check_allowed(&c.response(&e1)).is_ok());
    }
}

/// Example 5 (§11): the bar OA turning about OZ at O = (0, −l, 0), hit at A1 = (0, −a, 0) and
/// A2 = (0, b, 0) along +x, turning with ω = 1: the constraint and the assembled impact.
fn example_5(
    m: &Exact,
    jz: &Exact,
    l: &Exact,
    a: &Exact,
    b: &Exact,
) -> (Constrained<Exact>, Impact<Exact>) {
    use inertance::mechanics::body::RigidBody;
    use inertance::mechanics::contact::Contact;
    let zero = Exact::zero;
    let x = Vec3::new(Exact::one(), zero(), zero());
    let body = RigidBody::principal(m.clone(), Vec3::new(jz.clone(), jz.clone(), jz.clone()));
    let joint = Joint::Revolute {
        point: Vec3::new(zero(), -l.clone(), zero()),
        axis: Vec3::new(zero(), zero(), Exact::one()),
    };
    let c = Constrained::new(&body, joint.free_screws(), None).unwrap();
    let contact = |y: Exact| Contact {
        point: Vec3::new(zero(), y, zero()),
        normal: x.clone(),
        tangent: None,
        k_newton: zero(),
        k_poisson: zero(),
        k_energetic: zero(),
        mu: zero(),
    };
    // The admissible twist: ω = 1 about OZ at O, {v⁰} = D = [0 0 1 −l 0 0].
    let p = valid(
        body,
        c.free[0].clone(),
        vec![contact(-a.clone()), contact(b.clone())],
    )
    .with_constrained(c.clone())
    .unwrap();
    let impact = Impact::assemble(&p).unwrap();
    (c, impact)
}

/// rank [G | rhs] for a 2×2 G.
fn augmented_rank(g: &[Exact], rhs: [Exact; 2]) -> usize {
    let a = vec![
        g[0].clone(),
        g[1].clone(),
        rhs[0].clone(),
        g[2].clone(),
        g[3].clone(),
        rhs[1].clone(),
    ];
    inertance::linalg::null_space(&a, 2, 3).0
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// Example 5: one degree of freedom and two contacts, so Δ = 0 for every a, b, l
    /// (rank G = 1), with g_11 = (l − a)²/J_O, g_12 = (l − a)(l + b)/J_O, g_22 = (l + b)²/J_O,
    /// J_O = J_z + m l² (the paper prints g_12 with (l − b) for (l − a): ERRATA.md).
    ///
    /// Compatibility (Rouché–Capelli, eq. 98–101), two ways:
    /// * with the twist the constraint allows ({v⁰} = ω D, v_C⁰ = −lω i): v_ix⁰ = ω E_i·D
    ///   is proportional to G's column, so the system is compatible iff k1 = k2;
    /// * with the paper's input (v_C⁰ = 0, ω⁰ = ω k, which the constraint does not allow):
    ///   v_1x⁰ = aω, v_2x⁰ = −bω, and compatibility is exactly eq. (101),
    ///   (1 + k1) a (l + b) = −(1 + k2) b (l − a).
    #[test]
    fn example_5_singular_and_compatibility(
        m in positive(20, 3), jz in positive(20, 3), l in positive(9, 2), a in positive(9, 4), b in positive(9, 4),
        k1 in coefficient(), k2 in coefficient(),
    ) {
        prop_assume!(a != l);
        let (c, impact) = example_5(&m, &jz, &l, &a, &b);
        let jo = jz.clone() + m.clone() * &l * &l;
        prop_assert!(impact.det_hat().is_zero());
        prop_assert_eq!(impact.rank(), 1);
        let (la, lb) = (l.clone() - &a, l.clone() + &b);
        prop_assert_eq!(&impact.g_hat(), &vec![la.clone() * &la / &jo, la.clone() * &lb / &jo, la.clone() * &lb / &jo, lb.clone() * &lb / &jo]);
        let one = Exact::one();

        // The admissible twist: compatible iff k1 = k2.
        let rhs = [(one.clone() + &k1) * &impact.before_hat()[0][0], (one.clone() + &k2) * &impact.before_hat()[1][0]];
        prop_assert_eq!(augmented_rank(impact.g_hat(), rhs) == 1, k1 == k2);

        // The paper's twist (v_C⁰ = 0): refused by the solver, and compatible iff eq. (101).
        let paper = Screw::new(Vec3::new(Exact::zero(), Exact::zero(), one.clone()), Vec3::zeros());
        prop_assert!(c.check_allowed(&paper).is_err());
        let v0 = [impact.frames()[0].axes[0].reciprocal(&paper), impact.frames()[1].axes[0].reciprocal(&paper)];
        prop_assert_eq!(&v0, &[a.clone(), -b.clone()]);
        let rhs = [(one.clone() + &k1) * &v0[0], (one.clone() + &k2) * &v0[1]];
        let eq101 = (one.clone() + &k1) * &a * &lb == -((one.clone() + &k2) * &b * &la);
        prop_assert_eq!(augmented_rank(impact.g_hat(), rhs) == 1, eq101);
    }
}

/// Eq. (102) at a = b = l/2: solving (101) gives k2 = −4 − 3 k1 (negative for every k1 ≥ 0,
/// so never compatible with k ∈ [0, 1]); the paper's printed k2 = 1/3 − k1 does not satisfy
/// (101), and neither does its printed general formula (102) (which gives −2/3 − k1).
#[test]
fn example_5_eq_102_at_a_equals_b_equals_half_l() {
    let q = |n: i64, d: i64| Exact::new(n.into(), d.into());
    let (l, one) = (q(1, 1), Exact::one());
    let (a, b) = (q(1, 2), q(1, 2));
    let eq101 = |k1: &Exact, k2: &Exact| {
        (one.clone() + k1) * &a * (l.clone() + &b) == -((one.clone() + k2) * &b * (l.clone() - &a))
    };
    for k1 in [q(0, 1), q(1, 10), q(1, 3), q(1, 1)] {
        assert!(eq101(&k1, &(q(-4, 1) - q(3, 1) * &k1)));
        assert!(!eq101(&k1, &(q(1, 3) - &k1)));
        let printed_102 = (b.clone() * &l
            - a.clone() * &b
            - (one.clone() + &k1) * (a.clone() * &b + a.clone() * &l))
            / (b.clone() * &l + a.clone() * &b);
        assert_eq!(printed_102, q(-2, 3) - &k1);
        assert!(!eq101(&k1, &printed_102));
    }
}

/// Remark 2: Example 6's bar (revolute joint at O about z + sliding along OX) gives exactly
/// the free body's impulses and velocities after impact, for every k1, k2 — the motion is
/// free along every direction the impulses act on — and its constraint impulses vanish.
#[test]
fn remark_2_example_6_equals_the_free_body() {
    use inertance::scene::Scene;
    use inertance::scene::pipeline::run;
    let base = "[body]\nmass = 10\ninertia = [\"10/3\", \"10/3\", \"10/3\"]\nvelocity = [0, 0, 0]\nangular_velocity = [0, 0, 1]\n\
        [[contact]]\npoint = [0, \"-1/3\", 0]\nnormal = [1, 0, 0]\ntangent = [0, 1, 0]\nk = K1\n\
        [[contact]]\npoint = [0, \"1/3\", 0]\nnormal = [1, 0, 0]\ntangent = [0, 1, 0]\nk = K2\n";
    let joints = "[[constraints.joint]]\nkind = \"revolute\"\npoint = [0, -1, 0]\naxis = [0, 0, 1]\n\
        [[constraints.joint]]\nkind = \"prismatic\"\naxis = [1, 0, 0]\n";
    for (k1, k2) in [("0", "0"), ("0", "0.5"), ("1", "0.5"), ("0.3", "0.7")] {
        let text = base.replace("K1", k1).replace("K2", k2);
        let free = run::<Exact>(&Scene::parse(&text, "free").unwrap(), None)
            .unwrap()
            .report;
        let held = run::<Exact>(
            &Scene::parse(&format!("{text}{joints}"), "held").unwrap(),
            None,
        )
        .unwrap()
        .report;
        for (f, h) in free.models.iter().zip(&held.models) {
            assert_eq!(f.impulses, h.impulses, "k = ({k1}, {k2})");
            assert_eq!(
                (&f.angular_velocity, &f.velocity),
                (&h.angular_velocity, &h.velocity)
            );
            assert_eq!(
                (&f.lost_velocity_energy, &f.kinetic_energy_loss),
                (&h.lost_velocity_energy, &h.kinetic_energy_loss)
            );
            assert!(
                h.constraint_impulses
                    .iter()
                    .all(|q| q.exact.as_deref() == Some("0"))
            );
        }
        assert_eq!(free.inertance, held.inertance);
    }
}
