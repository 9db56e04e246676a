//! `inertance bench` on scenes of several bodies ([`crate::mechanics::system`]).
//!
//! One solve of a system scene is everything from the data, as the `systems` criterion bench
//! counts it: [`System::new`] from the bodies, twists, contacts and joints read from the scene
//! (its checks and the joints' tree factorization), [`Impact::assemble`], then the scene's law
//! with every output — its models under the simultaneous or the unilateral law, or each
//! restitution law it integrates when it is frictional — in f32, f64, double-double and exact.
//! The time is also given per body and per contact (the time per solve divided by the counts).
//! A type without an answer says why: the solve's own verdict (`singular`, `jammed`, a
//! frictional one such as `no-continuation`), or that the solve does not apply (a spatial
//! frictional impact has no exact integration; a number the type cannot hold).
//!
//! The report's systems section ([`run`]) times the planar chain of [`crate::tools::chain`]
//! for N = 1, 10, 100 (and 1000 without `--quick`) bars in f64 — ns per solve, per body, and
//! the log–log slope of the time against N between consecutive N — and the example scenes of
//! several bodies per scalar type.

use std::time::Duration;

use serde_json::{Value as Json, json};

use crate::impact::friction::solve_frictional_under;
use crate::impact::lean_system::LeanSystem;
use crate::impact::mechanism::Mechanism;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::impact::unilateral::{Law, UnilateralError};
use crate::mechanics::system::System;
use crate::scalar::dd::DoubleDouble;
use crate::scalar::{Exact, Scalar};
use crate::scene::Scene;
use crate::scene::pipeline::friction_tolerance;
use crate::tools::bench::{fmt_ns, time_three};
use crate::tools::chain::Chain;

/// Why a type has no time for a scene.
#[derive(Clone, Debug, PartialEq)]
pub enum NotTimed {
    /// The solve has no answer in this type, by its own verdict: `singular` (G singular under
    /// the simultaneous law), `jammed` (no admissible impulses under the unilateral law), or a
    /// frictional one (`no-continuation`, `undetermined`, `never-ends`).
    NoAnswer(&'static str),
    /// The solve does not apply to this scene in this type, and why.
    NotApplicable(String),
}

impl std::fmt::Display for NotTimed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NotTimed::NoAnswer(s) => f.write_str(s),
            NotTimed::NotApplicable(why) => write!(f, "not applicable: {why}"),
        }
    }
}

/// One scene timed per scalar type (`inertance bench --scene`).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneTiming {
    /// The scene's name.
    pub scene: String,
    /// Bodies (1 for one body's scene).
    pub bodies: usize,
    /// Contacts.
    pub contacts: usize,
    /// The law solved: its models (`newton + poisson`, `unilateral newton + poisson`) or, for
    /// a frictional scene, the restitution laws integrated (`friction: poisson`).
    pub law: String,
    /// What one solve is.
    pub solve: String,
    /// Per timed path or type: ns per solve, or why there is none.
    pub rows: Vec<(&'static str, Result<f64, NotTimed>)>,
}

impl SceneTiming {
    /// The JSON: `ns_per_solve` (null where not timed), `ns_per_body`, `ns_per_contact` (the
    /// same divided by the counts) and `not_timed` (why, per type without a time).
    pub fn to_json(&self) -> Json {
        let per = |count: usize| {
            self.rows
                .iter()
                .map(|(name, t)| {
                    let v = match t {
                        Ok(ns) => json!(ns / count.max(1) as f64),
                        Err(_) => Json::Null,
                    };
                    (name.to_string(), v)
                })
                .collect::<serde_json::Map<_, _>>()
        };
        let not_timed = self
            .rows
            .iter()
            .filter_map(|(name, t)| {
                t.as_ref()
                    .err()
                    .map(|e| (name.to_string(), json!(e.to_string())))
            })
            .collect::<serde_json::Map<_, _>>();
        json!({
            "scene": self.scene,
            "bodies": self.bodies,
            "contacts": self.contacts,
            "law": self.law,
            "solve": self.solve,
            "ns_per_solve": per(1),
            "ns_per_body": per(self.bodies),
            "ns_per_contact": per(self.contacts),
            "not_timed": not_timed,
        })
    }

