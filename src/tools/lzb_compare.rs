//! How far the paper's simultaneous law is from the LZB law on a scene, over a range of
//! stiffness ratios (`inertance analyze` on a scene under the LZB law, or with
//! `--lzb-ratios`): so a user learns whether the simultaneous answer can be trusted for it.
//!
//! The LZB outcome depends on the ratios of the contacts' stiffnesses, the simultaneous one
//! does not. For each ratio r, contact 1's stiffness is K₁ r (the other contacts' as the scene
//! writes them, η and e too) and the LZB impact is integrated
//! ([`crate::impact::multiple::solve_lzb`]); the simultaneous law's answer for each of the
//! scene's models is solved once on the same mechanism. Two gaps are reported per model:
//!
//! * the twist: ‖{v}_sim − {v}_LZB‖ / ‖{v}⁰‖ in the kinetic-energy norm ‖{v}‖² = 2T({v}) (the
//!   mass matrix's), so that angular and linear velocities of every body weigh as they move
//!   energy — 0 when the answers agree, 1 when they differ by as much motion as there was;
//! * the kinetic energy after impact: T_sim − T_LZB (J), also relative to T⁰.

use crate::impact::mechanism::Mechanism;
use crate::impact::multiple::{ContactLaw, LzbError, solve_lzb};
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::impact::unilateral::Law;
use crate::mechanics::screw::Screws;
use crate::scene::Scene;
use crate::scene::lzb::{contact_laws, num};
use crate::scene::pipeline::{RunError, friction_tolerance, prepare};

/// The ratios compared when none are given: from 1/100 to 100.
pub const DEFAULT_RATIOS: [f64; 9] = [0.01, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0, 10.0, 100.0];

/// The gap between one simultaneous model's answer and the LZB one at one ratio.
#[derive(Clone, Debug, PartialEq)]
pub struct Gap {
    /// ‖{v}_sim − {v}_LZB‖ / ‖{v}⁰‖ in the kinetic-energy norm.
    pub twist: f64,
    /// T_sim − T_LZB after impact (J).
    pub energy: f64,
}

/// One ratio: the LZB impulses and, per model, the gap (`None` for a model without an
/// answer); `None` as a whole for an integration that did not end within its budget.
#[derive(Clone, Debug, PartialEq)]
pub struct RatioRow {
    /// r: contact 1's stiffness is K₁ r.
    pub ratio: f64,
    /// The LZB impulses and per model the gaps, or `None` (runaway).
    pub outcome: Option<(Vec<f64>, Vec<Option<Gap>>)>,
}

/// The comparison over the ratios.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// The scene's models, in order.
    pub models: Vec<Model>,
    /// Per model, why it has no answer (`None` when it has one).
    pub simultaneous: Vec<Option<String>>,
    /// T⁰ (J).
    pub kinetic_energy_before: f64,
    /// K₁ as the scene writes it.
    pub stiffness: f64,
    /// Per ratio.
    pub rows: Vec<RatioRow>,
}

/// Compare the simultaneous law (`models`, the scene's when `None`) with the LZB law on `scene`
/// at each of `ratios` (module docs), the LZB integration held to the scene's tolerance (else
/// ε^(2/3)).
///
/// # Errors
/// [`RunError`]: the scene's bad input (`[solve] restitution`, LZB parameters out of range), a
/// contact with friction (the simultaneous side of the comparison is the paper's frictionless
/// solve, so the two answers would not be of one physics), or an LZB error other than a runaway
/// integration (which is a row without outcome).
pub fn compare(
    scene: &Scene,
    ratios: &[f64],
    models: Option<&[Model]>,
) -> Result<Comparison, RunError> {
    if let Some(i) = scene.first_rough_contact() {
        return Err(RunError::Scene(crate::scene::SceneError {
            file: scene.file.clone(),
            key: format!("contact[{i}].mu"),
            value: Some(scene.contacts[i].mu.text.clone()),
            message: "the comparison of the LZB law with the simultaneous law is frictionless \
                      (its simultaneous side is the paper's frictionless solve): set `mu = 0` to \
                      compare, or solve the scene under each law (`inertance solve --law lzb`, \
                      `--law simultaneous`)"
                .to_string(),
        }));
    }
    if scene.law != Law::Lzb {
        // `[solve] restitution` named by key, as `--law lzb` names it.
        scene
            .clone()
            .set_law(Law::Lzb, "the LZB law (`--lzb-ratios`)")?;
    }
    let laws = contact_laws(scene)?;
    let tolerance = scene.tolerance.unwrap_or_else(friction_tolerance::<f64>);
    let models = models.unwrap_or(&scene.models).to_vec();
    if scene.system.is_some() {
        compare_on(&scene.system::<f64>()?, models, &laws, ratios, tolerance)
    } else {
        compare_on(&prepare::<f64>(scene)?, models, &laws, ratios, tolerance)
    }
}

