//! `inertance analyze`: the analysis of a scene as a table or JSON (keys documented in
//! guide/degenerate-cases.md).

use serde_json::{Map, Value as Json, json};

use crate::analysis::wrench_space::WrenchSpace;
use crate::analysis::{
    Analysis, Classification, analyze, analyze_reduced, condition_number, largest_eigenvalue,
};
use crate::impact::mechanism::Mechanism;
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::Impact;
use crate::mechanics::contact::Surd;
use crate::mechanics::screw::Screws;
use crate::report::{Value, Wide};
use crate::scalar::Scalar;
use crate::scene::Scene;
use crate::scene::limits::{friction_limit, too_many};
use crate::scene::pipeline::{RunError, prepare};

/// The readout of an analysis, scalar-free.
#[derive(Clone, Debug)]
pub struct AnalysisReport {
    /// The scene's name.
    pub scene: String,
    /// A system's bodies by name, in order (empty for one body): each twist below is then one
    /// [ω; v_C] per body.
    pub bodies: Vec<String>,
    /// `"f64"` or `"exact"`.
    pub scalar: &'static str,
    /// N.
    pub contacts: usize,
    /// Δ = det G (physical, unit normals).
    pub det: Value,
    /// rank G.
    pub rank: usize,
    /// cond₂(G) = λ_max/λ_min.
    pub condition_number: f64,
    /// The zero-pivot tolerance (floats).
    pub tolerance: Option<f64>,
    /// T⁰ = ½ {v⁰}ᵀ η M {v⁰}: the scale of both energies (ΔE_c = T⁰ − T is a difference).
    pub kinetic_energy_before: Value,
    /// Per model.
    pub models: Vec<ModelReport>,
    /// (equal, reason).
    pub newton_equals_poisson: Option<(bool, String)>,
    /// Coincident contact pairs (1-based in text), whether the axes coincide, and the
    /// single-impulse reduction (Newton, Poisson; `None` where constraints absorb the
    /// normal's impulse) — at most [`crate::analysis::MAX_COINCIDENT`] pairs.
    pub coincident: Vec<((usize, usize), bool, Option<[Value; 2]>)>,
    /// Whether more pairs may be coincident than are listed.
    pub coincident_truncated: bool,
    /// For a scene with friction (`mu`, `[solve] restitution`): each frictional contact's
    /// sticking threshold and the frictional integration of each law.
    pub friction: Option<FrictionAnalysis>,
}

/// One model's analysis, readable.
#[derive(Clone, Debug)]
pub struct ModelReport {
    /// The model.
    pub model: Model,
    /// rank [G | b].
    pub augmented_rank: usize,
    /// The classification.
    pub classification: Classification,
    /// The impulses: unique, or the family's least-norm member.
    pub impulses: Option<Vec<Value>>,
    /// The family's directions (impulse space), empty unless singular-compatible; empty too
    /// beyond [`DENSE_CONTACTS`], where only `nullity` is reported.
    pub family: Vec<Vec<Value>>,
    /// N − rank G: the dimension of the family (0 unless singular-compatible).
    pub nullity: usize,
    /// Whether the velocities after impact are the same across the family.
    pub twist_fixed: bool,
    /// (approaching, compressive, varies along the family).
    pub admissible: Vec<(bool, Option<bool>, bool)>,
    /// ΔE_c < 0.
    pub energy_gain: Option<bool>,
    /// The velocity after impact [ω; v_C] of the reported solution.
    pub twist: Option<Vec<Value>>,
    /// (E_p, ΔE_c) of the reported solution.
    pub energies: Option<[Value; 2]>,
    /// Plain-language verdicts.
    pub verdicts: Vec<String>,
    /// The unilateral law's answer beside the simultaneous one: `Err` says why there is none
    /// (a jammed body).
    pub unilateral: Result<UnilateralReport, String>,
}

/// The unilateral law's resolution of a model (see [`crate::impact::unilateral`]).
#[derive(Clone, Debug)]
pub struct UnilateralReport {
    /// Per contact: takes an impulse (true) or separates.
    pub active: Vec<bool>,
    /// P_i: a solution's impulses (one of a set when G is singular).
    pub impulses: Vec<Value>,
    /// v_ix after impact, per contact: unique.
    pub normal_velocities: Vec<Value>,
    /// [ω; v_C] after impact: unique.
    pub twist: Vec<Value>,
    /// (E_p, ΔE_c): unique.
    pub energies: [Value; 2],
    /// Whether the impulses are unique (see [`crate::impact::unilateral::Activity`]).
    pub impulses_unique: bool,
    /// Whether the law decides the velocities after impact (Poisson with a set of
    /// compression impulses and unequal k_i may not).
    pub outcome_decided: bool,
}

/// Up to this many contacts `analyze` works on the N×N matrix G ([`crate::analysis::analyze`]):
/// its report lists a basis of the family of solutions and the unilateral law's answer. Beyond
/// it the analysis runs in the space of the contact wrenches
/// ([`crate::analysis::wrench_space`], cost linear in N): the family is given by its dimension
/// (`null_space_dimension`; `null_space` is absent), Δ = 0 and cond₂ G = ∞ whenever N > rank G.
pub const DENSE_CONTACTS: usize = 24;

