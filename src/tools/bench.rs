//! `inertance bench`: what each digit of accuracy costs in time.
//!
//! The same solve (assemble, then Newton and Poisson with every output) runs in every scalar
//! type on one corpus — seeded random well-conditioned scenes, plus the hard cases of
//! `tests/hard_cases/` when that folder is present (its free-body scenes; the bench times the
//! free-body solve) — and is compared with the exact result:
//! the time per solve (median over the corpus of per-scene medians) and the relative error
//! (per scene, the largest over impulses, twist after impact and energies, each relative to
//! its group's scale; energies relative to T⁰). Errors are measured on each type's exact
//! stored value ([`Scalar::exact_value`]), so a double-double's 10⁻³⁰ is not rounded away.
//!
//! The accuracy contract ([`crate::analysis::accuracy`]) is measured on the same scenes, the
//! constrained hard cases and seeded scenes spanning ratios of 10^±12
//! ([`crate::tools::accuracy`]): per float type and per output (impulses, twist, contact
//! velocities, E_p, ΔE_c) the largest ratio of the error to its bound, at most 1 when the
//! contract holds.
//!
//! The cost growth with the number of contacts is measured on `assemble` + `analyze` (both
//! models): a free body has six independent directions, so beyond six contacts G is always
//! singular and `analyze` (the family of solutions) is the operation that works for every N.
//!
//! The unilateral law ([`crate::impact::unilateral`]) is measured beside the simultaneous
//! solve: on the corpus, its time per solve (assemble + unilateral Newton + Poisson, every
//! output) and its error against the exact unilateral outcome, measured like the simultaneous
//! one; against N, the same solve next to the simultaneous one on the same scene — which is
//! impossible beyond six contacts (G singular) while the unilateral one still answers (its
//! velocities are unique; its impulses one of a set).

use std::path::Path;
use std::time::{Duration, Instant};

use num_rational::BigRational;
use num_traits::Signed;
use serde_json::{Value as Json, json};

use crate::analysis::accuracy::Output;
use crate::analysis::analyze;
use crate::impact::outputs::Outputs as Asked;
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::impact::unilateral::{Activity, active};
use crate::scalar::dd::DoubleDouble;
use crate::scalar::{Exact, Scalar};
use crate::scene::Scene;
use crate::tools::accuracy::ContractRow;
use crate::tools::system_bench::{NotTimed, SceneTiming};

/// Options of a bench run.
#[derive(Clone, Debug)]
pub struct BenchOptions {
    /// Fewer scenes and a shorter time budget (under a minute in all).
    pub quick: bool,
    /// Include `tests/hard_cases/*.toml` from this folder when it exists.
    pub hard_cases: Option<std::path::PathBuf>,
}

/// One scalar type's line of the table.
#[derive(Clone, Debug)]
pub struct ScalarRow {
    /// The scalar's name.
    pub name: &'static str,
    /// Median time per solve over the well-conditioned scenes, ns.
    pub median_ns: f64,
    /// Median relative error over the well-conditioned scenes.
    pub median_error: f64,
    /// Largest relative error over the well-conditioned scenes.
    pub max_error: f64,
    /// Over the hard cases (`None` without them): the largest relative error among those this
    /// type solves, and how many it declares singular (cond·ε too large for the type).
    pub max_error_hard: Option<(f64, usize)>,
    /// The unilateral law on the same well-conditioned scenes, against the exact unilateral
    /// outcome.
    pub unilateral: UnilateralRow,
}

/// One scalar type's unilateral solve over the well-conditioned scenes.
#[derive(Clone, Debug)]
pub struct UnilateralRow {
    /// Median time per assemble + unilateral Newton + Poisson, ns.
    pub median_ns: f64,
    /// Median relative error against the exact unilateral outcome.
    pub median_error: f64,
    /// Largest relative error (infinite when a scene gave no answer in this type).
    pub max_error: f64,
}

/// A solve's time against N, or why there is none.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Timing {
    /// Nanoseconds per solve.
    Ns(f64),
    /// G is singular in this type: the simultaneous solve is impossible.
    Singular,
    /// The unilateral law found no admissible impulses.
    Jammed,
    /// Not measured (exact arithmetic beyond the size limit).
    Skipped,
}

impl Timing {
    /// The time, when measured.
    pub fn ns(self) -> Option<f64> {
        match self {
            Timing::Ns(t) => Some(t),
            _ => None,
        }
    }
}

/// The cost of one scene with N contacts, per scalar type (in [`BenchReport::rows`] order).
#[derive(Clone, Debug)]
pub struct Growth {
    /// Contacts.
    pub contacts: usize,
    /// ns per assemble + analyze (both models); `None` when skipped.
    pub analyze: Vec<Option<f64>>,
    /// assemble + Newton + Poisson, simultaneous.
    pub simultaneous: Vec<Timing>,
    /// assemble + Newton + Poisson, unilateral.
    pub unilateral: Vec<Timing>,
    /// In exact arithmetic (or f64 where exact is skipped), the contacts taking an impulse
    /// under the unilateral Newton and Poisson laws.
    pub active: Option<(usize, usize)>,
}

/// A bench run's results.
#[derive(Clone, Debug)]
pub struct BenchReport {
    /// Well-conditioned scenes and hard cases used.
    pub scenes: (usize, usize),
    /// One row per scalar type, f32 → exact.
    pub rows: Vec<ScalarRow>,
    /// The cost against N.
    pub scaling: Vec<Growth>,
    /// Well-conditioned scenes whose exact unilateral answer leaves some contact without an
    /// impulse (there the simultaneous answer is not physical and the laws differ).
    pub unilateral_differs: usize,
    /// The frictional solve, planar and spatial ([`crate::tools::friction_bench`]).
    pub friction: crate::tools::friction_bench::FrictionBench,
    /// The accuracy contract measured per output, f32, f64 and double-double
    /// ([`crate::tools::accuracy`]), and how many scenes spanning ratios of 10^±12 it included.
    pub contract: (Vec<ContractRow>, usize),
    /// The lean path and the batch beside the generic solve ([`crate::tools::lean_bench`]).
    pub lean: crate::tools::lean_bench::LeanBench,
    /// The cost of `analyze` against N on the linear-cost route, f64 to 10⁵ contacts and
    /// exact to 10³, with the fitted exponent ([`crate::tools::n_curve`]).
    pub n_curve: Vec<crate::tools::n_curve::NCurve>,
    /// Scenes of several bodies: the planar chain against N and the examples per scalar type
    /// ([`crate::tools::system_bench`]).
    pub systems: crate::tools::system_bench::SystemsBench,
    /// The time per point of the sweeps issue 29's goals compare ([`crate::tools::goals`]).
    pub sweep_points: crate::tools::goals::SweepPoints,
}

