//! The LZB law's outputs beyond the text table ([`LzbReport::to_table`]): the JSON report
//! (`inertance solve --json`) and the impulse history (`--trajectory FILE.csv|.json|.svg`), one
//! sample per accepted step of the integration ([`crate::impact::multiple::Sample`]).
//!
//! The JSON keys are a public contract (guide/multiple-impacts.md), as those of the other
//! reports. Contacts and events number contacts from 1, as the table does (A1, A2, …).

use plotters::prelude::*;
use serde_json::{Value as Json, json};

use super::json_f64;
use super::trajectory::cell;
use crate::impact::multiple::Sample;
use crate::scene::lzb::LzbReport;

/// Line colours, one per contact (Tableau 10, as the sweep's plot), shared with the LZB sweep's
/// plot.
pub(crate) const PALETTE: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

/// What a panel of the history's plot draws of a sample.
type Pick = fn(&Sample) -> &[f64];

fn list(v: &[f64]) -> Json {
    Json::Array(v.iter().map(|&x| json_f64(x)).collect())
}

impl LzbReport {
    /// The JSON report (keys in guide/multiple-impacts.md): per contact its law, v⁰, P, v,
    /// E_max, W_c, W_r, the dissipation W_c − W_r, its tangential impulse τ (empty when
    /// frictionless) and the energy friction dissipated there, W_f; each body's twist after
    /// impact; ΔE_c, the dissipation (W_c − W_r), the friction dissipation (W_f) and the
    /// energy residual ΔE_c − Σ (W_c − W_r + W_f); the events; the order in which the contacts came
    /// to rest; the integration's tolerance, error estimate and statistics.
    pub fn to_json(&self) -> Json {
        let contacts: Vec<Json> = (0..self.impulses.len())
            .map(|i| {
                let l = &self.laws[i];
                json!({
                    "contact": i + 1,
                    "law": {
                        "stiffness": json_f64(l.stiffness),
                        "exponent": json_f64(l.exponent),
                        "restitution": json_f64(l.restitution),
                    },
                    "velocity_before": json_f64(self.before[i]),
                    "impulse": json_f64(self.impulses[i]),
                    "velocity_after": json_f64(self.after[i]),
                    "max_potential_energy": json_f64(self.max_energy[i]),
                    "work_compression": json_f64(self.work_compression[i]),
                    "work_expansion": json_f64(self.work_expansion[i]),
                    "dissipation": json_f64(self.work_compression[i] - self.work_expansion[i]),
                    "tangential_impulse": self.tangential[i].iter().map(|x| json_f64(*x)).collect::<Vec<_>>(),
                    "friction_dissipation": json_f64(self.friction_dissipation[i]),
                })
            })
            .collect();
        let twists: Vec<Json> = self
            .twists
            .iter()
            .map(|(name, w, v)| {
                json!({
                    "body": name,
                    "angular_velocity": w.map(json_f64),
                    "velocity": v.map(json_f64),
                })
            })
            .collect();
        let events: Vec<Json> = self
            .events
            .iter()
            .map(|e| json!({"tau": json_f64(e.tau), "contact": e.contact + 1, "kind": e.kind.name()}))
            .collect();
        let dissipation: f64 = (0..self.impulses.len())
            .map(|i| self.work_compression[i] - self.work_expansion[i])
            .sum();
        json!({
            "scene": self.name,
            "scalar": self.scalar,
            "law": "lzb",
            "contacts": contacts,
            "twist_after": twists,
            "kinetic_energy_loss": json_f64(self.kinetic_energy_loss),
            "dissipation": json_f64(dissipation),
            "friction_dissipation": json_f64(self.friction_dissipation.iter().sum::<f64>()),
            "energy_residual": json_f64(self.energy_residual),
            "events": events,
            "ending_order": self.ending_order.iter().map(|i| i + 1).collect::<Vec<_>>(),
            "integration": {
                "tolerance": json_f64(self.tolerance),
                "error_estimate": json_f64(self.error_estimate),
                "accepted_steps": self.stats.accepted,
                "rejected_steps": self.stats.rejected,
                "events": self.stats.events,
                "end": json_f64(self.end),
            },
        })
    }

