//! The unchanged solver run over the symbolic scalar [`RatFun`]: it derives the paper's closed
//! forms, which are then proved **as identities** (exact equality of rational functions, by
//! cross-multiplication — never by evaluation at points), and the derived formulas are
//! checked against the exact rational solver at random points.

use std::collections::HashMap;
use std::sync::OnceLock;
use std::time::Instant;

use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::constraint::Constrained;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::symbolic::{Assumption, AssumptionKind, RatFun, take_assumptions};
use inertance::scalar::{Exact, Scalar};
use num_bigint::BigInt;
use num_traits::Zero;
use proptest::prelude::*;

/// A validated problem (fixtures are valid by construction).
fn valid<T: Scalar>(
    body: inertance::mechanics::body::RigidBody<T>,
    velocity: inertance::mechanics::screw::Screw<T>,
    contacts: Vec<inertance::mechanics::contact::Contact<T>>,
) -> inertance::Problem<T> {
    inertance::Problem::new(body, velocity, contacts).expect("a valid problem")
}

fn s(name: &str) -> RatFun {
    RatFun::symbol(name)
}

fn n(k: i64) -> RatFun {
    RatFun::from_integer(k)
}

fn v3<T: Scalar>(x: T, y: T, z: T) -> Vec3<T> {
    Vec3::new(x, y, z)
}

/// A contact at `point` with normal +x and tangent +y (R_i = I), coefficient `k` in both
/// models.
fn contact<T: Scalar>(point: Vec3<T>, k: T) -> Contact<T> {
    Contact {
        point,
        normal: v3(T::one(), T::zero(), T::zero()),
        tangent: Some(v3(T::zero(), T::one(), T::zero())),
        k_newton: k.clone(),
        k_poisson: k.clone(),
        k_energetic: k,
        mu: T::zero(),
    }
}

/// The general two-contact free body: mass m, moments (Jx, Jy, Jz), twist before
/// [w1 w2 w3; v1 v2 v3], contacts at (x_i, y_i, z_i) with normals +x, tangents +y, and
/// coefficients k1, k2. `value` maps a symbol name to the scalar used for it, so the same
/// builder makes the symbolic problem and its exact instances.
fn general<T: Scalar>(value: &impl Fn(&str) -> T) -> Problem<T> {
    let p = |i: u32| {
        v3(
            value(&format!("x{i}")),
            value(&format!("y{i}")),
            value(&format!("z{i}")),
        )
    };
    valid(
        RigidBody::principal(value("m"), v3(value("Jx"), value("Jy"), value("Jz"))),
        Screw::new(
            v3(value("w1"), value("w2"), value("w3")),
            v3(value("v1"), value("v2"), value("v3")),
        ),
        vec![contact(p(1), value("k1")), contact(p(2), value("k2"))],
    )
}

/// The planar two-contact problem of eq. (16)–(20) with R_i = I: points (0, y_i, 0), twist
/// [0 0 w; vx vy 0].
fn planar<T: Scalar>(value: &impl Fn(&str) -> T) -> Problem<T> {
    let z = || T::zero();
    valid(
        RigidBody::principal(value("m"), v3(value("Jx"), value("Jy"), value("Jz"))),
        Screw::new(v3(z(), z(), value("w")), v3(value("vx"), value("vy"), z())),
        vec![
            contact(v3(z(), value("y1"), z()), value("k1")),
            contact(v3(z(), value("y2"), z()), value("k2")),
        ],
    )
}

/// Assemble once, solve both models: the unchanged solver.
fn solve<T: Scalar>(problem: &Problem<T>) -> (Impact<T>, Vec<(Model, Outcome<T>)>) {
    let mut impact = Impact::assemble(problem).expect("assembles");
    let outcomes = Model::ALL
        .iter()
        .map(|&model| {
            let mut out = Outcome::default();
            impact.solve(model, &mut out).expect("solves");
            (model, out)
        })
        .collect();
    (impact, outcomes)
}

