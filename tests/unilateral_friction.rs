//! The unilateral law with Coulomb friction (issue 25, item 3): Housner's rocking block, and
//! the frictionless law against Pfeiffer–Glocker's and Moreau's LCPs — exactly, in rationals.

use inertance::impact::friction::{
    Frictional, Hypothesis, ModeLabel, Phase, Restitution, Verdict, solve_frictional_under,
};
use inertance::impact::problem::Problem;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, Scalar, int, ratio};
use num_traits::Zero;

fn v<T: Scalar>(x: T, y: T, z: T) -> Vec3<T> {
    Vec3::new(x, y, z)
}

/// A block of half-width b, half-height h and mass m, centre at the origin, rocking with
/// angular velocity ω > 0 about its old corner A = (b, −h) on the floor y = −h; its new corner
/// B = (−b, −h) lands with speed 2bω. Contacts: A first, B second, normal −y (into the floor),
/// tangent +x, friction μ, Newton coefficient k.
fn rocking<T: Scalar>(b: T, h: T, m: T, omega: T, mu: T, k: T) -> Problem<T> {
    let izz = m.clone() * (b.clone() * &b + h.clone() * &h) / int::<T>(3);
    let corner = |x: T| {
        Contact::new(v(x, -h.clone(), int(0)), v(int(0), int(-1), int(0)), k.clone())
            .with_tangent(v(int(1), int(0), int(0)))
            .with_friction(mu.clone())
    };
    Problem::new(
        RigidBody::principal(m.clone(), v(izz.clone(), izz.clone(), izz)),
        // v_C = ω ẑ × (C − A) = ω (−h, −b).
        Screw::new(
            v(int(0), int(0), omega.clone()),
            v(-(omega.clone() * &h), -(omega * &b), int(0)),
        ),
        vec![corner(b.clone()), corner(-b)],
    )
    .unwrap()
}

/// The block of [`rocking`] with the centre's velocity shifted by (u, w) and its own Newton
/// coefficient at each corner.
#[allow(clippy::too_many_arguments)]
fn landing<T: Scalar>(b: T, h: T, m: T, omega: T, u: T, w: T, mu: T, ka: T, kb: T) -> Problem<T> {
    let mut p = rocking(b, h, m, omega, mu, T::zero());
    let mut contacts = p.contacts().to_vec();
    contacts[0].k_newton = ka;
    contacts[1].k_newton = kb;
    let mut velocity = p.velocity().clone();
    velocity.0[3] += u;
    velocity.0[4] += w;
    p = Problem::new(p.body().clone(), velocity, contacts).unwrap();
    p
}

fn solve<T: Scalar>(p: &Problem<T>, law: Restitution, hyp: Hypothesis) -> Frictional<T> {
    solve_frictional_under(p, law, hyp, 0.0).unwrap()
}

/// ω⁺/ω⁻ = 1 − (3/2) sin²α, sin²α = b²/(b² + h²) (Housner 1963).
fn housner(b: i64, h: i64) -> Exact {
    int::<Exact>(1) - ratio::<Exact>(3 * b * b, 2 * (b * b + h * h))
}

#[test]
fn housner_rocking_block_lands_on_its_new_corner_with_ratio_23_over_50() {
    let p = rocking::<Exact>(int(3), int(4), int(3), int(1), ratio(1, 2), int(0));
    let f = solve(&p, Restitution::Newton, Hypothesis::Unilateral);
    // b/h = 3/4: sin α = 3/5, ω⁺/ω⁻ = 1 − (3/2)(9/25) = 23/50.
    assert_eq!(housner(3, 4), ratio(23, 50));
    assert_eq!(f.velocity.0[2], ratio(23, 50));
    // The old corner is released from s = 0 and takes nothing; the new one sticks.
    assert_eq!(f.history(0), vec![ModeLabel::Released]);
    assert_eq!(f.history(1), vec![ModeLabel::Stick]);
    assert!(f.normal_hat(0).is_zero());
    assert_eq!(f.impulses, vec![int(0), int(0), ratio(657, 50), ratio(-162, 25)]);
    // The block turns about B after impact: B at rest, A lifting at 2b ω⁺ (normal −y).
    assert_eq!(f.after, vec![ratio(-69, 25), int(0), int(0), int(0)]);
    // The tangential impulse lies inside the cone: |τ|/p = 36/73 < μ = 1/2.
    assert_eq!(-f.impulses[3].clone() / &f.impulses[2], ratio(36, 73));
    assert!(f.verdicts.is_empty());
    assert!(f.energy_residual.is_zero());
}

