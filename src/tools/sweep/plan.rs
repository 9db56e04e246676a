//! The plan of a sweep: the options checked, the scene read, every varied path checked at both
//! ends of its range and the grid's corners solved once, so that a sweep fails before it
//! starts rather than at point 10 000; then, per point, the varied values, the scene there and
//! its solve.

use num_rational::BigRational;
use toml_edit::DocumentMut;

use super::answer::{Answer, body_names};
use super::coefficients::Coefficients;
use super::outputs::{Series, point_status, resolve_outputs, sweep_laws, written_outputs};
use super::slot::Slot;
use super::target::{SEED, Target};
use super::text::text;
use super::{SweepError, SweepOptions, Vary};
use crate::impact::friction::Restitution;
use crate::impact::unilateral::Law;
use crate::scalar::Exact;
use crate::scalar::dual::Dual;
use crate::scene::pipeline::RunError;
use crate::scene::seed::seeded;
use crate::scene::{Scene, SceneError, parse_document};

/// A solved point: its varied values, its report (or the status of a point without one) and,
/// with `--sensitivity`, per varied path the report of the dual-number run seeded on it
/// (`None` where the point has no answer: it is not differentiated).
pub(super) struct Solved {
    /// The varied values, outer first.
    pub(super) values: Vec<BigRational>,
    /// The report, or the status of a point without an answer.
    pub(super) report: Result<Answer, &'static str>,
    /// Per varied path, the dual run's report (its values carry the derivatives).
    pub(super) derivatives: Vec<Option<Answer>>,
}

/// A validated sweep.
pub(super) struct Plan {
    /// The scene file, for messages.
    pub(super) file: String,
    /// The scene's name, for the plot's caption.
    pub(super) name: String,
    /// The scene document as read, re-read at each point when a varied path has no [`Slot`].
    doc: DocumentMut,
    /// The scene as read, and where each varied number lives in it when every varied path
    /// can be set directly (see [`Slot`]); otherwise each point re-reads the document.
    base: Scene,
    slots: Option<Vec<Slot>>,
    /// The problem prepared once, when every varied number is a coefficient of restitution
    /// and no derivative is asked for ([`Coefficients`]).
    coefficients: Option<Coefficients>,
    /// The varied inputs, outer first.
    pub(super) vary: Vec<Vary>,
    /// Whether points are solved in exact rationals.
    pub(super) exact: bool,
    /// The restitution laws solved, in the scene's order: its models, or for a frictional
    /// sweep (some μ_i > 0 or varied, or `[solve] restitution`) the laws it integrates.
    pub(super) models: Vec<Restitution>,
    /// Whether the sweep integrates friction (adds the `Ef` column).
    pub(super) friction: bool,
    /// N, the number of contacts.
    pub(super) contacts: usize,
    /// A system's bodies by name (empty for one body): each gives its own twist columns.
    pub(super) bodies: Vec<String>,
    /// The points of the whole grid (every shard).
    pub(super) points: usize,
    /// The plotted series (none without `--plot`).
    pub(super) series: Vec<Series>,
    /// The impact law, when `--law` overrides the scene's.
    law: Option<Law>,
    /// Whether each point is also differentiated with respect to each varied path.
    pub(super) sensitivity: bool,
    /// Where each varied value goes in the document.
    targets: Vec<Target>,
}