/// The model-independent identities, proved for each model's outcome: eq. (34), Newton's
/// law (14) or Poisson's (21)–(23), E_p by eq. (31), and the twist by eq. (24).
fn check_identities(
    problem: &Problem<RatFun>,
    impact: &Impact<RatFun>,
    outcomes: &[(Model, Outcome<RatFun>)],
) {
    let g = |i: usize, j: usize| impact.g_hat()[i * 2 + j].clone();
    let k = |i: usize| problem.contacts()[i].k_newton.clone();
    for (model, out) in outcomes {
        // eq. 34: ΔE_c = −E_p + Σ P_i v_ix⁰.
        assert_eq!(
            out.kinetic_energy_loss,
            -out.lost_velocity_energy.clone() + impact.impulse_work(out),
            "{model}: eq. 34"
        );
        // eq. 31: E_p = ½(P1² g11 + 2 P1 P2 g12 + P2² g22).
        let (p1, p2) = (&out.impulses_hat[0], &out.impulses_hat[1]);
        let ep = (p1.clone() * p1 * g(0, 0) + n(2) * p1 * p2 * g(0, 1) + p2.clone() * p2 * g(1, 1))
            / n(2);
        assert_eq!(out.lost_velocity_energy, ep, "{model}: eq. 31");
        for i in 0..2 {
            // The contact velocity after impact, recomputed from the twist after impact.
            let after = impact.frames()[i].axes[0].reciprocal(&out.velocity);
            assert_eq!(
                after, out.after_hat[i][0],
                "{model}: eq. 13 vs eq. 24 at contact {i}"
            );
            let before = impact.before_hat()[i][0].clone();
            match model {
                // eq. 14: v_ix = −k_i v_ix⁰.
                Model::Newton => assert_eq!(after, -k(i) * &before, "Newton's law at {i}"),
                Model::Poisson => {
                    // eq. 21: the compression impulses stop the normal velocities …
                    let pc = &out.compression_hat;
                    let v = before.clone() - g(i, 0) * &pc[0] - g(i, 1) * &pc[1];
                    assert!(v.is_zero(), "eq. 21 at {i}");
                    // … and eq. 23: P_i = (1 + k_i) P_i^c.
                    assert_eq!(out.impulses_hat[i], (n(1) + k(i)) * &pc[i], "eq. 23 at {i}");
                }
            }
        }
    }
}

/// The general problem's derivation, shared by the tests (derived once per process).
struct Derived {
    problem: Problem<RatFun>,
    impact: Impact<RatFun>,
    outcomes: Vec<(Model, Outcome<RatFun>)>,
    assumptions: Vec<Assumption>,
    seconds: f64,
}

fn derived() -> &'static Derived {
    static DERIVED: OnceLock<Derived> = OnceLock::new();
    DERIVED.get_or_init(|| {
        take_assumptions();
        let start = Instant::now();
        let problem = general(&|name| s(name));
        let (impact, outcomes) = solve(&problem);
        let seconds = start.elapsed().as_secs_f64();
        let assumptions = take_assumptions();
        Derived {
            problem,
            impact,
            outcomes,
            assumptions,
            seconds,
        }
    })
}

/// g_11, g_12, g_22 of eq. (39) (R_1 = R_2 = I) and Δ = g_11 g_22 − g_12².
fn eq39() -> (RatFun, RatFun, RatFun, RatFun) {
    let (m, jy, jz) = (s("m"), s("Jy"), s("Jz"));
    let g = |ya: &str, za: &str, yb: &str, zb: &str| {
        n(1) / &m + s(za) * s(zb) / &jy + s(ya) * s(yb) / &jz
    };
    let (g11, g12, g22) = (
        g("y1", "z1", "y1", "z1"),
        g("y1", "z1", "y2", "z2"),
        g("y2", "z2", "y2", "z2"),
    );
    let delta = g11.clone() * &g22 - g12.clone() * &g12;
    (g11, g12, g22, delta)
}