    /// The impulse history as CSV: one row per sample, the columns `tau`, `primary` (the
    /// primary contact, from 1), then per contact i (from 1) `P{i}` (N s), `v{i}` (m/s,
    /// positive approaching) and `E{i}` (J, its potential energy), and for a rough contact its
    /// tangential impulse and slip velocity along its unit tangent axes: `tau{i}` and `vt{i}`
    /// in a plane (the contact's y sense), `tau{i}y`, `tau{i}z`, `vt{i}y`, `vt{i}z` in space.
    pub fn history_csv(&self) -> String {
        let n = self.impulses.len();
        let dims: Vec<usize> = (0..n).map(|i| self.tangential[i].len()).collect();
        let axes = |d: usize| -> &'static [&'static str] {
            match d {
                0 => &[],
                1 => &[""],
                _ => &["y", "z"],
            }
        };
        let mut out = String::from("tau,primary");
        for i in 1..=n {
            out += &format!(",P{i},v{i},E{i}");
            for a in axes(dims[i - 1]) {
                out += &format!(",tau{i}{a}");
            }
            for a in axes(dims[i - 1]) {
                out += &format!(",vt{i}{a}");
            }
        }
        out.push('\n');
        for s in &self.samples {
            out += &format!("{},{}", cell(s.tau), s.primary + 1);
            for i in 0..n {
                out += &format!(
                    ",{},{},{}",
                    cell(s.impulses[i]),
                    cell(s.velocities[i]),
                    cell(s.energies[i])
                );
                for x in s.tangential[i].iter().chain(&s.slips[i]) {
                    out += &format!(",{}", cell(*x));
                }
            }
            out.push('\n');
        }
        out
    }

    /// The impulse history as JSON: `{"law": "lzb", "samples": [{"tau", "primary",
    /// "impulses", "velocities", "energies", "tangential", "slips"}]}`, contacts numbered from
    /// 1 in `primary`; `tangential` and `slips` hold per contact its tangential impulse and
    /// slip velocity along its unit tangent axes (an empty list for a frictionless contact).
    pub fn history_json(&self) -> Json {
        let samples: Vec<Json> = self
            .samples
            .iter()
            .map(|s| {
                json!({
                    "tau": json_f64(s.tau),
                    "primary": s.primary + 1,
                    "impulses": list(&s.impulses),
                    "velocities": list(&s.velocities),
                    "energies": list(&s.energies),
                    "tangential": s.tangential.iter().map(|t| list(t)).collect::<Vec<_>>(),
                    "slips": s.slips.iter().map(|t| list(t)).collect::<Vec<_>>(),
                })
            })
            .collect();
        json!({"law": "lzb", "scalar": self.scalar, "samples": samples})
    }

    /// The impulse history as an SVG: above, each contact's impulse P_i against τ; below, its
    /// velocity v_i; one line per contact in each, in the contact's colour.
    ///
    /// # Errors
    /// What the plotting library reports.
    pub fn history_svg(&self) -> Result<String, String> {
        let err = |e: &dyn std::fmt::Display| e.to_string();
        let n = self.impulses.len();
        let taus: Vec<f64> = self.samples.iter().map(|s| s.tau).collect();
        let x1 = taus
            .iter()
            .copied()
            .fold(0.0_f64, f64::max)
            .max(f64::MIN_POSITIVE);
        let range = |pick: Pick| {
            let (lo, hi) = self
                .samples
                .iter()
                .flat_map(|s| pick(s).iter().copied())
                .fold((0.0_f64, 0.0_f64), |(lo, hi), y| (lo.min(y), hi.max(y)));
            let pad = 0.05 * (hi - lo).max(f64::MIN_POSITIVE);
            (lo - pad, hi + pad)
        };
        let impulses: Pick = |s| &s.impulses;
        let velocities: Pick = |s| &s.velocities;
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (960, 720)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| err(&e))?;
            let (top, bottom) = root.split_vertically(360);
            // Per panel: its area, the y axis, the legend's symbol, the y range, what it draws.
            let panels = [
                (&top, "impulse P_i [N s]", "P", range(impulses), impulses),
                (
                    &bottom,
                    "velocity v_i [m/s], positive approaching",
                    "v",
                    range(velocities),
                    velocities,
                ),
            ];
            for (k, (area, y_desc, symbol, (y0, y1), pick)) in panels.into_iter().enumerate() {
                let mut chart = ChartBuilder::on(area)
                    .caption(
                        if k == 0 {
                            format!("{}: LZB impulse history", self.name)
                        } else {
                            String::new()
                        },
                        ("sans-serif", 20),
                    )
                    .margin(15)
                    .x_label_area_size(40)
                    .y_label_area_size(80)
                    .build_cartesian_2d(0.0..x1, y0..y1)
                    .map_err(|e| err(&e))?;
                chart
                    .configure_mesh()
                    .x_desc("τ (P_j grows as F_j dτ)")
                    .y_desc(y_desc)
                    .draw()
                    .map_err(|e| err(&e))?;
                for i in 0..n {
                    let (r, g, b) = PALETTE[i % PALETTE.len()];
                    let colour = RGBColor(r, g, b);
                    chart
                        .draw_series(LineSeries::new(
                            self.samples.iter().map(|s| (s.tau, pick(s)[i])),
                            colour.stroke_width(2),
                        ))
                        .map_err(|e| err(&e))?
                        .label(format!("{symbol}{}", i + 1))
                        .legend(move |(x, y)| {
                            Rectangle::new([(x, y - 2), (x + 20, y + 2)], colour.filled())
                        });
                }
                chart
                    .configure_series_labels()
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .position(SeriesLabelPosition::UpperRight)
                    .draw()
                    .map_err(|e| err(&e))?;
            }
            root.present().map_err(|e| err(&e))?;
        }
        Ok(svg)
    }
}
