//! The accuracy contract ([`crate::analysis::accuracy`]) measured over a corpus, per scalar
//! type and per output: the largest ratio error/bound, which `inertance bench` reports and
//! `tests/accuracy_contract.rs` asserts to be at most 1.
//!
//! The corpus is the hard cases of `tests/hard_cases/` and seeded random scenes whose mass,
//! lengths and moments of inertia span 10^±12 ([`ratio_scenes`]). Each scene is solved in the
//! units [`crate::scene::scale`] chooses for it (constrained scenes as written) — the units
//! every float command solves in, and the bounds are unit-free — exactly, then in each float
//! type, and every float outcome is measured against the exact one.
//!
//! Systems of bodies are measured by the same code ([`system_rows`]) on their own corpus: the
//! system examples ([`system_examples`]) and seeded random free systems and joint trees
//! ([`system_scenes`]), each in the units [`crate::scene::scale::system`] chooses.

use std::path::Path;

use crate::analysis::accuracy::{Check, Conditioning, Contracted, Output, measure};
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::mechanics::system::System;
use crate::scalar::dd::DoubleDouble;
use crate::scalar::{Exact, Scalar};
use crate::scene::Scene;
use crate::scene::pipeline::prepare;
use crate::tools::bench::Seeded;

/// One float solve of one model measured against the exact one.
#[derive(Clone, Debug)]
pub struct Measurement {
    /// The scene's name and the model.
    pub case: String,
    /// cond₂ G.
    pub cond: f64,
    /// Per output, in [`Output::ALL`] order; `None` when the type declared G singular.
    pub checks: Option<[Check; 5]>,
}

/// One scalar type over the corpus.
#[derive(Clone, Debug)]
pub struct ContractRow {
    /// The scalar's name.
    pub scalar: &'static str,
    /// Every measurement.
    pub measurements: Vec<Measurement>,
}

impl ContractRow {
    /// The largest ratio error/bound of `output` over the solves, and its case.
    pub fn worst(&self, output: Output) -> (f64, &str) {
        let k = Output::ALL.iter().position(|o| *o == output).unwrap_or(0);
        self.measurements
            .iter()
            .filter_map(|m| m.checks.map(|c| (c[k].ratio(), m.case.as_str())))
            .fold((0.0, ""), |a, b| if b.0 > a.0 { b } else { a })
    }

    /// How many solves the type declared singular, and the smallest cond₂ G among them.
    pub fn declared_singular(&self) -> (usize, f64) {
        self.measurements
            .iter()
            .filter(|m| m.checks.is_none())
            .fold((0, f64::INFINITY), |(k, c), m| (k + 1, c.min(m.cond)))
    }
}

/// A mechanism a scene describes, as the contract measures it: the units float solves use, and
/// the mechanism read in any type.
trait Measured: Contracted {
    /// The scene in the units float solves use (as written when it is not scaled).
    fn in_solver_units(scene: &Scene) -> Scene;

    /// The mechanism of `scene`, exactly.
    fn read_exact(scene: &Scene) -> Option<Self>;

    /// The mechanism of `scene` in `T`.
    fn read<T: Scalar>(scene: &Scene) -> Option<Self::In<T>>;
}

impl Measured for Problem<Exact> {
    fn in_solver_units(scene: &Scene) -> Scene {
        crate::scene::scale::scale(scene).map_or_else(|| scene.clone(), |(s, _)| s)
    }

    fn read_exact(scene: &Scene) -> Option<Self> {
        prepare::<Exact>(scene).ok()
    }

    fn read<T: Scalar>(scene: &Scene) -> Option<Problem<T>> {
        prepare::<T>(scene).ok()
    }
}

impl Measured for System<Exact> {
    fn in_solver_units(scene: &Scene) -> Scene {
        crate::scene::scale::system::scale_system(scene).map_or_else(|| scene.clone(), |(s, _)| s)
    }

    fn read_exact(scene: &Scene) -> Option<Self> {
        scene.system::<Exact>().ok()
    }

    fn read<T: Scalar>(scene: &Scene) -> Option<System<T>> {
        scene.system::<T>().ok()
    }
}

/// An exactly solved scene: its impact, conditioning and each model's outcome.
struct Reference<M: Contracted> {
    name: String,
    scene: Scene,
    conditioning: Conditioning,
    outcomes: Vec<(Model, Outcome<Exact, M::Screw>)>,
    impact: Impact<Exact, M>,
}