    /// The readable lines: what one solve is, then per type its times or why there are none.
    pub fn to_text(&self) -> String {
        let mut s = format!(
            "{}: {} bod{}, {} contact{}; one solve = {}\n",
            self.scene,
            self.bodies,
            if self.bodies == 1 { "y" } else { "ies" },
            self.contacts,
            if self.contacts == 1 { "" } else { "s" },
            self.solve
        );
        for (name, t) in &self.rows {
            s += &format!("{name:>18}: ");
            s += &match t {
                Ok(ns) => format!(
                    "{ns:.0} ns per solve, {:.0} ns per body, {:.0} ns per contact",
                    ns / self.bodies.max(1) as f64,
                    ns / self.contacts.max(1) as f64
                ),
                Err(e) => e.to_string(),
            };
            s.push('\n');
        }
        s
    }
}

/// The law `scene` is solved under (see [`SceneTiming::law`]).
pub(crate) fn law_name(scene: &Scene) -> String {
    if scene.frictional() {
        let laws: Vec<&str> = scene.restitutions(None).iter().map(|l| l.name()).collect();
        format!("friction: {}", laws.join(", "))
    } else {
        let models: Vec<&str> = scene.models.iter().map(|m| m.name()).collect();
        let law = match scene.law {
            Law::Simultaneous => "",
            Law::Unilateral => "unilateral ",
            Law::Lzb => "lzb ",
        };
        format!("{law}{}", models.join(" + "))
    }
}

/// What one solve of `scene` is: `build` (`assemble`, or `System::new + assemble`), then its
/// law.
pub(crate) fn solve_description(scene: &Scene, build: &str) -> String {
    format!(
        "{build} + {} (each that answers), every output",
        law_name(scene)
    )
}

/// The verdict a solve's error gives, or why the solve does not apply.
fn solve_error(e: &SolveError) -> NotTimed {
    match e {
        SolveError::Singular { .. } => NotTimed::NoAnswer("singular"),
        other => NotTimed::NotApplicable(other.to_string()),
    }
}

fn unilateral_error(e: &UnilateralError) -> NotTimed {
    match e {
        UnilateralError::Jammed { .. } => NotTimed::NoAnswer("jammed"),
        UnilateralError::Solve(e) => solve_error(e),
        other => NotTimed::NotApplicable(other.to_string()),
    }
}