#[test]
fn general_free_body_identities() {
    let d = derived();
    eprintln!(
        "general two-contact free body: assembled and solved both models in {:.3} s",
        d.seconds
    );
    for a in &d.assumptions {
        eprintln!("  assumed: {a}");
    }
    let start = Instant::now();
    check_identities(&d.problem, &d.impact, &d.outcomes);
    eprintln!(
        "identities proved in {:.3} s",
        start.elapsed().as_secs_f64()
    );
}

/// The symbolic run assumed exactly what the LDLᵀ pivots need — the two pivots positive,
/// g_11 > 0 and Δ/g_11 > 0 (so Δ ≠ 0), and every denominator factor nonzero — and nothing
/// else; the conditions are themselves the paper's closed forms, as identities.
#[test]
fn assumptions_are_the_pivot_conditions() {
    let d = derived();
    let (g11, _, _, delta) = eq39();
    let of = |kind| -> Vec<&RatFun> {
        d.assumptions
            .iter()
            .filter(|a| a.kind == kind)
            .map(|a| &a.expr)
            .collect()
    };
    let positive = of(AssumptionKind::Positive);
    assert_eq!(positive.len(), 2);
    assert_eq!(*positive[0], g11);
    assert_eq!(*positive[1], delta.clone() / &g11);
    // Nonzero: the four symbols divided by, and the numerators of g_11 and Δ (each up to a
    // constant factor).
    let nonzero = of(AssumptionKind::NonZero);
    assert_eq!(nonzero.len(), 6);
    for name in ["Jx", "Jy", "Jz", "m"] {
        assert!(nonzero.iter().any(|e| **e == s(name)), "{name} ≠ 0");
    }
    let monomial = s("m") * s("Jy") * s("Jz");
    for target in [g11 * &monomial, delta * &monomial] {
        assert!(
            nonzero
                .iter()
                .any(|e| (target.clone() / *e).to_rational().is_some()),
            "{target} ≠ 0"
        );
    }
    // One division, one condition.
    take_assumptions();
    let _ = n(1) / (s("y1") - s("y2"));
    let log = take_assumptions();
    assert_eq!(log.len(), 1);
    assert_eq!(log[0].kind, AssumptionKind::NonZero);
    assert_eq!(log[0].to_string(), "y1 - y2 ≠ 0");
}

#[test]
fn general_free_body_closed_forms_eq_12_15_20_39() {
    let d = derived();
    let (y1, z1, y2, z2) = (s("y1"), s("z1"), s("y2"), s("z2"));
    let (k1, k2) = (s("k1"), s("k2"));
    // eq. 8 / 19: v_ix⁰ = u·(v_C + ω × r_i) = v1 + w2 z_i − w3 y_i.
    let vx0 = |y: &RatFun, z: &RatFun| s("v1") + s("w2") * z - s("w3") * y;
    assert_eq!(d.impact.before_hat()[0][0], vx0(&y1, &z1));
    assert_eq!(d.impact.before_hat()[1][0], vx0(&y2, &z2));
    // eq. 39 (R_1 = R_2 = I).
    let (g11, g12, g22, delta) = eq39();
    assert_eq!(d.impact.g_hat()[0], g11);
    assert_eq!(d.impact.g_hat()[1], g12);
    assert_eq!(d.impact.g_hat()[2], g12);
    assert_eq!(d.impact.g_hat()[3], g22);
    assert_eq!(d.impact.det_hat(), &delta);
    // eq. 20 (Cramer) for Newton, eq. 22–23 for Poisson.
    let (b1, b2) = (vx0(&y1, &z1), vx0(&y2, &z2));
    let cramer = |c1: &RatFun, c2: &RatFun| {
        (
            (c1.clone() * &g22 - g12.clone() * c2) / &delta,
            (g11.clone() * c2 - c1.clone() * &g12) / &delta,
        )
    };
    let (n1, n2) = cramer(&((n(1) + &k1) * &b1), &((n(1) + &k2) * &b2));
    let (c1, c2) = cramer(&b1, &b2);
    for (model, out) in &d.outcomes {
        let (p1, p2) = match model {
            Model::Newton => (n1.clone(), n2.clone()),
            Model::Poisson => ((n(1) + &k1) * &c1, (n(1) + &k2) * &c2),
        };
        assert_eq!(out.impulses_hat[0], p1, "{model}: P1");
        assert_eq!(out.impulses_hat[1], p2, "{model}: P2");
    }
    take_assumptions();
}

