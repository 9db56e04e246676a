//! A sweep under the LZB law (`[solve] law = "lzb"` or `--law lzb`): each point's scene
//! integrated by [`crate::scene::lzb::run_lzb`] in f64, with the LZB law's own columns — so a
//! user can follow how the outcome moves with a contact's stiffness K_i, exponent η_i or
//! energetic restitution e_i (`contact[i].stiffness`, `.exponent`, `.k_energetic`, `.k`), or
//! any other number of the scene.
//!
//! The grid, the shards and the files are those of every sweep ([`super`]); the points are
//! solved in parallel a chunk at a time. Each point re-reads the document (a stiffness that is
//! not written in the scene is added to its contact), and the scene must be valid — its LZB
//! laws included — at START and STOP of every varied range.
//!
//! ## CSV columns
//!
//! `point`, each varied path's value, then per contact i (from 1) `P{i}` (N s), `v{i}` (m/s
//! after impact, positive approaching), `Emax{i}`, `Wc{i}`, `Wr{i}` (J); each body's twist after
//! impact (`vCx … wz`, or `BODY.vCx … BODY.wz` for a system); `dEc` (ΔE_c), `residual`
//! (ΔE_c − Σ(W_c − W_r)), `error` (the impulses' error estimate, N s), `order` (the contacts in
//! the order they came to rest, e.g. `1 2`) and `status`: `ok`, or `runaway` for an
//! integration that did not end within its budget (its outputs empty).
//!
//! `--exact` and `--sensitivity` are refused: the integration is numerical and is not
//! differentiated. `--plot` draws the chosen columns (default `P1 … PN` and `dEc`) against the
//! first varied input, one line per value of the second.

use std::io::{BufWriter, Write};
use std::time::Instant;

use plotters::prelude::*;
use rayon::prelude::*;
use toml_edit::DocumentMut;

use super::file::Staged;
use super::plan::{check_shard_and_files, check_varied, grid_points, read_scene};
use super::plot::{segments, y_range};
use super::target::Target;
use super::text::{num, text};
use super::{CHUNK, SweepError, SweepOptions, SweepSummary, Vary};
use crate::impact::multiple::LzbError;
use crate::impact::unilateral::Law;
use crate::number::rational_to_f64;
use crate::report::lzb::PALETTE;
use crate::scene::Scene;
use crate::scene::lzb::{LzbReport, contact_laws, run_lzb};
use crate::scene::pipeline::RunError;

/// The contact keys that hold the LZB law's parameters: varied even when not written.
const LAW_KEYS: [&str; 3] = ["stiffness", "exponent", "k_energetic"];

/// Whether a sweep of `opts` runs the LZB law: `--law lzb`, or the scene's law without `--law`.
pub(super) fn runs_lzb(opts: &SweepOptions, base: &Scene) -> bool {
    opts.law.unwrap_or(base.law) == Law::Lzb
}

/// A validated LZB sweep.
struct LzbPlan {
    file: String,
    name: String,
    doc: DocumentMut,
    vary: Vec<Vary>,
    targets: Vec<Target>,
    contacts: usize,
    bodies: Vec<String>,
    /// The plotted columns, as indices into [`LzbPlan::outputs`].
    plotted: Vec<usize>,
}

/// Run an LZB sweep (module docs).
pub(super) fn sweep_lzb(opts: &SweepOptions, started: Instant) -> Result<SweepSummary, SweepError> {
    check_varied(&opts.vary)?;
    check_shard_and_files(opts)?;
    if opts.exact {
        return Err(SweepError::Options(
            "--exact: the LZB law is integrated numerically (adaptive Runge–Kutta in f64), so \
             its result is never exact: drop --exact"
                .into(),
        ));
    }
    if opts.sensitivity {
        return Err(SweepError::Options(
            "--sensitivity: the LZB law's integration is not differentiated: drop \
             --sensitivity (difference neighbouring points of the CSV instead)"
                .into(),
        ));
    }
    let points = grid_points(&opts.vary)?;
    let (file, doc, mut base) = read_scene(opts)?;
    if base.law != Law::Lzb {
        base.set_law(Law::Lzb, "`--law lzb`")?;
    }
    contact_laws(&base)?;
    let contacts = base.contacts.len();
    let bodies = super::answer::body_names(&base);
    let targets: Vec<Target> = opts
        .vary
        .iter()
        .map(|v| Target::of(&v.path, &base))
        .collect();
    let mut plan = LzbPlan {
        file,
        name: base.name.clone(),
        doc,
        vary: opts.vary.clone(),
        targets,
        contacts,
        bodies,
        plotted: Vec::new(),
    };
    plan.check_paths(&base)?;
    if opts.plot.is_some() {
        plan.plotted = plan.resolve(&opts.plot_outputs)?;
    }
    let range = match opts.shard {
        Some(s) => s.range(points),
        None => 0..points,
    };
    let runaway = match opts.threads {
        Some(n) if n > 0 => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| SweepError::Threads(e.to_string()))?;
            pool.install(|| plan.execute(opts, range.clone()))?
        }
        _ => plan.execute(opts, range.clone())?,
    };
    Ok(SweepSummary {
        points: range.len(),
        singular: runaway,
        seconds: started.elapsed().as_secs_f64(),
    })
}

