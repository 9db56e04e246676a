//! The LZB law integrated in double-double (`solve_lzb` over `DoubleDouble`, unit roundoff
//! u = 2⁻¹⁰⁴ ≈ 4.9·10⁻³²): against the exact closed forms
//! (`inertance::impact::multiple::closed_form`) it reaches far below f64's rounding, and its own
//! error estimate bounds its distance from the exact outcome; against the f64 integration on
//! scenes without a closed form (Newton's cradle, a bar on supports of unequal stiffness) the
//! two agree within the f64 run's error estimate.
//!
//! **The bound.** Every accepted step keeps each impulse's embedded error below
//! tol · (|Λ_q| + Π), Π = max v⁰ / max g_ii the impulse scale (module docs of
//! `impact::multiple::lzb`), and the estimate adds the largest of them per step, so after N
//! accepted steps it is at most N · tol · (max P + Π). The tests take the estimate as the
//! method does — the distance from the exact outcome within twice it, plus the rounding of the
//! O(n) operations that form an output from the state, 64 n u |P| — and check, separately,
//! that 2 N · tol · (max P + Π) is itself at most 10⁻² of f64's unit roundoff times P: with
//! tol = 10⁻²⁴ and N ≈ 6·10⁴ steps (one corner; fewer for more) that is about 10⁻¹⁹ relative,
//! so the distance asserted is two orders below what an f64 number can even hold of P — and
//! ten below the f64 integration's own error at its default tolerance (10⁻⁹ to 10⁻¹¹).

use inertance::impact::multiple::{ContactLaw, alike, solve_lzb};
use inertance::impact::problem::Problem;
use inertance::impact::solve::Impact;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::number::rational_to_f64;
use inertance::scalar::dd::DoubleDouble;
use inertance::scalar::{Exact, Scalar, ratio};
use inertance::scene::Scene;
use inertance::scene::lzb::contact_laws;
use inertance::scene::pipeline::{friction_tolerance, prepare};
use num_rational::BigRational;

/// The double-double tolerance of the closed-form tests.
const TOL: f64 = 1e-24;

/// |x − exact| for a double-double x, in f64 (the difference formed exactly).
fn distance(x: DoubleDouble, exact: &BigRational) -> f64 {
    let d = x.exact_value().expect("finite") - exact;
    rational_to_f64(&d).abs()
}

/// A box (half sides 3/10, 1/5, 1/10; mass 2) falling at 3/2 m/s onto `corners` of its
/// underside, normals −z, restitution k, spinning at `spin` about z (which leaves the normal
/// velocities alike) — as in `tests/lzb_exact.rs`.
fn box_landing<T: Scalar>(corners: &[(i64, i64)], k: (i64, i64), spin: (i64, i64)) -> Problem<T> {
    let (a, b, c) = (ratio::<T>(3, 10), ratio::<T>(1, 5), ratio::<T>(1, 10));
    let m = ratio::<T>(2, 1);
    let third = m.clone() / ratio::<T>(3, 1);
    let inertia = Vec3::new(
        third.clone() * (b.clone() * b.clone() + c.clone() * c.clone()),
        third.clone() * (a.clone() * a.clone() + c.clone() * c.clone()),
        third * (a.clone() * a.clone() + b.clone() * b.clone()),
    );
    let body = RigidBody::principal(m, inertia);
    let twist = Screw::new(
        Vec3::new(T::zero(), T::zero(), ratio::<T>(spin.0, spin.1)),
        Vec3::new(T::zero(), T::zero(), ratio::<T>(-3, 2)),
    );
    let contacts = corners
        .iter()
        .map(|&(sx, sy)| {
            Contact::new(
                Vec3::new(
                    ratio::<T>(sx, 1) * a.clone(),
                    ratio::<T>(sy, 1) * b.clone(),
                    -c.clone(),
                ),
                Vec3::new(T::zero(), T::zero(), ratio::<T>(-1, 1)),
                ratio::<T>(k.0, k.1),
            )
        })
        .collect();
    Problem::new(body, twist, contacts).expect("a valid box")
}

const FOUR: [(i64, i64); 4] = [(1, 1), (-1, 1), (-1, -1), (1, -1)];
const TWO: [(i64, i64); 2] = [(1, 1), (-1, -1)];
const ONE: [(i64, i64); 1] = [(1, -1)];

