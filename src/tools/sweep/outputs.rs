//! Which columns a sweep writes and which it plots: the per-model outputs ([`output_names`]),
//! the CSV header and a point's row, and the plotted series named by the user.

use super::SweepError;
use super::plan::Plan;
use super::text::num;
use crate::impact::friction::Restitution;
use crate::impact::restitution::Model;
use crate::impact::solve::SolveError;
use crate::impact::unilateral::UnilateralError;
use crate::number::{format_rational, rational_to_f64};
use crate::report::{ModelReport, Report, Value};
use crate::scene::Scene;
use crate::scene::pipeline::RunError;

/// The per-law outputs, in CSV order (after the `law_` prefix); a frictional sweep adds the
/// energy dissipated by friction, `Ef`.
pub(super) fn output_names(contacts: usize, friction: bool) -> Vec<String> {
    let mut v: Vec<String> = (1..=contacts).map(|i| format!("P{i}")).collect();
    v.extend(
        ["vCx", "vCy", "vCz", "wx", "wy", "wz", "Ep", "dEc"]
            .iter()
            .map(|s| s.to_string()),
    );
    if friction {
        v.push("Ef".into());
    }
    v
}

/// The laws a sweep solves and whether it integrates friction: a frictional sweep (some
/// μ_i > 0 or varied, or `[solve] restitution`) integrates the scene's restitution laws, any
/// other solves its models.
pub(super) fn sweep_laws<'a>(
    base: &Scene,
    mut varied: impl Iterator<Item = &'a str>,
) -> (Vec<Restitution>, bool) {
    let friction = base.frictional() || varied.any(|p| p.ends_with(".mu"));
    let laws = if friction {
        base.restitutions(None)
    } else {
        base.models.iter().map(|&m| Restitution::from(m)).collect()
    };
    (laws, friction)
}

/// The status of a point without an answer, when the physics says why: `singular` (G
/// singular under the simultaneous law), `jammed` (no admissible impulses under the
/// unilateral law), `no-continuation`, `undetermined`, `never-ends` (friction); `None` for an
/// error that stops the sweep.
pub(super) fn point_status(e: &RunError) -> Option<&'static str> {
    match e {
        RunError::Solve(SolveError::Singular { .. }) => Some("singular"),
        RunError::Unilateral(UnilateralError::Jammed { .. }) => Some("jammed"),
        RunError::Friction(f) => f.status(),
        _ => None,
    }
}

/// One plotted line: a model's output.
#[derive(Clone, Debug)]
pub(super) struct Series {
    /// Index into the plan's models.
    pub(super) model: usize,
    /// Index into [`output_names`].
    pub(super) output: usize,
}

/// One solved point.
pub(super) struct Row {
    /// The CSV fields, in [`Plan::header`] order.
    pub(super) fields: Vec<String>,
    /// The first varied value, the plot's x.
    pub(super) x: f64,
    /// The index of the second varied value (0 for a 1-D sweep): which line of the plot.
    pub(super) j: usize,
    /// Per plotted series, its y (NaN at a singular point).
    pub(super) ys: Vec<f64>,
    /// Whether G was singular here.
    pub(super) singular: bool,
    /// The `status` column: `ok`, `singular`, `jammed` or the verdicts joined by `+`.
    pub(super) status: String,
}

/// A model's numeric outputs, in [`output_names`] order.
pub(super) fn model_values(r: &ModelReport) -> Vec<f64> {
    let mut v: Vec<f64> = r.impulses.iter().map(|x| x.f64).collect();
    v.extend(r.velocity.iter().map(|x| x.f64));
    v.extend(r.angular_velocity.iter().map(|x| x.f64));
    v.push(r.lost_velocity_energy.f64);
    v.push(r.kinetic_energy_loss.f64);
    v
}

