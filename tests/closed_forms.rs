//! The paper's closed forms, checked in exact rationals over many rational parameter values
//! (not at one point). Angles are rational points of the unit circle,
//! (cos θ, sin θ) = ((1 − t²)/(1 + t²), 2t/(1 + t²)).

mod common;

use common::*;
use inertance::impact::restitution::Model;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, int};
use num_traits::{One, Zero};
use proptest::prelude::*;

fn half() -> Exact {
    Exact::new(1.into(), 2.into())
}

fn zero() -> Exact {
    Exact::zero()
}

fn v3(x: Exact, y: Exact, z: Exact) -> Vec3<Exact> {
    Vec3::new(x, y, z)
}

fn contact(
    point: Vec3<Exact>,
    normal: Vec3<Exact>,
    tangent: Option<Vec3<Exact>>,
    k: Exact,
) -> Contact<Exact> {
    Contact {
        point,
        normal,
        tangent,
        k_newton: k.clone(),
        k_poisson: k.clone(),
        k_energetic: k,
        mu: Exact::zero(),
    }
}

/// (cos θ, sin θ) for the rational parameter t (θ = 2 atan t).
fn circle(t: &Exact) -> (Exact, Exact) {
    let d = Exact::one() + t.clone() * t;
    ((Exact::one() - t.clone() * t) / &d, (t.clone() + t) / d)
}

