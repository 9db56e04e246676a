//! The report of a simulated system (`inertance simulate` on several `[[body]]`): the impact
//! log as one body's ([`super::simulation::impact_log`]); the whole run as JSON, in the one
//! body's schema with per-member arrays; the trajectory as CSV — per sample t, every member's
//! centre and velocity (and a box's attitude quaternion and angular velocity), the energies and
//! the closed contacts (an impact gives two rows at its time: before and after, as Siconos'
//! event rows) — and its plot (SVG: the energies and every member's height against time, the
//! impacts marked). The animation is [`super::animation_system`].

use serde_json::{Value as Json, json};

use super::json_f64;
use super::plot::{Series, energies_and};
use super::simulation::{
    end_name, end_of, events_json, impact_log, impacts_json, sig, v3, zeno_json,
};
use crate::simulate::body::{Shape, V3};
use crate::simulate::system::{SystemSetup, SystemSimulation};

/// What the system is made of: `3 spheres`, `2 boxes`, `3 bodies (1 sphere, 2 boxes)`,
/// `2 bodies (1 box, 1 rod)`.
fn made_of(setup: &SystemSetup) -> String {
    let of =
        |kind: fn(&Shape) -> bool| setup.members.iter().filter(|m| kind(&m.body.shape)).count();
    let kinds = [
        (
            of(|s| matches!(s, Shape::Sphere { .. })),
            "sphere",
            "spheres",
        ),
        (of(|s| matches!(s, Shape::Box { .. })), "box", "boxes"),
        (of(|s| matches!(s, Shape::Rod { .. })), "rod", "rods"),
    ];
    let count =
        |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    let present: Vec<String> = kinds
        .iter()
        .filter(|(n, ..)| *n > 0)
        .map(|&(n, one, many)| count(n, one, many))
        .collect();
    if present.len() == 1 {
        present[0].clone()
    } else {
        format!(
            "{} ({})",
            count(setup.members.len(), "body", "bodies"),
            present.join(", ")
        )
    }
}

/// The log.
pub fn to_text(name: &str, setup: &SystemSetup, sim: &SystemSimulation) -> String {
    let mut out = format!(
        "{name} — simulated, {}, law {}, f64 (tolerance {})\n",
        made_of(setup),
        setup.law.name(),
        sig(setup.options.tolerance)
    );
    out += &impact_log(&sim.impacts, &sim.events);
    let energy = |k: usize| {
        sim.samples.get(k).map_or_else(String::new, |s| {
            let e = s.kinetic + s.potential;
            if e.is_finite() {
                sig(e)
            } else {
                "(not finite)".to_string()
            }
        })
    };
    out += &format!(
        "ended at {}: {} impact{}, energy {} → {} J; {} steps ({} rejected), drift {} m\n",
        end_of(sim.end, sim.t_end, sim.stopped.as_ref()),
        sim.impacts.len(),
        if sim.impacts.len() == 1 { "" } else { "s" },
        energy(0),
        // a run stopped by an overflow has no energy to print (never `inf` as a result)
        Some(
            sim.state.kinetic_energy(&setup.members)
                + sim
                    .state
                    .potential_energy(&setup.members, &setup.options.gravity)
        )
        .filter(|e| e.is_finite())
        .map_or_else(|| "(not finite)".to_string(), sig),
        sim.steps.0,
        sim.steps.1,
        sig(sim.drift)
    );
    out
}

/// The trajectory as CSV.
pub fn to_csv(setup: &SystemSetup, sim: &SystemSimulation) -> String {
    let mut out = String::from("t");
    for s in &setup.members {
        for c in ["x", "y", "z", "vx", "vy", "vz"] {
            out += &format!(",{} {c}", s.name);
        }
        if s.turns() {
            for c in ["qw", "qi", "qj", "qk", "wx", "wy", "wz"] {
                out += &format!(",{} {c}", s.name);
            }
        }
    }
    out += ",kinetic,potential,closed\n";
    for s in &sim.samples {
        out += &format!("{:e}", s.t);
        for (b, m) in setup.members.iter().enumerate() {
            let (x, v) = (&s.state.x[b], &s.state.v[b]);
            for q in x.iter().chain(v.iter()) {
                out += &format!(",{q:e}");
            }
            if m.turns() {
                let q = s.state.q[b].quaternion();
                for c in [q.w, q.i, q.j, q.k].iter().chain(s.state.w[b].iter()) {
                    out += &format!(",{c:e}");
                }
            }
        }
        out += &format!(",{:e},{:e},{}\n", s.kinetic, s.potential, s.closed);
    }
    out
}

