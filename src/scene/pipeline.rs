//! From a scene to a report: compose exactly the stages the scene calls for.
//!
//! A scene declares its effects: the restitution models it asks for (`[solve] models`),
//! `[constraints]` (§9–11) and `[surface]` (§12); friction will join as an effect of its own. The pipeline
//! assembles the collision once (frames, inertances, Δ) and runs only the models listed; the
//! report names the effects it simulated.
//!
//! Every stage is generic over the scalar, so a dual-number run (a sensitivity,
//! [`crate::scalar::dual`]) is this same code: the float units of [`super::scale`] carry the
//! seeded tangent and scale each derivative back with its output, the exact path's hand-over
//! to the radical field is not taken (that field carries no derivative), and the spatial
//! frictional integrator refuses it.

use num_traits::Zero;

use crate::analysis::wrench_space::WrenchSpace;
use crate::impact::admissibility::{Inadmissible, energy_gain, verdicts};
use crate::impact::friction::{FrictionError, PlanarFrictionWork};
use crate::impact::outputs::Outputs;
use crate::impact::problem::{Problem, Reason};
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::impact::unilateral::{Activity, Law, UnilateralError};
use crate::mechanics::constraint::{Constrained, ConstraintError};
use crate::report::{FrictionReport, Report, Value};
use crate::scalar::symbolic::RatFun;
use crate::scalar::{Exact, Scalar};
use crate::scene::limits::{exact_limit, friction_limit};
use crate::scene::scale::{
    Units, out_of_range, output_below, output_beyond, precision_lost, scale, unrepresentable,
    unscale,
};
use crate::scene::{ConstraintsSpec, OUT_OF_RANGE, Scene, SceneError};