/// The most contacts `analyze` (as `solve`) takes in exact arithmetic
/// ([`crate::scene::limits`]).
pub use crate::scene::limits::MAX_EXACT_CONTACTS;

/// The most contacts `analyze` takes in floats: the analysis is linear in N (10⁵ contacts in
/// a fraction of a second); the limit bounds the report (a few hundred bytes per contact).
pub const MAX_FLOAT_CONTACTS: usize = 1_000_000;

/// The most contacts for which `analyze` reports the unilateral law (Lemke's method on the N×N
/// tableau of G, [`crate::impact::unilateral`]): beyond, the report says why it is missing.
pub fn max_unilateral_contacts<T: Scalar>() -> usize {
    crate::impact::unilateral::max_unilateral_contacts::<T>()
}

/// Analyse `scene` in the scalar type `T`.
///
/// # Errors
/// Besides the scene's own errors, a scene with more contacts than the type's limit
/// ([`MAX_EXACT_CONTACTS`], [`MAX_FLOAT_CONTACTS`]) is refused at once, naming the limit.
pub fn analyze_scene<T: Scalar>(
    scene: &Scene,
    models: Option<&[Model]>,
) -> Result<AnalysisReport, RunError> {
    let n = scene.contacts.len();
    let (limit, command, instead) = if T::IS_EXACT {
        (
            MAX_EXACT_CONTACTS,
            "analyze --exact",
            format!("; `analyze` without --exact takes up to {MAX_FLOAT_CONTACTS}"),
        )
    } else {
        (MAX_FLOAT_CONTACTS, "analyze", String::new())
    };
    if n > limit {
        return Err(RunError::Scene(too_many(
            scene,
            limit,
            &format!("`{command}`"),
            "its work is linear in N but the numbers and the report grow with it",
            &instead,
        )));
    }
    let models = models.unwrap_or(&scene.models);
    if scene.system.is_some() {
        return analyze_system::<T>(scene, models);
    }
    let problem = prepare::<T>(scene)?;
    let space = WrenchSpace::build(&problem)?;
    let finite = |x: &T| x.to_f64().is_finite();
    if !T::IS_EXACT
        && !(space.diagonal().iter().all(finite)
            && space.frames().iter().all(|f| f.norm2.iter().all(finite)))
    {
        // An axis or an inertance beyond f64 (a normal of length 10³⁰⁸: G was "not positive
        // semidefinite", or a verdict read "v_x⁰ = NaN"); `analyze` in floats is not scaled.
        return Err(RunError::Scene(crate::scene::scale::unrepresentable(
            scene,
            T::NAME,
            "",
        )));
    }
    if n <= DENSE_CONTACTS {
        let mut impact = Impact::assemble(&problem)?;
        let analysis: Analysis<T> = analyze(&mut impact, models);
        let (det, cond) = dense_det_cond(&mut impact);
        let norm2: Vec<T> = impact.frames().iter().map(|f| f.norm2[0].clone()).collect();
        let unilateral: Vec<Result<UnilateralReport, String>> = analysis
            .models
            .iter()
            .map(|m| unilateral_report(&mut impact, m.model, &norm2))
            .collect();
        let parts = Parts {
            before_x: impact.before_hat().iter().map(|v| v[0].clone()).collect(),
            norm2,
            kinetic_before: impact.kinetic_before().clone(),
            det,
            cond,
            unilateral,
        };
        return finish(scene, impact.problem(), analysis, parts)
            .map(|r| with_friction(r, scene, &problem));
    }
    let analysis = analyze_reduced(&space, models);
    let norm2: Vec<T> = space.frames().iter().map(|f| f.norm2[0].clone()).collect();
    let mut norms = T::one();
    for w in &norm2 {
        norms *= w;
    }
    let unilateral = if n <= max_unilateral_contacts::<T>() {
        let mut impact = Impact::assemble(&problem)?;
        analysis
            .models
            .iter()
            .map(|m| unilateral_report(&mut impact, m.model, &norm2))
            .collect()
    } else {
        let why = crate::impact::unilateral::UnilateralError::TooManyContacts {
            contacts: n,
            limit: max_unilateral_contacts::<T>(),
        }
        .to_string();
        vec![Err(why); analysis.models.len()]
    };
    let parts = Parts {
        before_x: space.before_hat().iter().map(|v| v[0].clone()).collect(),
        kinetic_before: space.kinetic_before().clone(),
        det: Value::of(&(space.det_hat() / &norms)),
        cond: space.condition_number(),
        norm2,
        unilateral,
    };
    finish(scene, space.problem(), analysis, parts).map(|r| with_friction(r, scene, &problem))
}

/// `report` with the frictional part of a one-body `scene` when it has friction.
fn with_friction<T: Scalar>(
    mut report: AnalysisReport,
    scene: &Scene,
    problem: &Problem<T>,
) -> AnalysisReport {
    report.friction = scene
        .frictional()
        .then(|| friction_analysis(scene, problem));
    report
}