/// One law's outputs at a solved point, in [`output_names`] order, with their exact texts
/// (P_i, E_p, ΔE_c): from the frictional readout of `law`, or — at a point of a frictional
/// sweep where every μ_i = 0 — from the paper's model of that name, which the integrator
/// equals exactly there (with E_f = 0). `None` when the law was not solved.
pub(super) fn law_values(
    report: &Report,
    law: Restitution,
    friction: bool,
) -> Option<(Vec<f64>, Vec<String>)> {
    let exact = |v: &Value| v.exact.clone().unwrap_or_default();
    if let Some(f) = report.friction.iter().find(|f| f.law == law) {
        let mut v: Vec<f64> = f.contacts.iter().map(|c| c.normal_impulse.f64).collect();
        v.extend(f.velocity.iter().chain(&f.angular_velocity).map(|x| x.f64));
        v.push(f.lost_velocity_energy.f64);
        v.push(f.kinetic_energy_loss.f64);
        v.push(f.friction_dissipation.f64);
        let mut e: Vec<String> = f
            .contacts
            .iter()
            .map(|c| exact(&c.normal_impulse))
            .collect();
        e.push(exact(&f.lost_velocity_energy));
        e.push(exact(&f.kinetic_energy_loss));
        return Some((v, e));
    }
    let model = match law {
        Restitution::Newton => Model::Newton,
        Restitution::Poisson => Model::Poisson,
        Restitution::Energetic => return None,
    };
    let r = report.model(model)?;
    let mut v = model_values(r);
    if friction {
        v.push(0.0);
    }
    let mut e: Vec<String> = r.impulses.iter().map(exact).collect();
    e.push(exact(&r.lost_velocity_energy));
    e.push(exact(&r.kinetic_energy_loss));
    Some((v, e))
}

/// The plotted series for the names asked for (see [`super::SweepOptions::plot_outputs`]).
pub(super) fn resolve_outputs(
    asked: &[String],
    models: &[Restitution],
    contacts: usize,
    friction: bool,
) -> Result<Vec<Series>, SweepError> {
    let names = output_names(contacts, friction);
    let mut out: Vec<Series> = Vec::new();
    let mut push = |s: Series| {
        if !out
            .iter()
            .any(|o| o.model == s.model && o.output == s.output)
        {
            out.push(s);
        }
    };
    if asked.is_empty() {
        for m in 0..models.len() {
            for o in (0..contacts).chain([names.len() - 1]) {
                push(Series {
                    model: m,
                    output: o,
                });
            }
        }
        return Ok(out);
    }
    for name in asked {
        for s in resolve_name(name.trim(), &names, models)? {
            push(s);
        }
    }
    Ok(out)
}

