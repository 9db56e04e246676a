//! From a scene of several bodies to its report: the system's impact under the scene's law
//! (simultaneous or unilateral), each restitution model asked for, and the checks every
//! solve runs — the energy identity (eq. 34) and, for a free system, the conservation of
//! momentum (both exact in exact types).
//!
//! A frictional scene (some μ_i > 0, or `[solve] restitution`) is integrated in impulse space
//! by [`crate::impact::friction`], as one body's is, each restitution law asked for: exactly,
//! event by event, when the system stays in a plane; adaptively in floats otherwise. Its checks
//! are the energy balance ΔE_c = Σ∫v·dΛ = T⁰ − T and, for a free system, the momentum.
//!
//! **Floats.** As one body's ([`super::pipeline::run_with`]), a float solve of a system runs in
//! units of mass, length and time that are powers of two chosen from all its bodies' numbers
//! ([`crate::scene::scale::system`]): every input scaled exactly, every output scaled back by
//! its dimension — each body's twist and kinetic energy, the impulses, the energies, the joints'
//! reactions (a force M·L/T and a moment M·L²/T at the anchor), the momentum, G and Δ (held
//! wide where f64 cannot hold them). A system in grams and millimetres, or an astronomical one,
//! is then solved as well as one in SI units: the scaling is exact and the laws are invariant
//! under it, so a scene rewritten in units that differ by powers of two gives the same answers,
//! bit for bit. A physical output that lost its precision in the scaled units, or that f64
//! cannot hold once scaled back, is refused, naming it and the input farthest from 1 — never
//! printed as NaN or ∞. The frictional path is scaled the same way; the exact path is not (it is
//! exact). How accurate the float answers are is stated per output by
//! [`crate::analysis::accuracy`] (its systems paragraph).

use crate::impact::admissibility::{energy_gain, verdicts};
use crate::impact::friction::solve_frictional_under;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::impact::unilateral::{Law, UnilateralError, active};
use crate::mechanics::system::{System, SystemScrew};
use crate::report::system::SystemReport;
use crate::report::system_friction::SystemFrictionReport;
use crate::scalar::Scalar;

use super::pipeline::{RunError, friction_tolerance};
use super::scale::system::{
    scale_system, system_out_of_range, system_precision_lost, unscale_system,
};
use super::scale::{Units, output_below, output_beyond, unrepresentable};
use super::{OUT_OF_RANGE, Scene};

/// A solved system scene: its report, and per model whether the energy identity held and,
/// for a free system, whether the momentum was conserved (exactly in exact types, to
/// rounding in floats).
#[derive(Clone, Debug)]
pub struct SolvedSystem {
    /// The readout.
    pub report: SystemReport,
    /// Per model, in report order: ΔE_c = −E_p + Σ P_i v_ix⁰ (eq. 34).
    pub energy_identity: Vec<bool>,
    /// Per model: momentum after equals momentum before (a free system; `true` otherwise).
    pub momentum_conserved: Vec<bool>,
    /// Per frictional law, in report order: the energy balance ΔE_c = Σ∫v·dΛ = T⁰ − T
    /// (exactly in exact types; to the integration's estimate in a spatial one).
    pub friction_energy_balance: Vec<bool>,
    /// Per frictional law: momentum conserved (a free system; `true` otherwise).
    pub friction_momentum_conserved: Vec<bool>,
}

/// Solve the system scene `scene` in `T` for `models` (the scene's own when `None`).
///
/// # Errors
/// A [`RunError`]: the scene (friction, a number `T` cannot hold, an invalid body or joint),
/// a singular G under the simultaneous law, a jam under the unilateral law when no model
/// answers.
pub fn run_system<T: Scalar>(
    scene: &Scene,
    models: Option<&[Model]>,
) -> Result<SolvedSystem, RunError> {
    if T::IS_EXACT {
        return run_as_written::<T>(scene, models);
    }
    let input_out_of_range =
        |e: &RunError| matches!(e, RunError::Scene(s) if s.message.ends_with(OUT_OF_RANGE));
    let unrepresentable = || RunError::Scene(unrepresentable(scene, T::NAME, SCALED));
    let Some((scaled, units)) = scale_system(scene) else {
        let mut solved = match run_as_written::<T>(scene, models) {
            Err(e) if input_out_of_range(&e) => return Err(unrepresentable()),
            solved => solved?,
        };
        finish_float::<T>(scene, &mut solved.report, None)?;
        return Ok(solved);
    };
    let mut solved = match run_as_written::<T>(&scaled, models) {
        Ok(solved) => solved,
        Err(e) if input_out_of_range(&e) => return Err(unrepresentable()),
        // Another refusal names the values as written: the scene's own error.
        Err(RunError::Scene(e)) => {
            run_as_written::<T>(scene, models)?;
            return Err(RunError::Scene(e));
        }
        Err(e) => return Err(e),
    };
    finish_float::<T>(scene, &mut solved.report, Some(&units))?;
    Ok(solved)
}