/// The whole run, for programs: the one body's keys ([`super::simulation::to_json`]; `zeno`
/// the accumulation of [`crate::simulate::system::zeno`], or null), the members (`bodies`:
/// name, mass, and a sphere's `radius`, a box's edges `box` or a rod's length `rod`), the
/// options, and the final `state` as one
/// `[x, y, z]` per member in `x` and `v`, one `[w, i, j, k]` in `q` and one `[x, y, z]` in
/// `omega` (a sphere's held: [`crate::simulate::system::members`]). An impact between two
/// members names the first as `feature` and the second as `obstacle`, as the log's `a on b`.
pub fn to_json(name: &str, setup: &SystemSetup, sim: &SystemSimulation) -> Json {
    let o = &setup.options;
    json!({
        "name": name,
        "law": setup.law.name(),
        "tolerance": json_f64(o.tolerance),
        "bodies": setup.members.iter().map(|s| match &s.body.shape {
            Shape::Box { half } => json!({
                "name": s.name,
                "mass": json_f64(s.mass()),
                "box": v3(&(half * 2.0)),
            }),
            Shape::Rod { half_length } => json!({
                "name": s.name,
                "mass": json_f64(s.mass()),
                "rod": json_f64(2.0 * half_length),
            }),
            _ => json!({
                "name": s.name,
                "mass": json_f64(s.mass()),
                "radius": json_f64(s.radius().unwrap_or(0.0)),
            }),
        }).collect::<Vec<_>>(),
        "obstacles": setup.planes.iter().map(|p| p.name.as_str()).collect::<Vec<_>>(),
        "options": {
            "gravity": v3(&o.gravity),
            "duration": json_f64(o.duration),
            "output_step": json_f64(o.output_step),
            "max_impacts": o.max_impacts,
            "simultaneity": json_f64(o.simultaneity),
            "rest_speed": json_f64(o.rest_speed),
        },
        "end": end_name(sim.end),
        "error": sim.stopped.as_ref().map(ToString::to_string),
        "t_end": json_f64(sim.t_end),
        "zeno": zeno_json(sim.zeno.as_ref()),
        "impacts": impacts_json(&sim.impacts),
        "events": events_json(&sim.events),
        "state": {
            "x": sim.state.x.iter().map(v3).collect::<Vec<_>>(),
            "v": sim.state.v.iter().map(v3).collect::<Vec<_>>(),
            "q": sim.state.q.iter().map(|q| {
                let q = q.quaternion();
                [q.w, q.i, q.j, q.k].map(json_f64)
            }).collect::<Vec<_>>(),
            "omega": sim.state.w.iter().map(v3).collect::<Vec<_>>(),
        },
        "steps": sim.steps.0,
        "rejected": sim.steps.1,
        "drift": json_f64(sim.drift),
    })
}

/// The direction the plot's lower chart follows each member along, and its label: up (−g)
/// under gravity, else the animation's horizontal axis (x for a run without gravity).
fn plotted_axis(setup: &SystemSetup) -> (V3, &'static str) {
    let view = super::animation_system::view(setup);
    if setup.options.gravity.norm() > 0.0 {
        (view.vertical, "height (along −g) [m]")
    } else {
        (view.horizontal, "position along x [m]")
    }
}

/// The plot: kinetic, potential and total energy against time (top), every member's height
/// (bottom; without gravity its position along the view's horizontal axis), a vertical mark at
/// every impact ([`super::plot`]).
///
/// # Errors
/// What the plotting library reports.
pub fn to_svg(name: &str, setup: &SystemSetup, sim: &SystemSimulation) -> Result<String, String> {
    let energies: Vec<(f64, f64, f64)> = sim
        .samples
        .iter()
        .map(|s| (s.t, s.kinetic, s.potential))
        .collect();
    let (axis, label) = plotted_axis(setup);
    let paths: Vec<Series> = setup
        .members
        .iter()
        .enumerate()
        .map(|(b, s)| Series {
            label: s.name.clone(),
            points: sim
                .samples
                .iter()
                .map(|p| (p.t, axis.dot(&p.state.x[b])))
                .collect(),
        })
        .collect();
    let impacts: Vec<f64> = sim.impacts.iter().map(|r| r.t).collect();
    energies_and(
        &format!("{name}: energy ({})", setup.law.name()),
        sim.t_end,
        &energies,
        &impacts,
        label,
        &paths,
    )
}