/// The series one name asks for: a column (`newton_P1`) names one, a per-model name (`P1`)
/// one per model solved.
fn resolve_name(
    name: &str,
    names: &[String],
    models: &[Restitution],
) -> Result<Vec<Series>, SweepError> {
    let (model, output) = match name.split_once('_') {
        Some((m, rest)) if Restitution::from_name(m).is_some() => (Restitution::from_name(m), rest),
        _ => (None, name),
    };
    let err = |reason: String| SweepError::Output {
        name: name.to_string(),
        reason,
    };
    if output.ends_with("_exact") {
        return Err(err(format!(
            "plot the f64 column `{}` instead",
            name.trim_end_matches("_exact")
        )));
    }
    let o = names.iter().position(|n| n == output).ok_or_else(|| {
        err(format!(
            "not an output of this sweep; expected one of: {}",
            available(names, models)
        ))
    })?;
    match model {
        None => Ok((0..models.len())
            .map(|m| Series {
                model: m,
                output: o,
            })
            .collect()),
        Some(model) => {
            let m = models.iter().position(|x| *x == model).ok_or_else(|| {
                err(format!(
                    "the scene does not solve the {model} model ([solve] models = [{}])",
                    models
                        .iter()
                        .map(|m| m.name())
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            })?;
            Ok(vec![Series {
                model: m,
                output: o,
            }])
        }
    }
}

/// Every name a plot may ask for, for messages: per-model names, then columns.
fn available(names: &[String], models: &[Restitution]) -> String {
    let mut all: Vec<String> = names.to_vec();
    for m in models {
        all.extend(names.iter().map(|n| format!("{m}_{n}")));
    }
    all.join(", ")
}

impl Plan {
    /// The CSV header: `point`, the varied paths, the per-model outputs, `status`.
    pub(super) fn header(&self) -> Vec<String> {
        let mut h = vec!["point".to_string()];
        for v in &self.vary {
            h.push(v.path.clone());
            if self.exact {
                h.push(format!("{}_exact", v.path));
            }
        }
        let names = output_names(self.contacts, self.friction);
        for m in &self.models {
            for n in &names {
                h.push(format!("{m}_{n}"));
            }
            if self.exact {
                for i in 1..=self.contacts {
                    h.push(format!("{m}_P{i}_exact"));
                }
                h.push(format!("{m}_Ep_exact"));
                h.push(format!("{m}_dEc_exact"));
            }
        }
        h.push("status".into());
        h
    }

    /// The columns per model.
    fn model_width(&self) -> usize {
        let n = self.contacts + 8 + usize::from(self.friction);
        if self.exact { n + self.contacts + 2 } else { n }
    }

    /// Solve point p into its CSV row and plotted values.
    pub(super) fn row(&self, p: usize) -> Result<Row, SweepError> {
        let (values, solved) = self.solve(p)?;
        let status = match &solved {
            Ok(r) => status(r),
            Err(s) => (*s).to_string(),
        };
        let report = solved.ok();
        let mut fields =
            Vec::with_capacity(2 + 2 * values.len() + self.models.len() * self.model_width());
        fields.push(p.to_string());
        for q in &values {
            fields.push(num(rational_to_f64(q)));
            if self.exact {
                fields.push(format_rational(q));
            }
        }
        let mut per_model: Vec<Option<Vec<f64>>> = Vec::with_capacity(self.models.len());
        for m in &self.models {
            let r = report
                .as_ref()
                .and_then(|r| law_values(r, *m, self.friction));
            match &r {
                None => fields.extend(std::iter::repeat_n(String::new(), self.model_width())),
                Some((values, exact)) => {
                    fields.extend(values.iter().map(|&x| num(x)));
                    if self.exact {
                        fields.extend(exact.iter().cloned());
                    }
                }
            }
            per_model.push(r.map(|(v, _)| v));
        }
        let singular = report.is_none();
        fields.push(status.clone());
        let ys = self
            .series
            .iter()
            .map(|s| {
                per_model[s.model]
                    .as_ref()
                    .and_then(|v| v.get(s.output).copied())
                    .unwrap_or(f64::NAN)
            })
            .collect();
        Ok(Row {
            fields,
            x: rational_to_f64(&values[0]),
            j: self.indices(p).1,
            ys,
            singular,
            status,
        })
    }
}

/// A solved point's status: `ok`, or the reasons its simultaneous answer is not physical
/// (`tensile`, `separating`, `still-approaching`, `energy-gain`), across the models, joined
/// by `+` in that order.
pub(super) fn status(report: &crate::report::Report) -> String {
    let names = [
        "tensile",
        "tensile-rate",
        "separating",
        "still-approaching",
        "energy-gain",
        "ambiguous",
        "split-not-unique",
        "unstable-slip",
        "no-continuation",
        "undetermined",
        "never-ends",
    ];
    let found: Vec<&str> = names
        .into_iter()
        .filter(|n| {
            report
                .models
                .iter()
                .any(|m| m.inadmissible.iter().any(|v| v.name() == *n))
                || report.friction.iter().any(|f| f.verdict_names.contains(n))
                || report.friction_failures.iter().any(|(_, _, s)| s == n)
        })
        .collect();
    if found.is_empty() {
        "ok".to_string()
    } else {
        found.join("+")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_resolve_by_column_or_per_model_name() {
        let models = vec![Restitution::Newton, Restitution::Poisson];
        let pairs = |names: &[&str]| -> Vec<(usize, usize)> {
            let asked: Vec<String> = names.iter().map(|s| s.to_string()).collect();
            resolve_outputs(&asked, &models, 2, false)
                .unwrap()
                .iter()
                .map(|s| (s.model, s.output))
                .collect()
        };
        // Default: P1, P2, dEc per model.
        assert_eq!(
            pairs(&[]),
            vec![(0, 0), (0, 1), (0, 9), (1, 0), (1, 1), (1, 9)]
        );
        assert_eq!(pairs(&["dEc"]), vec![(0, 9), (1, 9)]);
        assert_eq!(
            pairs(&["poisson_P2", "newton_Ep", "poisson_P2"]),
            vec![(1, 1), (0, 8)]
        );
        let asked = vec!["P3".to_string()];
        let e = resolve_outputs(&asked, &models, 2, false).unwrap_err();
        assert!(e.to_string().contains("newton_P1"), "{e}");
        let asked = vec!["poisson_P1".to_string()];
        let e = resolve_outputs(&asked, &[Restitution::Newton], 2, false).unwrap_err();
        assert!(e.to_string().contains("poisson"), "{e}");
    }
}