fn compare_on<M: Mechanism<f64>>(
    mechanism: &M,
    models: Vec<Model>,
    laws: &[ContactLaw],
    ratios: &[f64],
    tolerance: f64,
) -> Result<Comparison, RunError> {
    let t0 = mechanism.kinetic_energy(mechanism.velocity());
    let mut answers: Vec<Result<Outcome<f64, M::Screw>, String>> = Vec::new();
    match Impact::assemble(mechanism) {
        Ok(mut impact) => {
            for &model in &models {
                let mut sim = Outcome::default();
                answers.push(
                    impact
                        .solve(model, &mut sim)
                        .map(|()| sim)
                        .map_err(|e| e.to_string()),
                );
            }
        }
        Err(e) => answers.extend(models.iter().map(|_| Err(e.to_string()))),
    }
    let norm = |v: &M::Screw| (2.0 * mechanism.kinetic_energy(v)).max(0.0).sqrt();
    let scale = norm(mechanism.velocity());
    let mut rows = Vec::new();
    for &ratio in ratios {
        let mut scaled = laws.to_vec();
        if let Some(first) = scaled.first_mut() {
            first.stiffness *= ratio;
        }
        let out = match solve_lzb(mechanism, &scaled, tolerance) {
            Ok(out) => out,
            Err(LzbError::Runaway { .. }) => {
                rows.push(RatioRow {
                    ratio,
                    outcome: None,
                });
                continue;
            }
            Err(e) => return Err(e.into()),
        };
        let t_lzb = mechanism.kinetic_energy(&out.velocity);
        let gaps = answers
            .iter()
            .map(|a| {
                a.as_ref().ok().map(|sim| Gap {
                    twist: if scale > 0.0 {
                        norm(&sim.velocity.minus(&out.velocity)) / scale
                    } else {
                        0.0
                    },
                    energy: mechanism.kinetic_energy(&sim.velocity) - t_lzb,
                })
            })
            .collect();
        rows.push(RatioRow {
            ratio,
            outcome: Some((out.impulses, gaps)),
        });
    }
    Ok(Comparison {
        models,
        simultaneous: answers.into_iter().map(Result::err).collect(),
        kinetic_energy_before: t0,
        stiffness: laws.first().map_or(1.0, |l| l.stiffness),
        rows,
    })
}

impl Comparison {
    /// The largest twist gap of `model` (an index into `models`) over the ratios.
    pub fn largest_gap(&self, model: usize) -> Option<f64> {
        self.rows
            .iter()
            .filter_map(|r| r.outcome.as_ref())
            .filter_map(|(_, gaps)| gaps[model].as_ref().map(|g| g.twist))
            .reduce(f64::max)
    }

