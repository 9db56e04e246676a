//! The paper's Example 3 (§7): a planar bar of mass 1 kg striking two supports at once, built
//! in code and solved in f64 and in exact rationals, Newton and Poisson side by side.
//!
//! `cargo run --example planar_bar`

use inertance::scalar::ratio;
use inertance::{
    Contact, Exact, InvalidProblem, Model, Problem, RigidBody, Scalar, Screw, Vec3, solve,
};

/// Example 3 in any scalar type: J = (12, 1.6, 12) kg m², v_C⁰ = (3, 2, 0) m/s,
/// ω⁰ = 0.4 rad/s about z; supports at A₁ = (0, −2, 0) (k = 0.3) and A₂ = (0, 4, 0)
/// (k = 0.2), both with outward normal x.
fn example_3<T: Scalar>() -> Result<Problem<T>, InvalidProblem> {
    let q = ratio::<T>;
    let v = |x, y, z| Vec3::new(q(x, 1), q(y, 1), q(z, 1));
    let body = RigidBody::principal(q(1, 1), Vec3::new(q(12, 1), q(8, 5), q(12, 1)));
    let twist = Screw::new(Vec3::new(q(0, 1), q(0, 1), q(2, 5)), v(3, 2, 0));
    let contacts = vec![
        Contact::new(v(0, -2, 0), v(1, 0, 0), q(3, 10)),
        Contact::new(v(0, 4, 0), v(1, 0, 0), q(1, 5)),
    ];
    Problem::new(body, twist, contacts)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run(&mut std::io::stdout())
}

/// Solve and print to `out` (the tests read it).
pub fn run(out: &mut impl std::io::Write) -> Result<(), Box<dyn std::error::Error>> {
    let float = example_3::<f64>()?;
    let exact = example_3::<Exact>()?;
    writeln!(out, "Example 3, planar bar on two supports")?;
    for model in Model::ALL {
        let f = solve(&float, model)?;
        let e = solve(&exact, model)?;
        writeln!(out, "\n{model}: Δ = det G = {}", e.det)?;
        for (i, (pf, pe)) in f.impulses.iter().zip(&e.impulses).enumerate() {
            let text = pe.exact_text().unwrap_or_default();
            writeln!(
                out,
                "  P{} = {:.9} N s   (exact {text})",
                i + 1,
                pf.to_f64()
            )?;
        }
        let w = e.twist.top();
        let v = e.twist.bottom();
        writeln!(
            out,
            "  ω_z = {} rad/s, v_C = ({}, {}, {}) m/s",
            w[2], v[0], v[1], v[2]
        )?;
        writeln!(
            out,
            "  E_p = {} J, ΔE_c = {} J   (f64: {:.9}, {:.9})",
            e.lost_velocity_energy,
            e.kinetic_energy_loss,
            f.lost_velocity_energy,
            f.kinetic_energy_loss
        )?;
        for (i, v) in e.contact_velocities.iter().enumerate() {
            writeln!(
                out,
                "  v_{}x after impact = {} m/s",
                i + 1,
                v[0].exact_text().unwrap_or_default()
            )?;
        }
    }
    Ok(())
}