/// The median ns of one solve of `scene`'s law on the mechanism `build` returns (called once
/// per solve, inside the timing: a system is built from its data every time), within `budget`.
/// The models or laws without an answer in `T` are left out; when none answers, the first
/// one's verdict.
pub(crate) fn time_law<T: Scalar, M: Mechanism<T>>(
    scene: &Scene,
    budget: Duration,
    build: impl Fn() -> Result<M, NotTimed>,
) -> Result<f64, NotTimed> {
    let first = build()?;
    if scene.frictional() {
        let tolerance = scene.tolerance.unwrap_or_else(friction_tolerance::<T>);
        let mut laws = Vec::new();
        let mut failure = None;
        for law in scene.restitutions(None) {
            match solve_frictional_under(&first, law, scene.hypothesis(), tolerance) {
                Ok(_) => laws.push(law),
                Err(e) => {
                    failure.get_or_insert(match e.status() {
                        Some(s) => NotTimed::NoAnswer(s),
                        None => NotTimed::NotApplicable(e.to_string()),
                    });
                }
            }
        }
        if laws.is_empty() {
            return Err(failure.unwrap_or(NotTimed::NotApplicable("no law to solve".into())));
        }
        return time_three(budget, || {
            let m = build()?;
            for &law in &laws {
                std::hint::black_box(
                    solve_frictional_under(&m, law, scene.hypothesis(), tolerance)
                        .map_err(|e| NotTimed::NotApplicable(e.to_string()))?,
                );
            }
            Ok(())
        });
    }
    let law = scene.law;
    let solve_one = |impact: &mut Impact<T, M>, m: Model, out: &mut Outcome<T, M::Screw>| match law
    {
        Law::Simultaneous => impact.solve(m, out).map_err(|e| solve_error(&e)),
        Law::Unilateral => impact
            .solve_unilateral(m, out)
            .map(|_| ())
            .map_err(|e| unilateral_error(&e)),
        // Timed by `tools::lzb_bench` before this is reached.
        Law::Lzb => Err(NotTimed::NotApplicable(
            "the LZB law is integrated, not assembled and solved: `tools::lzb_bench` times it"
                .to_string(),
        )),
    };
    let mut out = Outcome::default();
    let mut impact = Impact::assemble(&first).map_err(|e| solve_error(&e))?;
    let mut models: Vec<Model> = Vec::new();
    let mut failure = None;
    for &m in &scene.models {
        match solve_one(&mut impact, m, &mut out) {
            Ok(()) => models.push(m),
            Err(e) => {
                failure.get_or_insert(e);
            }
        }
    }
    if models.is_empty() {
        return Err(failure.unwrap_or(NotTimed::NotApplicable("no model to solve".into())));
    }
    time_three(budget, || {
        let m = build()?;
        let mut impact = Impact::assemble(std::hint::black_box(&m)).map_err(|e| solve_error(&e))?;
        for &model in &models {
            solve_one(&mut impact, model, &mut out)?;
        }
        Ok(())
    })
}

/// ns per solve of the system scene `scene` in `T` (module docs).
fn time_system<T: Scalar>(scene: &Scene, budget: Duration) -> Result<f64, NotTimed> {
    let system = scene
        .system::<T>()
        .map_err(|e| NotTimed::NotApplicable(format!("{}: {}", e.key, e.message)))?;
    time_law::<T, System<T>>(scene, budget, || {
        System::new(
            system.bodies().to_vec(),
            system.velocity().clone(),
            system.contacts().to_vec(),
            system.pairs().to_vec(),
            system.joints().to_vec(),
        )
        .map_err(|e| NotTimed::NotApplicable(e.to_string()))
    })
}

/// Time the system scene `scene` in f32, f64, double-double and exact, each solve within
/// `budget` (module docs).
pub fn time_system_scene(scene: &Scene, budget: Duration) -> SceneTiming {
    if scene.law == Law::Lzb {
        return crate::tools::lzb_bench::time_lzb_scene(scene, budget);
    }
    SceneTiming {
        scene: scene.name.clone(),
        bodies: scene.system.as_ref().map_or(1, |s| s.bodies.len()),
        contacts: scene.contacts.len(),
        law: law_name(scene),
        solve: solve_description(scene, "System::new + assemble"),
        rows: vec![
            ("f32", time_system::<f32>(scene, budget)),
            ("f64", time_system::<f64>(scene, budget)),
            ("double-double", time_system::<DoubleDouble>(scene, budget)),
            ("exact", time_system::<Exact>(scene, budget)),
        ],
    }
}

/// One chain's time.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainPoint {
    /// Bars (bodies).
    pub links: usize,
    /// Contacts (1 for a single bar, else 2).
    pub contacts: usize,
    /// ns per solve (System::new + assemble + Newton + Poisson, every output), f64.
    pub ns: f64,
    /// The log–log slope of the time against N from the previous point.
    pub slope: Option<f64>,
    /// ns per solve of the lean path ([`crate::impact::lean_system`]: the system built once;
    /// per solve its factorization, responses, basis and Newton's law, impulses and twist).
    pub lean_ns: Option<f64>,
}

