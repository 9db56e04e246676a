//! Parameter sweeps: one scene solved over a grid of one or two varied inputs, in parallel,
//! streamed to CSV, optionally plotted.
//!
//! ```text
//! inertance sweep scene.toml --vary 'contact[1].k=0:1:101' [--vary ...] [--exact] \
//!     --out results.csv [--plot results.svg] [--shard I/N]
//! ```
//!
//! ## The grid
//!
//! Each `--vary PATH=START:STOP:COUNT` ([`Vary`]) names one number of the scene by its key path
//! (as in [`crate::scene::set_value`]: `contact[1].k`, `body.mass`, `body.velocity[0]`;
//! `contact[i].k_newton` / `k_poisson` vary one model's coefficient only) and COUNT ≥ 2 points
//! from START to STOP, both ends included. START and STOP are read exactly, as scene numbers
//! are, so `0:1:101` gives exactly 0, 1/100, …, 1 (in f64 mode each point is the correctly
//! rounded value). A decreasing range (`1:0:5`) is allowed; START = STOP is refused.
//!
//! With two `--vary`, the first is the outer index i and the second the inner index j: global
//! point p (0-based) is (i, j) = (p / COUNT₂, p mod COUNT₂).
//!
//! Every `--vary` is checked before anything is solved: the path must name a number of the
//! scene, and the scene must be valid at both START and STOP (so `k` up to 1.5 fails naming
//! the key and the value); the grid corners are solved once as a check. A point whose G is
//! singular (Δ = 0) is not an error: its row has `status` = `singular` and empty outputs.
//!
//! ## CSV columns
//!
//! * `point`: the global point index p.
//! * per varied path, its value as f64 (column named by the path, e.g. `contact[1].k`), and in
//!   `--exact` mode `PATH_exact` with the exact value `p/q`.
//! * per model solved (the scene's `[solve] models`, in that order), prefixed `newton_` /
//!   `poisson_`: `P1 … PN` (impulses), `vCx vCy vCz` (v_C after impact), `wx wy wz` (ω after
//!   impact), `Ep` (E_p) and `dEc` (ΔE_c). In `--exact` mode these are the f64 values of the
//!   exact results, followed (so the f64 columns keep their order) by `P1_exact … PN_exact`,
//!   `Ep_exact`, `dEc_exact`: `p/q`, or `c*sqrt(r)` for an impulse along a non-unit normal.
//! * `status`: `ok` or `singular` (then every output column of the row is empty).
//!
//! f64 values are written with full round-trip precision (Rust's `{:?}`, e.g. `0.1`, `1e-7`).
//!
//! ## Shards (array jobs)
//!
//! `--shard I/N` ([`Shard`], 1 ≤ I ≤ N, 1-based like Slurm's `--array=1-N` and
//! `$SLURM_ARRAY_TASK_ID`) solves the contiguous block of global points
//! `[⌊(I−1)·P/N⌋, ⌊I·P/N⌋)` of the P-point grid: the shards are disjoint, cover the grid, and
//! depend only on (I, N, P) (a shard is empty when N > P). **Every shard writes its own
//! header line**, so each file is a valid CSV on its own; concatenate in shard order dropping
//! all but the first header:
//!
//! ```sh
//! { cat out-1.csv; for i in $(seq 2 N); do tail -n +2 out-$i.csv; done; } > out.csv
//! ```
//!
//! which is byte-for-byte the unsharded CSV (`point` keeps the global index). A plot drawn
//! by a shard shows that shard's points only; plot the concatenated CSV instead.
//!
//! ## Memory, order, files
//!
//! Points are solved in parallel (rayon; a local pool of `threads` when given) in chunks of
//! [`CHUNK`] points; a chunk's rows are written in point order before the next chunk starts,
//! so memory is bounded by the chunk size and the CSV is in point order. The plot is the one
//! exception: it keeps (x, y) per point of each plotted series only, O(points × series).
//!
//! Files are written atomically: to `FILE.tmp`, renamed to `FILE` when complete; on error the
//! `.tmp` is removed and nothing half-written is left. The CSV is committed before the plot is
//! drawn, so a plot failure leaves the complete CSV in place.
//!
//! ## Plot
//!
//! An SVG (no fonts needed): x = the first varied input, y = the chosen outputs, one colour per
//! output, Newton solid and Poisson dashed, so the two models can be compared at a glance
//! (they coincide when every k_i is equal, eq. 50–55). Outputs are named like CSV columns
//! (`newton_P1`), or without the model prefix (`P1`, `dEc`) for every model solved; the
//! default is `P1 … PN` and `dEc` for every model. A 2-D sweep draws one line per value of
//! the second varied input, all in the output's colour. Singular points leave a gap.
//!
//! ## Progress
//!
//! With `progress`, a bar is drawn to stderr once a sweep has run for more than a second; never
//! when stderr is not a terminal.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rayon::prelude::*;
use toml_edit::DocumentMut;

use crate::number::{Number, format_rational, parse_number, rational_to_f64};
use crate::scene::pipeline::{RunError, run};
use crate::report::{ModelReport, Report};
use crate::impact::restitution::Model;
use crate::scalar::Exact;
use crate::scene::{Scene, SceneError, parse_document, set_value};
use crate::impact::solve::SolveError;

/// Points solved in parallel before their rows are written (bounds memory).
pub const CHUNK: usize = 1024;

/// A sweep this long (and still running) gets a progress bar, when asked for and on a terminal.
const PROGRESS_AFTER: Duration = Duration::from_secs(1);