#[test]
fn planar_closed_forms_eq_17_18_20() {
    take_assumptions();
    let start = Instant::now();
    let problem = planar(&|name| s(name));
    let (impact, outcomes) = solve(&problem);
    check_identities(&problem, &impact, &outcomes);
    let (m, jz, y1, y2) = (s("m"), s("Jz"), s("y1"), s("y2"));
    let (w, vx, vy, k1, k2) = (s("w"), s("vx"), s("vy"), s("k1"), s("k2"));
    // eq. 16 with R = I: a_i1 = 1, b_i1 = 0, f_i1 = −y_i.
    let (f1, f2) = (-y1.clone(), -y2.clone());
    // eq. 17.
    let g11 = n(1) / &m + f1.clone() * &f1 / &jz;
    let g12 = n(1) / &m + f1.clone() * &f2 / &jz;
    let g22 = n(1) / &m + f2.clone() * &f2 / &jz;
    assert_eq!(impact.g_hat()[0], g11);
    assert_eq!(impact.g_hat()[0], n(1) / &m + y1.clone() * &y1 / &jz);
    assert_eq!(impact.g_hat()[1], n(1) / &m + y1.clone() * &y2 / &jz);
    assert_eq!(impact.g_hat()[3], g22);
    // Δ = (y1 − y2)²/(m Jz): the collision is degenerate exactly when y1 = y2.
    let dy = y1.clone() - &y2;
    assert_eq!(*impact.det_hat(), dy.clone() * &dy / (m.clone() * &jz));
    // eq. 19: v_ix⁰ = a_i1 vx + b_i1 vy + f_i1 ω.
    let b1 = vx.clone() + f1.clone() * &w;
    let b2 = vx.clone() + f2.clone() * &w;
    assert_eq!(impact.before_hat()[0][0], b1);
    assert_eq!(impact.before_hat()[1][0], b2);
    // eq. 20.
    let delta = g11.clone() * &g22 - g12.clone() * &g12;
    let (c1, c2) = ((n(1) + &k1) * &b1, (n(1) + &k2) * &b2);
    let p1 = (c1.clone() * &g22 - g12.clone() * &c2) / &delta;
    let p2 = (g11.clone() * &c2 - c1.clone() * &g12) / &delta;
    let newton = &outcomes[0].1;
    assert_eq!(newton.impulses_hat[0], p1);
    assert_eq!(newton.impulses_hat[1], p2);
    // eq. 18, corrected: the paper prints f_11/m in ω; the angular change is over J_z.
    for (model, out) in &outcomes {
        let (p1, p2) = (&out.impulses_hat[0], &out.impulses_hat[1]);
        let v = out.velocity.as_slice();
        assert_eq!(
            v[2],
            w.clone() - (p1.clone() * &f1 + p2.clone() * &f2) / &jz,
            "{model}: ω"
        );
        assert_eq!(v[3], vx.clone() - (p1.clone() + p2) / &m, "{model}: v_x");
        assert_eq!(v[4], vy, "{model}: v_y (b_i1 = 0)");
        assert!(
            v[0].is_zero() && v[1].is_zero() && v[5].is_zero(),
            "{model}: stays planar"
        );
        // The printed forms (f_11/m in ω, f_i1/m in v_x) are not identities.
        assert_ne!(
            v[2],
            w.clone() - p1.clone() * &f1 / &m - p2.clone() * &f2 / &jz
        );
        assert_ne!(
            v[3],
            vx.clone() - p1.clone() * &f1 / &m - p2.clone() * &f2 / &m
        );
    }
    eprintln!(
        "planar: derived and proved in {:.3} s",
        start.elapsed().as_secs_f64()
    );
    eprintln!("planar Newton P1 = {}", newton.impulses_hat[0]);
    take_assumptions();
}