/// Why a scene could not be solved.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// Bad input.
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// The collision has no unique solution, or a frame could not be built.
    #[error("{0}")]
    Solve(#[from] SolveError),
    /// The unilateral law found no admissible impulses (a jammed body).
    #[error("{0}")]
    Unilateral(#[from] UnilateralError),
    /// The frictional integration could not follow the impact.
    #[error("{0}")]
    Friction(#[from] FrictionError),
    /// The LZB law gave no outcome, or was asked of a path that does not run it.
    #[error("{0}")]
    Lzb(#[from] crate::impact::multiple::LzbError),
}

/// A solved scene: its report, and whether the energy identity ΔE_c = −E_p + Σ P_i v_ix⁰
/// (eq. 34) held for each model — exactly in exact mode, to `16·N·ε·scale` in floats.
#[derive(Clone, Debug)]
pub struct Solved {
    /// The readout.
    pub report: Report,
    /// Per model, in report order.
    pub energy_identity: Vec<bool>,
}

/// Solve `scene` in the scalar type `T` for `models` (the scene's own when `None`).
pub fn run<T: Scalar>(scene: &Scene, models: Option<&[Model]>) -> Result<Solved, RunError> {
    run_with::<T>(scene, models, false)
}

/// As [`run`]; with `allow_singular`, a singular G (Δ = 0) is not an error: the report holds
/// the model-independent part (frames, inertances, Δ, velocities before impact) and no model
/// (used by `check` for the paper's singular examples).
///
/// In floats the scene is first put in units of mass, length and time that are powers of two
/// chosen from its own numbers ([`super::scale`]), so that scenes whose numbers span the range
/// of f64 are solved, and the report is scaled back. A float result that is still not finite is
/// refused, naming the input farthest from 1 — never reported as NaN or ∞.
pub fn run_with<T: Scalar>(
    scene: &Scene,
    models: Option<&[Model]>,
    allow_singular: bool,
) -> Result<Solved, RunError> {
    if T::IS_EXACT {
        // An energetic stop at an irrational s needs the radical field: rationals hand over
        // to it (a dual run does not: the radical field carries no derivative).
        return match run_as_written::<T>(scene, models, allow_singular) {
            Err(RunError::Friction(FrictionError::NeedsRadical { .. }))
                if T::NAME == Exact::NAME =>
            {
                run_as_written::<RatFun>(scene, models, allow_singular)
            }
            other => other,
        };
    }
    let unrepresentable = || {
        RunError::Scene(unrepresentable(
            scene,
            T::NAME,
            ", even in units of mass, length and time scaled to the scene",
        ))
    };
    let input_out_of_range =
        |e: &RunError| matches!(e, RunError::Scene(s) if s.message.ends_with(OUT_OF_RANGE));
    let prepared = match prepare_scaled::<T>(scene) {
        Err(e) if input_out_of_range(&e) => return Err(unrepresentable()),
        prepared => prepared?,
    };
    let mut solved = run_prepared_with(scene, &prepared.problem, models, allow_singular)?;
    finish_float::<T>(scene, &mut solved, prepared.units.as_ref(), SCALED)?;
    solved.report.scene.clone_from(&scene.name);
    Ok(solved)
}

/// How a float solve in units scaled to the scene was tried, for refusals.
const SCALED: &str = ", even in units of mass, length and time scaled to the scene";

/// A float report refused when a physical output lost its precision in the units it was
/// solved in ([`precision_lost`]), else put back into the scene's units (`units`, when it was
/// solved in scaled ones), its written constraint screws echoed as written, and refused when
/// a physical output is beyond `T` there (`how`: in which units it was solved). Exact reports
/// are only scaled back.
fn finish_float<T: Scalar>(
    scene: &Scene,
    solved: &mut Solved,
    units: Option<&Units>,
    how: &str,
) -> Result<(), RunError> {
    if !T::IS_EXACT
        && let Some(output) = precision_lost(&solved.report)
    {
        return Err(RunError::Scene(output_below(scene, T::NAME, output, how)));
    }
    if let Some(units) = units {
        unscale(&mut solved.report, units);
    }
    if T::IS_EXACT {
        return Ok(());
    }
    echo_written_screws(&mut solved.report, scene);
    match out_of_range(&solved.report) {
        Some(output) => Err(RunError::Scene(output_beyond(scene, T::NAME, output, how))),
        None => Ok(()),
    }
}

/// The constraint screws a scene writes out (`free`, and `blocked` when given) are inputs: a
/// number of theirs that f64 does not hold (a blocked screw written `"10^400"`, which came out
/// as `inf` in the table and `null` in the JSON) is reported as written, its text.
fn echo_written_screws(report: &mut Report, scene: &Scene) {
    let (Some(c), Some(ConstraintsSpec::Screws { free, blocked })) =
        (&mut report.constraints, &scene.constraints)
    else {
        return;
    };
    let written = blocked.as_ref().filter(|_| !c.blocked_derived);
    let pairs = c
        .free
        .iter_mut()
        .zip(free)
        .chain(c.blocked.iter_mut().zip(written.into_iter().flatten()));
    for (values, numbers) in pairs {
        for (v, n) in values.iter_mut().zip(numbers) {
            let zero = matches!(&n.exact, Ok(q) if q.is_zero());
            if !n.approx.is_finite() || (n.approx == 0.0 && !zero) {
                *v = Value {
                    exact: Some(n.text.clone()),
                    wide: None,
                    ..v.clone()
                };
            }
        }
    }
}

/// A scene's problem prepared in the float units [`super::scale`] picks for it: solved by
/// [`run_prepared_scaled`] and scaled back, as [`run_with`] does.
#[derive(Clone, Debug)]
pub struct Prepared<T: Scalar> {
    /// The problem, in the scaled units.
    pub problem: Problem<T>,
    /// The units, `None` when the scene is not scaled.
    pub units: Option<Units>,
}

/// Prepare `scene` in `T` in the units [`super::scale`] picks. The scaled scene serves only its
/// numbers: the report is read with the scene itself (its name, effects, surface as written).
/// A scaled scene that does not prepare for a reason other than the range (a point off the
/// surface, an invalid tangent) gives the unscaled scene's error, whose values are as written.
pub fn prepare_scaled<T: Scalar>(scene: &Scene) -> Result<Prepared<T>, RunError> {
    let Some((scaled, units)) = scale(scene) else {
        return Ok(Prepared {
            problem: prepare::<T>(scene)?,
            units: None,
        });
    };
    match prepare::<T>(&scaled) {
        Ok(problem) => Ok(Prepared {
            problem,
            units: Some(units),
        }),
        Err(RunError::Scene(s)) if !s.message.ends_with(OUT_OF_RANGE) => {
            prepare::<T>(scene)?;
            Err(RunError::Scene(s))
        }
        Err(e) => Err(e),
    }
}

/// As [`run_prepared`], for a problem prepared by [`prepare_scaled`]: the report scaled back,
/// and refused as in [`run_with`] when a physical output is beyond `T`.
pub fn run_prepared_scaled<T: Scalar>(
    scene: &Scene,
    prepared: &Prepared<T>,
    models: Option<&[Model]>,
) -> Result<Solved, RunError> {
    let mut solved = run_prepared_with(scene, &prepared.problem, models, false)?;
    finish_float::<T>(scene, &mut solved, prepared.units.as_ref(), SCALED)?;
    Ok(solved)
}

/// As [`run`]; with `allow_singular`, a singular G (Δ = 0) is not an error under the
/// simultaneous law: the report holds the model-independent part (frames, inertances, Δ,
/// velocities before impact) and no model (used by `check` for the paper's singular
/// examples). The unilateral law solves a singular G as any other (its velocities after impact
/// are unique), so its models are solved either way.
fn run_as_written<T: Scalar>(
    scene: &Scene,
    models: Option<&[Model]>,
    allow_singular: bool,
) -> Result<Solved, RunError> {
    run_prepared_with(scene, &prepare::<T>(scene)?, models, allow_singular)
}

/// As [`run`], for a `problem` already prepared from `scene` by [`prepare`]: preparing
/// (reading every number into `T`, validating, building constraints) costs several times
/// an f64 solve, so a caller solving one scene repeatedly (the Python bindings' `Scene`)
/// prepares it once. The problem is solved in the scene's own units (no [`super::scale`]), and a
/// float result that is not finite is refused as in [`run_with`].
pub fn run_prepared<T: Scalar>(
    scene: &Scene,
    problem: &Problem<T>,
    models: Option<&[Model]>,
) -> Result<Solved, RunError> {
    let mut solved = run_prepared_with(scene, problem, models, false)?;
    finish_float::<T>(
        scene,
        &mut solved,
        None,
        " in the scene's units (`run_with` scales them)",
    )?;
    Ok(solved)
}

fn run_prepared_with<T: Scalar>(
    scene: &Scene,
    problem: &Problem<T>,
    models: Option<&[Model]>,
    allow_singular: bool,
) -> Result<Solved, RunError> {
    scene.law_applies()?;
    if let Some(refusal) = T::IS_EXACT
        .then(|| exact_limit(scene))
        .flatten()
        .or_else(|| scene.frictional().then(|| friction_limit(scene)).flatten())
    {
        return Err(refusal.into());
    }
    if scene.frictional() {
        return run_frictional(scene, problem, models);
    }
    let models = models.unwrap_or(&scene.models);
    // The outputs printed, and what the checks read (admissibility, the energy identity).
    let checked = Outputs::IMPULSES | Outputs::NORMAL_VELOCITIES | Outputs::ENERGIES;
    let (contacts, limit) = (
        problem.contacts().len(),
        crate::impact::unilateral::max_unilateral_contacts::<T>(),
    );
    if scene.law == Law::Unilateral && contacts > limit {
        // Refused before G (N×N) is assembled.
        return Err(UnilateralError::TooManyContacts { contacts, limit }.into());
    }
    if scene.law == Law::Simultaneous && !allow_singular {
        surely_singular(problem)?;
    }
    let mut a = Assembled {
        impact: Impact::assemble_for(problem, scene.outputs | checked)?,
    };
    let models: &[Model] = if a.singular() && allow_singular && scene.law == Law::Simultaneous {
        &[]
    } else {
        models
    };
    let mut outcomes = Vec::with_capacity(models.len());
    let mut solves = Vec::with_capacity(models.len());
    // A model without an answer (a jam under the unilateral law) does not hide the others.
    let mut failures = Vec::new();
    let mut first_failure = None;
    for &m in models {
        match a.solve_law(m, scene.law) {
            Ok(s) => {
                outcomes.push((m, s.outcome.clone()));
                solves.push(s);
            }
            Err(RunError::Unilateral(e @ UnilateralError::Jammed { .. })) => {
                failures.push((m, e.to_string(), "jammed"));
                first_failure.get_or_insert(e);
            }
            Err(e) => return Err(e),
        }
    }
    if let (true, Some(e)) = (outcomes.is_empty(), first_failure) {
        return Err(e.into());
    }
    let ranges: Vec<Option<[(Value, Value); 6]>> = solves
        .iter()
        .map(|s| match s.activity {
            Some(act) if !act.outcome_decided => a.poisson_range(),
            _ => None,
        })
        .collect();
    let mut report = a.report(scene, &outcomes);
    report.outputs = scene.outputs;
    report.model_failures = failures;
    for (r, s) in report.models.iter_mut().zip(&solves) {
        r.law = scene.law;
        r.inadmissible.clone_from(&s.inadmissible);
        r.activity.clone_from(&s.activity);
        if s.activity.is_some() {
            r.active = crate::impact::unilateral::active(&s.outcome);
        }
    }
    for (r, range) in report.models.iter_mut().zip(ranges) {
        r.outcome_range = range;
    }
    Ok(Solved {
        report,
        energy_identity: solves.iter().map(|s| s.energy_identity).collect(),
    })
}

/// G = Eᵀ η W E has rank at most the body's degrees of freedom (6 when free): with more
/// contacts than that it is singular whatever the numbers, and the simultaneous law has no
/// unique answer. Decided before G (N×N) is formed, with rank G from the contact wrenches in
/// O(N) work and memory ([`WrenchSpace`]) — `solve` on 60,000 contacts allocated 28.8 GB for G
/// and aborted; `--exact` on 2000 factored G for two minutes.
fn surely_singular<T: Scalar>(problem: &Problem<T>) -> Result<(), SolveError> {
    let contacts = problem.contacts().len();
    let dof = problem.constraints().map_or(6, |c| c.dof());
    if contacts <= dof {
        return Ok(());
    }
    Err(SolveError::Singular {
        rank: WrenchSpace::build(problem)?.rank(),
        contacts,
        rounded: false,
    })
}

/// The relative tolerance of the spatial frictional integration in `T`: ε^(2/3) (f64:
/// 3.7·10⁻¹¹; double-double: 5·10⁻²²), which leaves the error estimate room above rounding.
pub fn friction_tolerance<T: Scalar>() -> f64 {
    T::epsilon_f64().powf(2.0 / 3.0)
}

/// A scene with friction (or an energetic law): each restitution law integrated in impulse
/// space; the report holds the model-independent part and one frictional readout per law.
fn run_frictional<T: Scalar>(
    scene: &Scene,
    problem: &Problem<T>,
    models: Option<&[Model]>,
) -> Result<Solved, RunError> {
    let a = Assembled {
        impact: Impact::assemble(problem)?,
    };
    let mut report = a.report(scene, &[]);
    let laws = scene.restitutions(models);
    report.effects.push("friction".into());
    report
        .effects
        .extend(laws.iter().map(|l| l.name().to_string()));
    let mut energy_identity = Vec::new();
    let kinetic = problem.body().kinetic_energy(problem.velocity());
    let mut first_failure = None;
    // One workspace for the laws: a planar scene's blocks, buffers and report are refilled
    // from one law to the next rather than built again.
    let mut work = PlanarFrictionWork::new();
    for law in laws {
        let tolerance = scene.tolerance.unwrap_or_else(friction_tolerance::<T>);
        let f = match work.solve_into(problem, law, scene.hypothesis(), tolerance) {
            Ok(f) => f,
            Err(e) => match e.status() {
                // A verdict of the physics for this law: the others still answer.
                Some(status) => {
                    report.friction_failures.push((law, e.to_string(), status));
                    first_failure.get_or_insert(e);
                    continue;
                }
                None => return Err(e.into()),
            },
        };
        energy_identity.push(f.energy_balance_holds(&kinetic));
        report.friction.push(FrictionReport::new(f));
    }
    if let (true, Some(e)) = (report.friction.is_empty(), first_failure) {
        return Err(e.into());
    }
    Ok(Solved {
        report,
        energy_identity,
    })
}

/// One model solved under a law, with what the report says about it.
#[derive(Clone, Debug)]
pub struct ModelSolve<T: Scalar> {
    /// The outcome (hatted).
    pub outcome: Outcome<T>,
    /// Whether ΔE_c = −E_p + Σ P_i v_ix⁰ (eq. 34) held.
    pub energy_identity: bool,
    /// Why a simultaneous outcome is not physical (empty: admissible); for the unilateral law,
    /// whose complementarity holds by construction, only an energy gain.
    pub inadmissible: Vec<Inadmissible>,
    /// The unilateral law's activity.
    pub activity: Option<Activity>,
}

/// A scene assembled in `T`: the model-independent part of its collision (frames, G, its
/// factorization, Δ), which holds the validated problem and its constraints.
#[derive(Clone, Debug)]
pub struct Assembled<T: Scalar> {
    /// The assembled collision.
    pub impact: Impact<T>,
}

/// Prepare `scene` in `T` and assemble its collision (a singular G is not an error here).
pub fn assemble<T: Scalar>(scene: &Scene) -> Result<Assembled<T>, RunError> {
    let problem = prepare::<T>(scene)?;
    Ok(Assembled {
        impact: Impact::assemble(&problem)?,
    })
}

impl<T: Scalar> Assembled<T> {
    /// Whether G is singular (rank G < N).
    pub fn singular(&self) -> bool {
        self.impact.singular()
    }

    /// The validated problem.
    pub fn problem(&self) -> &Problem<T> {
        self.impact.problem()
    }

    /// Solve one restitution model: the outcome (with the constraint impulses q for a
    /// constrained body) and whether the energy identity ΔE_c = −E_p + Σ P̂_i v̂_ix⁰ (eq. 34)
    /// holds — exactly in exact types, to `16·N·ε·scale` in floats.
    pub fn solve(&mut self, model: Model) -> Result<(Outcome<T>, bool), SolveError> {
        let mut out = Outcome::default();
        self.impact.solve(model, &mut out)?;
        let holds = self.energy_identity(&out);
        Ok((out, holds))
    }

    /// Solve one restitution model under `law`: with the admissibility verdicts of a
    /// simultaneous outcome, or the activity of a unilateral one.
    pub fn solve_law(&mut self, model: Model, law: Law) -> Result<ModelSolve<T>, RunError> {
        let mut outcome = Outcome::default();
        let (inadmissible, activity) = match law {
            Law::Simultaneous => {
                self.impact.solve(model, &mut outcome)?;
                (verdicts(&self.impact, model, &outcome), None)
            }
            Law::Unilateral => {
                let a = self.impact.solve_unilateral(model, &mut outcome)?;
                (
                    energy_gain(&self.impact, &outcome).into_iter().collect(),
                    Some(a),
                )
            }
            Law::Lzb => {
                return Err(crate::impact::multiple::LzbError::Unsupported {
                    what: "a solve by restitution model",
                }
                .into());
            }
        };
        Ok(ModelSolve {
            energy_identity: self.energy_identity(&outcome),
            outcome,
            inadmissible,
            activity,
        })
    }

    /// Poisson's undecided outcome: each twist component's least and greatest value over the
    /// vertices of the compression impulses (`None` when too many contacts to enumerate).
    fn poisson_range(&mut self) -> Option<[(Value, Value); 6]> {
        let outcomes = self.impact.poisson_vertex_outcomes().ok()??;
        let first = outcomes.first()?;
        Some(std::array::from_fn(|k| {
            let (mut lo, mut hi) = (first.velocity.0[k].clone(), first.velocity.0[k].clone());
            for o in &outcomes[1..] {
                let x = &o.velocity.0[k];
                if (x.clone() - &lo).signum_i8() < 0 {
                    lo = x.clone();
                }
                if (x.clone() - &hi).signum_i8() > 0 {
                    hi = x.clone();
                }
            }
            (Value::of(&lo), Value::of(&hi))
        }))
    }

    /// ΔE_c + E_p − Σ P̂_i v̂_ix⁰ = 0 (eq. 34) and ΔE_c = T⁰ − T (eq. 32): exactly in exact
    /// types, to 16·N·ε·(T⁰ + E_p) in floats.
    fn energy_identity(&self, out: &Outcome<T>) -> bool {
        let impact = &self.impact;
        let n = 16 * impact.contacts().max(1);
        let work = impact.impulse_work(out);
        let residual = out.kinetic_energy_loss.clone() + &out.lost_velocity_energy - &work;
        let scale = impact.kinetic_before().clone() + &out.lost_velocity_energy;
        // eq. 32: ΔE_c (from the momentum balance) = T⁰ − T (the kinetic energies), to the
        // rounding of T⁰ in floats.
        let problem = impact.problem();
        let difference =
            impact.kinetic_before().clone() - problem.body().kinetic_energy(&out.velocity);
        let eq32 = (out.kinetic_energy_loss.clone() - difference).is_negligible(&scale, n);
        residual.is_negligible(&scale, n) && eq32
    }

    /// The report of the outcomes solved.
    pub fn report(&self, scene: &Scene, outcomes: &[(Model, Outcome<T>)]) -> Report {
        let models: Vec<Model> = outcomes.iter().map(|(m, _)| *m).collect();
        let mut report = Report::new(
            &scene.name,
            scene.effects(&models),
            &self.impact,
            outcomes,
            self.problem().constraints(),
        );
        report.surface = scene
            .surface
            .as_ref()
            .map(|s| (s.text.clone(), s.surface.gradient_text()));
        report.axes = scene.axes.map(|a| a.name());
        report
    }
}

/// The validated problem in `T`: for a constrained scene, with its constraints (the initial
/// twist checked against them).
pub fn prepare<T: Scalar>(scene: &Scene) -> Result<Problem<T>, RunError> {
    // A pose the exact solver cannot hold is named by its angle, not by a computed entry.
    let problem =
        scene
            .problem::<T>()
            .map_err(|e| match scene.inexact_angle().filter(|_| T::IS_EXACT) {
                Some(angle) => angle,
                None => e,
            })?;
    match scene.constraint_screws::<T>()? {
        None => Ok(problem),
        Some(screws) => {
            let keys = screws.keys;
            let mut c = Constrained::new(problem.body(), screws.free, screws.blocked)
                .map_err(|e| constraint_error(scene, &keys, e))?;
            c.joints = screws.joints;
            problem.with_constrained(c).map_err(|e| match e.reason {
                Reason::Constraint(c) => constraint_error(scene, &keys, c),
                _ => RunError::Scene(SceneError {
                    file: scene.file.clone(),
                    key: e.field.to_string(),
                    value: None,
                    message: e.reason.to_string(),
                }),
            })
        }
    }
}

/// A constraint problem as a scene error naming the offending screws.
fn constraint_error(scene: &Scene, keys: &[String], e: ConstraintError) -> RunError {
    let key = match &e {
        ConstraintError::Immobile => "constraints".to_string(),
        ConstraintError::DependentFree { index } => keys
            .get(*index)
            .cloned()
            .unwrap_or_else(|| "constraints.free".into()),
        ConstraintError::DependentBlocked { index } => format!("constraints.blocked[{index}]"),
        ConstraintError::NotReciprocal { blocked, .. } => format!("constraints.blocked[{blocked}]"),
        ConstraintError::Dimension { .. } => "constraints.blocked".to_string(),
        ConstraintError::VelocityNotAllowed { .. } => "body.velocity".to_string(),
    };
    let message = match &e {
        ConstraintError::DependentFree { index }
            if keys.get(*index).is_some_and(|k| k.contains("joint")) =>
        {
            format!(
                "this joint's freedom is already given by the joints before it (free screw {index} is a combination of the earlier ones)"
            )
        }
        ConstraintError::NotReciprocal { free, .. } => {
            format!(
                "{e}; it is not reciprocal to {}",
                keys.get(*free).cloned().unwrap_or_default()
            )
        }
        ConstraintError::VelocityNotAllowed { .. } => {
            format!(
                "{e}; with body.angular_velocity, the twist [ω⁰; v_C⁰] must be a combination of the free screws"
            )
        }
        _ => e.to_string(),
    };
    RunError::Scene(SceneError {
        file: scene.file.clone(),
        value: scene.text_of(&key),
        key,
        message,
    })
}