impl Plan {
    /// Check the options, read the scene and check every varied path against it.
    pub(super) fn new(opts: &SweepOptions) -> Result<Plan, SweepError> {
        check_varied(&opts.vary)?;
        check_shard_and_files(opts)?;
        let points = grid_points(&opts.vary)?;
        let (file, doc, base) = read_scene(opts)?;
        let targets: Vec<Target> = opts
            .vary
            .iter()
            .map(|v| Target::of(&v.path, &base))
            .collect();
        check_paths(&opts.vary, &targets, &doc, &base, &file)?;
        let (models, friction) = sweep_laws(&base, opts.vary.iter().map(|v| v.path.as_str()));
        let contacts = base.contacts.len();
        let bodies = body_names(&base);
        let keys: Vec<String> = if opts.sensitivity {
            opts.vary.iter().map(|v| v.path.clone()).collect()
        } else {
            Vec::new()
        };
        let series = if opts.plot.is_some() {
            resolve_outputs(
                &opts.plot_outputs,
                &models,
                contacts,
                friction,
                &bodies,
                &keys,
            )?
        } else {
            Vec::new()
        };
        let slots = Slot::all(
            opts.vary.iter().map(|v| v.path.as_str()),
            &base,
            targets.iter().any(|t| t.param),
        );
        let mut plan = Plan {
            file,
            name: base.name.clone(),
            doc,
            base,
            slots,
            coefficients: None,
            vary: opts.vary.clone(),
            exact: opts.exact,
            models,
            friction,
            contacts,
            bodies,
            points,
            series,
            law: opts.law,
            sensitivity: opts.sensitivity,
            targets,
        };
        plan.coefficients = plan.prepare_coefficients();
        plan.solve_corners()?;
        Ok(plan)
    }

    /// The problem prepared once for a sweep over coefficients of restitution (without
    /// `--sensitivity`, whose dual runs read the scene), from the scene at the first point.
    fn prepare_coefficients(&self) -> Option<Coefficients> {
        let slots = self.slots.as_ref().filter(|_| !self.sensitivity)?;
        let scene = self.scene_at(&self.values(0)).ok()?;
        Coefficients::new(scene, slots, self.exact)
    }

    /// Solve the grid's corners once: irrational numbers in exact mode, constraints and
    /// tangents (and, with `--sensitivity`, a scene that cannot be differentiated) are caught
    /// before the sweep starts.
    fn solve_corners(&self) -> Result<(), SweepError> {
        let last: Vec<usize> = self.vary.iter().map(|v| v.count - 1).collect();
        let inner = self.vary.get(1).map_or(1, |v| v.count);
        let corners: Vec<usize> = match last[..] {
            [a] => vec![0, a],
            [a, b] => vec![0, b, a * inner, a * inner + b],
            _ => vec![],
        };
        for p in corners {
            let _ = self.solve(p)?;
        }
        Ok(())
    }

    /// The grid indices of point p: (i, j), j = 0 for a 1-D sweep.
    pub(super) fn indices(&self, p: usize) -> (usize, usize) {
        match self.vary.get(1) {
            Some(v) => (p / v.count, p % v.count),
            None => (p, 0),
        }
    }

    /// The varied values at point p.
    fn values(&self, p: usize) -> Vec<BigRational> {
        let (i, j) = self.indices(p);
        let mut out = vec![self.vary[0].value(i)];
        if let Some(v) = self.vary.get(1) {
            out.push(v.value(j));
        }
        out
    }

    /// The error at point p, naming the varied values there.
    fn point_error(&self, p: usize, values: &[BigRational], message: String) -> SweepError {
        let at = self
            .vary
            .iter()
            .zip(values)
            .map(|(v, q)| format!("{} = {}", v.path, text(q)))
            .collect::<Vec<_>>()
            .join(", ");
        SweepError::Point {
            point: p,
            at,
            message,
        }
    }

    /// The document at the varied values.
    fn doc_at(&self, values: &[BigRational]) -> Result<DocumentMut, String> {
        let mut doc = self.doc.clone();
        for (t, q) in self.targets.iter().zip(values) {
            t.set(&mut doc, q)?;
        }
        Ok(doc)
    }

    /// The scene at the varied values seeded to differentiate by varied input `i`.
    fn seeded_at(&self, scene: &Scene, values: &[BigRational], i: usize) -> Result<Scene, String> {
        let t = &self.targets[i];
        if self.slots.is_some() {
            return seeded(scene, &t.path).ok_or_else(|| {
                format!(
                    "`{}` names no number to differentiate by",
                    self.vary[i].path
                )
            });
        }
        let doc = t.seed(&self.doc_at(values)?, &values[i])?;
        let mut s =
            Scene::from_document_seeded(&doc, &self.file, &[], SEED).map_err(|e| e.to_string())?;
        s.law = scene.law;
        s.outputs = scene.outputs;
        Ok(s)
    }