/// Example 1 (a sphere hit at two points, the second at the angle θ): the solver runs over
/// the angle pair (cos θ, sin θ) with sin²θ = 1 − cos²θ and finds the paper's closed forms
/// P1 = m(1 + k)ω0R, P2 = 0, v_C = −kω0R i, ω unchanged, in both models.
#[test]
fn sphere_at_two_points_with_a_symbolic_angle() {
    take_assumptions();
    let start = Instant::now();
    let (m, r, w0, k) = (s("m"), s("R"), s("omega0"), s("k"));
    let (c, sn) = RatFun::angle("theta");
    let j = n(2) * &m * &r * &r / n(5);
    let contact = |point: Vec3<RatFun>, normal: Vec3<RatFun>, tangent: Vec3<RatFun>| Contact {
        point,
        normal,
        tangent: Some(tangent),
        k_newton: k.clone(),
        k_poisson: k.clone(),
        k_energetic: k.clone(),
        mu: RatFun::zero(),
    };
    let problem = valid(
        RigidBody::principal(m.clone(), v3(j.clone(), j.clone(), j)),
        Screw::new(v3(n(0), n(0), w0.clone()), v3(w0.clone() * &r, n(0), n(0))),
        vec![
            contact(
                v3(r.clone(), n(0), n(0)),
                v3(n(1), n(0), n(0)),
                v3(n(0), n(1), n(0)),
            ),
            contact(
                v3(r.clone() * &c, r.clone() * &sn, n(0)),
                v3(c.clone(), sn.clone(), n(0)),
                v3(-sn.clone(), c.clone(), n(0)),
            ),
        ],
    );
    let (impact, outcomes) = solve(&problem);
    let w0r = w0.clone() * &r;
    for (model, out) in &outcomes {
        assert_eq!(
            out.impulses_hat[0],
            m.clone() * (n(1) + &k) * &w0r,
            "{model}: P1"
        );
        assert!(out.impulses_hat[1].is_zero(), "{model}: P2");
        assert_eq!(out.velocity.bottom(), v3(-(w0r.clone() * &k), n(0), n(0)));
        assert_eq!(out.velocity.top(), problem.velocity().top());
        assert_eq!(
            out.kinetic_energy_loss,
            -out.lost_velocity_energy.clone() + impact.impulse_work(out)
        );
    }
    // Δ = sin²θ/m²: degenerate exactly when sin θ = 0 (both normals through C on one line).
    assert_eq!(*impact.det_hat(), sn.clone() * &sn / (m.clone() * &m));
    let log: Vec<String> = take_assumptions().iter().map(ToString::to_string).collect();
    eprintln!("sphere: Δ = {}", impact.det_hat());
    eprintln!("sphere: assumed {log:?}");
    eprintln!(
        "sphere: derived and proved in {:.3} s",
        start.elapsed().as_secs_f64()
    );
}