/// A small deterministic generator (SplitMix64), so the corpus is the same on every machine.
pub(crate) struct Seeded(pub(crate) u64);

impl Seeded {
    pub(crate) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A decimal with one fractional digit in [lo, hi].
    pub(crate) fn decimal(&mut self, lo: i64, hi: i64) -> String {
        let span = (hi - lo) as u64 * 10 + 1;
        let x = lo * 10 + (self.next() % span) as i64;
        format!("{}", x as f64 / 10.0)
    }

    /// A decimal with one fractional digit in [lo/10, hi/10].
    fn tenths(&mut self, lo: i64, hi: i64) -> String {
        let x = lo + (self.next() % (hi - lo + 1) as u64) as i64;
        format!("{}", x as f64 / 10.0)
    }
}

/// A random scene with `n` contacts (exactly rational: every number a short decimal).
fn random_scene(rng: &mut Seeded, n: usize) -> Option<Scene> {
    let v = |rng: &mut Seeded, lo, hi| {
        format!(
            "[{}, {}, {}]",
            rng.decimal(lo, hi),
            rng.decimal(lo, hi),
            rng.decimal(lo, hi)
        )
    };
    let mut text = format!(
        "[body]\nmass = {}\ninertia = [{}, {}, {}]\nvelocity = {}\nangular_velocity = {}\n",
        rng.decimal(1, 9),
        rng.decimal(1, 5),
        rng.decimal(1, 5),
        rng.decimal(1, 5),
        v(rng, -3, 3),
        v(rng, -1, 1)
    );
    for _ in 0..n {
        let mut normal = v(rng, -2, 2);
        if normal == "[0, 0, 0]" {
            normal = "[1, 0, 0]".into();
        }
        text += &format!(
            "[[contact]]\npoint = {}\nnormal = {normal}\nk_newton = {}\nk_poisson = {}\n",
            v(rng, -2, 2),
            rng.decimal(0, 1),
            rng.decimal(0, 1)
        );
    }
    Scene::parse(&text, "generated").ok()
}

/// A body landing on uneven ground at `n` contacts: points spread over the body, normals
/// [a, b, 1] tilted at most about 27° from z (so no nonnegative impulses cancel out and the
/// unilateral law always has an answer — random normals all round cage the body and jam it),
/// the body moving into the ground (v_z ≥ 1) and turning slowly. Beyond six contacts G is
/// singular, as for any free body.
fn landing_scene(rng: &mut Seeded, n: usize) -> Option<Scene> {
    let mut text = format!(
        "[body]\nmass = {}\ninertia = [{}, {}, {}]\nvelocity = [{}, {}, {}]\nangular_velocity = [{}, {}, {}]\n",
        rng.decimal(1, 9),
        rng.decimal(1, 5),
        rng.decimal(1, 5),
        rng.decimal(1, 5),
        rng.decimal(-1, 1),
        rng.decimal(-1, 1),
        rng.decimal(1, 3),
        rng.tenths(-3, 3),
        rng.tenths(-3, 3),
        rng.tenths(-3, 3),
    );
    for _ in 0..n {
        text += &format!(
            "[[contact]]\npoint = [{}, {}, {}]\nnormal = [{}, {}, 1]\nk_newton = {}\nk_poisson = {}\n",
            rng.decimal(-2, 2),
            rng.decimal(-2, 2),
            rng.decimal(-1, 1),
            rng.tenths(-5, 5),
            rng.tenths(-5, 5),
            rng.decimal(0, 1),
            rng.decimal(0, 1)
        );
    }
    Scene::parse(&text, "generated").ok()
}

/// The exact outputs of one solve, grouped: impulses, twist after, energies.
struct Outputs {
    groups: [Vec<BigRational>; 3],
    kinetic_before: BigRational,
}