    /// The scene at the varied values (under `--law`, when given), asking the solve for the
    /// outputs the CSV writes only ([`written_outputs`]).
    fn scene_at(&self, values: &[BigRational]) -> Result<Scene, String> {
        let mut scene = match &self.slots {
            Some(slots) => {
                let mut scene = self.base.clone();
                for (slot, q) in slots.iter().zip(values) {
                    slot.set(&mut scene, q);
                }
                scene
            }
            None => Scene::from_document(&self.doc_at(values)?, &self.file)
                .map_err(|e| e.to_string())?,
        };
        if let Some(law) = self.law {
            scene.law = law;
        }
        scene.outputs = written_outputs();
        Ok(scene)
    }

    /// Solve point p: its report, or the status of a point without one — `singular` (G
    /// singular under the simultaneous law) or `jammed` (no admissible impulses under the
    /// unilateral law) — and with `--sensitivity` its derivatives.
    pub(super) fn solve(&self, p: usize) -> Result<Solved, SweepError> {
        let values = self.values(p);
        let fail = |message: String| self.point_error(p, &values, message);
        if let Some(answer) = self.coefficients.as_ref().and_then(|c| c.solve(&values)) {
            return Ok(Solved {
                values,
                report: Ok(answer),
                derivatives: Vec::new(),
            });
        }
        let scene = self.scene_at(&values).map_err(fail)?;
        let solved = if self.exact {
            Answer::solve::<Exact>(&scene)
        } else {
            Answer::solve::<f64>(&scene)
        };
        let report = match solved {
            Ok(s) => Ok(s),
            Err(e) => Err(point_status(&e).ok_or_else(|| fail(e.to_string()))?),
        };
        let mut derivatives = Vec::new();
        if self.sensitivity && report.is_ok() {
            for (i, v) in self.vary.iter().enumerate() {
                let at = |e: RunError| fail(format!("d/d({}): {e}", v.path));
                let seeded = self.seeded_at(&scene, &values, i).map_err(fail)?;
                let solved = if self.exact {
                    Answer::solve::<Dual<Exact>>(&seeded)
                } else {
                    Answer::solve::<Dual<f64>>(&seeded)
                };
                derivatives.push(match solved {
                    Ok(s) => Some(s),
                    Err(e) if point_status(&e).is_some() => None,
                    Err(e) => return Err(at(e)),
                });
            }
        }
        Ok(Solved {
            values,
            report,
            derivatives,
        })
    }
}

/// The varied inputs as written back, for messages: `PATH=START:STOP:COUNT`.
fn specs(vary: &[Vary]) -> Vec<String> {
    vary.iter()
        .map(|v| {
            format!(
                "{}={}:{}:{}",
                v.path,
                text(&v.start),
                text(&v.stop),
                v.count
            )
        })
        .collect()
}

/// One or two varied inputs, of at least 2 points each, naming different numbers.
pub(super) fn check_varied(vary: &[Vary]) -> Result<(), SweepError> {
    match vary.len() {
        0 => {
            return Err(SweepError::Options(
                "nothing to sweep: give one or two --vary PATH=START:STOP:COUNT, e.g. --vary 'contact[1].k=0:1:101'".into(),
            ));
        }
        1 | 2 => {}
        n => {
            return Err(SweepError::Vary {
                spec: specs(vary).join(" "),
                reason: format!(
                    "{n} inputs varied; a sweep varies one or two (a line or a grid): run one sweep per pair"
                ),
            });
        }
    }
    for (k, v) in vary.iter().enumerate() {
        if v.count < 2 {
            return Err(SweepError::Vary {
                spec: specs(vary)[k].clone(),
                reason: format!("COUNT is {}: a sweep needs at least 2 points", v.count),
            });
        }
    }
    if let [a, b] = vary
        && overlap(&a.path, &b.path)
    {
        return Err(SweepError::Vary {
            spec: specs(vary)[1].clone(),
            reason: format!(
                "`{}` is already varied by the first --vary; the two --vary must name different numbers",
                a.path
            ),
        });
    }
    Ok(())
}