/// Every contact alike: the double-double integration meets P = (1 + e) v/g (exact, rational)
/// within twice its own error estimate, and twice that estimate is below 10⁻² of f64's rounding
/// of P (module docs).
#[test]
fn double_double_meets_the_closed_form_far_below_f64() {
    for corners in [&ONE[..], &TWO[..], &FOUR[..]] {
        for (k, eta, stiffness) in [((1, 2), 1.5, 1.0), ((0, 1), 1.0, 40.0), ((1, 1), 2.0, 0.3)] {
            let exact = box_landing::<Exact>(corners, k, (0, 1));
            let impact = Impact::assemble(&exact).expect("assembles");
            let n = corners.len();
            let v0: Vec<Exact> = impact.before_hat().iter().map(|v| v[0].clone()).collect();
            let e = k.0 as f64 / k.1 as f64;
            let laws = vec![ContactLaw::new(stiffness, eta, e).expect("valid"); n];
            let closed = alike(impact.g_hat(), &v0, &laws, &ratio::<Exact>(k.0, k.1))
                .expect("every corner alike");
            let g = impact.g_hat();
            let gmax = (0..n).map(|i| g[i * n + i].to_f64()).fold(0.0, f64::max);
            let pi = v0[0].to_f64() / gmax;
            let out = solve_lzb(&box_landing::<DoubleDouble>(corners, k, (2, 1)), &laws, TOL)
                .expect("ends");
            let p = closed.impulses[0].to_f64();
            let ceiling = out.stats.accepted as f64 * TOL * (p + pi);
            assert!(
                out.error_estimate <= ceiling,
                "{corners:?}, k {k:?}: estimate {:e} above N tol (P + Π) = {ceiling:e}",
                out.error_estimate
            );
            assert!(
                2.0 * ceiling <= 1e-2 * f64::EPSILON * p,
                "{corners:?}, k {k:?}: {} steps: N tol (P + Π) = {ceiling:e} is not far below \
                 f64's rounding of P",
                out.stats.accepted
            );
            let bound =
                2.0 * out.error_estimate + 64.0 * n as f64 * DoubleDouble::epsilon_f64() * p;
            for i in 0..n {
                let exact_p = closed.impulses[i].to_rational().expect("exact");
                let d = distance(out.impulses[i], &exact_p);
                assert!(
                    d <= bound,
                    "{corners:?}, k {k:?}, η {eta}: |P{} − (1 + e) v/g| = {d:e} above {bound:e}",
                    i + 1
                );
            }
            // Each contact leaves at −e v, to the same bound scaled by the largest row of G
            // (v = v⁰ − G P).
            let row = (0..n)
                .map(|i| (0..n).map(|j| g[i * n + j].to_f64().abs()).sum::<f64>())
                .fold(0.0, f64::max);
            for i in 0..n {
                let exact_v = closed.after[i].to_rational().expect("exact");
                let d = distance(out.after[i], &exact_v);
                assert!(
                    d <= row * bound + 64.0 * DoubleDouble::epsilon_f64(),
                    "v{}: {d:e}",
                    i + 1
                );
            }
        }
    }
}