/// The systems section of the bench report.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemsBench {
    /// The planar chain against N, f64.
    pub chain: Vec<ChainPoint>,
    /// The example scenes of several bodies, per scalar type.
    pub scenes: Vec<SceneTiming>,
}

/// The example scenes of several bodies the report times (compiled in: the bench runs from
/// any directory).
const EXAMPLES: [(&str, &str); 8] = [
    (
        "examples/cradle-3.toml",
        include_str!("../../examples/cradle-3.toml"),
    ),
    (
        "examples/cradle-5.toml",
        include_str!("../../examples/cradle-5.toml"),
    ),
    (
        "examples/box-on-box.toml",
        include_str!("../../examples/box-on-box.toml"),
    ),
    (
        "examples/double-pendulum-wall.toml",
        include_str!("../../examples/double-pendulum-wall.toml"),
    ),
    (
        "examples/leg-heel-toe.toml",
        include_str!("../../examples/leg-heel-toe.toml"),
    ),
    (
        "examples/rough-pendulum.toml",
        include_str!("../../examples/rough-pendulum.toml"),
    ),
    // The LZB law (f64 and double-double): the cradle, and a bar on two supports (one body).
    (
        "examples/cradle-3-lzb.toml",
        include_str!("../../examples/cradle-3-lzb.toml"),
    ),
    (
        "examples/bar-two-supports-lzb.toml",
        include_str!("../../examples/bar-two-supports-lzb.toml"),
    ),
];

/// ns per chain solve (f64, both models) for each of `sizes`, with the slopes.
pub fn chain_curve(sizes: &[usize], budget: Duration) -> Vec<ChainPoint> {
    let mut points: Vec<ChainPoint> = Vec::with_capacity(sizes.len());
    let both = [Model::Newton, Model::Poisson];
    for &n in sizes {
        let chain = Chain::<f64>::new(n);
        let mut out = Outcome::default();
        let Ok(ns) = time_three(budget, || chain.solve(&both, &mut out)) else {
            continue;
        };
        let slope = points
            .last()
            .map(|p| (ns / p.ns).ln() / (n as f64 / p.links as f64).ln());
        let system = chain.system();
        let lean_ns = LeanSystem::new(&system)
            .ok()
            .and_then(|mut lean| time_three(budget, || lean.solve(&system, Model::Newton)).ok());
        points.push(ChainPoint {
            links: n,
            contacts: chain.contacts.len(),
            ns,
            slope,
            lean_ns,
        });
    }
    points
}

/// Run the systems section: the chain to 100 bars (1000 without `quick`) and the examples.
pub fn run(quick: bool) -> SystemsBench {
    let budget = Duration::from_millis(if quick { 4 } else { 40 });
    let sizes: &[usize] = if quick {
        &[1, 10, 100]
    } else {
        &[1, 10, 100, 1000]
    };
    let scenes = EXAMPLES
        .iter()
        .filter_map(|(file, text)| Scene::parse(text, file).ok())
        .map(|scene| time_system_scene(&scene, budget))
        .collect();
    SystemsBench {
        chain: chain_curve(sizes, budget),
        scenes,
    }
}