/// A system of bodies ([`crate::mechanics::system`]): the N×N route for any N (a system's
/// contacts are few; its cost is in the bodies), with the frictional part as for one body.
fn analyze_system<T: Scalar>(scene: &Scene, models: &[Model]) -> Result<AnalysisReport, RunError> {
    let system = scene.system::<T>()?;
    let mut impact = Impact::assemble(&system)?;
    let analysis = analyze(&mut impact, models);
    let (det, cond) = dense_det_cond(&mut impact);
    let norm2: Vec<T> = impact.frames().iter().map(|f| f.norm2[0].clone()).collect();
    let unilateral: Vec<Result<UnilateralReport, String>> =
        if scene.contacts.len() <= max_unilateral_contacts::<T>() {
            analysis
                .models
                .iter()
                .map(|m| unilateral_report(&mut impact, m.model, &norm2))
                .collect()
        } else {
            let why = crate::impact::unilateral::UnilateralError::TooManyContacts {
                contacts: scene.contacts.len(),
                limit: max_unilateral_contacts::<T>(),
            }
            .to_string();
            vec![Err(why); analysis.models.len()]
        };
    let parts = Parts {
        before_x: impact.before_hat().iter().map(|v| v[0].clone()).collect(),
        norm2,
        kinetic_before: impact.kinetic_before().clone(),
        det,
        cond,
        unilateral,
    };
    let mut report = finish(scene, impact.problem(), analysis, parts)?;
    report.bodies = system_names(scene);
    report.friction = scene
        .frictional()
        .then(|| friction_analysis(scene, &system));
    Ok(report)
}

/// The body names of a system scene, in order.
fn system_names(scene: &Scene) -> Vec<String> {
    scene
        .system
        .as_ref()
        .map(|s| s.bodies.iter().map(|b| b.name.clone()).collect())
        .unwrap_or_default()
}

/// What the report needs besides the analysis, from either route.
struct Parts<T: Scalar> {
    /// v̂_ix⁰ per contact.
    before_x: Vec<T>,
    /// |x̂_i|² per contact.
    norm2: Vec<T>,
    kinetic_before: T,
    det: Value,
    cond: f64,
    unilateral: Vec<Result<UnilateralReport, String>>,
}

/// Δ and cond₂ G from the N×N matrix.
fn dense_det_cond<T: Scalar, M: Mechanism<T>>(impact: &mut Impact<T, M>) -> (Value, f64) {
    let n = impact.contacts();
    let norm2: Vec<T> = impact.frames().iter().map(|f| f.norm2[0].clone()).collect();
    let mut norms = T::one();
    for w in &norm2 {
        norms *= w;
    }
    let det = Value::of(&(impact.det_hat().clone() / &norms));
    // The physical G: g_ij / (|x̂_i||x̂_j|), in f64 for its eigenvalues.
    let g: Vec<f64> = (0..n * n)
        .map(|k| {
            Surd::over_norm(&impact.g_hat()[k], &(norm2[k / n].clone() * &norm2[k % n])).to_f64()
        })
        .collect();
    // cond₂ = λ_max(G)·λ_max(G⁻¹) for a symmetric positive definite G. In exact types G⁻¹ is
    // computed exactly and then rounded, so its eigenvalues are accurate even when G is far
    // too ill-conditioned for f64 eigenvalues of G itself to resolve λ_min.
    let cond = if T::IS_EXACT && impact.rank() == n && n > 0 {
        let mut inv = vec![0.0; n * n];
        for j in 0..n {
            let mut col: Vec<T> = (0..n)
                .map(|i| if i == j { T::one() } else { T::zero() })
                .collect();
            impact.solve_system(&mut col);
            for (i, x) in col.iter().enumerate() {
                // The physical inverse: S Ĝ⁻¹ S with S = diag(|x̂_i|).
                inv[i * n + j] = Surd::times_norm(x, &(norm2[i].clone() * &norm2[j])).to_f64();
            }
        }
        largest_eigenvalue(&g, n) * largest_eigenvalue(&inv, n)
    } else {
        condition_number(&g, n)
    };
    (det, cond)
}

