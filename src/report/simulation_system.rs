//! The report of a simulated system of spheres (`inertance simulate` on several `[[body]]`):
//! the impact log as one body's ([`super::simulation::impact_log`]), and the trajectory as CSV
//! — per sample t, every sphere's centre and velocity, the energies and the closed contacts
//! (an impact gives two rows at its time: before and after, as Siconos' event rows).

use super::simulation::{end_of, impact_log, sig};
use crate::simulate::system::{SystemSetup, SystemSimulation};

/// The log.
pub fn to_text(name: &str, setup: &SystemSetup, sim: &SystemSimulation) -> String {
    let mut out = format!(
        "{name} — simulated, {} spheres, law {}, f64 (tolerance {})\n",
        setup.spheres.len(),
        setup.law.name(),
        sig(setup.options.tolerance)
    );
    out += &impact_log(&sim.impacts, &sim.events);
    let energy = |k: usize| {
        sim.samples
            .get(k)
            .map_or_else(String::new, |s| sig(s.kinetic + s.potential))
    };
    out += &format!(
        "ended at {}: {} impact{}, energy {} → {} J; {} steps ({} rejected), drift {} m\n",
        end_of(sim.end, sim.t_end, sim.stopped.as_ref()),
        sim.impacts.len(),
        if sim.impacts.len() == 1 { "" } else { "s" },
        energy(0),
        sig(sim.state.kinetic_energy(&setup.spheres)
            + sim
                .state
                .potential_energy(&setup.spheres, &setup.options.gravity)),
        sim.steps.0,
        sim.steps.1,
        sig(sim.drift)
    );
    out
}

/// The trajectory as CSV.
pub fn to_csv(setup: &SystemSetup, sim: &SystemSimulation) -> String {
    let mut out = String::from("t");
    for s in &setup.spheres {
        for c in ["x", "y", "z", "vx", "vy", "vz"] {
            out += &format!(",{} {c}", s.name);
        }
    }
    out += ",kinetic,potential,closed\n";
    for s in &sim.samples {
        out += &format!("{:e}", s.t);
        for (x, v) in s.state.x.iter().zip(&s.state.v) {
            for q in x.iter().chain(v.iter()) {
                out += &format!(",{q:e}");
            }
        }
        out += &format!(",{:e},{:e},{}\n", s.kinetic, s.potential, s.closed);
    }
    out
}