/// One varied input: `PATH=START:STOP:COUNT` (COUNT ≥ 2 points, inclusive of both ends;
/// START/STOP are numbers as in scenes, read exactly: `0:1:101` gives 0, 1/100, …, 1 exactly).
/// A decreasing range is allowed; START = STOP is refused.
#[derive(Clone, Debug, PartialEq)]
pub struct Vary {
    /// The key path of the varied number, e.g. `contact[1].k`.
    pub path: String,
    /// The first value.
    pub start: BigRational,
    /// The last value.
    pub stop: BigRational,
    /// The number of values, ≥ 2.
    pub count: usize,
}

impl Vary {
    /// Parse `PATH=START:STOP:COUNT`; the path is checked against the scene by [`sweep`].
    pub fn parse(spec: &str) -> Result<Vary, SweepError> {
        let err = |reason: String| SweepError::Vary {
            spec: spec.to_string(),
            reason,
        };
        let (path, range) = spec.split_once('=').ok_or_else(|| {
            err("expected PATH=START:STOP:COUNT, e.g. contact[1].k=0:1:101".into())
        })?;
        let path = path.trim();
        if path.is_empty() {
            return Err(err(
                "the path before `=` is empty; name a number of the scene, e.g. contact[1].k"
                    .into(),
            ));
        }
        if path.contains(char::is_whitespace) {
            return Err(err(format!(
                "the path `{path}` contains whitespace; write it as in the scene, e.g. contact[1].k"
            )));
        }
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        if parts.len() != 3 {
            return Err(err(format!(
                "expected START:STOP:COUNT after `=`, found `{range}` ({} part{}); e.g. {path}=0:1:101",
                parts.len(),
                if parts.len() == 1 { "" } else { "s" }
            )));
        }
        let number = |what: &str, text: &str| -> Result<BigRational, SweepError> {
            let n = parse_number(text).map_err(|e| err(format!("{what}: {e}")))?;
            n.exact.map_err(|why| {
                err(format!(
                    "{what} `{text}` is not rational ({why}); write it as a decimal or a fraction"
                ))
            })
        };
        let start = number("START", parts[0])?;
        let stop = number("STOP", parts[1])?;
        let count: usize = parts[2].parse().map_err(|_| {
            err(format!(
                "COUNT `{}` is not a whole number of points (≥ 2)",
                parts[2]
            ))
        })?;
        if count < 2 {
            return Err(err(format!(
                "COUNT is {count}: a sweep needs at least 2 points (both ends are included)"
            )));
        }
        if start == stop {
            return Err(err(format!(
                "START and STOP are equal ({}): nothing would vary",
                parts[0]
            )));
        }
        Ok(Vary {
            path: path.to_string(),
            start,
            stop,
            count,
        })
    }

    /// The i-th value, start + (stop − start)·i/(count − 1), exactly.
    pub fn value(&self, i: usize) -> BigRational {
        if self.count < 2 {
            return self.start.clone();
        }
        let t = BigRational::new(BigInt::from(i), BigInt::from(self.count - 1));
        &self.start + (&self.stop - &self.start) * t
    }
}

/// A slice of a sweep, `I/N` with 1 ≤ I ≤ N: 1-based, as Slurm's `--array=1-N` indices
/// (`--shard $SLURM_ARRAY_TASK_ID/N`). See the module docs for which points it takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// I, from 1.
    pub index: usize,
    /// N, ≥ 1.
    pub count: usize,
}

impl Shard {
    /// Parse `I/N`.
    pub fn parse(spec: &str) -> Result<Shard, SweepError> {
        let err = |reason: String| SweepError::Shard {
            spec: spec.to_string(),
            reason,
        };
        let (i, n) = spec
            .split_once('/')
            .ok_or_else(|| err("expected I/N, e.g. 1/4 (shard I of N, counted from 1)".into()))?;
        let whole = |what: &str, t: &str| -> Result<usize, SweepError> {
            t.trim().parse().map_err(|_| {
                err(format!(
                    "{what} `{}` is not a whole number; expected I/N, e.g. 1/4",
                    t.trim()
                ))
            })
        };
        let shard = Shard {
            index: whole("I", i)?,
            count: whole("N", n)?,
        };
        shard.check().map_err(err)?;
        Ok(shard)
    }

    /// The global points of a `points`-point grid this shard solves:
    /// `[⌊(I−1)·P/N⌋, ⌊I·P/N⌋)`. Assumes a valid shard (1 ≤ I ≤ N).
    pub fn range(&self, points: usize) -> std::ops::Range<usize> {
        let n = self.count.max(1) as u128;
        let at = |k: usize| ((k as u128 * points as u128) / n) as usize;
        at(self.index.saturating_sub(1))..at(self.index.min(self.count))
    }

    fn check(&self) -> Result<(), String> {
        if self.count == 0 {
            Err("N is 0: there must be at least one shard".into())
        } else if self.index == 0 {
            Err(format!(
                "shards are numbered from 1 (as Slurm's --array=1-{n} with $SLURM_ARRAY_TASK_ID); use 1/{n} … {n}/{n}",
                n = self.count
            ))
        } else if self.index > self.count {
            Err(format!(
                "shard {} of {} does not exist; I must lie in 1 … {}",
                self.index, self.count, self.count
            ))
        } else {
            Ok(())
        }
    }
}