/// A nonzero rational t, so that θ ≠ 0 (θ = 0 puts both contacts on one axis: Δ = 0).
fn circle_parameter() -> impl Strategy<Value = Exact> {
    rational(12, 5).prop_filter("θ ≠ 0", |t| !t.is_zero())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// Example 1 (sphere at two points): P1 = m(1+k)ω0R, P2 = 0, {v_C} = −ω0Rk i, ω unchanged,
    /// v2y = ω0R(1 + k sin θ), E_p = ½mω0²R²(1+k)², ΔE_c = ½mω0²R²(1−k²), both models.
    #[test]
    fn sphere_at_two_points(m in positive(20, 3), r in positive(9, 4), w0 in rational(9, 2), k in coefficient(), t in circle_parameter()) {
        let (c, s) = circle(&t);
        let j = int::<Exact>(2) * &m * &r * &r / int::<Exact>(5);
        let p = valid(RigidBody::principal(m.clone(), v3(j.clone(), j.clone(), j)), Screw::new(v3(zero(), zero(), w0.clone()), v3(w0.clone() * &r, zero(), zero())), vec![
                contact(v3(r.clone(), zero(), zero()), v3(Exact::one(), zero(), zero()), Some(v3(zero(), Exact::one(), zero())), k.clone()),
                contact(v3(r.clone() * &c, r.clone() * &s, zero()), v3(c.clone(), s.clone(), zero()), Some(v3(-s.clone(), c.clone(), zero())), k.clone()),
            ]);
        let (_, outcomes) = solve_models(&p, &Model::ALL).unwrap();
        let w0r = w0.clone() * &r;
        for (_, o) in &outcomes {
            prop_assert_eq!(&o.impulses_hat[0], &(m.clone() * (Exact::one() + &k) * &w0r));
            prop_assert!(o.impulses_hat[1].is_zero());
            prop_assert_eq!(o.velocity.bottom(), v3(-(w0r.clone() * &k), zero(), zero()));
            prop_assert_eq!(o.velocity.top(), p.velocity().top());
            prop_assert_eq!(&o.after_hat[1][1], &(w0r.clone() * (Exact::one() + k.clone() * &s)));
            let e = half() * &m * &w0r * &w0r;
            prop_assert_eq!(&o.lost_velocity_energy, &(e.clone() * (Exact::one() + &k) * (Exact::one() + &k)));
            prop_assert_eq!(&o.kinetic_energy_loss, &(e * (Exact::one() - k.clone() * &k)));
        }
    }

    /// Example 8 (sphere in a corner, frames by §12): P1 = m v0 (1+k1), P2 = 2 m v0 (1+k2),
    /// {v_C} = (−k1 v0, −2k2 v0, 0), v1y = −2k2 v0, v2y = −k1 v0, v_iz = 0,
    /// E_p = ½ m v0² [(1+k1)² + 4(1+k2)²], ΔE_c = ½ m v0² [(1 − k1²) + 4(1 − k2²)].
    #[test]
    fn sphere_in_a_corner(m in positive(20, 3), r in positive(9, 4), v0 in positive(9, 2), k1 in coefficient(), k2 in coefficient()) {
        let j = int::<Exact>(2) * &m * &r * &r / int::<Exact>(5);
        let p = valid(RigidBody::principal(m.clone(), v3(j.clone(), j.clone(), j)), Screw::new(Vec3::zeros(), v3(v0.clone(), int::<Exact>(2) * &v0, zero())), vec![
                contact(v3(r.clone(), zero(), zero()), v3(int::<Exact>(2) * &r, zero(), zero()), None, k1.clone()),
                contact(v3(zero(), r.clone(), zero()), v3(zero(), int::<Exact>(2) * &r, zero()), None, k2.clone()),
            ]);
        let (impact, outcomes) = solve_models(&p, &[Model::Newton]).unwrap();
        let o = &outcomes[0].1;
        // Normals are ∇f = 2R e_i (not unit): P_i = P̂_i |∇f| = P̂_i · 2R.
        let two_r = int::<Exact>(2) * &r;
        let one = Exact::one();
        prop_assert_eq!(o.impulses_hat[0].clone() * &two_r, m.clone() * &v0 * (one.clone() + &k1));
        prop_assert_eq!(o.impulses_hat[1].clone() * &two_r, int::<Exact>(2) * &m * &v0 * (one.clone() + &k2));
        prop_assert_eq!(o.velocity.bottom(), v3(-(k1.clone() * &v0), -(int::<Exact>(2) * &k2 * &v0), zero()));
        // Tangential components in the unit frames (ŷ_1 = ẑ_1 × n̂_1 has norm |ẑ||n|).
        let unit = |i: usize, a: usize| o.after_hat[i][a].clone() / impact.frames()[i].norm2[a].clone();
        let scale = |i: usize, a: usize| impact.frames()[i].norm2[a].clone();
        // v_iy² = (ŷ·v)²/|ŷ|²: compare squares and signs to stay rational.
        let v1y2 = unit(0, 1) * &unit(0, 1) * scale(0, 1);
        let v2y2 = unit(1, 1) * &unit(1, 1) * scale(1, 1);
        prop_assert_eq!(v1y2, int::<Exact>(4) * &k2 * &k2 * &v0 * &v0);
        prop_assert_eq!(v2y2, k1.clone() * &k1 * &v0 * &v0);
        prop_assert!(o.after_hat[0][1] <= zero() && o.after_hat[1][1] <= zero());
        prop_assert!(o.after_hat[0][2].is_zero() && o.after_hat[1][2].is_zero());
        let e = half() * &m * &v0 * &v0;
        let sq = |x: Exact| x.clone() * x;
        prop_assert_eq!(&o.lost_velocity_energy, &(e.clone() * (sq(one.clone() + &k1) + int::<Exact>(4) * sq(one.clone() + &k2))));
        prop_assert_eq!(&o.kinetic_energy_loss, &(e * ((one.clone() - sq(k1.clone())) + int::<Exact>(4) * (one - sq(k2.clone())))));
    }

    /// The planar case (eq. 16–20, 31) with unit normals (a_i, b_i, 0) in the plane z = 0,
    /// f_i1 = x_i b_i − y_i a_i: the inertances (17), the velocities before (19), the Newton
    /// impulses by Cramer's rule (20), E_p (31), and the velocities after impact in their
    /// corrected form (eq. 18 is misprinted, see ERRATA.md):
    /// ω = ω⁰ − (P1 f11 + P2 f21)/J_z, v_x = v_x⁰ − (P1 a11 + P2 a21)/m, v_y = v_y⁰ − (P1 b11 + P2 b21)/m.
    #[test]
    fn planar_closed_forms(
        m in positive(20, 3), jx in positive(20, 3), jy in positive(20, 3), jz in positive(20, 3),
        t1 in rational(12, 5), t2 in rational(12, 5),
        x1 in rational(6, 2), y1 in rational(6, 2), x2 in rational(6, 2), y2 in rational(6, 2),
        vx in rational(6, 2), vy in rational(6, 2), w in rational(4, 2), k1 in coefficient(), k2 in coefficient(),
    ) {
        let ((a1, b1), (a2, b2)) = (circle(&t1), circle(&t2));
        let p = valid(RigidBody::principal(m.clone(), v3(jx, jy, jz.clone())), Screw::new(v3(zero(), zero(), w.clone()), v3(vx.clone(), vy.clone(), zero())), vec![
                Contact { point: v3(x1.clone(), y1.clone(), zero()), normal: v3(a1.clone(), b1.clone(), zero()), tangent: None, k_newton: k1.clone(), k_poisson: k1.clone(), k_energetic: k1.clone(), mu: zero() },
                Contact { point: v3(x2.clone(), y2.clone(), zero()), normal: v3(a2.clone(), b2.clone(), zero()), tangent: None, k_newton: k2.clone(), k_poisson: k2.clone(), k_energetic: k2.clone(), mu: zero() },
            ]);
        let f11 = x1 * &b1 - y1 * &a1;
        let f21 = x2 * &b2 - y2 * &a2;
        let g11 = Exact::one() / &m + f11.clone() * &f11 / &jz;
        let g12 = (a1.clone() * &a2 + b1.clone() * &b2) / &m + f11.clone() * &f21 / &jz;
        let g22 = Exact::one() / &m + f21.clone() * &f21 / &jz;
        let det = g11.clone() * &g22 - g12.clone() * &g12;
        prop_assume!(!det.is_zero());
        let (impact, outcomes) = solve_models(&p, &[Model::Newton]).unwrap();
        prop_assert_eq!(&impact.g_hat(), &vec![g11.clone(), g12.clone(), g12.clone(), g22.clone()]);
        prop_assert_eq!(impact.det_hat(), &det);
        let v1 = a1.clone() * &vx + b1.clone() * &vy + f11.clone() * &w;
        let v2 = a2.clone() * &vx + b2.clone() * &vy + f21.clone() * &w;
        prop_assert_eq!(&impact.before_hat()[0][0], &v1);
        prop_assert_eq!(&impact.before_hat()[1][0], &v2);
        let (r1, r2) = ((Exact::one() + &k1) * &v1, (Exact::one() + &k2) * &v2);
        let p1 = (r1.clone() * &g22 - r2.clone() * &g12) / &det;
        let p2 = (g11.clone() * &r2 - g12.clone() * &r1) / &det;
        let o = &outcomes[0].1;
        prop_assert_eq!(&o.impulses_hat, &vec![p1.clone(), p2.clone()]);
        prop_assert_eq!(&o.velocity.top()[2], &(w - (p1.clone() * &f11 + p2.clone() * &f21) / &jz));
        prop_assert_eq!(&o.velocity.bottom()[0], &(vx - (p1.clone() * &a1 + p2.clone() * &a2) / &m));
        prop_assert_eq!(&o.velocity.bottom()[1], &(vy - (p1.clone() * &b1 + p2.clone() * &b2) / &m));
        let ep = half() * (p1.clone() * &p1 * &g11 + int::<Exact>(2) * &p1 * &p2 * &g12 + p2.clone() * &p2 * &g22);
        prop_assert_eq!(&o.lost_velocity_energy, &ep);
    }

    /// §5.2, eq. (39): with R_1 = R_2 = I (normals along +x) the inertances are
    /// g_ij = 1/m + z_i z_j / J_y + y_i y_j / J_z.
    #[test]
    fn identity_rotation_inertances(b in body(), p1 in vec3(6, 2), p2 in vec3(6, 2)) {
        let x = v3(Exact::one(), zero(), zero());
        let p = valid(b.clone(), Screw::new(Vec3::zeros(), x.clone()), vec![contact(p1.clone(), x.clone(), None, zero()), contact(p2.clone(), x, None, zero())]);
        let impact = inertance::impact::solve::Impact::assemble(&p).unwrap();
        let g = |a: &Vec3<Exact>, c: &Vec3<Exact>| Exact::one() / &b.mass + a[2].clone() * &c[2] / b.inertia.entry(1, 1) + a[1].clone() * &c[1] / b.inertia.entry(2, 2);
        prop_assert_eq!(&impact.g_hat(), &vec![g(&p1, &p1), g(&p1, &p2), g(&p2, &p1), g(&p2, &p2)]);
    }

    /// §5.3: with R = I, k1 = k2, equal approach velocities and y_1 = −y_2 (eq. 47), the
    /// impulses are equal, P = (1 + k) v⁰ / (g11 + g12) (eq. 41–42).
    #[test]
    fn planar_equal_impulses(b in body(), x1 in rational(6, 2), x2 in rational(6, 2), y in rational(6, 2), v in positive(6, 2), k in coefficient()) {
        prop_assume!(!y.is_zero());
        let n = v3(Exact::one(), zero(), zero());
        let p = valid(b, Screw::new(Vec3::zeros(), v3(v.clone(), zero(), zero())), vec![contact(v3(x1, y.clone(), zero()), n.clone(), None, k.clone()), contact(v3(x2, -y, zero()), n, None, k.clone())]);
        let (impact, outcomes) = solve_models(&p, &Model::ALL).unwrap();
        let expected = (Exact::one() + &k) * &v / (impact.g_hat()[0].clone() + &impact.g_hat()[1]);
        for (_, o) in &outcomes {
            prop_assert_eq!(&o.impulses_hat, &vec![expected.clone(), expected.clone()]);
        }
    }
}

/// §5.3's other branch, y_1 = y_2, is not a unique solution: both axis screws coincide
/// ({E_1x} = {E_2x} = [1 0 0 0 0 −y]ᵀ), so Δ = 0 although eq. (48) "always holds" — the
/// equal-impulse solution is one member of a one-parameter family.
#[test]
fn planar_equal_ordinates_are_singular() {
    let n = v3(Exact::one(), zero(), zero());
    let p = valid(
        RigidBody::principal(int(1), v3(int(2), int(3), int(4))),
        Screw::new(Vec3::zeros(), v3(int(1), zero(), zero())),
        vec![
            contact(v3(int(1), int(2), zero()), n.clone(), None, zero()),
            contact(v3(int(-3), int(2), zero()), n, None, zero()),
        ],
    );
    let impact = inertance::impact::solve::Impact::assemble(&p).unwrap();
    assert!(impact.det_hat().is_zero());
    assert_eq!(impact.rank(), 1);
}
