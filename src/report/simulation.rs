//! What `inertance simulate` reports: the impact log as a table, the whole run as JSON, the
//! trajectory as CSV, and its plot (SVG: the energies and the body's angle against time, the
//! impacts marked).

use serde_json::{Value as Json, json};

use super::json_f64;
use super::plot::{Series, energies_and};
use crate::simulate::run::{End, Event, ImpactRecord, SimulateError, Simulation};
use crate::simulate::{Setup, State};

/// x to six significant digits, as `%g` writes it.
pub fn sig(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    let e = x.abs().log10().floor() as i32;
    if !(-5..6).contains(&e) {
        let t = format!("{x:.5e}");
        let (m, ex) = t.split_once('e').unwrap_or((&t, "0"));
        let m = if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.')
        } else {
            m
        };
        return format!("{m}e{ex}");
    }
    let decimals = (5 - e).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The body's angle (rad): about the plane's normal in a planar motion (signed), else the
/// angle of the rotation from the start's attitude.
pub fn angle(setup: &Setup, s: &State) -> f64 {
    let d = s.q * setup.start.q.inverse();
    match setup.plane {
        Some(n) => {
            let q = d.quaternion();
            2.0 * n.dot(&q.imag()).atan2(q.w)
        }
        None => d.angle(),
    }
}

fn end_text(sim: &Simulation) -> String {
    end_of(sim.end, sim.t_end, sim.stopped.as_ref())
}

/// Why and when a run ended.
pub(crate) fn end_of(end: End, t_end: f64, stopped: Option<&SimulateError>) -> String {
    match end {
        End::Duration => format!("the duration, t = {} s", sig(t_end)),
        End::Impacts => format!("the impact budget, t = {} s", sig(t_end)),
        End::Rest => format!("rest, t = {} s", sig(t_end)),
        End::Stopped => format!(
            "an error, t = {} s ({})",
            sig(t_end),
            stopped.map_or_else(String::new, ToString::to_string)
        ),
    }
}

/// The impact log and the run's summary, for people.
pub fn to_text(name: &str, setup: &Setup, sim: &Simulation) -> String {
    let mut out = format!(
        "{name} — simulated, law {}, f64 (tolerance {})\n",
        setup.law.name(),
        sig(setup.options.tolerance)
    );
    out += &impact_log(&sim.impacts, &sim.events);
    let first = sim.samples.first();
    let energy = |s: &State| {
        setup.body.kinetic_energy(s) - setup.body.mass * setup.options.gravity.dot(&s.x)
    };
    out += &format!(
        "ended at {}: {} impact{}, energy {} → {} J; {} steps ({} rejected), drift {} m\n",
        end_text(sim),
        sim.impacts.len(),
        if sim.impacts.len() == 1 { "" } else { "s" },
        first.map_or_else(String::new, |f| sig(f.kinetic + f.potential)),
        // a run stopped by an overflow has no energy to print (never `inf` as a result)
        Some(energy(&sim.state))
            .filter(|e| e.is_finite())
            .map_or_else(|| "(not finite)".to_string(), sig),
        sim.steps.0,
        sim.steps.1,
        sig(sim.drift)
    );
    out
}

