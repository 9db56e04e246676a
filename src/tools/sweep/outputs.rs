//! Which columns a sweep writes and which it plots: the per-model outputs ([`output_names`]),
//! the CSV header and a point's row, and the plotted series named by the user.

use super::SweepError;
use super::answer::Answer;
use super::cells::Cells;
use super::plan::Plan;
use super::text::num;
use crate::impact::friction::Restitution;
use crate::impact::outputs::Outputs;
use crate::impact::restitution::Model;
use crate::impact::solve::SolveError;
use crate::impact::unilateral::UnilateralError;
use crate::number::{format_rational, rational_to_f64};
use crate::report::system::SystemReport;
use crate::report::{Report, Value};
use crate::scene::Scene;
use crate::scene::pipeline::RunError;

/// The per-law outputs, in CSV order (after the `law_` prefix); a frictional sweep adds the
/// energy dissipated by friction, `Ef`.
///
/// A system's bodies (`bodies`, empty for one body) each give their six, named
/// `BODY.vCx` … `BODY.wz`.
pub(super) fn output_names(contacts: usize, friction: bool, bodies: &[String]) -> Vec<String> {
    const TWIST: [&str; 6] = ["vCx", "vCy", "vCz", "wx", "wy", "wz"];
    let mut v: Vec<String> = (1..=contacts).map(|i| format!("P{i}")).collect();
    if bodies.is_empty() {
        v.extend(TWIST.iter().map(|s| s.to_string()));
    } else {
        for b in bodies {
            v.extend(TWIST.iter().map(|s| format!("{b}.{s}")));
        }
    }
    v.extend(["Ep", "dEc"].iter().map(|s| s.to_string()));
    if friction {
        v.push("Ef".into());
    }
    v
}