/// How a float solve in units scaled to the scene was tried, for refusals.
const SCALED: &str = ", even in units of mass, length and time scaled to the scene";

/// A float report refused when a physical output lost its precision in the units it was solved
/// in, else scaled back (`units`, when it was solved in scaled ones) and refused when a
/// physical output is beyond `T` in the scene's units — naming the output
/// ([`crate::scene::scale::system`]).
fn finish_float<T: Scalar>(
    scene: &Scene,
    report: &mut SystemReport,
    units: Option<&Units>,
) -> Result<(), RunError> {
    if let Some(output) = system_precision_lost(report) {
        return Err(RunError::Scene(output_below(
            scene,
            T::NAME,
            output,
            SCALED,
        )));
    }
    if let Some(units) = units {
        unscale_system(report, units);
    }
    match system_out_of_range(report) {
        Some(output) => Err(RunError::Scene(output_beyond(
            scene,
            T::NAME,
            output,
            SCALED,
        ))),
        None => Ok(()),
    }
}

/// Solve the system scene `scene` in `T` in its own units (module docs).
fn run_as_written<T: Scalar>(
    scene: &Scene,
    models: Option<&[Model]>,
) -> Result<SolvedSystem, RunError> {
    scene.law_applies()?;
    if scene.frictional() {
        return run_frictional::<T>(scene, models);
    }
    let system = scene.system::<T>()?;
    let mut impact = Impact::assemble(&system)?;
    let models = models.unwrap_or(&scene.models);
    let mut outcomes = Vec::with_capacity(models.len());
    let mut inadmissible = Vec::with_capacity(models.len());
    let mut activities = Vec::with_capacity(models.len());
    let mut failures = Vec::new();
    let mut first_failure = None;
    for &m in models {
        let mut out: Outcome<T, SystemScrew<T>> = Outcome::default();
        match scene.law {
            Law::Simultaneous => {
                impact.solve(m, &mut out)?;
                inadmissible.push(verdicts(&impact, m, &out));
                activities.push(None);
            }
            Law::Unilateral => match impact.solve_unilateral(m, &mut out) {
                Ok(a) => {
                    inadmissible.push(energy_gain(&impact, &out).into_iter().collect());
                    activities.push(Some(a));
                }
                Err(e @ UnilateralError::Jammed { .. }) => {
                    failures.push((m, e.to_string(), "jammed"));
                    first_failure.get_or_insert(e);
                    continue;
                }
                Err(e) => return Err(e.into()),
            },
            Law::Lzb => {
                return Err(crate::impact::multiple::LzbError::Unsupported {
                    what: "a system solve by restitution model",
                }
                .into());
            }
        }
        outcomes.push((m, out));
    }
    if let (true, Some(e)) = (outcomes.is_empty(), first_failure) {
        return Err(e.into());
    }
    let names = body_names(scene);
    let mut effects = Vec::new();
    if !system.joints().is_empty() {
        effects.push("joints".to_string());
    }
    if scene.law == Law::Unilateral {
        effects.push("unilateral".to_string());
    }
    effects.extend(outcomes.iter().map(|(m, _)| m.name().to_string()));
    let mut report = SystemReport::new(&scene.name, effects, &names, &impact, &outcomes);
    report.obstacles = obstacle_names(scene);
    for ((r, (_, out)), (bad, activity)) in report
        .models
        .iter_mut()
        .zip(&outcomes)
        .zip(inadmissible.into_iter().zip(activities))
    {
        r.law = scene.law;
        r.inadmissible = bad;
        if activity.is_some() {
            r.active = active(out);
        }
        r.activity = activity;
    }
    report.model_failures = failures;
    let energy_identity = outcomes
        .iter()
        .map(|(_, out)| {
            let work = impact.impulse_work(out);
            let sum = out.kinetic_energy_loss.clone() + &out.lost_velocity_energy;
            let scale = impact.kinetic_before().clone() + &out.lost_velocity_energy;
            (sum - work).is_negligible(&scale, 16 * impact.contacts().max(1))
        })
        .collect();
    let momentum_conserved = outcomes
        .iter()
        .map(|(_, out)| !report.free || conserved(&system, system.velocity(), &out.velocity))
        .collect();
    Ok(SolvedSystem {
        report,
        energy_identity,
        momentum_conserved,
        friction_energy_balance: Vec::new(),
        friction_momentum_conserved: Vec::new(),
    })
}