/// A valid shard, and a plot that does not overwrite the CSV.
pub(super) fn check_shard_and_files(opts: &SweepOptions) -> Result<(), SweepError> {
    if let Some(s) = &opts.shard {
        s.check().map_err(|reason| SweepError::Shard {
            spec: format!("{}/{}", s.index, s.count),
            reason,
        })?;
    }
    if let Some(plot) = &opts.plot
        && plot == &opts.out
    {
        return Err(SweepError::Options(format!(
            "--out and --plot are the same file ({}); give the plot its own name, e.g. results.svg",
            plot.display()
        )));
    }
    Ok(())
}

/// The points of the whole grid, Π COUNT, if it can be counted.
pub(super) fn grid_points(vary: &[Vary]) -> Result<usize, SweepError> {
    vary.iter()
        .try_fold(1usize, |acc, v| acc.checked_mul(v.count))
        .ok_or_else(|| SweepError::Vary {
            spec: specs(vary).join(" "),
            reason: "the grid has more points than this machine can count; use fewer".into(),
        })
}

/// The scene file's name, its document, and the scene it validates to.
pub(super) fn read_scene(opts: &SweepOptions) -> Result<(String, DocumentMut, Scene), SweepError> {
    let file = opts.scene.display().to_string();
    let source = std::fs::read_to_string(&opts.scene).map_err(|e| SceneError {
        file: file.clone(),
        key: String::new(),
        value: None,
        message: format!("cannot read the file: {e}"),
    })?;
    let doc = parse_document(&source, &file)?;
    let base = Scene::from_document(&doc, &file)?;
    Ok((file, doc, base))
}

/// Each path must name a number, and the scene must be valid at both ends.
fn check_paths(
    vary: &[Vary],
    targets: &[Target],
    doc: &DocumentMut,
    base: &Scene,
    file: &str,
) -> Result<(), SweepError> {
    let keys = Target::keys(base);
    for ((v, t), spec) in vary.iter().zip(targets).zip(specs(vary)) {
        if !t.known(&v.path, base, &keys) {
            return Err(SweepError::Vary {
                spec,
                reason: format!(
                    "`{}` is not a number or parameter of the scene; vary one of: {}",
                    v.path,
                    listing(&keys)
                ),
            });
        }
        for (which, q) in [("START", &v.start), ("STOP", &v.stop)] {
            let mut d = doc.clone();
            t.set(&mut d, q).map_err(|e| SweepError::Vary {
                spec: spec.clone(),
                reason: e,
            })?;
            Scene::from_document(&d, file).map_err(|e| SweepError::Vary {
                spec: spec.clone(),
                reason: format!("the scene is invalid at {which} = {}: {e}", text(q)),
            })?;
        }
    }
    Ok(())
}

/// Whether two varied paths address the same number (`k` covers `k_newton`, `k_poisson`).
fn overlap(a: &str, b: &str) -> bool {
    let covers = |x: &str, y: &str| {
        x.strip_suffix(".k")
            .is_some_and(|c| y == format!("{c}.k_newton") || y == format!("{c}.k_poisson"))
    };
    a == b || covers(a, b) || covers(b, a)
}

/// A short list of the scene's numbers, for messages.
fn listing(keys: &[String]) -> String {
    const SHOWN: usize = 14;
    let mut s = keys
        .iter()
        .take(SHOWN)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    if keys.len() > SHOWN {
        s.push_str(&format!(", … ({} in all)", keys.len()));
    }
    s.push_str(" (`contact[i].k` sets both models' coefficients)");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_paths() {
        assert!(overlap("contact[1].k", "contact[1].k"));
        assert!(overlap("contact[1].k", "contact[1].k_poisson"));
        assert!(overlap("contact[0].k_newton", "contact[0].k"));
        assert!(!overlap("contact[0].k", "contact[1].k"));
        assert!(!overlap("contact[0].k_newton", "contact[0].k_poisson"));
    }
}