/// The readable report of `analysis` of `scene` (assembled as `problem`).
fn finish<T: Scalar, M: Mechanism<T>>(
    scene: &Scene,
    problem: &M,
    analysis: Analysis<T, M::Screw>,
    parts: Parts<T>,
) -> Result<AnalysisReport, RunError> {
    let n = problem.contacts().len();
    let Parts {
        before_x,
        norm2,
        kinetic_before,
        det,
        cond,
        mut unilateral,
    } = parts;
    let impulse = |p: &T, i: usize| -> Value { Value::surd(&Surd::times_norm(p, &norm2[i])) };
    // The speeds of approach are written into the verdicts: a normal of length 10³⁰⁸ squares
    // beyond f64, and "v_4x⁰ = NaN" was printed (`analyze` in floats is not scaled).
    let held = |v: &Value| v.f64.is_finite() || v.exact.is_some();
    if (0..n).any(|i| !held(&Value::surd(&Surd::over_norm(&before_x[i], &norm2[i])))) {
        return Err(RunError::Scene(crate::scene::scale::unrepresentable(
            scene,
            T::NAME,
            "",
        )));
    }
    let model_reports = analysis
        .models
        .iter()
        .map(|m| {
            let impulses = m.outcome.as_ref().map(|o| o.impulses_hat.iter().enumerate().map(|(i, p)| impulse(p, i)).collect::<Vec<_>>());
            let admissible: Vec<(bool, Option<bool>, bool)> =
                m.admissible.iter().map(|a| (a.approaching, a.compressive, a.varies)).collect();
            let mut verdicts = Vec::new();
            match m.classification {
                Classification::Unique => {}
                Classification::SingularCompatible => verdicts.push(format!(
                    "Δ = 0 but the system is compatible: a {}-parameter family of impulses satisfies the law; {}",
                    m.nullity,
                    if m.twist_fixed {
                        "the velocities after impact and both energies are the same for every member — only the impulses are undetermined"
                    } else {
                        "the velocities after impact change along the family (Poisson with unequal k_i)"
                    }
                )),
                Classification::SingularIncompatible => verdicts.push(
                    "Δ = 0 and the system is incompatible: no impulses make every contact obey the law at once; the simultaneous-collision hypothesis cannot hold".into(),
                ),
            }
            for (i, (approaching, compressive, varies)) in admissible.iter().enumerate() {
                let v0 = Value::surd(&Surd::over_norm(&before_x[i], &norm2[i]));
                if !approaching {
                    verdicts.push(format!(
                        "contact A{} is not approaching (v_{}x⁰ = {} ≤ 0, eq. 74): on its own it would not collide, yet the simultaneous-collision hypothesis stops it",
                        i + 1,
                        i + 1,
                        v0.text()
                    ));
                }
                if *compressive == Some(false) {
                    let shown = impulses.as_ref().map(|v| v[i].text()).unwrap_or_default();
                    let zero = m.outcome.as_ref().is_some_and(|o| o.impulses_hat[i].signum_i8() == 0);
                    let family = if *varies { " (for the least-norm member of the family)" } else { "" };
                    verdicts.push(if zero {
                        format!(
                            "the impulse at A{} is zero (eq. 73){family}: this contact takes no part in the collision",
                            i + 1
                        )
                    } else {
                        format!(
                            "the impulse at A{} is tensile (P{} = {shown} < 0, eq. 73){family}: the obstacle would have to pull; the hypothesis that all contacts collide simultaneously fails here",
                            i + 1,
                            i + 1
                        )
                    });
                }
            }
            if m.energy_gain == Some(true) {
                verdicts.push("ΔE_c < 0: the collision would gain kinetic energy".into());
            }
            ModelReport {
                model: m.model,
                augmented_rank: m.augmented_rank,
                classification: m.classification,
                impulses,
                family: m.family.iter().map(|z| z.iter().enumerate().map(|(i, p)| impulse(p, i)).collect()).collect(),
                nullity: m.nullity,
                twist_fixed: m.twist_fixed,
                admissible,
                energy_gain: m.energy_gain,
                twist: m.outcome.as_ref().map(|o| o.velocity.components().iter().map(Value::of).collect()),
                energies: m.outcome.as_ref().map(|o| [Value::of(&o.lost_velocity_energy), Value::of(&o.kinetic_energy_loss)]),
                verdicts,
                unilateral: unilateral.remove(0),
            }
        })
        .collect();
    let coincident = analysis
        .coincident
        .iter()
        .map(|c| {
            let (i, _) = c.pair;
            (
                c.pair,
                c.same_axis,
                c.single_impulse
                    .as_ref()
                    .map(|p| [impulse(&p[0], i), impulse(&p[1], i)]),
            )
        })
        .collect();
    let mut report = AnalysisReport {
        scene: scene.name.clone(),
        bodies: Vec::new(),
        scalar: T::NAME,
        contacts: n,
        det,
        rank: analysis.rank,
        condition_number: cond,
        tolerance: analysis.tolerance,
        kinetic_energy_before: Value::of(&kinetic_before),
        models: model_reports,
        newton_equals_poisson: analysis.newton_equals_poisson,
        coincident,
        coincident_truncated: analysis.coincident_truncated,
        // Set by the caller for one body ([`friction_analysis`]).
        friction: None,
    };
    if !T::IS_EXACT && report.rank == n && !report.det.f64.is_normal() {
        // Δ ~ M⁻ᴺ left f64 in the scene's units (a body of 10⁻³⁰⁰ kg): from the scaled scene.
        if let Some(det) = scaled_det::<T>(scene) {
            report.det = det;
        }
    }
    if !report.finite() {
        // Never an ∞ or NaN where a number belongs: the scene spans more than T holds.
        return Err(RunError::Scene(crate::scene::scale::unrepresentable(
            scene,
            T::NAME,
            "",
        )));
    }
    Ok(report)
}