#[test]
fn one_dof_constrained_body_energy_identity() {
    take_assumptions();
    let start = Instant::now();
    let (a, b) = (s("a"), s("b"));
    let body = RigidBody::principal(s("m"), v3(s("Jx"), s("Jy"), s("Jz")));
    // A revolute joint about the axis through (a, b, 0) along z: D = [k; p × k].
    let point = v3(a.clone(), b.clone(), n(0));
    let axis = v3(n(0), n(0), n(1));
    let free = Screw::new(axis.clone(), point.cross(&axis));
    let w = s("w");
    let velocity = Screw(free.0.clone() * w.clone());
    let constrained = Constrained::new(&body, vec![free], None).expect("valid constraint");
    let problem = valid(
        body,
        velocity,
        vec![contact(v3(s("x1"), s("y1"), s("z1")), s("k1"))],
    )
    .with_constrained(constrained.clone())
    .expect("an allowed twist");
    let mut impact = Impact::assemble(&problem).expect("assembles");
    for model in Model::ALL {
        let mut out = Outcome::default();
        impact.solve(model, &mut out).expect("solves");
        assert_eq!(
            out.kinetic_energy_loss,
            -out.lost_velocity_energy.clone() + impact.impulse_work(&out),
            "{model}: eq. 34 / 97 for the constrained body"
        );
        // The velocity after impact is still a rotation about the joint axis, and the
        // normal velocity obeys the law.
        let after = impact.frames()[0].axes[0].reciprocal(&out.velocity);
        let before = impact.before_hat()[0][0].clone();
        let omega = out.velocity.as_slice()[2].clone();
        assert_eq!(out.velocity, Screw(constrained.free[0].0.clone() * omega));
        if model == Model::Newton {
            assert_eq!(after, -s("k1") * &before);
        }
    }
    // eq. 83, 86: M_red = Dᵀ η M D = Jz + m (a² + b²) and Dᵀ η {E_1x} = b − y1 (the moment
    // arm of the normal about the joint axis), so g_11 = (y1 − b)² / (Jz + m (a² + b²)).
    let dy = s("y1") - &b;
    let g = dy.clone() * &dy / (s("Jz") + s("m") * (a.clone() * &a + b.clone() * &b));
    assert_eq!(impact.g_hat()[0], g);
    eprintln!(
        "1-dof constrained body: derived and proved in {:.3} s",
        start.elapsed().as_secs_f64()
    );
    take_assumptions();
}

/// A body free to move along one fully general screw D = [d1 d2 d3; d4 d5 d6] (η-orthogonal
/// complement U derived by the library), hit at a general point: the energy identity and
/// the closed forms M_red = Σ J_k d_k² + m Σ d_{k+3}² (eq. 83), g = (Dᵀ η E)² / M_red (eq. 86)
/// and P = (1 + k) v⁰ / g, as identities.
#[test]
fn general_one_dof_constrained_body() {
    take_assumptions();
    let start = Instant::now();
    let d: Vec<RatFun> = (1..=6).map(|i| s(&format!("d{i}"))).collect();
    let body = RigidBody::principal(s("m"), v3(s("Jx"), s("Jy"), s("Jz")));
    let free = Screw::new(
        v3(d[0].clone(), d[1].clone(), d[2].clone()),
        v3(d[3].clone(), d[4].clone(), d[5].clone()),
    );
    let w = s("w");
    let problem = valid(
        body.clone(),
        Screw(free.0.clone() * w.clone()),
        vec![contact(v3(s("x1"), s("y1"), s("z1")), s("k1"))],
    );
    let constrained = Constrained::new(&body, vec![free], None).expect("valid constraint");
    let problem = problem
        .with_constrained(constrained.clone())
        .expect("an allowed twist");
    let built = start.elapsed().as_secs_f64();
    let mut impact = Impact::assemble(&problem).expect("assembles");
    let m_red = s("Jx") * &d[0] * &d[0]
        + s("Jy") * &d[1] * &d[1]
        + s("Jz") * &d[2] * &d[2]
        + s("m") * (d[3].clone() * &d[3] + d[4].clone() * &d[4] + d[5].clone() * &d[5]);
    assert_eq!(constrained.reduced_mass(), vec![m_red.clone()]);
    let arm = d[3].clone() + d[1].clone() * s("z1") - d[2].clone() * s("y1");
    assert_eq!(impact.g_hat()[0], arm.clone() * &arm / &m_red);
    for model in Model::ALL {
        let mut out = Outcome::default();
        impact.solve(model, &mut out).expect("solves");
        assert_eq!(
            out.kinetic_energy_loss,
            -out.lost_velocity_energy.clone() + impact.impulse_work(&out),
            "{model}: eq. 34 / 97"
        );
        assert_eq!(
            out.impulses_hat[0],
            (n(1) + s("k1")) * &w * &m_red / &arm,
            "{model}: P"
        );
    }
    eprintln!(
        "general 1-dof body: constraint built in {built:.3} s, derived and proved in {:.3} s",
        start.elapsed().as_secs_f64()
    );
    take_assumptions();
}