/// One rough contact under the centre of mass, slipping at 2 m/s with μ = 3/10, e = 1/2, as
/// the unit test of `lzb.rs` in f64: P = (1 + e) v⁰/g = 3/2 and the slip 2 − μ P stays
/// positive, so τ = μ P = 9/20 and friction dissipates μ (3 − 9μ/8) = 639/800 J — in
/// double-double to its estimate (μ = 3/10 enters rounded to 2⁻¹⁰⁴ relative).
#[test]
fn double_double_friction_meets_the_sliding_closed_form() {
    let dd = |p: i64, q: i64| ratio::<DoubleDouble>(p, q);
    let body = RigidBody::principal(dd(1, 1), Vec3::new(dd(1, 2), dd(1, 2), dd(1, 2)));
    let twist = Screw::new(Vec3::zeros(), Vec3::new(dd(2, 1), dd(0, 1), dd(-1, 1)));
    let c = Contact::new(
        Vec3::zeros(),
        Vec3::new(dd(0, 1), dd(0, 1), dd(-1, 1)),
        dd(1, 2),
    )
    .with_friction(dd(3, 10));
    let p = Problem::new(body, twist, vec![c]).expect("valid");
    let law = ContactLaw::new(2.0, 1.5, 0.5).expect("valid");
    let out = solve_lzb(&p, &[law], TOL).expect("ends");
    assert!(out.blocks.plane.is_some(), "planar in the xz-plane");
    let q = |p: i64, q: i64| ratio::<Exact>(p, q).to_rational().expect("exact");
    let u = DoubleDouble::epsilon_f64();
    let bound = 2.0 * out.error_estimate + 64.0 * u;
    assert!(bound <= 1e-2 * f64::EPSILON * 1.5, "bound {bound:e}");
    assert!(distance(out.impulses[0], &q(3, 2)) <= bound);
    assert!(distance(out.tangential[0][0].abs(), &q(9, 20)) <= bound);
    assert!(distance(out.friction_dissipation[0], &q(639, 800)) <= 8.0 * bound);
}

/// The scene's solve in both types, each to its default tolerance ε^(2/3) (f64: 3.7·10⁻¹¹,
/// double-double: 1.3·10⁻²¹): every impulse and every velocity after agree within the sum of
/// the two estimates, doubled, and the rounding of f64 (the double-double one is the
/// reference: its estimate is below 10⁻⁶ of the f64 one).
fn agree(path: &str, stiffness_ratio: f64) {
    let scene = Scene::load(std::path::Path::new(path)).expect("loads");
    let mut laws = contact_laws(&scene).expect("valid laws");
    laws[0].stiffness *= stiffness_ratio;
    let (f, d) = if scene.system.is_some() {
        let a = solve_lzb(
            &scene.system::<f64>().expect("a system"),
            &laws,
            friction_tolerance::<f64>(),
        );
        let b = solve_lzb(
            &scene.system::<DoubleDouble>().expect("a system"),
            &laws,
            friction_tolerance::<DoubleDouble>(),
        );
        let a = a.expect("ends");
        let b = b.expect("ends");
        (
            (a.impulses, a.after, a.error_estimate, a.stats),
            (b.impulses, b.after, b.error_estimate, b.stats),
        )
    } else {
        let a = solve_lzb(
            &prepare::<f64>(&scene).expect("prepares"),
            &laws,
            friction_tolerance::<f64>(),
        )
        .expect("ends");
        let b = solve_lzb(
            &prepare::<DoubleDouble>(&scene).expect("prepares"),
            &laws,
            friction_tolerance::<DoubleDouble>(),
        )
        .expect("ends");
        (
            (a.impulses, a.after, a.error_estimate, a.stats),
            (b.impulses, b.after, b.error_estimate, b.stats),
        )
    };
    let n = f.0.len();
    let scale = f.0.iter().fold(0.0_f64, |m, p| m.max(p.abs()));
    assert!(
        d.2 <= 1e-6 * f.2,
        "{path}: the double-double estimate {:e} is not a reference for f64",
        d.2
    );
    let bound = 2.0 * (f.2 + d.2) + 64.0 * n as f64 * f64::EPSILON * scale;
    for i in 0..n {
        let gap = (f.0[i] - d.0[i].to_f64()).abs();
        assert!(
            gap <= bound,
            "{path} (K₁ × {stiffness_ratio}): P{}: f64 {} vs double-double {:?}: {gap:e} above \
             {bound:e} ({:?} and {:?} steps)",
            i + 1,
            f.0[i],
            d.0[i],
            f.3,
            d.3
        );
        let gap = (f.1[i] - d.1[i].to_f64()).abs();
        assert!(gap <= bound * 8.0, "{path}: v{}: {gap:e}", i + 1);
    }
}

/// Newton's cradle: three balls, Hertz contacts, the impulse travelling down the row.
#[test]
fn double_double_and_f64_agree_on_the_cradle() {
    agree("examples/cradle-3-lzb.toml", 1.0);
}

/// The bar on two supports with K₁ = 10 K₂: no closed form, the stiff support first.
#[test]
fn double_double_and_f64_agree_on_unequal_supports() {
    agree("examples/bar-two-supports-lzb.toml", 10.0);
}