/// The bodies' names, in order.
/// Per contact, the obstacle it touches, as the report names it ([`SystemSpec::obstacles`]).
///
/// [`SystemSpec::obstacles`]: crate::scene::model::system::SystemSpec::obstacles
pub(crate) fn obstacle_names(scene: &Scene) -> Vec<Option<String>> {
    scene
        .system
        .as_ref()
        .map(|s| s.obstacles.clone())
        .unwrap_or_default()
}

pub(crate) fn body_names(scene: &Scene) -> Vec<String> {
    scene
        .system
        .as_ref()
        .map(|s| s.bodies.iter().map(|b| b.name.clone()).collect())
        .unwrap_or_default()
}

/// A frictional system scene: each restitution law integrated in impulse space (module docs);
/// the report holds the model-independent part (G, the frames, the velocities before) and one
/// frictional readout per law.
fn run_frictional<T: Scalar>(
    scene: &Scene,
    models: Option<&[Model]>,
) -> Result<SolvedSystem, RunError> {
    let system = scene.system::<T>()?;
    let impact = Impact::assemble(&system)?;
    let laws = scene.restitutions(models);
    let mut effects = Vec::new();
    if !system.joints().is_empty() {
        effects.push("joints".to_string());
    }
    if scene.law == Law::Unilateral {
        effects.push("unilateral".to_string());
    }
    effects.push("friction".to_string());
    effects.extend(laws.iter().map(|l| l.name().to_string()));
    let mut report = SystemReport::new(&scene.name, effects, &body_names(scene), &impact, &[]);
    report.obstacles = obstacle_names(scene);
    let kinetic = system.kinetic_energy(system.velocity());
    let tolerance = scene.tolerance.unwrap_or_else(friction_tolerance::<T>);
    let mut balance = Vec::new();
    let mut momentum = Vec::new();
    let mut first_failure = None;
    for law in laws {
        let f = match solve_frictional_under(&system, law, scene.hypothesis(), tolerance) {
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
        balance.push(f.energy_balance_holds(&kinetic));
        momentum.push(!report.free || conserved(&system, system.velocity(), &f.velocity));
        report.friction.push(SystemFrictionReport::new(&system, &f));
    }
    if let (true, Some(e)) = (report.friction.is_empty(), first_failure) {
        return Err(e.into());
    }
    Ok(SolvedSystem {
        report,
        energy_identity: Vec::new(),
        momentum_conserved: Vec::new(),
        friction_energy_balance: balance,
        friction_momentum_conserved: momentum,
    })
}

/// Linear and angular momentum equal before and after: exactly in exact types, to 64 N ε of
/// the largest body momentum in floats.
fn conserved<T: Scalar>(
    system: &System<T>,
    before: &SystemScrew<T>,
    after: &SystemScrew<T>,
) -> bool {
    let (p0, l0) = system.momentum(before);
    let (p1, l1) = system.momentum(after);
    let mut scale = T::zero();
    for x in p0.iter().chain(&l0).chain(&p1).chain(&l1) {
        if x.abs_gt(&scale) {
            scale = if x.signum_i8() < 0 {
                -x.clone()
            } else {
                x.clone()
            };
        }
    }
    let n = 64 * system.bodies().len();
    (0..3).all(|k| {
        (p1[k].clone() - &p0[k]).is_negligible(&scale, n)
            && (l1[k].clone() - &l0[k]).is_negligible(&scale, n)
    })
}