/// What to sweep and where to write it.
#[derive(Clone, Debug, Default)]
pub struct SweepOptions {
    /// The scene file.
    pub scene: PathBuf,
    /// One or two varied inputs; the first is the outer index (and the plot's x).
    pub vary: Vec<Vary>,
    /// Solve in exact rationals (adds `_exact` columns).
    pub exact: bool,
    /// The CSV to write.
    pub out: PathBuf,
    /// The SVG plot to write, if any.
    pub plot: Option<PathBuf>,
    /// Outputs to plot: column names (`newton_P1`) or per-model names (`P1`, `dEc`);
    /// empty = `P1 … PN` and `dEc` for every model.
    pub plot_outputs: Vec<String>,
    /// Solve only this slice of the grid.
    pub shard: Option<Shard>,
    /// Worker threads; `None` (or 0) = all cores.
    pub threads: Option<usize>,
    /// Draw a progress bar on stderr for long sweeps (only on a terminal).
    pub progress: bool,
}

/// What a sweep did.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepSummary {
    /// Points solved (in this shard).
    pub points: usize,
    /// Of which singular (Δ = 0).
    pub singular: usize,
    /// Wall time, seconds.
    pub seconds: f64,
}

/// Why a sweep failed.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// A bad `--vary`.
    #[error("--vary {spec}: {reason}")]
    Vary {
        /// The spec as given.
        spec: String,
        /// What is wrong and how to fix it.
        reason: String,
    },
    /// A bad `--shard`.
    #[error("--shard {spec}: {reason}")]
    Shard {
        /// The spec as given.
        spec: String,
        /// What is wrong and how to fix it.
        reason: String,
    },
    /// The scene itself is unreadable or invalid.
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// An output to plot that the sweep does not produce.
    #[error("plot output `{name}`: {reason}")]
    Output {
        /// The name as given.
        name: String,
        /// What is wrong, and the names available.
        reason: String,
    },
    /// Other inconsistent options.
    #[error("{0}")]
    Options(String),
    /// The scene is invalid, or cannot be solved, at one point of the grid.
    #[error("point {point} ({at}): {message}")]
    Point {
        /// The global point index.
        point: usize,
        /// The varied values there, e.g. `contact[1].k = 0.3`.
        at: String,
        /// What went wrong.
        message: String,
    },
    /// A file could not be written.
    #[error("{}: {message}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// The plot could not be drawn.
    #[error("plot: {0}")]
    Plot(String),
    /// The worker threads could not be started.
    #[error("cannot start the worker threads: {0}")]
    Threads(String),
}

impl SweepError {
    /// Exit status: 2 for bad input (options, scene, a point where the scene is invalid),
    /// 1 for I/O, plot and thread failures.
    pub fn exit_code(&self) -> u8 {
        match self {
            SweepError::Vary { .. }
            | SweepError::Shard { .. }
            | SweepError::Scene(_)
            | SweepError::Output { .. }
            | SweepError::Options(_)
            | SweepError::Point { .. } => 2,
            SweepError::Io { .. } | SweepError::Plot(_) | SweepError::Threads(_) => 1,
        }
    }
}