impl LzbPlan {
    /// The output columns, in CSV order.
    fn outputs(&self) -> Vec<String> {
        const TWIST: [&str; 6] = ["vCx", "vCy", "vCz", "wx", "wy", "wz"];
        let n = self.contacts;
        let mut v = Vec::new();
        for key in ["P", "v", "Emax", "Wc", "Wr"] {
            v.extend((1..=n).map(|i| format!("{key}{i}")));
        }
        if self.bodies.is_empty() {
            v.extend(TWIST.iter().map(|s| s.to_string()));
        } else {
            for b in &self.bodies {
                v.extend(TWIST.iter().map(|s| format!("{b}.{s}")));
            }
        }
        v.extend(["dEc", "residual", "error"].map(String::from));
        v
    }

    /// The plotted columns named by the user (default `P1 … PN` and `dEc`).
    fn resolve(&self, names: &[String]) -> Result<Vec<usize>, SweepError> {
        let outputs = self.outputs();
        if names.is_empty() {
            let mut v: Vec<usize> = (0..self.contacts).collect();
            v.push(outputs.len() - 3);
            return Ok(v);
        }
        names
            .iter()
            .map(|name| {
                outputs
                    .iter()
                    .position(|o| o == name.trim())
                    .ok_or_else(|| SweepError::Output {
                        name: name.clone(),
                        reason: format!(
                            "not a column of an LZB sweep; plot one of: {}",
                            outputs.join(", ")
                        ),
                    })
            })
            .collect()
    }

    /// Each varied path names a number of the scene (or an LZB parameter of a contact), and
    /// the scene and its laws are valid at both ends of its range.
    fn check_paths(&self, base: &Scene) -> Result<(), SweepError> {
        let keys = Target::keys(base);
        for (k, (v, t)) in self.vary.iter().zip(&self.targets).enumerate() {
            let spec = format!(
                "{}={}:{}:{}",
                v.path,
                text(&v.start),
                text(&v.stop),
                v.count
            );
            if !(t.known(&v.path, base, &keys) || self.law_key(&v.path)) {
                return Err(SweepError::Vary {
                    spec,
                    reason: format!(
                        "`{}` is not a number or parameter of the scene; under the LZB law vary \
                         a contact's `stiffness`, `exponent`, `k_energetic` or `k` \
                         (`contact[0].stiffness`), or another number of the scene",
                        v.path
                    ),
                });
            }
            for (which, q) in [("START", &v.start), ("STOP", &v.stop)] {
                let mut doc = self.doc.clone();
                self.targets[k]
                    .set(&mut doc, q)
                    .map_err(|reason| SweepError::Vary {
                        spec: spec.clone(),
                        reason,
                    })?;
                Scene::from_document(&doc, &self.file)
                    .and_then(|s| contact_laws(&s))
                    .map_err(|e| SweepError::Vary {
                        spec: spec.clone(),
                        reason: format!("the scene is invalid at {which} = {}: {e}", text(q)),
                    })?;
            }
        }
        Ok(())
    }

    /// Whether `path` is `contact[i].KEY` for an LZB parameter KEY and a contact i.
    fn law_key(&self, path: &str) -> bool {
        let Some((contact, key)) = path.split_once('.') else {
            return false;
        };
        let index = contact
            .strip_prefix("contact[")
            .and_then(|s| s.strip_suffix(']'))
            .and_then(|s| s.parse::<usize>().ok());
        index.is_some_and(|i| i < self.contacts) && LAW_KEYS.contains(&key)
    }

    /// The varied values at point p, outer first.
    fn values(&self, p: usize) -> Vec<num_rational::BigRational> {
        match self.vary.get(1) {
            Some(v) => vec![self.vary[0].value(p / v.count), v.value(p % v.count)],
            None => vec![self.vary[0].value(p)],
        }
    }

    /// Point p's report, `None` for a runaway integration.
    fn solve(&self, p: usize) -> Result<Option<LzbReport>, SweepError> {
        let values = self.values(p);
        let fail = |message: String| SweepError::Point {
            point: p,
            at: self
                .vary
                .iter()
                .zip(&values)
                .map(|(v, q)| format!("{} = {}", v.path, text(q)))
                .collect::<Vec<_>>()
                .join(", "),
            message,
        };
        let mut doc = self.doc.clone();
        for (t, q) in self.targets.iter().zip(&values) {
            t.set(&mut doc, q).map_err(fail)?;
        }
        let mut scene = Scene::from_document(&doc, &self.file).map_err(|e| fail(e.to_string()))?;
        scene.law = Law::Lzb;
        match run_lzb(&scene) {
            Ok(r) => Ok(Some(r)),
            Err(RunError::Lzb(LzbError::Runaway { .. })) => Ok(None),
            Err(e) => Err(fail(e.to_string())),
        }
    }