/// What `analyze` says about friction (see [`crate::impact::friction`]).
#[derive(Clone, Debug)]
pub struct FrictionAnalysis {
    /// Per contact (`None` without friction, or a spatial scene in an exact type): μ̄_i, the
    /// coefficient from which a slip of this contact alone that comes to rest sticks
    /// (|τ'| ≤ μ p' with τ' = −G_tt⁻¹ G_tx p': μ̄ = |G_tt⁻¹ G_tx|; Keller's threshold, the
    /// rod's μ̄ = 3 sin θ cos θ / (1 + 3 sin² θ) in derivations/friction-rod.md). Below it
    /// such a slip reverses instead.
    pub stick_thresholds: Vec<Option<Value>>,
    /// The frictional readouts, one per law, as `solve` gives them (one body).
    pub readouts: Vec<crate::report::FrictionReport>,
    /// A system's frictional readouts, one per law: its name, JSON and text, as `solve`
    /// gives them.
    pub system_readouts: Vec<(String, Json, String)>,
    /// Laws without an answer, and why; or why no integration ran (an exact type on a
    /// spatial scene).
    pub failures: Vec<String>,
}

/// The friction part of the analysis of `scene` in `T`.
fn friction_analysis<T: Scalar, M: Mechanism<T>>(scene: &Scene, problem: &M) -> FrictionAnalysis {
    use crate::impact::friction::Blocks;
    if let Some(refusal) = friction_limit(scene) {
        // The thresholds and the integration both work on the 3N×3N blocks.
        return FrictionAnalysis {
            stick_thresholds: vec![None; problem.contacts().len()],
            readouts: Vec::new(),
            system_readouts: Vec::new(),
            failures: vec![refusal.to_string()],
        };
    }
    let planar = Blocks::planar(problem);
    let spatial = if planar.is_none() && !T::IS_EXACT {
        let frames: Option<Vec<_>> = (0..problem.contacts().len())
            .map(|i| problem.frame(i, true).ok())
            .collect();
        frames.map(|f| Blocks::spatial(problem, &f))
    } else {
        None
    };
    let stick_thresholds = match planar.as_ref().or(spatial.as_ref()) {
        None => vec![None; problem.contacts().len()],
        Some(b) => (0..b.contacts())
            .map(|i| {
                let o = b.offset[i];
                match b.dims[i] {
                    0 => None,
                    // A body that cannot move along the tangent (a constraint) has
                    // g_tt = 0: no slip, no threshold.
                    1 if b.at(o + 1, o + 1).is_zero() => None,
                    1 => {
                        let r = b.at(o + 1, o).clone() / b.at(o + 1, o + 1).clone();
                        Some(Value::of(&if r.signum_i8() < 0 { -r } else { r }))
                    }
                    _ => {
                        // |G_tt⁻¹ G_tx| with the 2×2 tangential block.
                        let (a, bb, c, d) = (
                            b.at(o + 1, o + 1).to_f64(),
                            b.at(o + 1, o + 2).to_f64(),
                            b.at(o + 2, o + 1).to_f64(),
                            b.at(o + 2, o + 2).to_f64(),
                        );
                        let (x, y) = (b.at(o + 1, o).to_f64(), b.at(o + 2, o).to_f64());
                        let det = a * d - bb * c;
                        let (u, w) = ((d * x - bb * y) / det, (a * y - c * x) / det);
                        // A singular tangential block (a constrained body): no threshold.
                        let t = u.hypot(w);
                        t.is_finite().then(|| Value::float(t))
                    }
                }
            })
            .collect(),
    };
    let (mut readouts, mut system_readouts) = (Vec::new(), Vec::new());
    let laws =
        |f: Vec<(crate::impact::friction::Restitution, String, &'static str)>| -> Vec<String> {
            f.into_iter()
                .map(|(law, m, _)| format!("{law}: {m}"))
                .collect()
        };
    let failures = if let Some(spec) = &scene.system {
        match crate::scene::system_pipeline::run_system::<T>(scene, None) {
            Ok(s) => {
                let bodies: Vec<String> = spec.bodies.iter().map(|b| b.name.clone()).collect();
                let free = s.report.free;
                system_readouts = (s.report.friction.iter())
                    .map(|f| {
                        (
                            f.law.name().to_string(),
                            f.to_json(&bodies),
                            f.to_text(&bodies, free),
                        )
                    })
                    .collect();
                laws(s.report.friction_failures)
            }
            Err(e) => vec![e.to_string()],
        }
    } else {
        match crate::scene::pipeline::run_with::<T>(scene, None, true) {
            Ok(s) => {
                readouts = s.report.friction;
                laws(s.report.friction_failures)
            }
            Err(e) => vec![e.to_string()],
        }
    };
    FrictionAnalysis {
        stick_thresholds,
        readouts,
        system_readouts,
        failures,
    }
}

/// Δ = det G of a float solve in the units [`crate::scene::scale`] picks, scaled back by
/// 2^(−aN) and held beyond f64 as a [`Wide`]; `None` when the scene is not scaled or the scaled
/// one does not assemble.
fn scaled_det<T: Scalar>(scene: &Scene) -> Option<Value> {
    let (scaled, units) = crate::scene::scale::scale(scene)?;
    let impact = Impact::assemble(&prepare::<T>(&scaled).ok()?).ok()?;
    let mut norms = T::one();
    for f in impact.frames() {
        norms *= &f.norm2[0];
    }
    let det = (impact.det_hat().clone() / &norms).to_f64();
    let k = -units.mass * impact.contacts() as i64;
    Some(Value {
        wide: Wide::of(det, k),
        ..Value::float(crate::scene::scale::ldexp(det, k))
    })
}