impl SystemsBench {
    /// The readable tables.
    pub fn to_text(&self) -> String {
        let mut s = String::from(
            "\nSystems: the planar chain of N hinged bars (tools::chain: tip and middle bar striking the ground), f64, one solve = System::new + assemble + Newton + Poisson, every output; slope: of log t against log N from the previous N; lean: the lean path (impact::lean_system), the system built once, per solve its factorization and Newton's law, impulses and twist only:\n\n| N bodies | contacts | time per solve | per body | slope | lean | lean per body |\n|---|---|---|---|---|---|---|\n",
        );
        for p in &self.chain {
            s += &format!(
                "| {} | {} | {} | {} | {} | {} | {} |\n",
                p.links,
                p.contacts,
                fmt_ns(p.ns),
                fmt_ns(p.ns / p.links as f64),
                p.slope.map_or("—".into(), |x| format!("{x:.2}")),
                p.lean_ns.map_or("—".into(), fmt_ns),
                p.lean_ns.map_or("—".into(), |t| fmt_ns(t / p.links as f64))
            );
        }
        s += "\nSystems: the example scenes of several bodies, and the LZB law's examples (one solve = System::new + assemble + the scene's law, every output; under the LZB law its integration, in f64 and double-double, f32 and exact not applicable; time per solve / per body / per contact):\n\n| scene | bodies | contacts | law |";
        let names: Vec<&str> = self
            .scenes
            .first()
            .map(|t| t.rows.iter().map(|(n, _)| *n).collect())
            .unwrap_or_default();
        for n in &names {
            s += &format!(" {n} |");
        }
        s += "\n|---|---|---|---|";
        s += &"---|".repeat(names.len());
        s += "\n";
        for t in &self.scenes {
            s += &format!(
                "| {} | {} | {} | {} |",
                t.scene, t.bodies, t.contacts, t.law
            );
            for (_, r) in &t.rows {
                s += &match r {
                    Ok(ns) => format!(
                        " {} / {} / {} |",
                        fmt_ns(*ns),
                        fmt_ns(ns / t.bodies.max(1) as f64),
                        fmt_ns(ns / t.contacts.max(1) as f64)
                    ),
                    Err(e) => format!(" {e} |"),
                };
            }
            s += "\n";
        }
        s
    }

    /// The JSON: `chain` (per N: bodies, contacts, ns per solve and per body, slope) and
    /// `scenes` ([`SceneTiming::to_json`] each).
    pub fn to_json(&self) -> Json {
        json!({
            "chain": self.chain.iter().map(|p| json!({
                "bodies": p.links,
                "contacts": p.contacts,
                "ns_per_solve": p.ns,
                "ns_per_body": p.ns / p.links as f64,
                "slope": p.slope,
            })).collect::<Vec<_>>(),
            "scenes": self.scenes.iter().map(SceneTiming::to_json).collect::<Vec<_>>(),
        })
    }
}

impl SystemsBench {
    /// Draw the chain's cost against N (log–log; per solve ●, per body ▲) on `area`.
    ///
    /// # Errors
    /// What plotters reports.
    pub(crate) fn plot_chain<DB: plotters::prelude::DrawingBackend>(
        &self,
        area: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), Box<dyn std::error::Error>>
    where
        DB::ErrorType: 'static,
    {
        use plotters::prelude::*;
        let nmax = self
            .chain
            .iter()
            .map(|p| p.links)
            .max()
            .unwrap_or(10)
            .max(10) as f64;
        let ys = || {
            self.chain
                .iter()
                .flat_map(|p| [p.ns, p.ns / p.links as f64])
        };
        let (lo, hi) = (
            ys().fold(f64::INFINITY, f64::min).min(1e3) / 3.0,
            ys().fold(10.0, f64::max) * 3.0,
        );
        let mut chart = ChartBuilder::on(area)
            .caption(
                "chain of N bars, f64 (● per solve, ▲ per body)",
                ("sans-serif", 18),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d((1f64..nmax * 1.5).log_scale(), (lo..hi).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("bodies N")
            .y_desc("time [ns]")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .draw()?;
        let solve: Vec<(f64, f64)> = self.chain.iter().map(|p| (p.links as f64, p.ns)).collect();
        let body: Vec<(f64, f64)> = self
            .chain
            .iter()
            .map(|p| (p.links as f64, p.ns / p.links as f64))
            .collect();
        chart.draw_series(LineSeries::new(solve.clone(), BLUE.stroke_width(2)))?;
        chart.draw_series(solve.into_iter().map(|p| Circle::new(p, 4, BLUE.filled())))?;
        chart.draw_series(LineSeries::new(body.clone(), RED.stroke_width(2)))?;
        chart.draw_series(
            body.into_iter()
                .map(|p| TriangleMarker::new(p, 5, RED.filled())),
        )?;
        Ok(())
    }
}