/// What the solve computes for a sweep: the outputs its columns hold (impulses, the twist,
/// E_p and ΔE_c), whatever the scene's `[solve] outputs` print. The tangent frames and the
/// tangential inertances and velocities, which no column holds, were about a third of the
/// assembly; an output asked for is bit for bit the one every output gives
/// ([`crate::impact::outputs`]).
pub(super) fn written_outputs() -> Outputs {
    Outputs::IMPULSES | Outputs::TWIST | Outputs::ENERGIES
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

/// One plotted line: a model's output, or its derivative with respect to a varied input.
#[derive(Clone, Debug)]
pub(super) struct Series {
    /// Index into the plan's models.
    pub(super) model: usize,
    /// Index into [`output_names`].
    pub(super) output: usize,
    /// The derivative with respect to this varied input (an index into the plan's `vary`),
    /// or the output itself.
    pub(super) wrt: Option<usize>,
}

/// One solved point.
pub(super) struct Row {
    /// The CSV fields, in [`Plan::header`] order.
    pub(super) fields: Cells,
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

/// The indices among [`output_names`] that also get an exact column: P_i, E_p, ΔE_c (for
/// `bodies` bodies, one for a single body).
pub(super) fn exact_outputs(contacts: usize, bodies: usize) -> impl Iterator<Item = usize> {
    let twists = 6 * bodies.max(1);
    (0..contacts).chain([contacts + twists, contacts + twists + 1])
}

/// One law's outputs at a solved point, in [`output_names`] order: from the frictional
/// readout of `law`, or — at a point of a frictional sweep where every μ_i = 0 — from the
/// paper's model of that name, which the integrator equals exactly there (with E_f = 0, whose
/// derivative is 0 too: no μ_i moves at such a point unless seeded, which makes it frictional).
/// `None` when the law was not solved.
pub(super) fn law_outputs(answer: &Answer, law: Restitution, friction: bool) -> Option<Vec<Value>> {
    match answer {
        Answer::Body(r) => body_outputs(r, law, friction),
        Answer::System(r) => system_outputs(r, law, friction),
    }
}

/// The paper's model a restitution law is (`None` for the energetic law, which is not one).
fn model_of(law: Restitution) -> Option<Model> {
    match law {
        Restitution::Newton => Some(Model::Newton),
        Restitution::Poisson => Some(Model::Poisson),
        Restitution::Energetic => None,
    }
}

/// Outputs in [`output_names`] order: the impulses, the twist values (a body's v_C then ω,
/// body after body), E_p, ΔE_c, then E_f when given.
fn in_order<'a>(
    impulses: impl Iterator<Item = &'a Value>,
    twists: impl Iterator<Item = &'a Value>,
    energies: [&'a Value; 2],
    friction: Option<Value>,
) -> Vec<Value> {
    let mut v: Vec<Value> = impulses.chain(twists).chain(energies).cloned().collect();
    v.extend(friction);
    v
}

/// [`law_outputs`] of one body's report.
pub(super) fn body_outputs(
    report: &Report,
    law: Restitution,
    friction: bool,
) -> Option<Vec<Value>> {
    if let Some(f) = report.friction.iter().find(|f| f.law == law) {
        return Some(in_order(
            f.contacts.iter().map(|c| &c.normal_impulse),
            f.velocity.iter().chain(&f.angular_velocity),
            [&f.lost_velocity_energy, &f.kinetic_energy_loss],
            Some(f.friction_dissipation.clone()),
        ));
    }
    let r = report.model(model_of(law)?)?;
    Some(in_order(
        r.impulses.iter(),
        r.velocity.iter().chain(&r.angular_velocity),
        [&r.lost_velocity_energy, &r.kinetic_energy_loss],
        friction.then(|| zero_like(&r.kinetic_energy_loss)),
    ))
}

/// [`law_outputs`] of a system's report: each body's twist in turn.
pub(super) fn system_outputs(
    report: &SystemReport,
    law: Restitution,
    friction: bool,
) -> Option<Vec<Value>> {
    fn twists(t: &[([Value; 3], [Value; 3])]) -> impl Iterator<Item = &Value> {
        t.iter().flat_map(|(w, vc)| vc.iter().chain(w))
    }
    if let Some(f) = report.friction.iter().find(|f| f.law == law) {
        return Some(in_order(
            f.contacts.iter().map(|c| &c.normal_impulse),
            twists(&f.twists),
            [&f.lost_velocity_energy, &f.kinetic_energy_loss],
            Some(f.friction_dissipation.clone()),
        ));
    }
    let model = model_of(law)?;
    let m = report.models.iter().find(|m| m.model == model)?;
    Some(in_order(
        m.impulses.iter(),
        twists(&m.twists),
        [&m.lost_velocity_energy, &m.kinetic_energy_loss],
        friction.then(|| zero_like(&m.kinetic_energy_loss)),
    ))
}

/// Zero in the form of `v`: with an exact text and a derivative when `v` has them.
fn zero_like(v: &Value) -> Value {
    let zero = |v: &Value| Value {
        exact: v.exact.as_ref().map(|_| "0".to_string()),
        ..Value::float(0.0)
    };
    Value {
        derivative: v.derivative.as_deref().map(|d| Box::new(zero(d))),
        ..zero(v)
    }
}

/// One law's outputs at a solved point as f64, in [`output_names`] order (see
/// [`law_outputs`]).
pub(super) fn law_values(answer: &Answer, law: Restitution, friction: bool) -> Option<Vec<f64>> {
    Some(
        law_outputs(answer, law, friction)?
            .iter()
            .map(|x| x.f64)
            .collect(),
    )
}

/// A derivative as a CSV cell and a plotted y: empty and NaN when it does not exist or is not
/// finite.
fn derivative_cell(v: &Value) -> (String, f64) {
    match v.derivative.as_deref() {
        Some(d) if d.f64.is_finite() => (num(d.f64), d.f64),
        _ => (String::new(), f64::NAN),
    }
}

/// The exact text of a derivative (`--exact`), empty when there is none.
fn derivative_exact(v: &Value) -> String {
    match v.derivative.as_deref() {
        Some(d) if d.f64.is_finite() => d.exact.clone().unwrap_or_default(),
        _ => String::new(),
    }
}

/// The plotted series for the names asked for (see [`super::SweepOptions::plot_outputs`]);
/// `keys` are the varied paths when derivatives are computed (`--sensitivity`), else empty.
pub(super) fn resolve_outputs(
    asked: &[String],
    models: &[Restitution],
    contacts: usize,
    friction: bool,
    bodies: &[String],
    keys: &[String],
) -> Result<Vec<Series>, SweepError> {
    let names = output_names(contacts, friction, bodies);
    let mut out: Vec<Series> = Vec::new();
    let mut push = |s: Series| {
        if !out
            .iter()
            .any(|o| o.model == s.model && o.output == s.output && o.wrt == s.wrt)
        {
            out.push(s);
        }
    };
    if asked.is_empty() {
        let wrts = std::iter::once(None).chain((!keys.is_empty()).then_some(Some(0)));
        for wrt in wrts {
            for model in 0..models.len() {
                for output in (0..contacts).chain([names.len() - 1]) {
                    push(Series { model, output, wrt });
                }
            }
        }
        return Ok(out);
    }
    for name in asked {
        for s in resolve_name(name.trim(), &names, models, keys)? {
            push(s);
        }
    }
    Ok(out)
}

/// The series one name asks for: a column (`newton_P1`) names one, a per-model name (`P1`)
/// one per model solved; `d(NAME)/d(KEY)` their derivatives with respect to the varied KEY.
fn resolve_name(
    name: &str,
    names: &[String],
    models: &[Restitution],
    keys: &[String],
) -> Result<Vec<Series>, SweepError> {
    let err = |reason: String| SweepError::Output {
        name: name.to_string(),
        reason,
    };
    let (name, wrt) = match name
        .strip_prefix("d(")
        .and_then(|rest| rest.strip_suffix(')'))
        .and_then(|rest| rest.split_once(")/d("))
    {
        Some((output, key)) => {
            if keys.is_empty() {
                return Err(err(
                    "a derivative is plotted only with --sensitivity".to_string()
                ));
            }
            let k = keys.iter().position(|k| k == key).ok_or_else(|| {
                err(format!(
                    "`{key}` is not varied; derivatives are taken with respect to: {}",
                    keys.join(", ")
                ))
            })?;
            (output, Some(k))
        }
        None => (name, None),
    };
    let (model, output) = match name.split_once('_') {
        Some((m, rest)) if Restitution::from_name(m).is_some() => (Restitution::from_name(m), rest),
        _ => (None, name),
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
                wrt,
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
                wrt,
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
    /// The CSV header: `point`, the varied paths, the per-model outputs, with `--sensitivity`
    /// their derivatives per varied path, `status`.
    pub(super) fn header(&self) -> Vec<String> {
        let mut h = vec!["point".to_string()];
        for v in &self.vary {
            h.push(v.path.clone());
            if self.exact {
                h.push(format!("{}_exact", v.path));
            }
        }
        let names = output_names(self.contacts, self.friction, &self.bodies);
        let model_columns = |m: &Restitution| -> Vec<String> {
            let mut c: Vec<String> = names.iter().map(|n| format!("{m}_{n}")).collect();
            if self.exact {
                c.extend(
                    exact_outputs(self.contacts, self.bodies.len())
                        .map(|k| format!("{m}_{}_exact", names[k])),
                );
            }
            c
        };
        for m in &self.models {
            h.extend(model_columns(m));
        }
        if self.sensitivity {
            for v in &self.vary {
                for m in &self.models {
                    h.extend(model_columns(m).into_iter().map(
                        |c| match c.strip_suffix("_exact") {
                            Some(c) => format!("d({c})/d({})_exact", v.path),
                            None => format!("d({c})/d({})", v.path),
                        },
                    ));
                }
            }
        }
        h.push("status".into());
        h
    }

    /// The columns per model.
    fn model_width(&self) -> usize {
        let n = self.contacts + 6 * self.bodies.len().max(1) + 2 + usize::from(self.friction);
        if self.exact { n + self.contacts + 2 } else { n }
    }

    /// Solve point p into its CSV row and plotted values.
    pub(super) fn row(&self, p: usize) -> Result<Row, SweepError> {
        let solved = self.solve(p)?;
        let values = &solved.values;
        let status = match &solved.report {
            Ok(r) => status(r),
            Err(s) => (*s).to_string(),
        };
        let report = solved.report.as_ref().ok();
        let keys = if self.sensitivity { self.vary.len() } else { 0 };
        let mut fields = Cells::with_capacity(
            2 + 2 * values.len() + (1 + keys) * self.models.len() * self.model_width(),
        );
        fields.push_usize(p);
        for q in values {
            fields.push_f64(rational_to_f64(q));
            if self.exact {
                fields.push(&format_rational(q));
            }
        }
        let outputs: Vec<Option<Vec<Value>>> = self
            .models
            .iter()
            .map(|m| report.and_then(|r| law_outputs(r, *m, self.friction)))
            .collect();
        for v in &outputs {
            match v {
                None => fields.push_empty(self.model_width()),
                Some(v) => {
                    for x in v {
                        fields.push_f64(x.f64);
                    }
                    if self.exact {
                        for k in exact_outputs(self.contacts, self.bodies.len()) {
                            fields.push(v[k].exact.as_deref().unwrap_or_default());
                        }
                    }
                }
            }
        }
        // Per varied path and model, the derivatives (NaN where there are none).
        let mut slopes: Vec<Vec<Option<Vec<f64>>>> = Vec::with_capacity(keys);
        for k in 0..keys {
            let dual = solved.derivatives.get(k).and_then(Option::as_ref);
            let mut per_model = Vec::with_capacity(self.models.len());
            for (m, plain) in self.models.iter().zip(&outputs) {
                let d = match (plain, dual) {
                    (Some(_), Some(r)) => law_outputs(r, *m, self.friction),
                    _ => None,
                };
                match &d {
                    None => fields.push_empty(self.model_width()),
                    Some(d) => {
                        for x in d {
                            fields.push(&derivative_cell(x).0);
                        }
                        if self.exact {
                            for k in exact_outputs(self.contacts, self.bodies.len()) {
                                fields.push(&derivative_exact(&d[k]));
                            }
                        }
                    }
                }
                per_model.push(d.map(|d| d.iter().map(|x| derivative_cell(x).1).collect()));
            }
            slopes.push(per_model);
        }
        fields.push(&status);
        let ys = self
            .series
            .iter()
            .map(|s| {
                let y = match s.wrt {
                    None => outputs[s.model]
                        .as_ref()
                        .and_then(|v| v.get(s.output))
                        .map(|x| x.f64),
                    Some(k) => slopes[k][s.model]
                        .as_ref()
                        .and_then(|v| v.get(s.output).copied()),
                };
                y.unwrap_or(f64::NAN)
            })
            .collect();
        Ok(Row {
            fields,
            x: rational_to_f64(&values[0]),
            j: self.indices(p).1,
            ys,
            singular: report.is_none(),
            status,
        })
    }
}

/// A solved point's status: `ok`, or the reasons its simultaneous answer is not physical
/// (`tensile`, `separating`, `still-approaching`, `energy-gain`), across the models, joined
/// by `+` in that order.
pub(super) fn status(answer: &Answer) -> String {
    let report = match answer {
        Answer::Body(r) => r,
        Answer::System(r) => return system_status(r),
    };
    body_status(report)
}

/// [`status`] of a system: its models' verdicts and failures.
fn system_status(r: &crate::report::system::SystemReport) -> String {
    let mut found: Vec<&str> = Vec::new();
    let names = r
        .models
        .iter()
        .flat_map(|m| m.inadmissible.iter().map(|v| v.name()))
        .chain(r.model_failures.iter().map(|(_, _, s)| *s))
        .chain(
            r.friction
                .iter()
                .flat_map(|f| f.verdict_names.iter().copied()),
        )
        .chain(r.friction_failures.iter().map(|(_, _, s)| *s));
    for n in names {
        if !found.contains(&n) {
            found.push(n);
        }
    }
    if found.is_empty() {
        "ok".to_string()
    } else {
        found.join("+")
    }
}

/// [`status`] of one body's report.
pub(super) fn body_status(report: &crate::report::Report) -> String {
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
        "jammed",
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
                || report.model_failures.iter().any(|(_, _, s)| s == n)
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
            resolve_outputs(&asked, &models, 2, false, &[], &[])
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
        let e = resolve_outputs(&asked, &models, 2, false, &[], &[]).unwrap_err();
        assert!(e.to_string().contains("newton_P1"), "{e}");
        let asked = vec!["poisson_P1".to_string()];
        let e = resolve_outputs(&asked, &[Restitution::Newton], 2, false, &[], &[]).unwrap_err();
        assert!(e.to_string().contains("poisson"), "{e}");
    }

    #[test]
    fn derivatives_resolve_against_the_varied_paths() {
        let models = vec![Restitution::Newton, Restitution::Poisson];
        let keys = vec!["contact[1].k".to_string(), "body.mass".to_string()];
        let series = |names: &[&str], keys: &[String]| {
            let asked: Vec<String> = names.iter().map(|s| s.to_string()).collect();
            resolve_outputs(&asked, &models, 2, false, &[], keys).map(|v| {
                v.iter()
                    .map(|s| (s.model, s.output, s.wrt))
                    .collect::<Vec<_>>()
            })
        };
        // Default with --sensitivity: the outputs, then their slopes along the first path.
        let default = series(&[], &keys).unwrap();
        assert_eq!(default.len(), 12);
        assert_eq!(
            default[6..],
            [
                (0, 0, Some(0)),
                (0, 1, Some(0)),
                (0, 9, Some(0)),
                (1, 0, Some(0)),
                (1, 1, Some(0)),
                (1, 9, Some(0))
            ]
        );
        assert_eq!(
            series(
                &["d(newton_P2)/d(body.mass)", "d(Ep)/d(contact[1].k)"],
                &keys
            )
            .unwrap(),
            vec![(0, 1, Some(1)), (0, 8, Some(0)), (1, 8, Some(0))]
        );
        let e = series(&["d(P1)/d(body.inertia[0])"], &keys).unwrap_err();
        assert!(e.to_string().contains("not varied"), "{e}");
        let e = series(&["d(P1)/d(contact[1].k)"], &[]).unwrap_err();
        assert!(e.to_string().contains("--sensitivity"), "{e}");
    }

    #[test]
    fn the_frictionless_dissipation_is_zero_with_a_zero_derivative() {
        let mut v = Value::float(2.5);
        assert_eq!(zero_like(&v), Value::float(0.0));
        v.exact = Some("5/2".into());
        v.derivative = Some(Box::new(Value {
            exact: Some("1/3".into()),
            ..Value::float(1.0 / 3.0)
        }));
        let z = zero_like(&v);
        assert_eq!((z.f64, z.exact.as_deref()), (0.0, Some("0")));
        let d = z.derivative.unwrap();
        assert_eq!((d.f64, d.exact.as_deref()), (0.0, Some("0")));
    }
}