impl AnalysisReport {
    /// Whether every reported number is finite (the condition number may be ∞: G singular);
    /// Δ beyond f64 counts when held as a [`Wide`], and an exact value by its text (a sphere
    /// spinning at 10³⁰⁸ rad/s has T⁰ = 2·10⁶¹⁵ J, which `analyze --exact` refused as beyond
    /// what "exact can hold").
    fn finite(&self) -> bool {
        let ok = |v: &Value| v.f64.is_finite() || v.exact.is_some();
        let all = |v: &[Value]| v.iter().all(ok);
        (ok(&self.det) || self.det.wide.is_some())
            && ok(&self.kinetic_energy_before)
            && self.tolerance.is_none_or(f64::is_finite)
            && self.models.iter().all(|m| {
                m.impulses.as_deref().is_none_or(all)
                    && m.family.iter().all(|z| all(z))
                    && m.twist.as_deref().is_none_or(all)
                    && m.energies.as_ref().is_none_or(|e| all(e))
                    && m.unilateral.as_ref().map_or(true, |u| {
                        all(&u.impulses)
                            && all(&u.normal_velocities)
                            && all(&u.twist)
                            && all(&u.energies)
                    })
            })
    }
}

/// The unilateral law on the assembled `impact` for `model`, read out in the paper's units.
fn unilateral_report<T: Scalar, M: Mechanism<T>>(
    impact: &mut Impact<T, M>,
    model: Model,
    norm2: &[T],
) -> Result<UnilateralReport, String> {
    let mut out = crate::impact::solve::Outcome::default();
    let activity = impact
        .solve_unilateral(model, &mut out)
        .map_err(|e| e.to_string())?;
    Ok(UnilateralReport {
        active: crate::impact::unilateral::active(&out),
        impulses: out
            .impulses_hat
            .iter()
            .zip(norm2)
            .map(|(p, w)| Value::surd(&Surd::times_norm(p, w)))
            .collect(),
        normal_velocities: out
            .after_hat
            .iter()
            .zip(norm2)
            .map(|(v, w)| Value::surd(&Surd::over_norm(&v[0], w)))
            .collect(),
        twist: out.velocity.components().iter().map(Value::of).collect(),
        energies: [
            Value::of(&out.lost_velocity_energy),
            Value::of(&out.kinetic_energy_loss),
        ],
        impulses_unique: activity.impulses_unique,
        outcome_decided: activity.outcome_decided,
    })
}

/// `[ω; v_C]` as text: `ω = (…), v_C = (…)`.
fn body_twist_text(t: &[Value]) -> String {
    let part =
        |r: std::ops::Range<usize>| t[r].iter().map(Value::text).collect::<Vec<_>>().join(", ");
    format!("ω = ({}), v_C = ({})", part(0..3), part(3..6))
}

fn json_f64(x: f64) -> Json {
    // JSON has no infinity: an infinite condition number is written as the string "inf".
    serde_json::Number::from_f64(x)
        .map(Json::Number)
        .unwrap_or_else(|| Json::String("inf".into()))
}

impl AnalysisReport {
    /// A twist after impact as text: `ω = (…), v_C = (…)` for one body; for a system, each
    /// body's by name.
    fn twist_text(&self, t: &[Value]) -> String {
        if self.bodies.is_empty() {
            return body_twist_text(t);
        }
        self.bodies
            .iter()
            .zip(t.chunks(6))
            .map(|(name, t)| format!("\n    {name}: {}", body_twist_text(t)))
            .collect()
    }

    /// A twist after impact as JSON: the six numbers [ω; v_C] for one body; for a system, per
    /// body `{name, angular_velocity, velocity}`.
    fn twist_json(&self, t: &[Value]) -> Json {
        let vec = |v: &[Value]| Json::Array(v.iter().map(Value::json).collect());
        if self.bodies.is_empty() {
            return vec(t);
        }
        Json::Array(
            self.bodies
                .iter()
                .zip(t.chunks(6))
                .map(|(name, t)| {
                    json!({"name": name, "angular_velocity": vec(&t[..3]), "velocity": vec(&t[3..])})
                })
                .collect(),
        )
    }