/// Solve `scene` exactly; `None` when G is singular or the scene has no simultaneous solve.
fn reference<M: Measured>(scene: &Scene) -> Option<Reference<M>> {
    let scene = M::in_solver_units(scene);
    let problem = M::read_exact(&scene)?;
    let mut impact = Impact::assemble(&problem).ok()?;
    let conditioning = Conditioning::of(&mut impact)?;
    let mut outcomes = Vec::new();
    for &m in &scene.models {
        let mut out = Outcome::default();
        impact.solve(m, &mut out).ok()?;
        outcomes.push((m, out));
    }
    Some(Reference {
        name: scene.name.clone(),
        scene,
        conditioning,
        outcomes,
        impact,
    })
}

/// Every model of `r` solved in `T` and measured; nothing when the scene cannot be read
/// into `T`.
fn measure_in<M: Measured, T: Scalar>(r: &Reference<M>, into: &mut Vec<Measurement>) {
    let Some(problem) = M::read::<T>(&r.scene) else {
        return;
    };
    let Ok(mut impact) = Impact::assemble(&problem) else {
        return;
    };
    for (model, exact) in &r.outcomes {
        let mut out = Outcome::default();
        let checks = match impact.solve(*model, &mut out) {
            Ok(()) => measure(&r.impact, &r.conditioning, *model, exact, &impact, &out),
            Err(_) => None,
        };
        into.push(Measurement {
            case: format!("{} {}", r.name, model.name()),
            cond: r.conditioning.cond,
            checks,
        });
    }
}

/// The contract measured on `scenes` (of one body each) in f32, f64 and double-double.
pub fn run(scenes: &[Scene]) -> Vec<ContractRow> {
    rows::<Problem<Exact>>(scenes)
}

/// The contract measured on system scenes (`[[body]]`) in f32, f64 and double-double: the
/// same measurement on a [`System`] ([`crate::analysis::accuracy`], systems).
pub fn system_rows(scenes: &[Scene]) -> Vec<ContractRow> {
    rows::<System<Exact>>(scenes)
}

fn rows<M: Measured>(scenes: &[Scene]) -> Vec<ContractRow> {
    let refs: Vec<Reference<M>> = scenes.iter().filter_map(reference::<M>).collect();
    let mut rows = vec![
        ContractRow {
            scalar: f32::NAME,
            measurements: Vec::new(),
        },
        ContractRow {
            scalar: f64::NAME,
            measurements: Vec::new(),
        },
        ContractRow {
            scalar: DoubleDouble::NAME,
            measurements: Vec::new(),
        },
    ];
    for r in &refs {
        measure_in::<M, f32>(r, &mut rows[0].measurements);
        measure_in::<M, f64>(r, &mut rows[1].measurements);
        measure_in::<M, DoubleDouble>(r, &mut rows[2].measurements);
    }
    rows
}

/// The hard cases in `dir` (`*.toml`, sorted), as scenes.
pub fn hard_cases(dir: &Path) -> Vec<Scene> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files.iter().filter_map(|f| Scene::load(f).ok()).collect()
}

/// `count` seeded random free-body scenes spanning ratios of 10^±12: a mass 10^a kg
/// (a ∈ [−12, 12]), a length unit 10^b m (b ∈ [−12, 12]), radii of gyration 10^t times it per
/// axis (t ∈ [−6, 6] each, so J/(m L²) spans 10^±12 and the moments differ by up to 10¹²),
/// contact points at 10^s times the length unit (s ∈ [−3, 3] per contact), 1–4 contacts,
/// random normals, velocities 10^d (d ∈ [−3, 3]) in those units. Every number a short decimal,
/// so the exact solve is the reference. Many such scenes have a large cond G; a type that
/// cannot resolve it declares G singular.
pub fn ratio_scenes(count: usize, seed: u64) -> Vec<Scene> {
    let mut rng = Seeded(seed);
    let mut pick = |lo: i64, hi: i64| lo + (rng.next() % (hi - lo + 1) as u64) as i64;
    let mut scenes = Vec::with_capacity(count);
    let mut attempt = 0;
    while scenes.len() < count && attempt < 100 * count {
        attempt += 1;
        let (a, b, d) = (pick(-12, 12), pick(-12, 12), pick(-3, 3));
        let digits = |p: &mut dyn FnMut(i64, i64) -> i64| format!("{}.{}", p(1, 9), p(0, 9));
        let num = |p: &mut dyn FnMut(i64, i64) -> i64, e: i64| {
            let sign = if p(0, 1) == 0 { "" } else { "-" };
            format!("\"{sign}{}e{e}\"", digits(p))
        };
        let mass = format!("\"{}e{a}\"", digits(&mut pick));
        let inertia: Vec<String> = (0..3)
            .map(|_| {
                let t = pick(-6, 6);
                // J = m (ρ 10^(b+t))², written as one decimal.
                let rho = pick(10, 99);
                format!("\"{}e{}\"", rho * rho, a + 2 * (b + t) - 2)
            })
            .collect();
        let v: Vec<String> = (0..3).map(|_| num(&mut pick, b + d)).collect();
        let w: Vec<String> = (0..3).map(|_| num(&mut pick, d)).collect();
        let mut text = format!(
            "name = \"ratios-{}\"\n[body]\nmass = {mass}\ninertia = [{}]\nvelocity = [{}]\nangular_velocity = [{}]\n",
            scenes.len(),
            inertia.join(", "),
            v.join(", "),
            w.join(", ")
        );
        for _ in 0..pick(1, 4) {
            let s = pick(-3, 3);
            let p: Vec<String> = (0..3).map(|_| num(&mut pick, b + s)).collect();
            let n: Vec<String> = (0..3).map(|_| pick(-4, 4).to_string()).collect();
            if n.iter().all(|x| x == "0") {
                continue;
            }
            text += &format!(
                "[[contact]]\npoint = [{}]\nnormal = [{}]\nk_newton = 0.{}\nk_poisson = 0.{}\n",
                p.join(", "),
                n.join(", "),
                pick(0, 9),
                pick(0, 9)
            );
        }
        if let Ok(scene) = Scene::parse(&text, "generated")
            && !scene.contacts.is_empty()
        {
            scenes.push(scene);
        }
    }
    scenes
}