fn outputs<T: Scalar>(impact: &Impact<T>, outs: &[Outcome<T>]) -> Option<Outputs> {
    let x = |v: &T| v.exact_value();
    let mut groups: [Vec<BigRational>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    for o in outs {
        for p in &o.impulses_hat {
            groups[0].push(x(p)?);
        }
        for v in o.velocity.as_slice() {
            groups[1].push(x(v)?);
        }
        groups[2].push(x(&o.lost_velocity_energy)?);
        groups[2].push(x(&o.kinetic_energy_loss)?);
    }
    Some(Outputs {
        groups,
        kinetic_before: x(impact.kinetic_before())?,
    })
}

/// The largest relative error of `a` against the exact `e` (see the module docs).
fn relative_error(a: &Outputs, e: &Outputs) -> f64 {
    let mut worst = 0f64;
    for (g, (ga, ge)) in a.groups.iter().zip(&e.groups).enumerate() {
        let mut scale = ge.iter().fold(BigRational::from_integer(0.into()), |m, x| {
            if x.abs() > m { x.abs() } else { m }
        });
        if g == 2 && e.kinetic_before > scale {
            scale = e.kinetic_before.clone();
        }
        if scale == BigRational::from_integer(0.into()) {
            continue;
        }
        for (x, y) in ga.iter().zip(ge) {
            let err = crate::number::rational_to_f64(&((x - y).abs() / &scale));
            worst = worst.max(err);
        }
    }
    worst
}

/// Assemble `p` into `impact` (reusing its buffers) and solve both models; `None` if G is
/// singular in this type.
fn solve_all<T: Scalar>(
    p: &Problem<T>,
    impact: &mut Impact<T>,
    outs: &mut [Outcome<T>; 2],
) -> Option<()> {
    impact.reassemble(p).ok()?;
    impact.solve(Model::Newton, &mut outs[0]).ok()?;
    impact.solve(Model::Poisson, &mut outs[1]).ok()
}

/// Assemble `p` into `impact` and solve both models under the unilateral law; `None` when it
/// fails (jammed, or G unassemblable in this type).
fn solve_unilateral_all<T: Scalar>(
    p: &Problem<T>,
    impact: &mut Impact<T>,
    outs: &mut [Outcome<T>; 2],
) -> Result<[Activity; 2], Timing> {
    impact.reassemble(p).map_err(|_| Timing::Singular)?;
    let jam = |_| Timing::Jammed;
    let n = impact
        .solve_unilateral(Model::Newton, &mut outs[0])
        .map_err(jam)?;
    let q = impact
        .solve_unilateral(Model::Poisson, &mut outs[1])
        .map_err(jam)?;
    Ok([n, q])
}

/// The unilateral outputs of `p` with a new impact, and which contacts are active per model.
fn unilateral_outputs<T: Scalar>(p: &Problem<T>) -> Option<(Outputs, [Vec<bool>; 2])> {
    let mut outs = [Outcome::default(), Outcome::default()];
    let mut impact = Impact::assemble(p).ok()?;
    solve_unilateral_all(p, &mut impact, &mut outs).ok()?;
    let active = [active(&outs[0]), active(&outs[1])];
    Some((outputs(&impact, &outs)?, active))
}

/// Median wall time (ns) of one call of `f` over three runs of at least `budget` each; `Err`
/// when `f` fails.
///
/// The clock is read once per run, not once per call: the number of calls per run is found
/// first by doubling until a run takes `budget`, so a call of a few nanoseconds is not
/// measured together with the ~20 ns of reading the clock.
pub(crate) fn time_three<E>(
    budget: Duration,
    mut f: impl FnMut() -> Result<(), E>,
) -> Result<f64, E> {
    f()?;
    let mut reps = 1u64;
    loop {
        let start = Instant::now();
        for _ in 0..reps {
            f()?;
        }
        if start.elapsed() >= budget || reps >= 1 << 40 {
            break;
        }
        reps *= 2;
    }
    let mut samples = Vec::with_capacity(3);
    for _ in 0..3 {
        let start = Instant::now();
        for _ in 0..reps {
            f()?;
        }
        samples.push(start.elapsed().as_nanos() as f64 / reps as f64);
    }
    samples.sort_by(f64::total_cmp);
    Ok(samples[1])
}

/// Median ns per assemble + unilateral Newton + Poisson of `p`.
fn time_unilateral<T: Scalar>(p: &Problem<T>, budget: Duration) -> Timing {
    let mut outs = [Outcome::default(), Outcome::default()];
    let Ok(mut impact) = Impact::assemble(p) else {
        return Timing::Singular;
    };
    match time_three(budget, || {
        solve_unilateral_all(std::hint::black_box(p), &mut impact, &mut outs).map(|_| ())
    }) {
        Ok(t) => Timing::Ns(t),
        Err(e) => e,
    }
}

/// Median ns per assemble + simultaneous Newton + Poisson of `p`.
fn time_simultaneous<T: Scalar>(p: &Problem<T>, budget: Duration) -> Timing {
    time_solve(p, budget).map_or(Timing::Singular, Timing::Ns)
}

/// [`solve_all`] with a new impact.
fn solve_new<T: Scalar>(p: &Problem<T>, outs: &mut [Outcome<T>; 2]) -> Option<Impact<T>> {
    let mut impact = Impact::assemble(p).ok()?;
    impact.solve(Model::Newton, &mut outs[0]).ok()?;
    impact.solve(Model::Poisson, &mut outs[1]).ok()?;
    Some(impact)
}

/// Median wall time of one solve of `p` (ns), repeating until each of three samples takes
/// at least `budget`.
fn time_solve<T: Scalar>(p: &Problem<T>, budget: Duration) -> Option<f64> {
    time_solve_for(p, budget, Asked::ALL)
}

/// [`time_solve`] computing only `asked` ([`crate::impact::outputs`]).
fn time_solve_for<T: Scalar>(p: &Problem<T>, budget: Duration, asked: Asked) -> Option<f64> {
    let mut outs = [Outcome::default(), Outcome::default()];
    let mut impact = Impact::assemble_for(p, asked).ok()?;
    time_three(budget, || {
        solve_all(std::hint::black_box(p), &mut impact, &mut outs).ok_or(())
    })
    .ok()
}

/// ns per lean solve (`impact::lean`: assemble + each of `models`, impulses and twist) of a
/// free body with 2 to 4 contacts, built from the problem each time like [`time_solve_for`];
/// `None` where the lean route refuses it (another N, a tensor, an ill-conditioned G).
fn time_lean(p: &Problem<f64>, budget: Duration, models: &[Model]) -> Option<f64> {
    fn time<const N: usize>(p: &Problem<f64>, budget: Duration, models: &[Model]) -> Option<f64> {
        use crate::impact::lean::Lean;
        // The models as constants in the timed closure, as a caller who knows the law writes
        // it (a loop over a runtime list measured 10–20 ns more per scene).
        let run = |newton_only: bool| {
            time_three(budget, || -> Result<(), ()> {
                let lean = Lean::<f64, N>::new(std::hint::black_box(p)).map_err(|_| ())?;
                std::hint::black_box(lean.solve(Model::Newton).map_err(|_| ())?);
                if !newton_only {
                    std::hint::black_box(lean.solve(Model::Poisson).map_err(|_| ())?);
                }
                Ok(())
            })
            .ok()
        };
        match models {
            [Model::Newton] => run(true),
            _ => run(false),
        }
    }
    match p.contacts().len() {
        2 => time::<2>(p, budget, models),
        3 => time::<3>(p, budget, models),
        4 => time::<4>(p, budget, models),
        _ => None,
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// A corpus scene with its exact simultaneous outputs and, for the well-conditioned ones, its
/// exact unilateral outputs.
type Case = (Scene, Outputs, Option<Outputs>);

/// Times and errors of one scalar type over the corpus.
fn measure<T: Scalar>(well: &[Case], hard: &[Case], budget: Duration) -> ScalarRow {
    let run = |set: &[Case], timed: bool| -> (Vec<f64>, Vec<f64>) {
        let (mut times, mut errors) = (Vec::new(), Vec::new());
        for (scene, exact, _) in set {
            let Ok(p) = scene.problem::<T>() else {
                continue;
            };
            let mut outs = [Outcome::default(), Outcome::default()];
            match solve_new(&p, &mut outs).and_then(|impact| outputs(&impact, &outs)) {
                Some(o) => errors.push(relative_error(&o, exact)),
                // Singular in this type (or a non-finite result): no usable answer at all.
                None => errors.push(f64::INFINITY),
            }
            if let Some(t) = timed.then(|| time_solve(&p, budget)).flatten() {
                times.push(t);
            }
        }
        (times, errors)
    };
    let (times, errors) = run(well, true);
    let (_, hard_errors) = run(hard, false);
    let (mut u_times, mut u_errors) = (Vec::new(), Vec::new());
    for (scene, _, exact) in well {
        let (Ok(p), Some(exact)) = (scene.problem::<T>(), exact) else {
            continue;
        };
        u_errors
            .push(unilateral_outputs(&p).map_or(f64::INFINITY, |(o, _)| relative_error(&o, exact)));
        if let Timing::Ns(t) = time_unilateral(&p, budget) {
            u_times.push(t);
        }
    }
    ScalarRow {
        name: T::NAME,
        median_ns: median(times),
        median_error: median(errors.clone()),
        max_error: errors.iter().cloned().fold(0.0, f64::max),
        max_error_hard: (!hard.is_empty()).then(|| {
            let solved = hard_errors
                .iter()
                .cloned()
                .filter(|e| e.is_finite())
                .fold(0.0, f64::max);
            (
                solved,
                hard_errors.iter().filter(|e| e.is_infinite()).count(),
            )
        }),
        unilateral: UnilateralRow {
            median_ns: median(u_times),
            median_error: median(u_errors.clone()),
            max_error: u_errors.iter().cloned().fold(0.0, f64::max),
        },
    }
}

/// ns per assemble + analyze (both models) of `scene` in `T`, within `budget`.
fn time_analyze<T: Scalar>(scene: &Scene, budget: Duration) -> Option<f64> {
    let p = scene.problem::<T>().ok()?;
    let (mut reps, start) = (0u64, Instant::now());
    while start.elapsed() < budget || reps == 0 {
        let mut impact = Impact::assemble(&p).ok()?;
        std::hint::black_box(analyze(&mut impact, &Model::ALL));
        reps += 1;
    }
    Some(start.elapsed().as_nanos() as f64 / reps as f64)
}

/// Run the bench.
pub fn run(opts: &BenchOptions) -> BenchReport {
    let mut rng = Seeded(0x1e47_a9ce);
    let count = if opts.quick { 8 } else { 32 };
    let budget = Duration::from_millis(if opts.quick { 4 } else { 40 });
    let exact_of = |scene: &Scene| -> Option<Outputs> {
        let p = scene.problem::<Exact>().ok()?;
        let mut outs = [Outcome::default(), Outcome::default()];
        let impact = solve_new(&p, &mut outs)?;
        outputs(&impact, &outs)
    };
    // Well-conditioned: cond₂(G) ≤ 10⁴ by the f64 eigenvalues of G.
    let mut well = Vec::new();
    let mut unilateral_differs = 0;
    while well.len() < count {
        let n = [2, 2, 3, 4, 6][well.len() % 5];
        let Some(scene) = random_scene(&mut rng, n) else {
            continue;
        };
        let Ok(p) = scene.problem::<f64>() else {
            continue;
        };
        let Ok(impact) = Impact::assemble(&p) else {
            continue;
        };
        if impact.singular() || crate::analysis::condition_number(impact.g_hat(), n) > 1e4 {
            continue;
        }
        if let Some(e) = exact_of(&scene) {
            let u = scene
                .problem::<Exact>()
                .ok()
                .and_then(|p| unilateral_outputs(&p));
            if u.as_ref()
                .is_some_and(|(_, act)| act.iter().any(|a| a.iter().any(|x| !x)))
            {
                unilateral_differs += 1;
            }
            well.push((scene, e, u.map(|(o, _)| o)));
        }
    }
    let mut hard = Vec::new();
    if let Some(dir) = opts.hard_cases.as_deref().filter(|d| d.is_dir()) {
        let mut files: Vec<_> = std::fs::read_dir(dir)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.path())
            .collect();
        files.sort();
        for f in files
            .iter()
            .filter(|f| f.extension().is_some_and(|x| x == "toml"))
        {
            // The bench times the free-body solve; constrained hard cases stay in the tests.
            let Ok(scene) = Scene::load(f) else { continue };
            if scene.constraints.is_some() {
                continue;
            }
            if let Some(e) = exact_of(&scene) {
                hard.push((scene, e, None));
            }
        }
    }
    // The contract: every scene above (the constrained hard cases too) and scenes spanning
    // ratios of 10^±12.
    let ratio_count = if opts.quick { 24 } else { 120 };
    let mut contract_scenes: Vec<Scene> = well.iter().map(|c| c.0.clone()).collect();
    if let Some(dir) = opts.hard_cases.as_deref().filter(|d| d.is_dir()) {
        contract_scenes.extend(crate::tools::accuracy::hard_cases(dir));
    }
    contract_scenes.extend(crate::tools::accuracy::ratio_scenes(
        ratio_count,
        0x5eed_0016,
    ));
    let contract = (crate::tools::accuracy::run(&contract_scenes), ratio_count);
    let rows = vec![
        measure::<f32>(&well, &hard, budget),
        measure::<f64>(&well, &hard, budget),
        measure::<DoubleDouble>(&well, &hard, budget),
        measure::<Exact>(&well, &hard, budget),
    ];
    let sizes: &[usize] = if opts.quick {
        &[2, 3, 6, 12, 24]
    } else {
        &[2, 3, 4, 6, 8, 12, 16, 24]
    };
    let scaling = sizes
        .iter()
        .filter_map(|&n| {
            let scene = landing_scene(&mut rng, n)?;
            let b = budget;
            let exact = n <= if opts.quick { 12 } else { 24 };
            let skipped = || Timing::Skipped;
            let active = |act: Option<(Outputs, [Vec<bool>; 2])>| {
                act.map(|(_, [a, b])| {
                    let count = |x: &Vec<bool>| x.iter().filter(|y| **y).count();
                    (count(&a), count(&b))
                })
            };
            Some(Growth {
                contacts: n,
                analyze: vec![
                    time_analyze::<f32>(&scene, b),
                    time_analyze::<f64>(&scene, b),
                    time_analyze::<DoubleDouble>(&scene, b),
                    exact.then(|| time_analyze::<Exact>(&scene, b)).flatten(),
                ],
                simultaneous: vec![
                    with_problem::<f32>(&scene, |p| time_simultaneous(p, b)),
                    with_problem::<f64>(&scene, |p| time_simultaneous(p, b)),
                    with_problem::<DoubleDouble>(&scene, |p| time_simultaneous(p, b)),
                    if exact {
                        with_problem::<Exact>(&scene, |p| time_simultaneous(p, b))
                    } else {
                        skipped()
                    },
                ],
                unilateral: vec![
                    with_problem::<f32>(&scene, |p| time_unilateral(p, b)),
                    with_problem::<f64>(&scene, |p| time_unilateral(p, b)),
                    with_problem::<DoubleDouble>(&scene, |p| time_unilateral(p, b)),
                    if exact {
                        with_problem::<Exact>(&scene, |p| time_unilateral(p, b))
                    } else {
                        skipped()
                    },
                ],
                active: if exact {
                    active(
                        scene
                            .problem::<Exact>()
                            .ok()
                            .and_then(|p| unilateral_outputs(&p)),
                    )
                } else {
                    active(
                        scene
                            .problem::<f64>()
                            .ok()
                            .and_then(|p| unilateral_outputs(&p)),
                    )
                },
            })
        })
        .collect();
    BenchReport {
        scenes: (well.len(), hard.len()),
        rows,
        scaling,
        unilateral_differs,
        friction: crate::tools::friction_bench::run(opts.quick),
        contract,
        lean: crate::tools::lean_bench::run(opts.quick),
        n_curve: crate::tools::n_curve::run(opts.quick),
        systems: crate::tools::system_bench::run(opts.quick),
        sweep_points: crate::tools::goals::sweep_points(opts.quick),
    }
}

/// `f` on `scene`'s problem in `T` (`Singular` when it cannot be built).
fn with_problem<T: Scalar>(scene: &Scene, f: impl FnOnce(&Problem<T>) -> Timing) -> Timing {
    scene.problem::<T>().map_or(Timing::Singular, |p| f(&p))
}

/// Time one scene in every scalar type, and in f64 the cheapest public path, impulses and
/// twist only (`f64/impulses,twist`), the lean path for both models (`f64/lean`) and for
/// Newton's alone (`f64/lean-newton`: the work of one `impulseDynamics` call, which has
/// Newton's law only); each a time per solve or why there is none
/// ([`crate::tools::system_bench::NotTimed`]).
///
/// One solve is the scene's law: its models, simultaneous or unilateral, or its frictional
/// restitution laws. A scene with radicals (which the `exact` row cannot read) adds the row
/// `exact/radicals`, the same solve in the symbolic field, as `solve --exact` runs it. A scene of several bodies is timed per type only, each solve from its
/// data ([`crate::tools::system_bench::time_system_scene`]).
pub fn time_scene(scene: &Scene, quick: bool) -> SceneTiming {
    let budget = Duration::from_millis(if quick { 20 } else { 200 });
    if scene.law == crate::impact::unilateral::Law::Lzb {
        return crate::tools::lzb_bench::time_lzb_scene(scene, budget);
    }
    if scene.system.is_some() {
        return crate::tools::system_bench::time_system_scene(scene, budget);
    }
    let simultaneous =
        scene.law == crate::impact::unilateral::Law::Simultaneous && !scene.frictional();
    let problem = |t: Result<Problem<f64>, crate::scene::SceneError>| {
        t.map_err(|e| NotTimed::NotApplicable(format!("{}: {}", e.key, e.message)))
    };
    let only_simultaneous = || {
        NotTimed::NotApplicable(format!(
            "the simultaneous frictionless solve only; this scene is solved under {}",
            crate::tools::system_bench::law_name(scene)
        ))
    };
    let lean = |models: &[Model]| -> Result<f64, NotTimed> {
        if !simultaneous {
            return Err(only_simultaneous());
        }
        let p = problem(scene.problem::<f64>())?;
        time_lean(&p, budget, models).ok_or_else(|| {
            NotTimed::NotApplicable(
                "the lean path takes a free body with principal moments, 2 to 4 contacts and a \
                 well-conditioned G"
                    .into(),
            )
        })
    };
    fn typed<T: Scalar>(
        scene: &Scene,
        budget: Duration,
        simultaneous: bool,
    ) -> Result<f64, NotTimed> {
        let p = scene
            .problem::<T>()
            .map_err(|e| NotTimed::NotApplicable(format!("{}: {}", e.key, e.message)))?;
        if simultaneous {
            time_solve(&p, budget).ok_or(NotTimed::NoAnswer("singular"))
        } else {
            crate::tools::system_bench::time_law::<T, Problem<T>>(scene, budget, || Ok(p.clone()))
        }
    }
    let mut timing = SceneTiming {
        scene: scene.name.clone(),
        bodies: 1,
        contacts: scene.contacts.len(),
        // The simultaneous path times both models, whichever the scene asks for.
        law: if simultaneous {
            "newton + poisson".into()
        } else {
            crate::tools::system_bench::law_name(scene)
        },
        solve: if simultaneous {
            "assemble + newton + poisson, every output".into()
        } else {
            crate::tools::system_bench::solve_description(scene, "assemble")
        },
        rows: vec![
            (
                "f64/impulses,twist",
                if simultaneous {
                    problem(scene.problem::<f64>()).and_then(|p| {
                        time_solve_for(&p, budget, Asked::IMPULSES | Asked::TWIST)
                            .ok_or(NotTimed::NoAnswer("singular"))
                    })
                } else {
                    Err(only_simultaneous())
                },
            ),
            ("f64/lean", lean(&[Model::Newton, Model::Poisson])),
            ("f64/lean-newton", lean(&[Model::Newton])),
            ("f32", typed::<f32>(scene, budget, simultaneous)),
            ("f64", typed::<f64>(scene, budget, simultaneous)),
            (
                "double-double",
                typed::<DoubleDouble>(scene, budget, simultaneous),
            ),
            ("exact", typed::<Exact>(scene, budget, simultaneous)),
        ],
    };
    if !scene.is_rational() {
        // Radicals (a body posed at 30°, a normal 2/sqrt(5)): `solve --exact` runs in the
        // symbolic field, timed here as its own row.
        timing.rows.push((
            "exact/radicals",
            typed::<crate::scalar::symbolic::RatFun>(scene, budget, simultaneous),
        ));
    }
    timing
}

/// What [`time_batch`] measured.
#[derive(Clone, Debug, PartialEq)]
pub struct BatchTiming {
    /// Points per batch.
    pub points: usize,
    /// Timed runs of the whole batch (after one warm-up run).
    pub runs: usize,
    /// rayon's worker threads (the batch runs on the global pool).
    pub threads: usize,
    /// The median over the runs of the batch's wall time divided by its points, ns.
    pub ns_per_point: f64,
}

/// Time [`crate::tools::sweep::solve_batch`] — the batch API the Python bindings' `solve_batch`
/// calls — on the scene `doc` (read from `file`) at the points of `vary`: one warm-up run, then
/// `runs` runs of the whole batch, each on all of rayon's threads; the median wall time per point.
/// Everything the call needs (the document, the value arrays) is built beforehand, as a Python
/// caller holds its scene and arrays before calling.
///
/// # Errors
/// Whatever `solve_batch` refuses (an unknown path, arrays of different lengths, a value that
/// makes the scene invalid).
pub fn time_batch(
    doc: &toml_edit::DocumentMut,
    file: &str,
    vary: &[crate::tools::sweep::Varied],
    runs: usize,
) -> Result<BatchTiming, crate::tools::sweep::SweepError> {
    let points = vary.first().map_or(0, |v| v.values.len());
    std::hint::black_box(crate::tools::sweep::solve_batch(doc, file, vary, None)?);
    let mut times = Vec::with_capacity(runs.max(1));
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        std::hint::black_box(crate::tools::sweep::solve_batch(doc, file, vary, None)?);
        times.push(t.elapsed().as_secs_f64() * 1e9 / points.max(1) as f64);
    }
    Ok(BatchTiming {
        points,
        runs: runs.max(1),
        threads: rayon::current_num_threads(),
        ns_per_point: median(times),
    })
}

pub(crate) fn fmt_ns(ns: f64) -> String {
    if !ns.is_finite() {
        "—".into()
    } else if ns < 1e3 {
        format!("{ns:.0} ns")
    } else if ns < 1e6 {
        format!("{:.1} µs", ns / 1e3)
    } else {
        format!("{:.1} ms", ns / 1e6)
    }
}

fn fmt_timing(t: Timing) -> String {
    match t {
        Timing::Ns(ns) => fmt_ns(ns),
        Timing::Singular => "singular".into(),
        Timing::Jammed => "jammed".into(),
        Timing::Skipped => "—".into(),
    }
}

fn fmt_err(e: f64) -> String {
    if e == 0.0 {
        "0".into()
    } else if e.is_infinite() {
        "singular".into()
    } else {
        format!("{e:.1e}")
    }
}

impl BenchReport {
    /// The readable tables.
    pub fn to_text(&self) -> String {
        let mut s = format!(
            "inertance bench: {} well-conditioned scenes (N = 2–6, cond₂ G ≤ 1e4){}; one solve = assemble + Newton + Poisson, every output\n\n",
            self.scenes.0,
            if self.scenes.1 > 0 {
                format!(", {} hard cases", self.scenes.1)
            } else {
                String::new()
            }
        );
        s += "| scalar | median time per solve | median rel. error | max rel. error | max rel. error, hard cases |\n|---|---|---|---|---|\n";
        for r in &self.rows {
            s += &format!(
                "| {} | {} | {} | {} | {} |\n",
                r.name,
                fmt_ns(r.median_ns),
                fmt_err(r.median_error),
                fmt_err(r.max_error),
                r.max_error_hard
                    .map_or("—".into(), |(e, singular)| if singular > 0 {
                        format!("{} ({singular} declared singular)", fmt_err(e))
                    } else {
                        fmt_err(e)
                    })
            );
        }
        s += "\nCost growth with N (assemble + analyze, both models):\n\n| N |";
        for r in &self.rows {
            s += &format!(" {} |", r.name);
        }
        s += "\n|---|";
        s += &"---|".repeat(self.rows.len());
        s += "\n";
        for g in &self.scaling {
            s += &format!("| {} |", g.contacts);
            for t in &g.analyze {
                s += &format!(" {} |", t.map_or("—".into(), fmt_ns));
            }
            s += "\n";
        }
        s += &format!(
            "\nUnilateral law on the same scenes (assemble + unilateral Newton + Poisson, every output; error against the exact unilateral outcome; in {} of {} scenes some contact takes no impulse, where the laws differ):\n\n",
            self.unilateral_differs, self.scenes.0
        );
        s += "| scalar | median time per solve | ÷ simultaneous | median rel. error | max rel. error |\n|---|---|---|---|---|\n";
        for r in &self.rows {
            let u = &r.unilateral;
            s += &format!(
                "| {} | {} | {:.1}× | {} | {} |\n",
                r.name,
                fmt_ns(u.median_ns),
                u.median_ns / r.median_ns,
                fmt_err(u.median_error),
                fmt_err(u.max_error)
            );
        }
        s += "\nSimultaneous vs unilateral against N (assemble + Newton + Poisson, same scene per N; active: contacts taking an impulse under the unilateral Newton / Poisson laws):\n\n| N |";
        for r in &self.rows {
            s += &format!(" {0} simultaneous | {0} unilateral |", r.name);
        }
        s += " active |\n|---|";
        s += &"---|---|".repeat(self.rows.len());
        s += "---|\n";
        for g in &self.scaling {
            s += &format!("| {} |", g.contacts);
            for (a, b) in g.simultaneous.iter().zip(&g.unilateral) {
                s += &format!(" {} | {} |", fmt_timing(*a), fmt_timing(*b));
            }
            s += &format!(
                " {} |\n",
                g.active.map_or("—".into(), |(n, p)| format!("{n} / {p}"))
            );
        }
        s += &self.contract_text();
        s += &self.lean.to_text();
        s += "\nCost of `analyze` against N (linear-cost route: the contact wrenches' Gram–Schmidt, both models; fit t ∝ N^p over N ≥ 100):\n\n| scalar | N: time | p |\n|---|---|---|\n";
        for c in &self.n_curve {
            s += &format!(
                "| {} | {} | {} |\n",
                c.scalar,
                c.points
                    .iter()
                    .map(|(n, t)| format!("{n}: {}", fmt_ns(*t)))
                    .collect::<Vec<_>>()
                    .join(", "),
                c.exponent.map_or("—".into(), |p| format!("{p:.2}"))
            );
        }
        s += &self.friction.to_text();
        s += &self.systems.to_text();
        s + &crate::tools::goals::to_text(&self.goals())
    }

    /// Issue 29's goals measured in this run ([`crate::tools::goals`]).
    pub fn goals(&self) -> Vec<crate::tools::goals::Goal> {
        crate::tools::goals::goals(&self.sweep_points, &self.lean, &self.friction)
    }

    /// The JSON report.
    pub fn to_json(&self) -> Json {
        let num = |x: f64| {
            serde_json::Number::from_f64(x)
                .map(Json::Number)
                .unwrap_or(Json::Null)
        };
        // Per scalar: ns, or "singular" / "jammed", or null when not measured.
        let by_scalar = |t: &[Timing]| {
            self.rows
                .iter()
                .zip(t)
                .map(|(r, x)| {
                    let v = match x {
                        Timing::Ns(ns) => num(*ns),
                        Timing::Singular => "singular".into(),
                        Timing::Jammed => "jammed".into(),
                        Timing::Skipped => Json::Null,
                    };
                    (r.name.to_string(), v)
                })
                .collect::<serde_json::Map<_, _>>()
        };
        json!({
            "scenes": {"well_conditioned": self.scenes.0, "hard_cases": self.scenes.1},
            "scalars": self.rows.iter().map(|r| json!({
                "scalar": r.name,
                "median_ns_per_solve": num(r.median_ns),
                "median_relative_error": num(r.median_error),
                "max_relative_error": num(r.max_error),
                "max_relative_error_hard_cases": r.max_error_hard.map(|h| num(h.0)),
                "hard_cases_declared_singular": r.max_error_hard.map(|h| h.1),
                "unilateral": {
                    "median_ns_per_solve": num(r.unilateral.median_ns),
                    "median_relative_error": num(r.unilateral.median_error),
                    "max_relative_error": num(r.unilateral.max_error),
                },
            })).collect::<Vec<_>>(),
            "unilateral_differs": self.unilateral_differs,
            "contract": self.contract_json(),
            "friction": self.friction.to_json(),
            "lean": self.lean.to_json(),
            "systems": self.systems.to_json(),
            "goals": crate::tools::goals::to_json(&self.goals()),
            "n_curve": self.n_curve.iter().map(|c| json!({
                "scalar": c.scalar,
                "points": c.points.iter().map(|(n, t)| json!({"contacts": n, "ns_per_analyze": num(*t)})).collect::<Vec<_>>(),
                "exponent": c.exponent.map(num),
            })).collect::<Vec<_>>(),
            "scaling": self.scaling.iter().map(|g| json!({
                "contacts": g.contacts,
                "ns_per_assemble_and_analyze": self.rows.iter().zip(&g.analyze).map(|(r, x)| (r.name.to_string(), x.map(num).unwrap_or(Json::Null))).collect::<serde_json::Map<_, _>>(),
                "ns_per_solve_simultaneous": by_scalar(&g.simultaneous),
                "ns_per_solve_unilateral": by_scalar(&g.unilateral),
                "unilateral_active": g.active.map(|(n, p)| json!({"newton": n, "poisson": p})),
            })).collect::<Vec<_>>(),
        })
    }

    /// The contract's table: per scalar, the largest error/bound per output.
    fn contract_text(&self) -> String {
        let (rows, ratios) = &self.contract;
        let mut s = format!(
            "\nAccuracy contract (analysis::accuracy): the largest error / bound per output over every solve of the scenes above (hard cases included) and {ratios} scenes spanning ratios of 10^±12; ≤ 1 is the contract:\n\n| scalar | solves | declared singular (smallest cond₂ G) |"
        );
        for o in Output::ALL {
            s += &format!(" {} |", o.name());
        }
        s += "\n|---|---|---|";
        s += &"---|".repeat(Output::ALL.len());
        s += "\n";
        for r in rows {
            let (singular, cond) = r.declared_singular();
            let solves = r.measurements.len() - singular;
            s += &format!(
                "| {} | {solves} | {} |",
                r.scalar,
                if singular > 0 {
                    format!("{singular} ({cond:.1e})")
                } else {
                    "0".into()
                }
            );
            for o in Output::ALL {
                s += &format!(" {} |", fmt_err(r.worst(o).0));
            }
            s += "\n";
        }
        s
    }

    /// The contract's JSON: per scalar, solves, declared singular, and per output the largest
    /// ratio and its case.
    fn contract_json(&self) -> Json {
        let num = |x: f64| {
            serde_json::Number::from_f64(x)
                .map(Json::Number)
                .unwrap_or(Json::Null)
        };
        let (rows, ratios) = &self.contract;
        json!({
            "ratio_scenes": ratios,
            "scalars": rows.iter().map(|r| {
                let (singular, _) = r.declared_singular();
                json!({
                    "scalar": r.scalar,
                    "solves": r.measurements.len() - singular,
                    "declared_singular": singular,
                    "max_error_over_bound": Output::ALL.iter().map(|o| {
                        let (ratio, case) = r.worst(*o);
                        (o.name().to_string(), json!({"ratio": num(ratio), "case": case}))
                    }).collect::<serde_json::Map<_, _>>(),
                })
            }).collect::<Vec<_>>(),
        })
    }

    /// Write the plot: error versus time per scalar type (log–log; exact results, error 0,
    /// are drawn on the floor 10⁻³⁵), the cost growth with N (solid: assemble + analyze;
    /// dashed with triangles: the unilateral solve), and a system's cost against its bodies
    /// (the planar chain, per solve and per body).
    pub fn plot(&self, path: &Path) -> Result<(), String> {
        use plotters::prelude::*;
        let tmp = path.with_extension("svg.tmp");
        let result = (|| -> Result<(), Box<dyn std::error::Error>> {
            let root = SVGBackend::new(&tmp, (1600, 480)).into_drawing_area();
            root.fill(&WHITE)?;
            let (left, rest) = root.split_horizontally(560);
            let (right, systems) = rest.split_horizontally(540);
            self.systems.plot_chain(&systems)?;
            // Exponents on linear axes, labelled as powers of ten: plotters' log axes stop
            // labelling long before 10⁻³⁵, where the double-double and exact points sit.
            let floor = -35f64;
            let tmax = self
                .rows
                .iter()
                .map(|r| r.median_ns)
                .filter(|x| x.is_finite())
                .fold(10.0, f64::max)
                .log10()
                .ceil()
                + 1.0;
            let mut chart = ChartBuilder::on(&left)
                .caption("accuracy vs time per solve", ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(1f64..tmax, floor..0f64)?;
            chart
                .configure_mesh()
                .x_desc("median time per solve [ns]")
                .y_desc("relative error (median ●, max ▲)")
                .x_label_formatter(&|x| format!("1e{x:.0}"))
                .y_label_formatter(&|y| format!("1e{y:.0}"))
                .x_labels(8)
                .y_labels(8)
                .draw()?;
            let colors = [RED, BLUE, GREEN, BLACK];
            for (r, c) in self.rows.iter().zip(colors) {
                let y = |e: f64| {
                    if e > 0.0 && e.is_finite() {
                        e.log10().max(floor)
                    } else if e == 0.0 {
                        floor
                    } else {
                        0.0
                    }
                };
                let (x, med, max) = (r.median_ns.log10(), y(r.median_error), y(r.max_error));
                if !x.is_finite() {
                    continue;
                }
                chart.draw_series(LineSeries::new(vec![(x, med), (x, max)], c.stroke_width(2)))?;
                chart.draw_series(std::iter::once(TriangleMarker::new(
                    (x, max),
                    6,
                    c.filled(),
                )))?;
                chart
                    .draw_series(std::iter::once(Circle::new((x, med), 6, c.filled())))?
                    .label(if r.median_error == 0.0 {
                        format!("{} (error 0, drawn at 1e-35)", r.name)
                    } else {
                        r.name.to_string()
                    })
                    .legend(move |(px, py)| Circle::new((px, py), 5, c.filled()));
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperRight)
                .draw()?;

            let nmax = self.scaling.iter().map(|g| g.contacts).max().unwrap_or(2) as f64;
            let tops = self
                .scaling
                .iter()
                .flat_map(|g| {
                    g.analyze
                        .iter()
                        .flatten()
                        .cloned()
                        .chain(g.unilateral.iter().filter_map(|t| t.ns()))
                })
                .fold(10.0, f64::max)
                * 3.0;
            let mut growth = ChartBuilder::on(&right)
                .caption(
                    "cost vs N (solid: assemble + analyze; dashed: unilateral solve)",
                    ("sans-serif", 18),
                )
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d((2f64..nmax).log_scale(), (10f64..tops).log_scale())?;
            growth
                .configure_mesh()
                .x_desc("contacts N")
                .y_desc("time [ns]")
                .x_label_formatter(&|x| format!("{x:.0}"))
                .y_label_formatter(&|y| format!("{y:.0e}"))
                .draw()?;
            for (k, (r, c)) in self.rows.iter().zip(colors).enumerate() {
                let pts: Vec<(f64, f64)> = self
                    .scaling
                    .iter()
                    .filter_map(|g| g.analyze[k].map(|x| (g.contacts as f64, x)))
                    .collect();
                let unilateral: Vec<(f64, f64)> = self
                    .scaling
                    .iter()
                    .filter_map(|g| g.unilateral[k].ns().map(|x| (g.contacts as f64, x)))
                    .collect();
                growth.draw_series(DashedLineSeries::new(
                    unilateral.clone(),
                    6,
                    4,
                    c.stroke_width(2),
                ))?;
                growth.draw_series(
                    unilateral
                        .into_iter()
                        .map(|p| TriangleMarker::new(p, 4, c.filled())),
                )?;
                growth
                    .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))?
                    .label(r.name)
                    .legend(move |(px, py)| {
                        PathElement::new(vec![(px, py), (px + 16, py)], c.stroke_width(2))
                    });
                growth.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, c.filled())))?;
            }
            growth
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperLeft)
                .draw()?;
            root.present()?;
            Ok(())
        })();
        match result {
            Ok(()) => std::fs::rename(&tmp, path).map_err(|e| format!("{}: {e}", path.display())),
            Err(e) => {
                let _ = std::fs::remove_file(&tmp);
                Err(format!("{}: {e}", path.display()))
            }
        }
    }
}