    /// The JSON report.
    pub fn to_json(&self) -> Json {
        let vec = |v: &[Value]| Json::Array(v.iter().map(Value::json).collect());
        let mut models = Map::new();
        for m in &self.models {
            let mut o = Map::new();
            o.insert("det".into(), self.det.json());
            o.insert("rank".into(), json!(self.rank));
            o.insert("augmented_rank".into(), json!(m.augmented_rank));
            o.insert("classification".into(), json!(m.classification.name()));
            o.insert(
                "admissible".into(),
                Json::Array(m.admissible.iter().map(|(a, c, v)| json!({"approaching": a, "compressive": c, "varies_along_family": v})).collect()),
            );
            o.insert("energy_gain".into(), json!(m.energy_gain));
            o.insert(
                "impulses".into(),
                m.impulses.as_ref().map_or(Json::Null, |p| vec(p)),
            );
            if m.classification == Classification::SingularCompatible {
                let mut family = json!({
                    "particular": m.impulses.as_ref().map(|p| vec(p)),
                    "null_space_dimension": m.nullity,
                    "velocities_fixed": m.twist_fixed,
                    "energies_fixed": m.twist_fixed,
                    "impulses_fixed": m.admissible.iter().map(|a| !a.2).collect::<Vec<_>>(),
                });
                // The basis, when materialised (up to DENSE_CONTACTS): absent beyond.
                if let (Some(f), true) = (family.as_object_mut(), m.family.len() == m.nullity) {
                    f.insert(
                        "null_space".into(),
                        Json::Array(m.family.iter().map(|z| vec(z)).collect()),
                    );
                }
                o.insert("family".into(), family);
            }
            o.insert(
                "twist_after".into(),
                m.twist.as_ref().map_or(Json::Null, |t| self.twist_json(t)),
            );
            if let Some([ep, de]) = &m.energies {
                o.insert("lost_velocity_energy".into(), Value::json(ep));
                o.insert("kinetic_energy_loss".into(), Value::json(de));
            }
            o.insert("verdicts".into(), json!(m.verdicts));
            o.insert(
                "unilateral".into(),
                match &m.unilateral {
                    Err(why) => json!({ "solved": false, "reason": why }),
                    Ok(u) => json!({
                        "solved": true,
                        "active": u.active,
                        "impulses": vec(&u.impulses),
                        "impulses_unique": u.impulses_unique,
                        "outcome_decided": u.outcome_decided,
                        "normal_velocities_after": vec(&u.normal_velocities),
                        "twist_after": self.twist_json(&u.twist),
                        "lost_velocity_energy": u.energies[0].json(),
                        "kinetic_energy_loss": u.energies[1].json(),
                    }),
                },
            );
            models.insert(m.model.name().into(), Json::Object(o));
        }
        let mut top = json!({
            "scene": self.scene,
            "scalar": self.scalar,
            "contacts": self.contacts,
            "det": self.det.json(),
            "rank": self.rank,
            "condition_number": json_f64(self.condition_number),
            "kinetic_energy_before": self.kinetic_energy_before.json(),
            "models": Json::Object(models),
            "coincident": self.coincident.iter().map(|((i, j), same, single)| json!({
                "contacts": [i + 1, j + 1],
                "same_axis": same,
                "single_impulse": single.as_ref().map(|p| json!({"newton": p[0].json(), "poisson": p[1].json()})),
            })).collect::<Vec<_>>(),
            "coincident_truncated": self.coincident_truncated,
        });
        if let Some(obj) = top.as_object_mut() {
            if !self.bodies.is_empty() {
                obj.insert("bodies".into(), json!(self.bodies));
            }
            if let Some((equal, reason)) = &self.newton_equals_poisson {
                obj.insert(
                    "newton_equals_poisson".into(),
                    json!({"equal": equal, "reason": reason}),
                );
            }
            if let Some(f) = &self.friction {
                obj.insert(
                    "friction".into(),
                    json!({
                        "stick_thresholds": f.stick_thresholds.iter().map(|t| t.as_ref().map(Value::json)).collect::<Vec<_>>(),
                        "laws": f.readouts.iter().map(|r| (r.law.name().to_string(), r.to_json()))
                            .chain(f.system_readouts.iter().map(|(law, j, _)| (law.clone(), j.clone())))
                            .collect::<Map<_, _>>(),
                        "failures": f.failures,
                    }),
                );
            }
            if let Some(t) = self.tolerance {
                obj.insert("rank_tolerance".into(), json_f64(t));
                obj.insert(
                    "forward_error_estimate".into(),
                    json_f64(self.condition_number * f64::EPSILON * self.contacts as f64),
                );
            }
        }
        top
    }

