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

fn solve<T: Scalar>(p: &Problem<T>, law: Restitution, hyp: Hypothesis) -> Frictional<T> {
    solve_frictional_under(p, law, hyp, 0.0).unwrap()
}

fn rocking_u<T: Scalar>(b: T, h: T, m: T, omega: T, u: T, w: T, mu: T, ka: T, kb: T) -> Problem<T> {
    let izz = m.clone() * (b.clone() * &b + h.clone() * &h) / int::<T>(3);
    let corner = |x: T, k: T| {
        Contact::new(v(x, -h.clone(), int(0)), v(int(0), int(-1), int(0)), k.clone())
            .with_tangent(v(int(1), int(0), int(0)))
            .with_friction(mu.clone())
    };
    Problem::new(
        RigidBody::principal(m.clone(), v(izz.clone(), izz.clone(), izz)),
        Screw::new(
            v(int(0), int(0), omega.clone()),
            v(-(omega.clone() * &h) + u, -(omega * &b) + w, int(0)),
        ),
        vec![corner(b.clone(), ka), corner(-b, kb)],
    )
    .unwrap()
}

#[test]
fn probe() {
    for w in [-1, -2, -4] { for om in [ratio::<Exact>(1,4), ratio(1,2), int(0)] {
        let p = rocking_u::<Exact>(int(1), int(2), int(3), om.clone(), int(0), int(w), int(0), int(0), int(1));
        let f = solve_frictional_under(&p, Restitution::Newton, Hypothesis::Unilateral, 0.0).unwrap();
        println!("w {w} om {om}: {:?} {:?} v0 {:?} imp {:?} after {:?} {:?}", f.history(0), f.history(1), f.blocks.v0, f.impulses, f.after, f.segments.iter().map(|s| (s.from.clone(), s.rates.clone())).collect::<Vec<_>>());
        let mut imp = inertance::impact::solve::Impact::assemble(&p).unwrap();
        let mut out = inertance::impact::solve::Outcome::default();
        imp.solve_unilateral(inertance::impact::restitution::Model::Newton, &mut out).unwrap();
        println!("   moreau {:?} after {:?} {:?} {:?}", out.impulses_hat, out.after_hat, out.velocity, f.velocity);
    }}
}