/// Run a sweep: validate everything, then solve the (shard's) points and write the CSV and
/// the plot. See the module docs for the conventions.
pub fn sweep(opts: &SweepOptions) -> Result<SweepSummary, SweepError> {
    let started = Instant::now();
    let plan = Plan::new(opts)?;
    let range = match opts.shard {
        Some(s) => s.range(plan.points),
        None => 0..plan.points,
    };
    let singular = match opts.threads {
        Some(n) if n > 0 => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| SweepError::Threads(e.to_string()))?;
            pool.install(|| plan.execute(opts, range.clone(), started))?
        }
        _ => plan.execute(opts, range.clone(), started)?,
    };
    Ok(SweepSummary {
        points: range.len(),
        singular,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// The per-model outputs, in CSV order (after the `model_` prefix).
fn output_names(contacts: usize) -> Vec<String> {
    let mut v: Vec<String> = (1..=contacts).map(|i| format!("P{i}")).collect();
    v.extend(
        ["vCx", "vCy", "vCz", "wx", "wy", "wz", "Ep", "dEc"]
            .iter()
            .map(|s| s.to_string()),
    );
    v
}

/// One plotted line: a model's output.
#[derive(Clone, Debug)]
struct Series {
    /// Index into the plan's models.
    model: usize,
    /// Index into [`output_names`].
    output: usize,
}

/// A validated sweep.
struct Plan {
    file: String,
    name: String,
    doc: DocumentMut,
    /// The scene as read, and where each varied number lives in it when every varied path
    /// can be set directly (see [`Slot`]); otherwise each point re-reads the document.
    base: Scene,
    slots: Option<Vec<Slot>>,
    vary: Vec<Vary>,
    exact: bool,
    models: Vec<Model>,
    contacts: usize,
    points: usize,
    series: Vec<Series>,
}

/// One solved point.
struct Row {
    fields: Vec<String>,
    x: f64,
    j: usize,
    ys: Vec<f64>,
    singular: bool,
}

impl Plan {
    fn new(opts: &SweepOptions) -> Result<Plan, SweepError> {
        let specs = || {
            opts.vary
                .iter()
                .map(|v| {
                    format!(
                        "{}={}:{}:{}",
                        v.path,
                        text(&v.start),
                        text(&v.stop),
                        v.count
                    )
                })
                .collect::<Vec<_>>()
        };
        match opts.vary.len() {
            0 => {
                return Err(SweepError::Options(
                    "nothing to sweep: give one or two --vary PATH=START:STOP:COUNT, e.g. --vary 'contact[1].k=0:1:101'".into(),
                ));
            }
            1 | 2 => {}
            n => {
                return Err(SweepError::Vary {
                    spec: specs().join(" "),
                    reason: format!(
                        "{n} inputs varied; a sweep varies one or two (a line or a grid): run one sweep per pair"
                    ),
                });
            }
        }
        for (k, v) in opts.vary.iter().enumerate() {
            if v.count < 2 {
                return Err(SweepError::Vary {
                    spec: specs()[k].clone(),
                    reason: format!("COUNT is {}: a sweep needs at least 2 points", v.count),
                });
            }
        }
        if let [a, b] = &opts.vary[..]
            && overlap(&a.path, &b.path)
        {
            return Err(SweepError::Vary {
                spec: specs()[1].clone(),
                reason: format!(
                    "`{}` is already varied by the first --vary; the two --vary must name different numbers",
                    a.path
                ),
            });
        }
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
        let points = opts
            .vary
            .iter()
            .try_fold(1usize, |acc, v| acc.checked_mul(v.count))
            .ok_or_else(|| SweepError::Vary {
                spec: specs().join(" "),
                reason: "the grid has more points than this machine can count; use fewer".into(),
            })?;

        let file = opts.scene.display().to_string();
        let source = std::fs::read_to_string(&opts.scene).map_err(|e| SceneError {
            file: file.clone(),
            key: String::new(),
            value: None,
            message: format!("cannot read the file: {e}"),
        })?;
        let doc = parse_document(&source, &file)?;
        let base = Scene::from_document(&doc, &file)?;
        let keys: Vec<String> = base.numbers().map(|(k, _)| k).collect();

        // Each path must name a number, and the scene must be valid at both ends.
        for (v, spec) in opts.vary.iter().zip(specs()) {
            let known = keys.iter().any(|k| {
                *k == v.path
                    || v.path
                        .strip_suffix(".k")
                        .is_some_and(|c| *k == format!("{c}.k_newton"))
            });
            if !known {
                return Err(SweepError::Vary {
                    spec,
                    reason: format!(
                        "`{}` is not a number of the scene; vary one of its numbers: {}",
                        v.path,
                        listing(&keys)
                    ),
                });
            }
            for (which, q) in [("START", &v.start), ("STOP", &v.stop)] {
                let mut d = doc.clone();
                set_value(&mut d, &v.path, &toml_text(q)).map_err(|e| SweepError::Vary {
                    spec: spec.clone(),
                    reason: e,
                })?;
                Scene::from_document(&d, &file).map_err(|e| SweepError::Vary {
                    spec: spec.clone(),
                    reason: format!("the scene is invalid at {which} = {}: {e}", text(q)),
                })?;
            }
        }

        let models = base.models.clone();
        let contacts = base.contacts.len();
        let series = if opts.plot.is_some() {
            resolve_outputs(&opts.plot_outputs, &models, contacts)?
        } else {
            Vec::new()
        };
        let slots = opts
            .vary
            .iter()
            .map(|v| Slot::find(&v.path, &base))
            .collect::<Option<Vec<_>>>();
        let plan = Plan {
            file,
            name: base.name.clone(),
            doc,
            base,
            slots,
            vary: opts.vary.clone(),
            exact: opts.exact,
            models,
            contacts,
            points,
            series,
        };
        // Solve the grid's corners once: irrational numbers in exact mode, constraints and
        // tangents are caught before the sweep starts.
        let last: Vec<usize> = plan.vary.iter().map(|v| v.count - 1).collect();
        let inner = plan.vary.get(1).map_or(1, |v| v.count);
        let corners: Vec<usize> = match last[..] {
            [a] => vec![0, a],
            [a, b] => vec![0, b, a * inner, a * inner + b],
            _ => vec![],
        };
        for p in corners {
            plan.solve(p)?;
        }
        Ok(plan)
    }

    /// The grid indices of point p: (i, j), j = 0 for a 1-D sweep.
    fn indices(&self, p: usize) -> (usize, usize) {
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

    /// The scene at the varied values.
    fn scene_at(&self, values: &[BigRational]) -> Result<Scene, String> {
        if let Some(slots) = &self.slots {
            let mut scene = self.base.clone();
            for (slot, q) in slots.iter().zip(values) {
                slot.set(&mut scene, q);
            }
            return Ok(scene);
        }
        let mut doc = self.doc.clone();
        for (v, q) in self.vary.iter().zip(values) {
            set_value(&mut doc, &v.path, &toml_text(q))?;
        }
        Scene::from_document(&doc, &self.file).map_err(|e| e.to_string())
    }

    /// Solve point p: its report, or `None` when G is singular.
    fn solve(&self, p: usize) -> Result<(Vec<BigRational>, Option<Report>), SweepError> {
        let values = self.values(p);
        let scene = self
            .scene_at(&values)
            .map_err(|e| self.point_error(p, &values, e))?;
        let solved = if self.exact {
            run::<Exact>(&scene, None)
        } else {
            run::<f64>(&scene, None)
        };
        match solved {
            Ok(s) => Ok((values, Some(s.report))),
            Err(RunError::Solve(SolveError::Singular { .. })) => Ok((values, None)),
            Err(e) => Err(self.point_error(p, &values, e.to_string())),
        }
    }

    fn header(&self) -> Vec<String> {
        let mut h = vec!["point".to_string()];
        for v in &self.vary {
            h.push(v.path.clone());
            if self.exact {
                h.push(format!("{}_exact", v.path));
            }
        }
        let names = output_names(self.contacts);
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
        let n = self.contacts + 8;
        if self.exact { n + self.contacts + 2 } else { n }
    }

    fn row(&self, p: usize) -> Result<Row, SweepError> {
        let (values, report) = self.solve(p)?;
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
                .and_then(|r| r.models.iter().find(|x| x.model == *m));
            per_model.push(r.map(model_values));
            match r {
                None => fields.extend(std::iter::repeat_n(String::new(), self.model_width())),
                Some(r) => {
                    for x in model_values(r) {
                        fields.push(num(x));
                    }
                    if self.exact {
                        let exact = |v: &crate::report::Value| v.exact.clone().unwrap_or_default();
                        fields.extend(r.impulses.iter().map(exact));
                        fields.push(exact(&r.lost_velocity_energy));
                        fields.push(exact(&r.kinetic_energy_loss));
                    }
                }
            }
        }
        let singular = report.is_none();
        fields.push(if singular { "singular" } else { "ok" }.into());
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
        })
    }

    /// Solve `range`, write the CSV (and the plot); the number of singular points.
    fn execute(
        &self,
        opts: &SweepOptions,
        range: std::ops::Range<usize>,
        started: Instant,
    ) -> Result<usize, SweepError> {
        let csv_file = Staged::create(&opts.out)?;
        let io_err = |e: &dyn std::fmt::Display| SweepError::Io {
            path: opts.out.clone(),
            message: format!("cannot write {}: {e}", csv_file.tmp.display()),
        };
        let file = csv_file.open()?;
        let mut writer = csv::Writer::from_writer(BufWriter::new(file));
        writer.write_record(self.header()).map_err(|e| io_err(&e))?;

        let bar =
            ProgressBar::with_draw_target(Some(range.len() as u64), ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(
            "sweep {bar:40} {pos}/{len} points, {elapsed} elapsed, ~{eta} left",
        ) {
            bar.set_style(style);
        }
        let mut bar_shown = false;
        let may_show = opts.progress && std::io::stderr().is_terminal();

        // Per series, (j, x, y) in point order.
        let mut plotted: Vec<Vec<(usize, f64, f64)>> = vec![Vec::new(); self.series.len()];
        let mut singular = 0;
        let mut lo = range.start;
        while lo < range.end {
            let hi = (lo + CHUNK).min(range.end);
            let rows = (lo..hi)
                .into_par_iter()
                .map(|p| {
                    let r = self.row(p);
                    bar.inc(1);
                    r
                })
                .collect::<Result<Vec<Row>, SweepError>>()?;
            for row in rows {
                writer.write_record(&row.fields).map_err(|e| io_err(&e))?;
                singular += usize::from(row.singular);
                for (s, y) in row.ys.iter().enumerate() {
                    plotted[s].push((row.j, row.x, *y));
                }
            }
            if may_show && !bar_shown && started.elapsed() > PROGRESS_AFTER && hi < range.end {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                bar_shown = true;
            }
            lo = hi;
        }
        bar.finish_and_clear();

        let buffered = writer.into_inner().map_err(|e| io_err(&e.error()))?;
        let file = buffered.into_inner().map_err(|e| io_err(&e.error()))?;
        file.sync_all().map_err(|e| io_err(&e))?;
        drop(file);
        csv_file.commit()?;

        if let Some(path) = &opts.plot {
            let svg = self.render(&plotted)?;
            let staged = Staged::create(path)?;
            let mut f = staged.open()?;
            f.write_all(svg.as_bytes())
                .and_then(|()| f.sync_all())
                .map_err(|e| SweepError::Io {
                    path: path.clone(),
                    message: format!("cannot write {}: {e}", staged.tmp.display()),
                })?;
            drop(f);
            staged.commit()?;
        }
        Ok(singular)
    }

    /// The SVG of the plotted series.
    fn render(&self, plotted: &[Vec<(usize, f64, f64)>]) -> Result<String, SweepError> {
        use plotters::prelude::*;
        let err = |e: &dyn std::fmt::Display| SweepError::Plot(e.to_string());

        let v0 = &self.vary[0];
        let (a, b) = (rational_to_f64(&v0.start), rational_to_f64(&v0.stop));
        let (x0, x1) = (a.min(b), a.max(b));
        let ys = plotted
            .iter()
            .flatten()
            .map(|t| t.2)
            .filter(|y| y.is_finite());
        let (mut y0, mut y1) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
            (lo.min(y), hi.max(y))
        });
        if !y0.is_finite() {
            (y0, y1) = (-1.0, 1.0);
        }
        let pad = if y1 > y0 {
            0.05 * (y1 - y0)
        } else {
            0.5 * y0.abs().max(1.0)
        };
        let (y0, y1) = (y0 - pad, y1 + pad);

        // Colour by output, dash by model.
        let mut colours: Vec<usize> = Vec::new();
        for s in &self.series {
            if !colours.contains(&s.output) {
                colours.push(s.output);
            }
        }
        let names = output_names(self.contacts);
        let dots = v0.count <= 41;

        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (960, 600)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| err(&e))?;
            let mut caption = format!("{}: sweep over {}", self.name, v0.path);
            if let Some(v1) = self.vary.get(1) {
                caption.push_str(&format!(" (one line per {})", v1.path));
            }
            let mut chart = ChartBuilder::on(&root)
                .caption(caption, ("sans-serif", 20))
                .margin(15)
                .x_label_area_size(45)
                .y_label_area_size(80)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(|e| err(&e))?;
            chart
                .configure_mesh()
                .x_desc(v0.path.as_str())
                .y_desc("impulse P / velocity / energy (scene units)")
                .draw()
                .map_err(|e| err(&e))?;
            for (s, points) in self.series.iter().zip(plotted) {
                let k = colours.iter().position(|c| *c == s.output).unwrap_or(0);
                let (r, g, b) = PALETTE[k % PALETTE.len()];
                let colour = RGBColor(r, g, b).to_rgba();
                let style = colour.stroke_width(2);
                let dashed = s.model > 0;
                let label = format!("{} {}", self.models[s.model], names[s.output]);
                // One line per value of the second input, broken at singular points.
                let mut slices: BTreeMap<usize, Vec<Vec<(f64, f64)>>> = BTreeMap::new();
                for &(j, x, y) in points {
                    let segs = slices.entry(j).or_insert_with(|| vec![Vec::new()]);
                    if y.is_finite() {
                        if let Some(seg) = segs.last_mut() {
                            seg.push((x, y));
                        }
                    } else if segs.last().is_some_and(|seg| !seg.is_empty()) {
                        segs.push(Vec::new());
                    }
                }
                let mut labelled = false;
                for seg in slices.into_values().flatten().filter(|s| !s.is_empty()) {
                    let drawn = if dashed {
                        chart.draw_series(DashedLineSeries::new(seg.clone(), 8, 5, style))
                    } else {
                        chart.draw_series(LineSeries::new(seg.clone(), style))
                    }
                    .map_err(|e| err(&e))?;
                    if !labelled {
                        drawn.label(label.clone()).legend(move |(x, y)| {
                            plotters::element::DashedPathElement::new(
                                vec![(x, y), (x + 24, y)],
                                // Solid: one dash longer than the sample.
                                if dashed { 6 } else { 30 },
                                if dashed { 3 } else { 10 },
                                style,
                            )
                        });
                        labelled = true;
                    }
                    if dots {
                        chart
                            .draw_series(
                                seg.iter()
                                    .map(|&(x, y)| Circle::new((x, y), 2, colour.filled())),
                            )
                            .map_err(|e| err(&e))?;
                    }
                }
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| err(&e))?;
            root.present().map_err(|e| err(&e))?;
        }
        Ok(svg)
    }
}