/// The names of the general problem's symbols.
const SYMBOLS: [&str; 18] = [
    "m", "Jx", "Jy", "Jz", "w1", "w2", "w3", "v1", "v2", "v3", "x1", "y1", "z1", "x2", "y2", "z2",
    "k1", "k2",
];

fn q(n: i64, d: i64) -> Exact {
    Exact::new(BigInt::from(n), BigInt::from(d))
}

fn point_strategy() -> impl Strategy<Value = HashMap<String, Exact>> {
    let positive = || (1i64..=12, 1i64..=4).prop_map(|(a, b)| q(a, b));
    let any = || (-9i64..=9, 1i64..=4).prop_map(|(a, b)| q(a, b));
    let k = || (0i64..=8).prop_map(|a| q(a, 8));
    (
        (positive(), positive(), positive(), positive()),
        proptest::collection::vec(any(), 12),
        (k(), k()),
    )
        .prop_map(|((m, jx, jy, jz), free, (k1, k2))| {
            let mut values = HashMap::new();
            for (name, v) in SYMBOLS[..4].iter().zip([m, jx, jy, jz]) {
                values.insert((*name).to_owned(), v);
            }
            for (name, v) in SYMBOLS[4..16].iter().zip(free) {
                values.insert((*name).to_owned(), v);
            }
            values.insert("k1".to_owned(), k1);
            values.insert("k2".to_owned(), k2);
            values
        })
        // Off the degenerate locus Δ = 0 (both contacts on one line parallel to x).
        .prop_filter("Δ ≠ 0", |v| v["y1"] != v["y2"] || v["z1"] != v["z2"])
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// The derived impulses, velocities and energies, evaluated at random rational points,
    /// equal the exact rational solver's results there.
    #[test]
    fn derived_formulas_match_the_exact_solver(values in point_strategy()) {
        let d = derived();
        let exact = general(&|name| values.get(name).cloned().unwrap_or_else(Exact::zero));
        let (_, outcomes) = solve(&exact);
        // RatFun evaluates at BigRational points; the solver's values compare through them.
        let at: HashMap<String, num_rational::BigRational> =
            values.iter().map(|(k, v)| (k.clone(), v.to_big_rational())).collect();
        for ((model, sym), (_, ex)) in d.outcomes.iter().zip(&outcomes) {
            for i in 0..2 {
                prop_assert_eq!(sym.impulses_hat[i].eval(&at), Some(ex.impulses_hat[i].to_big_rational()), "{} P{}", model, i + 1);
            }
            for k in 0..6 {
                prop_assert_eq!(sym.velocity.as_slice()[k].eval(&at), Some(ex.velocity.as_slice()[k].to_big_rational()));
            }
            prop_assert_eq!(sym.lost_velocity_energy.eval(&at), Some(ex.lost_velocity_energy.to_big_rational()));
            prop_assert_eq!(sym.kinetic_energy_loss.eval(&at), Some(ex.kinetic_energy_loss.to_big_rational()));
        }
        prop_assert_eq!(d.impact.det_hat().eval(&at), Some(solve(&exact).0.det_hat().to_big_rational()));
    }
}
