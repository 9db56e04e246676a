//! Issue 29's throughput goals, each printed by `inertance bench` as what this run measured
//! beside the goal and the baseline it is a ratio to — both timed in the same run, since the
//! machines are shared and only ratios taken back to back compare.
//!
//! | goal | measured as |
//! |---|---|
//! | a sweep point of a world-frame scene ≤ 2× the same point of the paper-form scene | whole sweeps, one thread, to a CSV: the tilted box (`examples/tilted-box.toml`) against Example 3 (`examples/planar-bar.toml`) over `contact[1].k` and over a velocity of the body |
//! | a point over a pose angle ≤ 2× a point over k | the tilted box over θ against over `contact[1].k` |
//! | the batch ≥ 4× the lean path one scene at a time | [`crate::tools::lean_bench`]'s two classes (Example-3-class; random boxes the lean route accepts) |
//! | planar friction f64 ≤ 5× the frictionless solve | [`crate::tools::friction_bench`] |
//! | spatial friction f64 ≤ 30 µs a solve at tolerance 10⁻⁸ on the ball-in-corner class | the median over [`crate::tools::ball_in_corner`]'s scenes |
//!
//! The goals measured elsewhere are named with where: exact against python-flint
//! (`benches/peers/compare.py`), the lean path and a validated problem against the same closed
//! form written by hand (`cargo bench --bench solve`, which prints both ratios), Python's
//! `solve_batch` against the Rust batch (`benches/peers/compare.py`'s batch section).
//!
//! A sweep point is timed by [`crate::tools::sweep::sweep`] itself, on the scene written to a
//! temporary directory (removed after): the sweep over n points less the same sweep over n/5,
//! divided by the 4n/5 points between, so that what a sweep costs once (reading the scene,
//! solving the grid's corners, the file) is not spread over its points; each the fastest of
//! three rounds taken in turn, so that a burst of load in one round does not decide.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde_json::{Value as Json, json};

use crate::tools::friction_bench::{FrictionBench, PLANAR_GOAL};
use crate::tools::lean_bench::LeanBench;
use crate::tools::sweep::{SweepOptions, Vary, sweep};

/// Which way a goal points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bound {
    /// The measured value must be at most the goal.
    AtMost,
    /// The measured value must be at least the goal.
    AtLeast,
}

/// One goal: what was measured in this run against what it is compared with.
#[derive(Clone, Debug, PartialEq)]
pub struct Goal {
    /// What is measured.
    pub what: String,
    /// The measured value (a ratio, or µs for [`Goal::unit`] `"µs"`); `None` where it could not
    /// be measured in this run (then `note` says why).
    pub measured: Option<f64>,
    /// `"×"` for a ratio, `"µs"` for a time.
    pub unit: &'static str,
    /// The goal's bound.
    pub bound: Bound,
    /// The goal's value.
    pub goal: f64,
    /// The baseline the ratio is taken against, or the conditions of a time.
    pub baseline: String,
    /// Why a value is missing, or a caveat.
    pub note: String,
}

impl Goal {
    /// Whether the goal is met in this run (`None` when not measured).
    pub fn met(&self) -> Option<bool> {
        let x = self.measured.filter(|x| x.is_finite())?;
        Some(match self.bound {
            Bound::AtMost => x <= self.goal,
            Bound::AtLeast => x >= self.goal,
        })
    }
}