/// A varied number that can be set in a validated [`Scene`] directly, without re-reading the
/// document: the numbers whose validity is convex (a value between two valid ones is valid:
/// m, J > 0, k ∈ [0, 1], no condition on velocities or points), so checking START and STOP
/// covers the whole range. Normals, tangents and constraints (which must not be zero vectors)
/// go through [`set_value`] and [`Scene::from_document`] at every point.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Slot {
    Mass,
    Inertia(usize),
    Velocity(usize),
    AngularVelocity(usize),
    Point(usize, usize),
    K(usize),
    KNewton(usize),
    KPoisson(usize),
}

impl Slot {
    /// The slot of `path` in `scene`, if it is one of the directly settable numbers.
    fn find(path: &str, scene: &Scene) -> Option<Slot> {
        let index = |s: &str, limit: usize| -> Option<usize> {
            let i: usize = s.strip_prefix('[')?.strip_suffix(']')?.parse().ok()?;
            (i < limit).then_some(i)
        };
        if let Some(rest) = path.strip_prefix("body.") {
            if rest == "mass" {
                return Some(Slot::Mass);
            }
            let (key, idx) = rest.split_at(rest.find('[')?);
            let i = index(idx, 3)?;
            return match key {
                "inertia" => Some(Slot::Inertia(i)),
                "velocity" => Some(Slot::Velocity(i)),
                "angular_velocity" => Some(Slot::AngularVelocity(i)),
                _ => None,
            };
        }
        let rest = path.strip_prefix("contact")?;
        let (idx, key) = rest.split_once('.')?;
        let c = index(idx, scene.contacts.len())?;
        match key {
            "k" => Some(Slot::K(c)),
            "k_newton" => Some(Slot::KNewton(c)),
            "k_poisson" => Some(Slot::KPoisson(c)),
            _ => {
                let i = index(key.strip_prefix("point")?, 3)?;
                Some(Slot::Point(c, i))
            }
        }
    }