/// The system examples of `dir` (`examples/`): every scene with `[[body]]` tables and a
/// simultaneous solve in rationals (cradles, box on box, the double pendulum, the leg).
pub fn system_examples(dir: &Path) -> Vec<Scene> {
    hard_cases(dir)
        .into_iter()
        .filter(|s| s.system.is_some() && s.is_rational())
        .collect()
}

/// `count` seeded random systems of 2–4 bodies, alternately free (1–4 contacts between random
/// pairs of bodies) and held by joints (a random tree of revolute and spherical joints, its
/// root hinged to the ground or free, struck at 1–3 contacts with obstacles or between
/// bodies). Masses 10^a kg (a ∈ [−6, 6] per body: ratios up to 10¹²), moments m ρ² with ρ of
/// 10^±1 m per axis, integer positions, anchors and axes, and twists before impact that the
/// joints allow, exactly (integer joint rates). One scene in three is made nearly singular:
/// a second contact 10^−s m (s ∈ [3, 7]) from the first with a normal 10^−3 apart. Every number
/// is a short decimal, so the exact solve is the reference.
pub fn system_scenes(count: usize, seed: u64) -> Vec<Scene> {
    let mut rng = Seeded(seed);
    let mut pick = |lo: i64, hi: i64| lo + (rng.next() % (hi - lo + 1) as u64) as i64;
    let mut scenes = Vec::with_capacity(count);
    let mut attempt = 0;
    while scenes.len() < count && attempt < 100 * count {
        attempt += 1;
        let text = system_text(scenes.len(), &mut pick);
        if let Ok(scene) = Scene::parse(&text, "generated")
            && scene.system::<Exact>().is_ok()
        {
            scenes.push(scene);
        }
    }
    scenes
}