/// When, where and under what load a bench report was measured: the header of
/// `inertance bench --out FILE.md`, so that a table in the repository says which run it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// The start of the run, RFC 3339 in UTC to the second.
    pub when: String,
    /// Logical cores the process may use.
    pub cores: usize,
    /// The load averages over 1, 5 and 15 minutes at the start (`/proc/loadavg`), where the
    /// system gives them.
    pub load: Option<[f64; 3]>,
    /// Whether the run was `--quick`.
    pub quick: bool,
}

impl Measured {
    /// The machine now.
    pub fn now(quick: bool) -> Measured {
        let load = std::fs::read_to_string("/proc/loadavg").ok().and_then(|s| {
            let v: Vec<f64> = s
                .split_whitespace()
                .take(3)
                .filter_map(|x| x.parse().ok())
                .collect();
            <[f64; 3]>::try_from(v).ok()
        });
        Measured {
            when: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            load,
            quick,
        }
    }

    /// One line for the head of a report.
    pub fn to_text(&self) -> String {
        let load = self.load.map_or("not known".into(), |[a, b, c]| {
            format!("{a:.2}, {b:.2}, {c:.2} (1, 5, 15 min)")
        });
        format!(
            "Measured {} by `inertance bench{}` (inertance {}), {} logical cores, load average at the start {load}; timings are of this machine and load, the ratios of rounds taken in turn.",
            self.when,
            if self.quick { " --quick" } else { "" },
            env!("CARGO_PKG_VERSION"),
            self.cores,
        )
    }
}

/// Write `text` to `path` atomically: to `path.tmp`, renamed to `path` when complete; the
/// `.tmp` is removed on failure, so no half-written file is left.
pub fn write_atomically(path: &Path, text: &str) -> Result<(), String> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = std::path::PathBuf::from(tmp);
    let done = std::fs::write(&tmp, text).and_then(|()| std::fs::rename(&tmp, path));
    done.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        format!("{}: {e}", path.display())
    })
}