    /// Point p's CSV fields and its output values (empty for a runaway point).
    fn row(&self, p: usize) -> Result<(Vec<String>, Vec<f64>), SweepError> {
        let mut fields = vec![p.to_string()];
        fields.extend(self.values(p).iter().map(|q| num(rational_to_f64(q))));
        let report = self.solve(p)?;
        let Some(r) = report else {
            fields.extend(std::iter::repeat_n(String::new(), self.outputs().len() + 1));
            fields.push("runaway".into());
            return Ok((fields, Vec::new()));
        };
        let mut ys: Vec<f64> = Vec::new();
        for v in [
            &r.impulses,
            &r.after,
            &r.max_energy,
            &r.work_compression,
            &r.work_expansion,
        ] {
            ys.extend(v);
        }
        for (_, w, v) in &r.twists {
            ys.extend(v.iter().chain(w));
        }
        ys.extend([r.kinetic_energy_loss, r.energy_residual, r.error_estimate]);
        fields.extend(ys.iter().map(|&y| num(y)));
        let order: Vec<String> = r.ending_order.iter().map(|i| (i + 1).to_string()).collect();
        fields.push(order.join(" "));
        fields.push("ok".into());
        Ok((fields, ys))
    }

    /// Solve `range` chunk by chunk into the committed CSV, then draw the plot; the runaway
    /// points.
    fn execute(
        &self,
        opts: &SweepOptions,
        range: std::ops::Range<usize>,
    ) -> Result<usize, SweepError> {
        let staged = Staged::create(&opts.out)?;
        let io_err = |e: &dyn std::fmt::Display| SweepError::Io {
            path: opts.out.clone(),
            message: format!("cannot write {}: {e}", staged.tmp.display()),
        };
        let mut writer = csv::Writer::from_writer(BufWriter::new(staged.open()?));
        let mut header = vec!["point".to_string()];
        header.extend(self.vary.iter().map(|v| v.path.clone()));
        header.extend(self.outputs());
        header.extend(["order", "status"].map(String::from));
        writer.write_record(&header).map_err(|e| io_err(&e))?;
        let mut runaway = 0;
        // Per plotted column: (j, x, y), in point order.
        let mut series: Vec<Vec<(usize, f64, f64)>> = vec![Vec::new(); self.plotted.len()];
        let mut lo = range.start;
        while lo < range.end {
            let hi = (lo + CHUNK).min(range.end);
            let rows = (lo..hi)
                .into_par_iter()
                .map(|p| self.row(p))
                .collect::<Result<Vec<_>, _>>()?;
            for (p, (fields, ys)) in (lo..hi).zip(rows) {
                writer.write_record(&fields).map_err(|e| io_err(&e))?;
                runaway += usize::from(ys.is_empty());
                let values = self.values(p);
                let x = rational_to_f64(&values[0]);
                let j = self.vary.get(1).map_or(0, |v| p % v.count);
                for (s, &k) in self.plotted.iter().enumerate() {
                    series[s].push((j, x, ys.get(k).copied().unwrap_or(f64::NAN)));
                }
            }
            lo = hi;
        }
        let buffered = writer.into_inner().map_err(|e| io_err(&e.error()))?;
        let file = buffered.into_inner().map_err(|e| io_err(&e.error()))?;
        file.sync_all().map_err(|e| io_err(&e))?;
        drop(file);
        staged.commit()?;
        if let Some(path) = &opts.plot {
            let svg = self.render(&series)?;
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
        Ok(runaway)
    }

    /// The SVG: the plotted columns against the first varied input, one colour per column,
    /// one line per value of the second varied input, a gap at a runaway point.
    fn render(&self, series: &[Vec<(usize, f64, f64)>]) -> Result<String, SweepError> {
        let err = |e: &dyn std::fmt::Display| SweepError::Plot(e.to_string());
        let v0 = &self.vary[0];
        let (a, b) = (rational_to_f64(&v0.start), rational_to_f64(&v0.stop));
        let (x0, x1) = (a.min(b), a.max(b));
        let (y0, y1) = y_range(series);
        let names = self.outputs();
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (960, 600)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| err(&e))?;
            let mut caption = format!("{}: LZB sweep over {}", self.name, v0.path);
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
                .y_desc("LZB outputs (scene units)")
                .draw()
                .map_err(|e| err(&e))?;
            for (s, points) in series.iter().enumerate() {
                let (r, g, b) = PALETTE[s % PALETTE.len()];
                let colour = RGBColor(r, g, b);
                let mut labelled = false;
                for seg in segments(points) {
                    let drawn = chart
                        .draw_series(LineSeries::new(seg, colour.stroke_width(2)))
                        .map_err(|e| err(&e))?;
                    if !labelled {
                        drawn
                            .label(names[self.plotted[s]].clone())
                            .legend(move |(x, y)| {
                                Rectangle::new([(x, y - 2), (x + 20, y + 2)], colour.filled())
                            });
                        labelled = true;
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