/// The time per point of the bench's sweeps, µs (`None` where a sweep failed: the reason).
#[derive(Clone, Debug, PartialEq)]
pub struct SweepPoints {
    /// Points n of the sweeps over k and over a velocity, and over θ (each timed less the
    /// same sweep over n/5).
    pub points: (usize, usize),
    /// (label, µs per point or why not).
    pub micros: Vec<(&'static str, Result<f64, String>)>,
}

/// The sweeps timed: (label, scene, the scene's text, the varied path and range).
const SWEEPS: [(&str, &str, &str, &str); 5] = [
    (
        "paper form over k",
        "planar-bar.toml",
        include_str!("../../examples/planar-bar.toml"),
        "contact[1].k=0:1",
    ),
    (
        "world frame over k",
        "tilted-box.toml",
        include_str!("../../examples/tilted-box.toml"),
        "contact[1].k=0:1",
    ),
    (
        "paper form over a velocity",
        "planar-bar.toml",
        include_str!("../../examples/planar-bar.toml"),
        "body.velocity[0]=1:3",
    ),
    (
        "world frame over a velocity",
        "tilted-box.toml",
        include_str!("../../examples/tilted-box.toml"),
        "body.velocity[2]=-2:-1",
    ),
    (
        "world frame over a pose angle",
        "tilted-box.toml",
        include_str!("../../examples/tilted-box.toml"),
        "theta=1:80",
    ),
];

/// Time a point of each of [`SWEEPS`] (module docs).
pub fn sweep_points(quick: bool) -> SweepPoints {
    let (many, few) = if quick { (1001, 101) } else { (10001, 1001) };
    let dir = std::env::temp_dir().join(format!("inertance-bench-goals-{}", std::process::id()));
    // Per sweep, the fastest whole sweep over n/5 and over n points, µs.
    let mut best: Vec<Result<[f64; 2], String>> = vec![Ok([f64::INFINITY; 2]); SWEEPS.len()];
    let setup = std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()));
    for _round in 0..3 {
        for (i, (_, file, text, vary)) in SWEEPS.iter().enumerate() {
            let n = if vary.starts_with("theta") { few } else { many };
            for (j, count) in [n / 5, n].into_iter().enumerate() {
                let t = setup
                    .clone()
                    .and_then(|()| time_sweep(&dir, file, text, &format!("{vary}:{count}")));
                best[i] = match (&best[i], t) {
                    (Ok(b), Ok(t)) => {
                        let mut b = *b;
                        b[j] = b[j].min(t);
                        Ok(b)
                    }
                    (Err(e), _) => Err(e.clone()),
                    (_, Err(e)) => Err(e),
                };
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let micros = SWEEPS
        .iter()
        .zip(best)
        .map(|((label, _, _, vary), t)| {
            let n = if vary.starts_with("theta") { few } else { many };
            let per_point = t.and_then(|[small, large]| {
                let x = (large - small) / (n - n / 5) as f64;
                if x > 0.0 {
                    Ok(x)
                } else {
                    Err(format!(
                        "{n} points took no longer than {} ({large:.0} µs against {small:.0} µs): too noisy to tell",
                        n / 5
                    ))
                }
            });
            (*label, per_point)
        })
        .collect();
    SweepPoints {
        points: (many, few),
        micros,
    }
}

/// µs for one sweep over `vary` of the scene `text`, written as `file` in `dir`, one thread,
/// to a CSV in `dir`.
fn time_sweep(dir: &Path, file: &str, text: &str, vary: &str) -> Result<f64, String> {
    let scene: PathBuf = dir.join(file);
    std::fs::write(&scene, text).map_err(|e| format!("{}: {e}", scene.display()))?;
    let vary = Vary::parse(vary).map_err(|e| e.to_string())?;
    let opts = SweepOptions {
        scene,
        vary: vec![vary],
        exact: false,
        out: dir.join("points.csv"),
        plot: None,
        plot_outputs: Vec::new(),
        shard: None,
        threads: Some(1),
        progress: false,
        law: None,
        sensitivity: false,
    };
    let start = Instant::now();
    sweep(&opts).map_err(|e| e.to_string())?;
    Ok(start.elapsed().as_secs_f64() * 1e6)
}

impl SweepPoints {
    /// µs per point of the sweep labelled `label`.
    fn of(&self, label: &str) -> Result<f64, String> {
        self.micros
            .iter()
            .find(|(l, _)| *l == label)
            .map_or_else(|| Err(format!("no sweep `{label}`")), |(_, t)| t.clone())
    }

    /// The ratio of two sweeps' points, or why there is none.
    fn ratio(&self, a: &str, b: &str) -> (Option<f64>, String) {
        match (self.of(a), self.of(b)) {
            (Ok(x), Ok(y)) => (Some(x / y), String::new()),
            (Err(e), _) | (_, Err(e)) => (None, e),
        }
    }
}

/// Every goal of issue 29 measured in this run, from the bench's own sections and the sweeps.
pub fn goals(sweeps: &SweepPoints, lean: &LeanBench, friction: &FrictionBench) -> Vec<Goal> {
    let mut out = Vec::new();
    let point = |label: &str| {
        sweeps
            .of(label)
            .map_or_else(|e| e, |t| format!("{t:.1} µs a point"))
    };
    for (what, a, b) in [
        (
            "sweep point, world frame ÷ paper form, over k",
            "world frame over k",
            "paper form over k",
        ),
        (
            "sweep point, world frame ÷ paper form, over a velocity",
            "world frame over a velocity",
            "paper form over a velocity",
        ),
        (
            "sweep point of the world frame, over a pose angle ÷ over k",
            "world frame over a pose angle",
            "world frame over k",
        ),
    ] {
        let (measured, note) = sweeps.ratio(a, b);
        out.push(Goal {
            what: what.into(),
            measured,
            unit: "×",
            bound: Bound::AtMost,
            goal: 2.0,
            baseline: format!("{} ({b}); this: {}", point(b), point(a)),
            note,
        });
    }
    for class in &lean.classes {
        let speedup = class.lean_ns / class.batch_accepted_ns;
        out.push(Goal {
            what: format!("batch per scene, {} (lean one by one ÷ batch)", class.class),
            measured: speedup.is_finite().then_some(speedup),
            unit: "×",
            bound: Bound::AtLeast,
            goal: 4.0,
            baseline: format!(
                "lean {:.1} ns a scene; batch {:.1} ns, {} lanes",
                class.lean_ns, class.batch_accepted_ns, lean.lanes
            ),
            note: String::new(),
        });
    }
    let planar = friction.planar.f64_ratio();
    out.push(Goal {
        what: "planar friction f64 ÷ frictionless f64".into(),
        measured: planar.is_finite().then_some(planar),
        unit: "×",
        bound: Bound::AtMost,
        goal: PLANAR_GOAL,
        baseline: format!(
            "frictionless {:.0} ns a solve ({} scenes)",
            friction.planar.frictionless_f64_ns, friction.planar.scenes
        ),
        note: String::new(),
    });
    let (ball, scenes) = friction.ball_in_corner;
    out.push(Goal {
        what: "spatial friction f64, a solve of the ball-in-corner class at tolerance 1e-8".into(),
        measured: ball.filter(|t| t.is_finite()),
        unit: "µs",
        bound: Bound::AtMost,
        goal: crate::tools::ball_in_corner::GOAL_US,
        baseline: format!("the median over {scenes} scenes (tools::ball_in_corner)"),
        note: if ball.is_some() {
            String::new()
        } else {
            "no scene of the class solved".into()
        },
    });
    out
}

/// The goals' table.
pub fn to_text(goals: &[Goal]) -> String {
    let mut s = String::from(
        "\nIssue 29's goals, each measured in this run against its baseline (the exact path against python-flint and Python's solve_batch against the Rust batch: benches/peers/compare.py; the lean path and a validated problem against the closed form written by hand: cargo bench --bench solve):\n\n| goal | measured | goal | met | baseline |\n|---|---|---|---|---|\n",
    );
    for g in goals {
        let measured = match g.measured {
            Some(x) if g.unit == "µs" => format!("{x:.1} µs"),
            Some(x) => format!("{x:.2}×"),
            None => format!("not measured: {}", g.note),
        };
        let bound = match g.bound {
            Bound::AtMost => "≤",
            Bound::AtLeast => "≥",
        };
        let goal = if g.unit == "µs" {
            format!("{bound} {} µs", g.goal)
        } else {
            format!("{bound} {}×", g.goal)
        };
        let met = match g.met() {
            Some(true) => "yes",
            Some(false) => "no",
            None => "—",
        };
        let baseline = if g.measured.is_some() && !g.note.is_empty() {
            format!("{}; {}", g.baseline, g.note)
        } else {
            g.baseline.clone()
        };
        s += &format!(
            "| {} | {measured} | {goal} | {met} | {baseline} |\n",
            g.what
        );
    }
    s
}

/// The goals as JSON: per goal `what`, `measured` (null where not measured), `unit`,
/// `bound` (`"at_most"` / `"at_least"`), `goal`, `met`, `baseline`, `note`.
pub fn to_json(goals: &[Goal]) -> Json {
    let num = |x: f64| {
        serde_json::Number::from_f64(x)
            .map(Json::Number)
            .unwrap_or(Json::Null)
    };
    Json::Array(
        goals
            .iter()
            .map(|g| {
                json!({
                    "what": g.what,
                    "measured": g.measured.map(num),
                    "unit": g.unit,
                    "bound": match g.bound { Bound::AtMost => "at_most", Bound::AtLeast => "at_least" },
                    "goal": num(g.goal),
                    "met": g.met(),
                    "baseline": g.baseline,
                    "note": g.note,
                })
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_goal_is_met_on_its_side_of_the_bound_only() {
        let goal = |measured, bound| Goal {
            what: "x".into(),
            measured,
            unit: "×",
            bound,
            goal: 2.0,
            baseline: String::new(),
            note: String::new(),
        };
        assert_eq!(goal(Some(2.0), Bound::AtMost).met(), Some(true));
        assert_eq!(goal(Some(2.5), Bound::AtMost).met(), Some(false));
        assert_eq!(goal(Some(1.5), Bound::AtLeast).met(), Some(false));
        assert_eq!(goal(Some(4.0), Bound::AtLeast).met(), Some(true));
        assert_eq!(goal(None, Bound::AtMost).met(), None);
        assert_eq!(goal(Some(f64::NAN), Bound::AtMost).met(), None);
    }

    /// Every sweep the goals time runs on its scene, and the ratios come from its points.
    #[test]
    fn the_sweeps_run_and_their_ratios_are_of_their_points() {
        let dir = std::env::temp_dir().join(format!("inertance-goals-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut micros = Vec::new();
        for (label, file, text, vary) in SWEEPS {
            let t = time_sweep(&dir, file, text, &format!("{vary}:3"));
            assert!(t.as_ref().is_ok_and(|t| *t > 0.0), "{label}: {t:?}");
            micros.push((label, t));
        }
        std::fs::remove_dir_all(&dir).unwrap();
        let sweeps = SweepPoints {
            points: (3, 3),
            micros,
        };
        let (r, note) = sweeps.ratio("world frame over a pose angle", "world frame over k");
        let x = sweeps.of("world frame over a pose angle").unwrap();
        let y = sweeps.of("world frame over k").unwrap();
        assert_eq!((r, note), (Some(x / y), String::new()));
        let missing = sweeps.ratio("nothing", "world frame over k");
        assert_eq!(missing, (None, "no sweep `nothing`".to_string()));
    }
}
