//! Coulomb friction in impulse space (issue 13): the model against the paper (μ = 0), against
//! closed forms we did not write, and against its own invariants.

mod common;

use inertance::impact::friction::{Restitution, solve_frictional};
use inertance::impact::problem::Problem;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::{Exact, Scalar, int, ratio};

fn v<T: Scalar>(x: T, y: T, z: T) -> Vec3<T> {
    Vec3::new(x, y, z)
}

/// The paper's Example 3 (§7) with friction μ at both contacts.
fn example_3<T: Scalar>(mu: T) -> Problem<T> {
    let c = |y: i64, k: T| {
        Contact::new(v(int(0), int(y), int(0)), v(int(1), int(0), int(0)), k)
            .with_tangent(v(int(0), int(1), int(0)))
            .with_friction(mu.clone())
    };
    Problem::new(
        RigidBody {
            mass: int(1),
            inertia: v(int(12), ratio(8, 5), int(12)),
        },
        Screw::new(v(int(0), int(0), ratio(2, 5)), v(int(3), int(2), int(0))),
        vec![c(-2, ratio(3, 10)), c(4, ratio(1, 5))],
    )
    .unwrap()
}

#[test]
fn scratch() {
    for mu in [ratio::<RatFun>(0, 1), ratio(1, 10), ratio(1, 2), int(1)] {
        for law in Restitution::ALL {
            let out = match solve_frictional(&example_3(mu.clone()), law, 1e-10) { Ok(o) => o, Err(e) => { println!("mu={mu:?} {law}: {e}"); continue; } };
            println!("mu={} {law}", mu.exact_text().unwrap()); println!(": P={:?} twist={:?} dEc={} Ef={} res={} verdicts={:?}", out.impulses.iter().map(|x| x.exact_text().unwrap()).collect::<Vec<_>>(), out.velocity.as_slice().iter().map(|x| x.exact_text().unwrap()).collect::<Vec<_>>(), out.kinetic_energy_loss.exact_text().unwrap(), out.friction_dissipation.exact_text().unwrap(), out.energy_residual.exact_text().unwrap(), out.verdicts);
            for s in &out.segments { println!("   [{}, {}] {} {:?} {:?}", s.from.exact_text().unwrap(), s.to.exact_text().unwrap(), s.phase, s.modes, s.rates.iter().map(|x| x.exact_text().unwrap()).collect::<Vec<_>>()); }
        }
    }
}