    /// Set the number to q, as [`set_value`] and [`Scene::from_document`] would.
    fn set(self, scene: &mut Scene, q: &BigRational) {
        let n = Number {
            text: text(q),
            exact: Ok(q.clone()),
            approx: rational_to_f64(q),
            symbols: Vec::new(),
        };
        match self {
            Slot::Mass => scene.mass = n,
            Slot::Inertia(i) => scene.inertia[i] = n,
            Slot::Velocity(i) => scene.velocity[i] = n,
            Slot::AngularVelocity(i) => scene.angular_velocity[i] = n,
            Slot::Point(c, i) => scene.contacts[c].point[i] = n,
            Slot::K(c) => {
                scene.contacts[c].k_newton = n.clone();
                scene.contacts[c].k_poisson = n;
            }
            Slot::KNewton(c) => scene.contacts[c].k_newton = n,
            Slot::KPoisson(c) => scene.contacts[c].k_poisson = n,
        }
    }
}

/// Line colours, one per output (Tableau 10: distinct, readable on white).
const PALETTE: [(u8, u8, u8); 10] = [
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

/// A model's numeric outputs, in [`output_names`] order.
fn model_values(r: &ModelReport) -> Vec<f64> {
    let mut v: Vec<f64> = r.impulses.iter().map(|x| x.f64).collect();
    v.extend(r.velocity.iter().map(|x| x.f64));
    v.extend(r.angular_velocity.iter().map(|x| x.f64));
    v.push(r.lost_velocity_energy.f64);
    v.push(r.kinetic_energy_loss.f64);
    v
}

/// The plotted series for the names asked for (see [`SweepOptions::plot_outputs`]).
fn resolve_outputs(
    asked: &[String],
    models: &[Model],
    contacts: usize,
) -> Result<Vec<Series>, SweepError> {
    let names = output_names(contacts);
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
    let available = || {
        let mut all: Vec<String> = names.clone();
        for m in models {
            all.extend(names.iter().map(|n| format!("{m}_{n}")));
        }
        all.join(", ")
    };
    for name in asked {
        let name = name.trim();
        let (model, output) = match name.split_once('_') {
            Some((m, rest)) if Model::from_name(m).is_some() => (Model::from_name(m), rest),
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
                available()
            ))
        })?;
        match model {
            None => {
                for m in 0..models.len() {
                    push(Series {
                        model: m,
                        output: o,
                    });
                }
            }
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
                push(Series {
                    model: m,
                    output: o,
                });
            }
        }
    }
    Ok(out)
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