/// The impact log and the events of a run, one body's or a system's: one row per contact
/// struck (`A on B`: a feature or sphere on a plane or sphere).
pub(crate) fn impact_log(impacts: &[ImpactRecord], events: &[Event]) -> String {
    let mut out = String::new();
    // Velocities and impulses below 10⁻¹² of the run's largest are rounding noise of zero.
    let vmax = impacts
        .iter()
        .flat_map(|r| {
            r.contacts
                .iter()
                .flat_map(|c| [c.before.abs(), c.after.abs()])
        })
        .fold(0.0, f64::max);
    let pmax = impacts
        .iter()
        .flat_map(|r| r.contacts.iter().map(|c| c.impulse.abs()))
        .fold(0.0, f64::max);
    let flush = |x: f64, scale: f64| if x.abs() <= 1e-12 * scale { 0.0 } else { x };
    let rows: Vec<[String; 7]> = impacts
        .iter()
        .flat_map(|r| {
            r.contacts.iter().enumerate().map(move |(k, c)| {
                let first = k == 0;
                [
                    if first {
                        r.index.to_string()
                    } else {
                        String::new()
                    },
                    if first { sig(r.t) } else { String::new() },
                    format!(
                        "{} on {}{}",
                        c.feature,
                        c.plane,
                        if c.persisting { " (closed)" } else { "" }
                    ),
                    sig(flush(c.before, vmax)),
                    sig(flush(c.after, vmax)),
                    sig(flush(c.impulse, pmax)),
                    if first {
                        sig(r.kinetic_before - r.kinetic_after)
                    } else {
                        String::new()
                    },
                ]
            })
        })
        .collect();
    let head = [
        "#",
        "t [s]",
        "contacts",
        "ġ⁻ [m/s]",
        "ġ⁺ [m/s]",
        "P [N s]",
        "ΔE_c [J]",
    ];
    let width: Vec<usize> = (0..7)
        .map(|i| {
            rows.iter()
                .map(|r| r[i].chars().count())
                .chain([head[i].chars().count()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: &[String]| -> String {
        let mut s = String::from(" ");
        for (i, c) in cells.iter().enumerate() {
            let pad = width[i] - c.chars().count();
            if i == 2 {
                s += &format!(" {c}{}", " ".repeat(pad));
            } else {
                s += &format!(" {}{c}", " ".repeat(pad));
            }
        }
        s.trim_end().to_string() + "\n"
    };
    if rows.is_empty() {
        out += "  no impact\n";
    } else {
        out += &line(&head.map(String::from));
        for r in &rows {
            out += &line(r);
        }
    }
    for r in impacts {
        for v in &r.verdicts {
            out += &format!("  impact {}: not physical: {v}\n", r.index);
        }
        if let Some(n) = &r.note {
            out += &format!("  impact {}: {n}\n", r.index);
        }
        if r.spread > 0.0 {
            out += &format!(
                "  impact {}: joins contacts up to {} s apart (simultaneity)\n",
                r.index,
                sig(r.spread)
            );
        }
    }
    if !events.is_empty() {
        out += "events:\n";
        for e in events {
            out += &format!("  t = {} s: {}\n", sig(e.t), e.what);
        }
    }
    out
}

/// The whole run, for programs.
pub fn to_json(name: &str, setup: &Setup, sim: &Simulation) -> Json {
    json!({
        "name": name,
        "law": setup.law.name(),
        "tolerance": setup.options.tolerance,
        "end": end_name(sim.end),
        "error": sim.stopped.as_ref().map(ToString::to_string),
        "t_end": json_f64(sim.t_end),
        "zeno": zeno_json(sim.zeno.as_ref()),
        "impacts": impacts_json(&sim.impacts),
        "events": events_json(&sim.events),
        "state": {"x": v3(&sim.state.x), "v": v3(&sim.state.v), "omega": v3(&sim.state.w)},
        "steps": sim.steps.0,
        "rejected": sim.steps.1,
        "drift": json_f64(sim.drift),
    })
}

/// A vector as JSON (a non-finite component as null).
pub(crate) fn v3(v: &nalgebra::Vector3<f64>) -> Json {
    json!([json_f64(v.x), json_f64(v.y), json_f64(v.z)])
}

/// Why a run ended, as the JSON names it.
pub(crate) fn end_name(end: End) -> &'static str {
    match end {
        End::Duration => "duration",
        End::Impacts => "impacts",
        End::Rest => "rest",
        End::Stopped => "stopped",
    }
}

/// The impacts of a run, one body's or a system's, as JSON: per impact its time, spread,
/// kinetic energies, verdicts and note, and per contact struck the two sides (`feature` on
/// `obstacle`: for two spheres the first and the second), the gap, the normal rates before
/// and after, the impulse and whether it was closed.
pub(crate) fn impacts_json(impacts: &[ImpactRecord]) -> Json {
    impacts
        .iter()
        .map(|r| {
            json!({
                "index": r.index,
                "t": json_f64(r.t),
                "spread": json_f64(r.spread),
                "kinetic_before": json_f64(r.kinetic_before),
                "kinetic_after": json_f64(r.kinetic_after),
                "verdicts": r.verdicts,
                "note": r.note,
                "contacts": r.contacts.iter().map(|c| json!({
                    "feature": c.feature,
                    "obstacle": c.plane,
                    "gap": json_f64(c.gap),
                    "before": json_f64(c.before),
                    "after": json_f64(c.after),
                    "impulse": json_f64(c.impulse),
                    "closed": c.persisting,
                })).collect::<Vec<_>>(),
            })
        })
        .collect()
}

/// The events of a run as JSON.
pub(crate) fn events_json(events: &[Event]) -> Json {
    events
        .iter()
        .map(|e| json!({"t": json_f64(e.t), "what": e.what}))
        .collect()
}

/// The trajectory: per sample t, C, the angle, v, ω, the energies and the closed contacts.
pub fn to_csv(setup: &Setup, sim: &Simulation) -> String {
    let mut out = String::from("t,x,y,z,angle,vx,vy,vz,wx,wy,wz,kinetic,potential,energy,closed\n");
    for s in &sim.samples {
        let st = &s.state;
        let row = [
            s.t,
            st.x.x,
            st.x.y,
            st.x.z,
            angle(setup, st),
            st.v.x,
            st.v.y,
            st.v.z,
            st.w.x,
            st.w.y,
            st.w.z,
            s.kinetic,
            s.potential,
            s.kinetic + s.potential,
        ];
        let cells: Vec<String> = row.iter().map(|x| format!("{x:e}")).collect();
        out += &format!("{},{}\n", cells.join(","), s.closed);
    }
    out
}

/// The plot: kinetic, potential and total energy against time (top), the angle (bottom), a
/// vertical mark at every impact ([`super::plot`]).
///
/// # Errors
/// What the plotting library reports.
pub fn to_svg(name: &str, setup: &Setup, sim: &Simulation) -> Result<String, String> {
    let energies: Vec<(f64, f64, f64)> = sim
        .samples
        .iter()
        .map(|s| (s.t, s.kinetic, s.potential))
        .collect();
    let angles = Series {
        label: "angle".to_string(),
        points: sim
            .samples
            .iter()
            .map(|s| (s.t, angle(setup, &s.state)))
            .collect(),
    };
    let impacts: Vec<f64> = sim.impacts.iter().map(|r| r.t).collect();
    energies_and(
        &format!("{name}: energy ({})", setup.law.name()),
        sim.t_end,
        &energies,
        &impacts,
        if setup.plane.is_some() {
            "angle about the plane's normal [rad]"
        } else {
            "rotation from the start [rad]"
        },
        &[angles],
    )
}

/// An accumulation of impacts as JSON (`t_inf`, `after`, `ratio`), or null.
pub(crate) fn zeno_json(zeno: Option<&crate::simulate::run::Zeno>) -> Json {
    zeno.map_or(
        Json::Null,
        |z| json!({"t_inf": json_f64(z.t_inf), "after": z.after, "ratio": json_f64(z.ratio)}),
    )
}