/// One random system scene (see [`system_scenes`]), number `n`.
fn system_text(n: usize, pick: &mut dyn FnMut(i64, i64) -> i64) -> String {
    fn vector(pick: &mut dyn FnMut(i64, i64) -> i64, lo: i64, hi: i64) -> [i64; 3] {
        [pick(lo, hi), pick(lo, hi), pick(lo, hi)]
    }
    let bodies = pick(2, 4) as usize;
    let jointed = n % 2 == 1;
    let cross = |a: [i64; 3], b: [i64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let list = |v: [i64; 3]| format!("[{}, {}, {}]", v[0], v[1], v[2]);
    let centres: Vec<[i64; 3]> = (0..bodies).map(|_| vector(pick, -3, 3)).collect();
    // Each body's twist about the world origin, [ω; v_O], exact integers.
    let mut twists: Vec<([i64; 3], [i64; 3])> = Vec::with_capacity(bodies);
    let mut joints = String::new();
    for b in 0..bodies {
        let free = (vector(pick, -3, 3), vector(pick, -3, 3));
        if !jointed {
            twists.push(free);
            continue;
        }
        // The parent: the ground (None) or an earlier body; the root may float free.
        let parent = if b == 0 {
            None
        } else {
            let p = pick(-1, b as i64 - 1);
            (p >= 0).then_some(p as usize)
        };
        if b == 0 && pick(0, 2) == 0 {
            twists.push(free);
            continue;
        }
        let base = parent.map_or(([0; 3], [0; 3]), |p| twists[p]);
        let anchor = vector(pick, -3, 3);
        let (w, kind, axis) = if pick(0, 1) == 0 {
            let mut axis = vector(pick, -2, 2);
            if axis == [0; 3] {
                axis = [0, 0, 1];
            }
            let rate = pick(-3, 3);
            (axis.map(|x| rate * x), "revolute", Some(axis))
        } else {
            (vector(pick, -3, 3), "spherical", None)
        };
        let v = cross(anchor, w);
        twists.push((
            [0, 1, 2].map(|k| base.0[k] + w[k]),
            [0, 1, 2].map(|k| base.1[k] + v[k]),
        ));
        let names = match parent {
            Some(p) => format!("[\"b{b}\", \"b{p}\"]"),
            None => format!("[\"b{b}\"]"),
        };
        joints += &format!(
            "[[joint]]\nkind = \"{kind}\"\nbodies = {names}\nanchor = {}\n",
            list(anchor)
        );
        if let Some(axis) = axis {
            joints += &format!("axis = {}\n", list(axis));
        }
    }
    let mut text = format!("name = \"system-{n}\"\n[solve]\nmodels = [\"newton\", \"poisson\"]\n");
    for (b, c) in centres.iter().enumerate() {
        let a = pick(-6, 6);
        let mass = format!("\"{}.{}e{a}\"", pick(1, 9), pick(0, 9));
        let inertia: Vec<String> = (0..3)
            .map(|_| {
                let rho = pick(10, 99);
                format!("\"{}e{}\"", rho * rho, a + 2 * pick(-1, 1) - 4)
            })
            .collect();
        let (w, vo) = twists[b];
        let vc = {
            let x = cross(w, *c);
            [0, 1, 2].map(|k| vo[k] + x[k])
        };
        text += &format!(
            "[[body]]\nname = \"b{b}\"\nmass = {mass}\ninertia = [{}]\nposition = {}\nvelocity = {}\nangular_velocity = {}\n",
            inertia.join(", "),
            list(*c),
            list(vc),
            list(w)
        );
    }
    text += &joints;
    let contacts = pick(1, if jointed { 3 } else { 4 });
    let near = pick(0, 2) == 0;
    // (point in tenths of a metre, its shift 10^−s along x, normal, what it joins, k).
    type Written = ([i64; 3], Option<i64>, [i64; 3], String, (i64, i64));
    let mut written: Vec<Written> = Vec::new();
    for i in 0..contacts {
        let point = vector(pick, -30, 30);
        let mut normal = vector(pick, -4, 4);
        if normal == [0; 3] {
            normal = [1, 0, 0];
        }
        let first = pick(0, bodies as i64 - 1);
        let second = pick(-1, bodies as i64 - 1);
        let k = (pick(0, 9), pick(0, 9));
        let with = if second >= 0 && second != first {
            format!("bodies = [\"b{first}\", \"b{second}\"]")
        } else if jointed {
            format!("body = \"b{first}\"\nobstacle = \"o{i}\"")
        } else {
            let other = (first + 1) % bodies as i64;
            format!("bodies = [\"b{first}\", \"b{other}\"]")
        };
        written.push((point, None, normal, with, k));
    }
    if near && let Some((point, _, normal, with, k)) = written.first().cloned() {
        // The same contact moved 10^−s m with its normal turned by about 10^−3.
        let s = pick(3, 7);
        let mut turned = normal.map(|x| 1000 * x);
        turned[pick(0, 2) as usize] += 1;
        let with = with.replace("obstacle = \"o0\"", "obstacle = \"near\"");
        written.push((point, Some(s), turned, with, k));
    }
    for (point, shift, normal, with, (kn, kp)) in &written {
        let x = |k: usize| match shift {
            Some(s) if k == 0 => format!("\"{}/10 + 1e-{s}\"", point[0]),
            _ => format!("\"{}/10\"", point[k]),
        };
        let point = format!("[{}, {}, {}]", x(0), x(1), x(2));
        match with.split("obstacle = ").nth(1) {
            Some(name) => {
                text += &format!(
                    "[[obstacle]]\nname = {name}\nnormal = {}\npoint = {point}\n",
                    list(normal.map(|x| -x))
                );
                text += &format!(
                    "[[contact]]\n{with}\npoint = {point}\nk_newton = 0.{kn}\nk_poisson = 0.{kp}\n"
                );
            }
            None => {
                text += &format!(
                    "[[contact]]\n{with}\npoint = {point}\nnormal = {}\nk_newton = 0.{kn}\nk_poisson = 0.{kp}\n",
                    list(*normal)
                );
            }
        }
    }
    text
}