    /// The readable section.
    pub fn to_text(&self) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        let n = self
            .rows
            .iter()
            .find_map(|r| r.outcome.as_ref().map(|o| o.0.len()))
            .unwrap_or(0);
        let _ = writeln!(
            s,
            "\nThe simultaneous law against the LZB law (Liu, Zhao & Brogliato 2008):\n  contact \
             1's stiffness K₁ r (K₁ = {}), the other contacts' and every η and e as the scene \
             writes them; twist gap ‖v_sim − v_LZB‖/‖v⁰‖ in the kinetic-energy norm, ΔT = \
             T_sim − T_LZB after impact (T⁰ = {} J).",
            num(self.stiffness),
            num(self.kinetic_energy_before)
        );
        for (m, why) in self.models.iter().zip(&self.simultaneous) {
            if let Some(e) = why {
                let _ = writeln!(s, "  simultaneous {}: no answer ({e})", m.name());
            }
        }
        let mut rows = vec![{
            let mut h = vec!["r".to_string()];
            h.extend((1..=n).map(|i| format!("P{i} LZB [N s]")));
            for m in &self.models {
                h.push(format!("twist gap {}", m.name()));
                h.push(format!("ΔT {} [J]", m.name()));
            }
            h
        }];
        for r in &self.rows {
            let mut row = vec![num(r.ratio)];
            match &r.outcome {
                None => {
                    row.push("the LZB integration did not end within its budget".into());
                }
                Some((p, gaps)) => {
                    row.extend(p.iter().map(|x| num(*x)));
                    for g in gaps {
                        match g {
                            Some(g) => {
                                row.push(format!("{:.2} %", 100.0 * g.twist));
                                row.push(num(g.energy));
                            }
                            None => row.extend(["—".to_string(), "—".to_string()]),
                        }
                    }
                }
            }
            rows.push(row);
        }
        let cols = rows.iter().map(Vec::len).max().unwrap_or(0);
        let widths: Vec<usize> = (0..cols)
            .map(|k| {
                rows.iter()
                    .filter(|r| r.len() > 1 && r.len() == cols)
                    .map(|r| r.get(k).map_or(0, |c| c.chars().count()))
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        for r in &rows {
            let mut line = String::from(" ");
            for (k, cell) in r.iter().enumerate() {
                let pad = widths
                    .get(k)
                    .copied()
                    .unwrap_or(0)
                    .saturating_sub(cell.chars().count());
                line.push_str("  ");
                line.push_str(&" ".repeat(pad));
                line.push_str(cell);
            }
            let _ = writeln!(s, "{}", line.trim_end());
        }
        for (k, m) in self.models.iter().enumerate() {
            if let Some(g) = self.largest_gap(k) {
                let verdict = if g <= 0.01 {
                    "the simultaneous answer can be trusted here"
                } else {
                    "the simultaneous answer depends on the contacts' stiffnesses here: trust it \
                     only where the gap is small, or solve with `--law lzb`"
                };
                let (lo, hi) = (
                    num(self.rows.first().map_or(1.0, |r| r.ratio)),
                    num(self.rows.last().map_or(1.0, |r| r.ratio)),
                );
                let (largest, over) = if lo == hi {
                    ("twist gap", format!("at r = {lo}"))
                } else {
                    ("largest twist gap", format!("over r = {lo}…{hi}"))
                };
                let _ = writeln!(
                    s,
                    "  {}: {largest} {:.2} % {over}: {verdict}.",
                    m.name(),
                    100.0 * g,
                );
            }
        }
        s
    }

    /// The JSON section (`"lzb"` of `analyze --json`).
    pub fn to_json(&self) -> serde_json::Value {
        use crate::report::json_f64;
        use serde_json::json;
        let models: Vec<&str> = self.models.iter().map(|m| m.name()).collect();
        let simultaneous: serde_json::Map<String, serde_json::Value> = self
            .models
            .iter()
            .zip(&self.simultaneous)
            .map(|(m, a)| {
                (
                    m.name().to_string(),
                    match a {
                        None => json!({"status": "ok"}),
                        Some(e) => json!({"error": e}),
                    },
                )
            })
            .collect();
        let rows: Vec<serde_json::Value> = self
            .rows
            .iter()
            .map(|r| match &r.outcome {
                None => json!({"ratio": json_f64(r.ratio), "status": "runaway"}),
                Some((p, gaps)) => {
                    let g: serde_json::Map<String, serde_json::Value> = models
                        .iter()
                        .zip(gaps)
                        .map(|(m, g)| {
                            (
                                m.to_string(),
                                match g {
                                    Some(g) => json!({"twist_gap": json_f64(g.twist), "energy_gap": json_f64(g.energy)}),
                                    None => serde_json::Value::Null,
                                },
                            )
                        })
                        .collect();
                    json!({
                        "ratio": json_f64(r.ratio),
                        "status": "ok",
                        "impulses": p.iter().map(|x| json_f64(*x)).collect::<Vec<_>>(),
                        "gaps": g,
                    })
                }
            })
            .collect();
        json!({
            "varied": "contact[0].stiffness",
            "stiffness": json_f64(self.stiffness),
            "kinetic_energy_before": json_f64(self.kinetic_energy_before),
            "simultaneous": simultaneous,
            "ratios": rows,
        })
    }
}