#[test]
fn housner_ratio_holds_exactly_for_pythagorean_aspect_ratios() {
    for (b, h) in [(3, 4), (4, 3), (5, 12), (8, 15), (7, 24), (1, 1), (1, 2)] {
        for (m, omega) in [(int::<Exact>(3), int::<Exact>(1)), (ratio(7, 2), ratio(5, 3))] {
            let p = rocking::<Exact>(int(b), int(h), m.clone(), omega.clone(), int(10), int(0));
            let f = solve(&p, Restitution::Newton, Hypothesis::Unilateral);
            let ratio_after = f.velocity.0[2].clone() / &omega;
            assert_eq!(ratio_after, housner(b, h), "b = {b}, h = {h}, ω = {omega}");
            assert_eq!(f.history(0), vec![ModeLabel::Released], "b = {b}, h = {h}");
            assert_eq!(f.history(1), vec![ModeLabel::Stick], "b = {b}, h = {h}");
        }
    }
}

#[test]
fn housner_ratio_in_f64_within_the_bound_of_a_two_by_two_elimination() {
    // The rates come from one 2×2 system (B's normal and tangential rows of K), solved by
    // Gaussian elimination with partial pivoting: relative error ≤ κ_∞ (δK + δrhs + growth)
    // with δK ≤ 4ε (each entry of K is a sum of at most 4 rounded products), δrhs ≤ ε, and the
    // elimination's backward error ≤ 2·2·ρ·ε, ρ ≤ 2; the twist after adds ≤ 4ε relative.
    // Bound: (4 + 1 + 8 + 4)·κ_∞·ε ≤ 17 κ_∞ ε, κ_∞ computed here from K.
    for (b, h) in [(3.0, 4.0), (4.0, 3.0), (5.0, 12.0), (0.3, 0.7), (1.0, 1.0)] {
        let p = rocking::<f64>(b, h, 2.5, 1.3, 10.0, 0.0);
        let f = solve(&p, Restitution::Newton, Hypothesis::Unilateral);
        let k = |q, r| *f.blocks.at(q, r);
        let (a, bb, c, d) = (k(2, 2), k(2, 3), k(3, 2), k(3, 3));
        let det = a * d - bb * c;
        let norm = (a.abs() + bb.abs()).max(c.abs() + d.abs());
        let inv = (d.abs() + bb.abs()).max(c.abs() + a.abs()) / det.abs();
        let kappa = norm * inv;
        let expected = 1.0 - 1.5 * b * b / (b * b + h * h);
        let got = f.velocity.0[2] / 1.3;
        let bound = 17.0 * kappa * f64::EPSILON * expected.abs().max(1.0);
        assert!(
            (got - expected).abs() <= bound,
            "b = {b}, h = {h}: {got} vs {expected} (bound {bound:e}, κ = {kappa})"
        );
        assert_eq!(f.history(0), vec![ModeLabel::Released]);
    }
}

#[test]
fn the_simultaneous_law_asks_the_old_corner_to_pull() {
    // The same landing under the paper's hypothesis: A is held at zero normal velocity and
    // needs a tensile rate from s = 0 (both corners then slide: no cone holds a pull).
    let p = rocking::<Exact>(int(3), int(4), int(3), int(1), ratio(1, 2), int(0));
    let f = solve(&p, Restitution::Newton, Hypothesis::Simultaneous);
    assert!(f.verdicts.contains(&Verdict::TensileRate {
        contact: 0,
        s: 0.0,
        phase: Phase::Compression
    }));
    assert!(f.normal_hat(0).signum_i8() < 0);
}

#[test]
fn a_released_corner_re_engages_when_newtons_path_catches_it() {
    // The block also falls (w = −2) and drifts (u = −1): A approaches at 2 but B's impulse
    // lifts it faster than its compression path, so A is released; in restitution B has
    // k = 0 (no rebound rate) and A's Newton path −k_A v_A⁰ (s − 1) = −2(s − 1) descends to
    // meet A's velocity, −30/17 from s = 1, at s = 1 + 15/17 = 32/17, where A re-engages and
    // is driven to −k_A v_A⁰ = −2 at s = 2.
    let p = landing::<Exact>(
        int(3), int(4), int(3), int(1), int(-1), int(-2), ratio(1, 2), int(1), int(0),
    );
    let f = solve(&p, Restitution::Newton, Hypothesis::Unilateral);
    assert_eq!(f.history(0), vec![ModeLabel::Released, ModeLabel::SlideMinus]);
    let s: Vec<Exact> = f.segments.iter().map(|g| g.from.clone()).collect();
    assert_eq!(s, vec![int(0), int(1), ratio(32, 17)]);
    assert_eq!(f.blocks.v0[0], int(2));
    assert_eq!(f.after[0], int(-2));
    // A's impulse is taken after re-engaging only: its rate 17/9 over 2/17.
    assert_eq!(f.normal_hat(0).clone(), ratio(2, 9));
    assert!(f.verdicts.is_empty());
    assert!(f.energy_residual.is_zero());
}
