//! What `inertance simulate` reports: the impact log as a table, the whole run as JSON, the
//! trajectory as CSV, and its plot (SVG: the energies and the body's angle against time, the
//! impacts marked).

use plotters::prelude::*;
use serde_json::{Value as Json, json};

use super::json_f64;
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
    let v3 = |v: &nalgebra::Vector3<f64>| json!([json_f64(v.x), json_f64(v.y), json_f64(v.z)]);
    json!({
        "name": name,
        "law": setup.law.name(),
        "tolerance": setup.options.tolerance,
        "end": end_name(sim.end),
        "error": sim.stopped.as_ref().map(ToString::to_string),
        "t_end": json_f64(sim.t_end),
        "zeno": sim.zeno.as_ref().map(|z| json!({"t_inf": json_f64(z.t_inf), "after": z.after, "ratio": json_f64(z.ratio)})),
        "impacts": impacts_json(&sim.impacts),
        "events": events_json(&sim.events),
        "state": {"x": v3(&sim.state.x), "v": v3(&sim.state.v), "omega": v3(&sim.state.w)},
        "steps": sim.steps.0,
        "rejected": sim.steps.1,
        "drift": json_f64(sim.drift),
    })
}

/// How a run ended, as the JSON names it.
pub fn end_name(end: End) -> &'static str {
    match end {
        End::Duration => "duration",
        End::Impacts => "impacts",
        End::Rest => "rest",
        End::Stopped => "stopped",
    }
}

/// The impact log for programs (one body's or a system's: a contact between two spheres names
/// the first as its `feature` and the second as its `obstacle`).
pub fn impacts_json(impacts: &[ImpactRecord]) -> Json {
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

/// The other events for programs.
pub fn events_json(events: &[Event]) -> Json {
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
/// vertical mark at every impact.
///
/// # Errors
/// What the plotting library reports.
pub fn to_svg(name: &str, setup: &Setup, sim: &Simulation) -> Result<String, String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let t1 = sim.t_end.max(f64::MIN_POSITIVE);
    let energies: Vec<(f64, f64, f64)> = sim
        .samples
        .iter()
        .map(|s| (s.kinetic, s.potential, s.kinetic + s.potential))
        .collect();
    let base = 0.0_f64;
    let (e0, e1) = energies
        .iter()
        .flat_map(|&(k, p, e)| [k, p, e])
        .fold((base, base), |(lo, hi), y| (lo.min(y), hi.max(y)));
    let pad = 0.05 * (e1 - e0).max(f64::MIN_POSITIVE);
    let angles: Vec<f64> = sim.samples.iter().map(|s| angle(setup, &s.state)).collect();
    let (a0, a1) = angles
        .iter()
        .fold((0.0f64, 0.0f64), |(lo, hi), &y| (lo.min(y), hi.max(y)));
    let apad = 0.05 * (a1 - a0).max(1e-9);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 720)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let (top, bottom) = root.split_vertically(360);
        let mut chart = ChartBuilder::on(&top)
            .caption(
                format!("{name}: energy ({})", setup.law.name()),
                ("sans-serif", 20),
            )
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(0.0..t1, (e0 - pad)..(e1 + pad))
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc("energy [J]")
            .draw()
            .map_err(|e| err(&e))?;
        let series: [(&str, RGBColor, fn(&(f64, f64, f64)) -> f64); 3] = [
            ("kinetic", RGBColor(31, 119, 180), |e| e.0),
            ("potential", RGBColor(44, 160, 44), |e| e.1),
            ("total", RGBColor(0, 0, 0), |e| e.2),
        ];
        for (label, colour, pick) in series {
            chart
                .draw_series(LineSeries::new(
                    sim.samples
                        .iter()
                        .zip(&energies)
                        .map(|(s, e)| (s.t, pick(e))),
                    colour.stroke_width(2),
                ))
                .map_err(|e| err(&e))?
                .label(label)
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 2), (x + 20, y + 2)], colour.filled())
                });
        }
        let red = RGBColor(214, 39, 40);
        chart
            .draw_series(
                sim.impacts.iter().map(|r| {
                    PathElement::new(vec![(r.t, e0 - pad), (r.t, e1 + pad)], red.mix(0.4))
                }),
            )
            .map_err(|e| err(&e))?
            .label("impact")
            .legend(move |(x, y)| Rectangle::new([(x, y - 2), (x + 20, y + 2)], red.filled()));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| err(&e))?;
        let mut chart = ChartBuilder::on(&bottom)
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(0.0..t1, (a0 - apad)..(a1 + apad))
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc(if setup.plane.is_some() {
                "angle about the plane's normal [rad]"
            } else {
                "rotation from the start [rad]"
            })
            .draw()
            .map_err(|e| err(&e))?;
        chart
            .draw_series(LineSeries::new(
                sim.samples.iter().zip(&angles).map(|(s, &a)| (s.t, a)),
                RGBColor(148, 103, 189).stroke_width(2),
            ))
            .map_err(|e| err(&e))?;
        chart
            .draw_series(
                sim.impacts.iter().map(|r| {
                    PathElement::new(vec![(r.t, a0 - apad), (r.t, a1 + apad)], red.mix(0.4))
                }),
            )
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    Ok(svg)
}