/// A full-precision f64 for the CSV.
fn num(x: f64) -> String {
    format!("{x:?}")
}

/// An exact value as a person writes it: `3`, `0.01`, or `1/3`.
fn text(q: &BigRational) -> String {
    match decimal(q) {
        Some(d) => d,
        None => format_rational(q),
    }
}

/// The TOML text of an exact value: an integer or decimal literal when it has a short one
/// (so messages show `1.5`), else the string `"p/q"`; either is read back exactly.
fn toml_text(q: &BigRational) -> String {
    match decimal(q) {
        Some(d) => d,
        None => format!("\"{}\"", format_rational(q)),
    }
}

/// q as a terminating decimal of at most 40 places, if it is one.
fn decimal(q: &BigRational) -> Option<String> {
    if q.is_integer() {
        return Some(q.numer().to_string());
    }
    let (two, five) = (BigInt::from(2), BigInt::from(5));
    let mut den = q.denom().clone();
    let mut places = [0u32; 2];
    for (k, p) in [&two, &five].into_iter().enumerate() {
        while (&den % p).is_zero() {
            den /= p;
            places[k] += 1;
        }
    }
    let scale = places[0].max(places[1]);
    if !den.is_one() || scale > 40 {
        return None;
    }
    let scaled = q * BigRational::from_integer(BigInt::from(10).pow(scale));
    let digits = scaled.numer().abs().to_string();
    let digits = format!("{digits:0>width$}", width = scale as usize + 1);
    let (int, frac) = digits.split_at(digits.len() - scale as usize);
    let sign = if q.is_negative() { "-" } else { "" };
    Some(format!("{sign}{int}.{frac}"))
}

/// A file written as `FILE.tmp` and renamed to `FILE` on [`Staged::commit`]; removed if
/// dropped uncommitted.
struct Staged {
    path: PathBuf,
    tmp: PathBuf,
    done: bool,
}

impl Staged {
    fn create(path: &Path) -> Result<Staged, SweepError> {
        let mut tmp = path.as_os_str().to_owned();
        tmp.push(".tmp");
        Ok(Staged {
            path: path.to_path_buf(),
            tmp: PathBuf::from(tmp),
            done: false,
        })
    }

    fn open(&self) -> Result<File, SweepError> {
        File::create(&self.tmp).map_err(|e| SweepError::Io {
            path: self.path.clone(),
            message: format!(
                "cannot create {}: {e}; check that the directory exists and is writable",
                self.tmp.display()
            ),
        })
    }

