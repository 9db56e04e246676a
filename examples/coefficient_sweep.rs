//! A sweep in a plain loop: the second support's coefficient of restitution k₂ of the paper's
//! Example 3 from 0 to 1, Newton against Poisson (they differ because k₁ ≠ k₂ and g₁₂ ≠ 0,
//! eq. 53–55). The `sweep` command does this for scene files, in parallel, to CSV and SVG.
//!
//! `cargo run --example coefficient_sweep`

use inertance::{Contact, Model, Problem, RigidBody, Screw, Vec3, solve};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run(&mut std::io::stdout())
}

/// Sweep and print to `out` (the tests read it).
pub fn run(out: &mut impl std::io::Write) -> Result<(), Box<dyn std::error::Error>> {
    let body = RigidBody::principal(1.0, Vec3::new(12.0, 1.6, 12.0));
    let twist = Screw::new(Vec3::new(0.0, 0.0, 0.4), Vec3::new(3.0, 2.0, 0.0));
    let normal = Vec3::new(1.0, 0.0, 0.0);
    writeln!(
        out,
        "{:>5} {:>12} {:>12} {:>12} {:>12}",
        "k2", "P2 newton", "P2 poisson", "ΔE_c newton", "ΔE_c poisson"
    )?;
    for step in 0..=10 {
        let k2 = f64::from(step) / 10.0;
        let contacts = vec![
            Contact::new(Vec3::new(0.0, -2.0, 0.0), normal, 0.3),
            Contact::new(Vec3::new(0.0, 4.0, 0.0), normal, k2),
        ];
        let problem = Problem::new(body.clone(), twist.clone(), contacts)?;
        let newton = solve(&problem, Model::Newton)?;
        let poisson = solve(&problem, Model::Poisson)?;
        writeln!(
            out,
            "{k2:>5.1} {:>12.6} {:>12.6} {:>12.6} {:>12.6}",
            newton.impulses[1].to_f64(),
            poisson.impulses[1].to_f64(),
            newton.kinetic_energy_loss,
            poisson.kinetic_energy_loss
        )?;
    }
    Ok(())
}