    /// The readable report.
    pub fn to_text(&self) -> String {
        let mut s = format!("{} — analysis in {}\n\n", self.scene, self.scalar);
        s += &format!(
            "Δ = det G = {}, rank G = {} of {}",
            self.det.text(),
            self.rank,
            self.contacts
        );
        match self.tolerance {
            Some(t) => s += &format!(" (pivots ≤ N·ε·max g_ii = {t:.3e} count as zero)\n"),
            None => s += " (decided exactly)\n",
        }
        let c = self.condition_number;
        s += &format!(
            "cond₂(G) = {}",
            if !c.is_finite() {
                "∞".into()
            } else if c < 1e6 {
                format!("{c:.6}")
            } else {
                format!("{c:.3e}")
            }
        );
        if self.tolerance.is_some() && self.condition_number.is_finite() {
            s += &format!(
                ", forward error of the impulses ≲ cond·N·ε = {:.1e} (relative)",
                self.condition_number * f64::EPSILON * self.contacts as f64
            );
        }
        s += "\n";
        for ((i, j), same, single) in &self.coincident {
            let reduction = match single {
                Some(p) => format!(
                    "single-impulse reduction (eq. 69–72): P = {} (Newton), {} (Poisson)",
                    p[0].text(),
                    p[1].text()
                ),
                None => format!(
                    "no single-impulse reduction: the constraints absorb any impulse along n{} (g{}{} = 0)",
                    i + 1,
                    i + 1,
                    i + 1
                ),
            };
            s += &format!(
                "A{} ≡ A{}: coincident points{} — {reduction}\n",
                i + 1,
                j + 1,
                if *same {
                    " with the same normal ({E_ix} = {E_jx}, so Δ = 0)"
                } else {
                    " with different normals"
                },
            );
        }
        if self.coincident_truncated {
            s += &format!(
                "… more coincident pairs than listed (at most {} are, of at most {} candidates)\n",
                crate::analysis::MAX_COINCIDENT,
                crate::analysis::MAX_COINCIDENT_CANDIDATES
            );
        }
        for m in &self.models {
            s += &format!(
                "\n{}: {} (rank [G | b] = {})\n",
                m.model,
                m.classification.name(),
                m.augmented_rank
            );
            if let Some(p) = &m.impulses {
                let label = if m.classification == Classification::Unique {
                    "impulses"
                } else {
                    "least-norm impulses"
                };
                s += &format!(
                    "  {label}: {}\n",
                    p.iter().map(Value::text).collect::<Vec<_>>().join(", ")
                );
            }
            for z in &m.family {
                s += &format!(
                    "  + t · ({})\n",
                    z.iter().map(Value::text).collect::<Vec<_>>().join(", ")
                );
            }
            if m.family.len() < m.nullity {
                s += &format!(
                    "  + a {}-parameter family (its basis is listed up to {DENSE_CONTACTS} contacts)\n",
                    m.nullity
                );
            }
            if let (Some(t), false) = (&m.twist, m.nullity == 0) {
                if m.twist_fixed {
                    s += &format!(
                        "  velocities after impact (the same for the whole family): {}\n",
                        self.twist_text(t)
                    );
                } else {
                    s += &format!(
                        "  velocities after impact (least-norm member; they vary): {}\n",
                        self.twist_text(t)
                    );
                }
            }
            if let Some([ep, de]) = &m.energies {
                s += &format!(
                    "  E_p = {}, ΔE_c = {}{}\n",
                    ep.text(),
                    de.text(),
                    if m.nullity == 0 || !m.twist_fixed {
                        ""
                    } else {
                        " (the same for the whole family)"
                    }
                );
            }
            for (i, (a, c, v)) in m.admissible.iter().enumerate() {
                s += &format!(
                    "  A{}: {}, impulse {}{}\n",
                    i + 1,
                    if *a { "approaching" } else { "NOT approaching" },
                    match c {
                        Some(true) => "compressive",
                        Some(false) => "NOT compressive",
                        None => "—",
                    },
                    if *v { " (varies along the family)" } else { "" }
                );
            }
            for v in &m.verdicts {
                s += &format!("  ! {v}\n");
            }
            s += &format!(
                "  unilateral {} (complementarity, `--law unilateral`):\n",
                m.model
            );
            match &m.unilateral {
                Err(why) => s += &format!("    {why}\n"),
                Ok(u) => {
                    for (i, a) in u.active.iter().enumerate() {
                        s += &format!(
                            "    A{}: {}, P{} = {}, v{}x = {}\n",
                            i + 1,
                            if *a { "active" } else { "separates" },
                            i + 1,
                            u.impulses[i].text(),
                            i + 1,
                            u.normal_velocities[i].text()
                        );
                    }
                    s += &format!(
                        "    velocities after impact: {}\n",
                        self.twist_text(&u.twist)
                    );
                    s += &format!(
                        "    E_p = {}, ΔE_c = {}\n",
                        u.energies[0].text(),
                        u.energies[1].text()
                    );
                    if !u.outcome_decided {
                        s += "    the law does not decide the outcome: the compression impulses form a set and the k_i differ, so the velocities after impact depend on which are taken; these are one possibility\n";
                    } else if !u.impulses_unique {
                        s += "    these velocities after impact are unique; the impulses may be one of a set\n";
                    }
                }
            }
        }
        if let Some((equal, reason)) = &self.newton_equals_poisson {
            s += &format!(
                "\nNewton {} Poisson: {reason}\n",
                if *equal { "=" } else { "≠" }
            );
        }
        if let Some(f) = &self.friction {
            s += "\nFriction (the analysis above is of the frictionless system):\n";
            for (i, t) in f.stick_thresholds.iter().enumerate() {
                if let Some(t) = t {
                    s += &format!(
                        "  A{}: a slip of this contact alone that comes to rest sticks iff μ ≥ μ̄ = {} (else it reverses)\n",
                        i + 1,
                        t.text()
                    );
                }
            }
            for r in &f.readouts {
                s += &r.to_text();
            }
            for (_, _, text) in &f.system_readouts {
                s += text;
            }
            for m in &f.failures {
                s += &format!("  no answer: {m}\n");
            }
        }
        // A system's twist starts on the next line: no space before it.
        s.replace(": \n", ":\n")
    }
}
