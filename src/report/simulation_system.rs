//! The report of a simulated system of spheres (`inertance simulate` on several `[[body]]`):
//! the impact log as one body's ([`super::simulation::impact_log`]), its JSON (one body's
//! schema, [`to_json`]), and the trajectory as CSV
//! — per sample t, every sphere's centre and velocity, the energies and the closed contacts
//! (an impact gives two rows at its time: before and after, as Siconos' event rows).

use serde_json::{Value as Json, json};

use super::json_f64;
use super::simulation::{end_name, end_of, events_json, impact_log, impacts_json, sig};
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

/// The whole run, for programs: one body's schema ([`super::simulation::to_json`]) with the
/// spheres' names, their final state per sphere, and no Zeno (a system runs to its budget).
pub fn to_json(name: &str, setup: &SystemSetup, sim: &SystemSimulation) -> Json {
    let v3 = |v: &nalgebra::Vector3<f64>| json!([json_f64(v.x), json_f64(v.y), json_f64(v.z)]);
    json!({
        "name": name,
        "law": setup.law.name(),
        "tolerance": setup.options.tolerance,
        "bodies": setup.spheres.iter().map(|s| s.name.clone()).collect::<Vec<_>>(),
        "end": end_name(sim.end),
        "error": sim.stopped.as_ref().map(ToString::to_string),
        "t_end": json_f64(sim.t_end),
        "impacts": impacts_json(&sim.impacts),
        "events": events_json(&sim.events),
        "state": {
            "x": sim.state.x.iter().map(v3).collect::<Vec<_>>(),
            "v": sim.state.v.iter().map(v3).collect::<Vec<_>>(),
        },
        "steps": sim.steps.0,
        "rejected": sim.steps.1,
        "drift": json_f64(sim.drift),
    })
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