    fn commit(mut self) -> Result<(), SweepError> {
        std::fs::rename(&self.tmp, &self.path).map_err(|e| SweepError::Io {
            path: self.path.clone(),
            message: format!("cannot rename {} to it: {e}", self.tmp.display()),
        })?;
        self.done = true;
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    #[test]
    fn vary_parses_good_specs() {
        let v = Vary::parse("contact[1].k=0:1:101").unwrap();
        assert_eq!(v.path, "contact[1].k");
        assert_eq!(
            (v.start.clone(), v.stop.clone(), v.count),
            (q(0, 1), q(1, 1), 101)
        );
        for i in 0..=100 {
            assert_eq!(v.value(i), q(i as i64, 100), "point {i}");
        }
        // Decreasing ranges are allowed; fractions and decimals are exact.
        let d = Vary::parse("contact[1].k=1:0:5").unwrap();
        assert_eq!(d.value(1), q(3, 4));
        assert_eq!(d.value(4), q(0, 1));
        let f = Vary::parse(" body.mass = 1/3 : 0.7 : 3 ").unwrap();
        assert_eq!(
            (f.path.as_str(), f.start.clone(), f.stop.clone()),
            ("body.mass", q(1, 3), q(7, 10))
        );
        assert_eq!(f.value(1), q(31, 60));
        let e = Vary::parse("body.velocity[0]=-2:1e-1:2").unwrap();
        assert_eq!(e.start, q(-2, 1));
        assert_eq!(e.stop, q(1, 10));
    }

    #[test]
    fn vary_refuses_bad_specs_naming_the_problem() {
        let reason = |spec: &str| match Vary::parse(spec) {
            Err(SweepError::Vary { spec: s, reason }) => {
                assert_eq!(s, spec);
                reason
            }
            other => panic!("{spec}: expected a Vary error, got {other:?}"),
        };
        assert!(reason("k=0:1").contains("START:STOP:COUNT"));
        assert!(reason("contact[1].k=0:1:1").contains("at least 2"));
        assert!(reason("contact[1].k=0:1:0").contains("at least 2"));
        assert!(reason("=0:1:3").contains("path"));
        assert!(reason("contact[1].k").contains("PATH=START:STOP:COUNT"));
        assert!(reason("contact[1].k=zero:1:3").contains("START"));
        assert!(reason("contact[1].k=0:1..2:3").contains("STOP"));
        assert!(reason("contact[1].k=0:1:many").contains("COUNT `many`"));
        assert!(reason("contact[1].k=0:1:-3").contains("COUNT"));
        assert!(reason("contact[1].k=0:sqrt(2):3").contains("not rational"));
        assert!(reason("contact[1].k=0.5:1/2:3").contains("equal"));
        assert!(reason("contact [1].k=0:1:3").contains("whitespace"));
    }

    #[test]
    fn shard_parses_and_refuses() {
        assert_eq!(Shard::parse("1/4").unwrap(), Shard { index: 1, count: 4 });
        assert_eq!(Shard::parse("4/4").unwrap(), Shard { index: 4, count: 4 });
        for (spec, needle) in [
            ("0/4", "numbered from 1"),
            ("5/4", "does not exist"),
            ("a/b", "not a whole number"),
            ("1/0", "at least one shard"),
            ("3", "expected I/N"),
            ("-1/4", "not a whole number"),
        ] {
            match Shard::parse(spec) {
                Err(e @ SweepError::Shard { .. }) => {
                    assert!(e.to_string().contains(needle), "{spec}: {e}");
                    assert_eq!(e.exit_code(), 2);
                }
                other => panic!("{spec}: {other:?}"),
            }
        }
    }

    #[test]
    fn shards_are_disjoint_and_cover() {
        for points in [0usize, 1, 2, 3, 7, 10, 11, 100, 101, 1000, 1023, 4097] {
            for n in 1..=17 {
                let mut next = 0;
                for i in 1..=n {
                    let r = Shard { index: i, count: n }.range(points);
                    assert_eq!(r.start, next, "P = {points}, {i}/{n}");
                    assert!(r.end >= r.start);
                    // Balanced: sizes differ by at most one.
                    assert!(r.len() <= points / n + 1);
                    next = r.end;
                }
                assert_eq!(next, points, "P = {points}, N = {n}");
            }
        }
        // Reproducible, and large grids do not overflow.
        let big = Shard { index: 3, count: 7 }.range(usize::MAX);
        assert_eq!(big, Shard { index: 3, count: 7 }.range(usize::MAX));
        assert!(big.start < big.end);
    }

    #[test]
    fn toml_text_reads_back_exactly() {
        for (n, d, want) in [
            (0, 1, "0"),
            (3, 2, "1.5"),
            (1, 100, "0.01"),
            (-1, 8, "-0.125"),
            (-7, 1, "-7"),
            (1, 3, "\"1/3\""),
            (-2, 3, "\"-2/3\""),
        ] {
            let x = q(n, d);
            let t = toml_text(&x);
            assert_eq!(t, want);
            let read = parse_number(t.trim_matches('"')).unwrap().exact.unwrap();
            assert_eq!(read, x);
        }
    }

    #[test]
    fn outputs_resolve_by_column_or_per_model_name() {
        let models = Model::ALL.to_vec();
        let pairs = |names: &[&str]| -> Vec<(usize, usize)> {
            let asked: Vec<String> = names.iter().map(|s| s.to_string()).collect();
            resolve_outputs(&asked, &models, 2)
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
        let e = resolve_outputs(&asked, &models, 2).unwrap_err();
        assert!(e.to_string().contains("newton_P1"), "{e}");
        let asked = vec!["poisson_P1".to_string()];
        let e = resolve_outputs(&asked, &[Model::Newton], 2).unwrap_err();
        assert!(e.to_string().contains("poisson"), "{e}");
    }

    const SCENE: &str = r#"
        [body]
        mass = 1
        inertia = [12, 1.6, 12]
        velocity = [3, 2, 0]
        angular_velocity = [0, 0, 0.4]
        [[contact]]
        point = [0, -2, 0]
        normal = [1, 0, 0]
        k = 0.3
        [[contact]]
        point = [0, 4, 0]
        normal = [1, 0, 0]
        k_newton = 0.2
        k_poisson = "1/7"
    "#;

    #[test]
    fn direct_slots_agree_with_rereading_the_document() {
        let doc = parse_document(SCENE, "s.toml").unwrap();
        let base = Scene::from_document(&doc, "s.toml").unwrap();
        let paths = [
            "body.mass",
            "body.inertia[2]",
            "body.velocity[0]",
            "body.angular_velocity[1]",
            "contact[0].point[1]",
            "contact[1].point[2]",
            "contact[0].k",
            "contact[1].k",
            "contact[0].k_newton",
            "contact[1].k_poisson",
        ];
        for path in paths {
            let slot = Slot::find(path, &base).unwrap_or_else(|| panic!("{path}"));
            for x in [q(1, 3), q(1, 100), q(1, 1), q(5, 8), q(3, 7)] {
                let mut d = doc.clone();
                set_value(&mut d, path, &toml_text(&x)).unwrap();
                let reread = Scene::from_document(&d, "s.toml").unwrap();
                let mut direct = base.clone();
                slot.set(&mut direct, &x);
                assert_eq!(direct, reread, "{path} = {x}");
            }
        }
        for path in [
            "contact[0].normal[0]",
            "contact[2].k",
            "contact[0].tangent[0]",
            "body.inertia[3]",
            "body.inertia",
            "contact[0].point",
            "name",
        ] {
            assert_eq!(Slot::find(path, &base), None, "{path}");
        }
    }

    #[test]
    fn overlapping_paths() {
        assert!(overlap("contact[1].k", "contact[1].k"));
        assert!(overlap("contact[1].k", "contact[1].k_poisson"));
        assert!(overlap("contact[0].k_newton", "contact[0].k"));
        assert!(!overlap("contact[0].k", "contact[1].k"));
        assert!(!overlap("contact[0].k_newton", "contact[0].k_poisson"));
    }
}
