//! The unilateral law with Coulomb friction in spatial scenes (issue 25): the adaptive
//! integrator's release and re-engagement ([`inertance::impact::friction::spatial`]) against
//! the exact planar answer, against its invariants, and with μ → 0 against the frictionless
//! unilateral law (Pfeiffer–Glocker's compression LCP and Moreau's, `src/impact/unilateral.rs`).

use inertance::impact::friction::{
    Frictional, Hypothesis, ModeLabel, Restitution, solve_frictional_under,
};
use inertance::impact::problem::Problem;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};

/// Rotation about y (the floor's normal) by θ: the plane of the motion, z, turns to
/// (sin θ, 0, cos θ), which is not a coordinate plane for θ = 1 rad (irrational entries), so
/// the solve takes the spatial integrator.
fn turn(theta: f64, x: Vec3<f64>) -> Vec3<f64> {
    let (s, c) = theta.sin_cos();
    Vec3::new(c * x[0] + s * x[2], x[1], -s * x[0] + c * x[2])
}

/// Housner's rocking block of tests/unilateral_friction.rs (half-width b, half-height h,
/// mass m, rocking at ω about its old corner A = (b, −h) on the floor y = −h; contacts A then
/// B = (−b, −h), normal −y, tangent +x) with an isotropic inertia m(b² + h²)/3, turned by θ
/// about y; `spin` adds a yaw rate about the floor's normal.
fn rocking(b: f64, h: f64, m: f64, omega: f64, mu: f64, k: f64, theta: f64, spin: f64) -> Problem<f64> {
    let i = m * (b * b + h * h) / 3.0;
    let corner = |x: f64| {
        Contact::new(
            turn(theta, Vec3::new(x, -h, 0.0)),
            Vec3::new(0.0, -1.0, 0.0),
            k,
        )
        .with_tangent(turn(theta, Vec3::new(1.0, 0.0, 0.0)))
        .with_friction(mu)
    };
    Problem::new(
        RigidBody::principal(m, Vec3::new(i, i, i)),
        Screw::new(
            turn(theta, Vec3::new(0.0, spin, omega)),
            turn(theta, Vec3::new(-omega * h, -omega * b, 0.0)),
        ),
        vec![corner(b), corner(-b)],
    )
    .unwrap()
}

fn solve(p: &Problem<f64>, law: Restitution, tol: f64) -> Frictional<f64> {
    solve_frictional_under(p, law, Hypothesis::Unilateral, tol).unwrap()
}

#[test]
fn housner_block_turned_out_of_its_plane_matches_the_exact_ratio_within_the_estimate() {
    let (b, h, omega) = (3.0, 4.0, 1.0);
    for tol in [1e-6, 1e-9] {
        let p = rocking(b, h, 3.0, omega, 0.5, 0.0, 1.0, 0.0);
        let f = solve(&p, Restitution::Newton, tol);
        let est = f.error_estimate.expect("the spatial integrator");
        let w = turn(-1.0, f.velocity.top());
        eprintln!("{tol}: {w:?} est {est:e} hist {:?} {:?}", f.history(0), f.history(1));
        assert!((w[2] - 23.0 / 50.0 * omega).abs() <= est, "{w:?} est {est:e}");
    }
}
