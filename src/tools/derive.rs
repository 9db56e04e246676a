//! `inertance derive`: the unchanged solver run over the symbolic scalar, so that it derives
//! the closed forms of a scene whose values name symbols.
//!
//! A scene value may be an expression in declared symbols (`mass = "m"`,
//! `point = [0, "-a", 0]`, `k = "k1"`, `normal = ["cos(theta)", "sin(theta)", 0]`). The
//! pipeline of `solve` runs in [`RatFun`] — frames, inertances g_ij (eq. 12), Δ = det G, the
//! Newton and Poisson impulses (eq. 15, 21–23), the twist after impact (eq. 24), the contact
//! velocities (eq. 13, 25, 26), E_p (eq. 28), ΔE_c (eq. 32) and, for a constrained body, q
//! (eq. 90–93) — every operation exact, every zero test a proof. What comes out:
//!
//! * every quantity as a rational function of the symbols (common content, monomials and
//!   the factors elimination reintroduces cancelled; see [`crate::scalar::symbolic::ratfun`]);
//! * **the conditions** under which the formulas hold: each division by an expression with
//!   symbols records that it is ≠ 0 (among them Δ ≠ 0 through the pivots), each sign the
//!   solver took records > 0 ([`crate::scalar::symbolic::Assumption`]);
//! * **the degenerate locus**: Δ as a factored polynomial — where it vanishes the collision
//!   is singular (§8);
//! * the energy identity ΔE_c = −E_p + Σ P_i v_ix⁰ (eq. 34) decided as an identity;
//! * **for a singular family** (Δ ≡ 0 for every value of the symbols: rank G < N
//!   identically), instead of impulses: for each model the compatibility conditions
//!   z_kᵀ b = 0 (one per null vector z_k of the symmetric G; Rouché–Capelli, eq. 61–68 and
//!   98–102) in factored form, and, where they hold identically, the family of solutions —
//!   the particular one with its last pivoted entries zero, plus the null directions.

use serde_json::{Value as Json, json};

use crate::impact::mechanism::Mechanism;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::mechanics::screw::Screws;
use crate::report::system::SystemReport;
use crate::report::{Report, Value, WrenchReport};
use crate::scalar::Scalar;
use crate::scalar::symbolic::{
    Assumption, AssumptionKind, Factored, RatFun, factor, take_assumptions,
};
use crate::scene::Scene;
use crate::scene::pipeline::{RunError, assemble};

/// A symbolic derivation of a scene.
#[derive(Clone, Debug)]
pub struct Derived {
    /// The symbols declared.
    pub symbols: Vec<String>,
    /// Every quantity, as an expression (`Value::exact`) with its LaTeX form.
    pub report: Readout,
    /// Δ = det G.
    pub det: RatFun,
    /// Δ's numerator, factored: the locus Δ = 0 (`None` when Δ is a nonzero constant).
    pub locus: Option<Factored>,
    /// For a singular family (Δ ≡ 0): rank G and what each model needs.
    pub singular: Option<Singular>,
    /// Per model solved: whether eq. 34 holds identically.
    pub energy_identity: Vec<(Model, bool)>,
    /// The conditions the derivation assumed, in order of first use.
    pub conditions: Vec<Assumption>,
}

/// What a derivation reads out: one body's report, or a system's
/// ([`crate::mechanics::system`]).
#[derive(Clone, Debug)]
pub enum Readout {
    /// One body.
    Body(Report),
    /// A system of bodies.
    System(SystemReport),
}

impl Readout {
    /// One body's report (`None` for a system).
    pub fn body(&self) -> Option<&Report> {
        match self {
            Readout::Body(r) => Some(r),
            Readout::System(_) => None,
        }
    }

    /// A system's report (`None` for one body).
    pub fn system(&self) -> Option<&SystemReport> {
        match self {
            Readout::Body(_) => None,
            Readout::System(r) => Some(r),
        }
    }

    fn scene(&self) -> &str {
        match self {
            Readout::Body(r) => &r.scene,
            Readout::System(r) => &r.scene,
        }
    }

    fn effects(&self) -> &[String] {
        match self {
            Readout::Body(r) => &r.effects,
            Readout::System(r) => &r.effects,
        }
    }

    fn to_json(&self) -> Json {
        match self {
            Readout::Body(r) => r.to_json(),
            Readout::System(r) => r.to_json(),
        }
    }

    fn quantities(&self) -> Vec<(String, Vec<(String, Value)>)> {
        match self {
            Readout::Body(r) => quantities(r),
            Readout::System(r) => system_quantities(r),
        }
    }
}

/// A collision that is singular for every value of the symbols.
#[derive(Clone, Debug)]
pub struct Singular {
    /// rank G (generic: as a matrix of rational functions).
    pub rank: usize,
    /// N.
    pub contacts: usize,
    /// Per model.
    pub models: Vec<Family>,
}

/// A model's system G x = b when G is singular.
#[derive(Clone, Debug)]
pub struct Family {
    /// Which model.
    pub model: Model,
    /// z_kᵀ b for each null vector z_k: the system is compatible iff all vanish.
    pub conditions: Vec<RatFun>,
    /// Their numerators, factored (the readable form of "= 0").
    pub factored: Vec<Factored>,
    /// When every condition vanishes identically: the particular solution (hatted impulses,
    /// see [`crate::mechanics::contact`]) and the directions of the family in impulse space (the null
    /// vectors z_k; for Poisson diag(1 + k_i^P) z_k).
    pub solution: Option<(Vec<RatFun>, Vec<Vec<RatFun>>)>,
    /// The outcome of the particular solution (velocities after impact, energies), when
    /// compatible.
    pub outcome: Option<Particular>,
    /// Per null direction z_k, the change of the twist after impact per unit t_k:
    /// −Σ_j c_j z_kj W{E_jx} with c_j = 1 (Newton) or 1 + k_j^P (Poisson). Zero for Newton
    /// (G z = 0 ⇒ W E z = 0, eq. 57–58); for Poisson zero only when the c_j agree along z.
    pub twist_change: Vec<Vec<RatFun>>,
}

/// A body's label in a singular family's lines: empty for one body, its name for a system's.
#[derive(Clone, Debug, Default)]
struct BodyLabel {
    text: String,
    latex: String,
}

/// What a singular family's particular solution gives after impact.
#[derive(Clone, Debug)]
pub struct Particular {
    /// The twist after impact: [ω; v_C] (a system: each body's in turn, in the scene's order).
    pub twist: Vec<RatFun>,
    /// E_p (eq. 28).
    pub lost_velocity_energy: RatFun,
    /// ΔE_c (eq. 32).
    pub kinetic_energy_loss: RatFun,
}

/// The symbols `derive` takes when none are named (`inertance derive` without `--symbols`,
/// Python's `derive(scene)`): the parameters of the scene's `[params]`, each a symbol, in
/// order — except those in `set`, which were given a value (`--param NAME=…`).
pub fn default_symbols(doc: &toml_edit::DocumentMut, set: &[&str]) -> Vec<String> {
    doc.get("params")
        .and_then(toml_edit::Item::as_table_like)
        .map(|t| {
            t.iter()
                .map(|(k, _)| k.to_string())
                .filter(|k| !set.contains(&k.as_str()))
                .collect()
        })
        .unwrap_or_default()
}

/// Derive `scene` symbolically for `models` (the scene's own when `None`).
///
/// # Errors
/// Bad input ([`RunError::Scene`]), more contacts than
/// [`crate::scene::limits::MAX_DERIVE_CONTACTS`], and frames that cannot be built; a singular
/// G is not an error (see [`Derived::singular`]).
pub fn derive(
    scene: &Scene,
    symbols: &[String],
    models: Option<&[Model]>,
) -> Result<Derived, RunError> {
    if let Some(refusal) = crate::scene::limits::derive_limit(scene) {
        return Err(refusal.into());
    }
    // Never a law named but not applied: the closed forms are the simultaneous law's, for one
    // body as for a system.
    let refused = match scene.law {
        crate::impact::unilateral::Law::Simultaneous => None,
        crate::impact::unilateral::Law::Unilateral => Some((
            "\"unilateral\"",
            "derive gives the simultaneous law's closed forms; the unilateral law's answer is \
             piecewise (which contacts separate): solve it with `solve --exact`",
        )),
        crate::impact::unilateral::Law::Lzb => Some((
            "\"lzb\"",
            "derive gives the simultaneous law's closed forms; the LZB law is integrated \
             numerically and has none: solve it with `solve`",
        )),
    };
    if let Some((value, message)) = refused {
        return Err(RunError::Scene(crate::scene::SceneError {
            file: scene.file.clone(),
            key: "solve.law".into(),
            value: Some(value.into()),
            message: message.into(),
        }));
    }
    let models = models.unwrap_or(&scene.models).to_vec();
    take_assumptions();
    if scene.system.is_some() {
        return derive_system(scene, symbols, &models);
    }
    let mut a = assemble::<RatFun>(scene)?;
    // The printed quantities carry the normals' norms (P_i = P̂_i |n_i|, v_ix = v̂_ix / |n_i|,
    // g_ij = ĝ_ij / (|n_i| |n_j|)): their conditions (|n_i|² ≠ 0, a base of √ positive).
    for f in a.impact.frames() {
        let _ = f.norm2[0].sqrt_exact();
        let _ = RatFun::from_integer(1) / &f.norm2[0];
    }
    let mut outcomes = Vec::new();
    let mut energy_identity = Vec::new();
    if !a.singular() {
        for &m in &models {
            let (out, holds) = a.solve(m)?;
            energy_identity.push((m, holds));
            outcomes.push((m, out));
        }
    }
    let singular = if a.singular() {
        Some(singular_family(&mut a.impact, &models)?)
    } else {
        None
    };
    let mut norms = RatFun::from_integer(1);
    for f in a.impact.frames() {
        norms *= &f.norm2[0];
    }
    let det = a.impact.det_hat().clone() / &norms;
    let conditions = take_assumptions();
    // The report also computes what the formulas do not need (tangential angles divide by
    // tangential speeds): its conditions are not the formulas' and are dropped.
    let report = Readout::Body(a.report(scene, &outcomes));
    take_assumptions();
    // Only the numerator can vanish (the denominator's factors are assumed nonzero).
    let locus = if det.numer().is_constant() {
        None
    } else {
        Some(factor(det.numer()))
    };
    // A division by an expression that is identically zero: some value is 0 in disguise.
    if let Some(c) = conditions
        .iter()
        .find(|c| num_traits::Zero::is_zero(&c.expr))
    {
        return Err(identically_zero(scene, c));
    }
    Ok(Derived {
        symbols: symbols.to_vec(),
        report,
        det,
        locus,
        singular,
        energy_identity,
        conditions,
    })
}

/// [`derive`] for a system of bodies: its closed forms through the system's solve
/// ([`crate::scene::system_pipeline`]) in rational functions; a system singular for every
/// value of the symbols gets its family as one body does ([`singular_family`]).
fn derive_system(scene: &Scene, symbols: &[String], models: &[Model]) -> Result<Derived, RunError> {
    use crate::mechanics::system::SystemScrew;
    if scene.frictional() {
        // The refusal `solve` gives, naming the key.
        crate::scene::system_pipeline::run_system::<RatFun>(scene, Some(models))?;
    }
    let system = scene.system::<RatFun>()?;
    let mut impact = Impact::assemble(&system)?;
    let mut outcomes = Vec::with_capacity(models.len());
    let mut energy_identity = Vec::with_capacity(models.len());
    let singular = impact.rank() < impact.contacts();
    for &m in models.iter().filter(|_| !singular) {
        let mut out: Outcome<RatFun, SystemScrew<RatFun>> = Outcome::default();
        impact.solve(m, &mut out)?;
        let sum = out.kinetic_energy_loss.clone() + &out.lost_velocity_energy;
        energy_identity.push((
            m,
            num_traits::Zero::is_zero(&(sum - impact.impulse_work(&out))),
        ));
        outcomes.push((m, out));
    }
    let singular = if singular {
        Some(singular_family(&mut impact, models)?)
    } else {
        None
    };
    let mut norms = RatFun::from_integer(1);
    for f in impact.frames() {
        let _ = f.norm2[0].sqrt_exact();
        norms *= &f.norm2[0];
    }
    let det = impact.det_hat().clone() / &norms;
    // The formulas' conditions; the readout's own (its frames' angles) are dropped.
    let conditions = take_assumptions();
    let names: Vec<String> = scene
        .system
        .as_ref()
        .map(|s| s.bodies.iter().map(|b| b.name.clone()).collect())
        .unwrap_or_default();
    let mut effects = Vec::new();
    if !system.joints().is_empty() {
        effects.push("joints".to_string());
    }
    effects.extend(models.iter().map(|m| m.name().to_string()));
    let mut report = SystemReport::new(&scene.name, effects, &names, &impact, &outcomes);
    report.obstacles = crate::scene::system_pipeline::obstacle_names(scene);
    take_assumptions();
    if let Some(c) = conditions
        .iter()
        .find(|c| num_traits::Zero::is_zero(&c.expr))
    {
        return Err(identically_zero(scene, c));
    }
    let locus = if det.numer().is_constant() {
        None
    } else {
        Some(factor(det.numer()))
    };
    Ok(Derived {
        symbols: symbols.to_vec(),
        report: Readout::System(report),
        det,
        locus,
        singular,
        energy_identity,
        conditions,
    })
}

/// The refusal of a derivation that needs an identically zero value to be nonzero.
fn identically_zero(scene: &Scene, c: &Assumption) -> RunError {
    RunError::Scene(crate::scene::SceneError {
        file: scene.file.clone(),
        key: String::new(),
        value: None,
        message: format!(
            "the derivation needs a value that is identically zero to be nonzero ({c}): \
             a symbolic input makes the collision degenerate (a zero normal, mass or moment?)"
        ),
    })
}

/// A system's quantities as (name, value) lines: G and the approach speeds, then per model
/// the impulses, each body's ω and v_C by name (`newton.upper.omega[2]`), the contacts'
/// normal velocities, E_p, ΔE_c and each joint's reaction at its anchor.
fn system_quantities(r: &SystemReport) -> Vec<(String, Vec<(String, Value)>)> {
    let n = r.inertance.len();
    let mut g = Vec::new();
    for i in 0..n {
        for j in i..n {
            g.push((format!("g{}{}xx", i + 1, j + 1), r.inertance[i][j].clone()));
        }
    }
    for (i, c) in r.contacts_before.iter().enumerate() {
        g.push((format!("v{}x0", i + 1), c.components[0].clone()));
    }
    let mut sections = vec![("inertances and velocities before impact".to_string(), g)];
    for mr in &r.models {
        let m = mr.model.name();
        let mut v = Vec::new();
        for (i, p) in mr.impulses.iter().enumerate() {
            v.push((format!("{m}.P{}", i + 1), p.clone()));
        }
        if let Some(pc) = &mr.compression_impulses {
            for (i, p) in pc.iter().enumerate() {
                v.push((format!("{m}.P{}c", i + 1), p.clone()));
            }
        }
        for (name, (w, vc)) in r.bodies.iter().zip(&mr.twists) {
            for (k, x) in w.iter().enumerate() {
                v.push((format!("{m}.{name}.omega[{k}]"), x.clone()));
            }
            for (k, x) in vc.iter().enumerate() {
                v.push((format!("{m}.{name}.vC[{k}]"), x.clone()));
            }
        }
        for (i, c) in mr.contacts.iter().enumerate() {
            v.push((format!("{m}.v{}x", i + 1), c.components[0].clone()));
        }
        v.push((format!("{m}.Ep"), mr.lost_velocity_energy.clone()));
        v.push((format!("{m}.dEc"), mr.kinetic_energy_loss.clone()));
        for (j, w) in mr.joint_reactions.iter().enumerate() {
            for (k, f) in w.force.iter().enumerate() {
                v.push((format!("{m}.J{}.F[{k}]", j + 1), f.clone()));
            }
            for (k, x) in w.moment.iter().enumerate() {
                v.push((format!("{m}.J{}.M[{k}]", j + 1), x.clone()));
            }
        }
        sections.push((format!("{m} (after impact)"), v));
    }
    sections
}

/// The singular family of a collision with rank G < N for every value of the symbols: per
/// model, the compatibility conditions and, where they hold identically, the family — for one
/// body or a system alike (the mechanism's screws, each body's in turn).
fn singular_family<M: Mechanism<RatFun>>(
    impact: &mut Impact<RatFun, M>,
    models: &[Model],
) -> Result<Singular, RunError> {
    let n = impact.contacts();
    let basis = impact.null_space();
    let one = RatFun::from_integer(1);
    let mut families = Vec::new();
    for &m in models {
        let mut b = Vec::new();
        impact.rhs(m, &mut b);
        let conditions: Vec<RatFun> = basis
            .iter()
            .map(|z| {
                z.iter()
                    .zip(&b)
                    .fold(RatFun::from_integer(0), |s, (zi, bi)| s + zi.clone() * bi)
            })
            .collect();
        let factored = conditions.iter().map(|c| factor(c.numer())).collect();
        let compatible = conditions.iter().all(num_traits::Zero::is_zero);
        let (mut solution, mut outcome, mut twist_change) = (None, None, Vec::new());
        if compatible {
            let mut x = Vec::new();
            impact
                .solve_singular(&b, &mut x)
                .ok_or(RunError::Solve(SolveError::Singular {
                    rank: impact.rank(),
                    contacts: n,
                    rounded: false,
                }))?;
            // Impulses are c_i x_i, c_i = 1 (Newton) or 1 + k_i^P (Poisson, eq. 23): so are
            // the family's directions in impulse space.
            let c: Vec<RatFun> = impact
                .problem()
                .contacts()
                .iter()
                .map(|k| match m {
                    Model::Newton => one.clone(),
                    Model::Poisson => one.clone() + &k.k_poisson,
                })
                .collect();
            let mut out = Outcome::<RatFun, M::Screw>::default();
            if m == Model::Poisson {
                out.compression_hat.clone_from(&x);
            }
            out.impulses_hat = x.iter().zip(&c).map(|(xi, ci)| xi.clone() * ci).collect();
            impact.complete(&mut out);
            let dirs: Vec<Vec<RatFun>> = basis
                .iter()
                .map(|z| z.iter().zip(&c).map(|(zj, cj)| zj.clone() * cj).collect())
                .collect();
            twist_change = dirs
                .iter()
                .map(|d| {
                    let mut dv = impact.problem().velocity().zero_like();
                    for (dj, r) in d.iter().zip(impact.responses()) {
                        dv.add_scaled(&-dj.clone(), r);
                    }
                    dv.components()
                })
                .collect();
            solution = Some((out.impulses_hat.clone(), dirs));
            outcome = Some(Particular {
                twist: out.velocity.components(),
                lost_velocity_energy: out.lost_velocity_energy,
                kinetic_energy_loss: out.kinetic_energy_loss,
            });
        }
        families.push(Family {
            model: m,
            conditions,
            factored,
            solution,
            outcome,
            twist_change,
        });
    }
    Ok(Singular {
        rank: impact.rank(),
        contacts: n,
        models: families,
    })
}

/// Quantities of a report as (name, value) lines, named as in `inertance check`.
fn quantities(r: &Report) -> Vec<(String, Vec<(String, Value)>)> {
    let n = r.inertance.len();
    let mut sections = Vec::new();
    let mut g = Vec::new();
    for i in 0..n {
        for j in i..n {
            g.push((format!("g{}{}xx", i + 1, j + 1), r.inertance[i][j].clone()));
        }
    }
    for (i, c) in r.contacts_before.iter().enumerate() {
        g.push((format!("v{}x0", i + 1), c.components[0].clone()));
    }
    if let Some(c) = &r.constraints {
        let d = c.reduced_mass.len();
        for a in 0..d {
            for b in a..d {
                let name = if d == 1 {
                    "Mred".to_string()
                } else {
                    format!("Mred[{}]", a * d + b)
                };
                g.push((name, c.reduced_mass[a][b].clone()));
            }
        }
    }
    sections.push(("inertances and velocities before impact".to_string(), g));
    for mr in &r.models {
        let m = mr.model.name();
        let mut v = Vec::new();
        for (i, p) in mr.impulses.iter().enumerate() {
            if p.exact.is_some() {
                v.push((format!("{m}.P{}", i + 1), p.clone()));
            } else {
                // |n_i| has no exact form: the impulse as a multiple of the normal as written.
                v.push((
                    format!("{m}.P{}/|n{}|", i + 1, i + 1),
                    mr.impulse_multiples[i].clone(),
                ));
            }
        }
        if let Some(pc) = &mr.compression_impulses {
            for (i, p) in pc.iter().enumerate() {
                v.push((format!("{m}.P{}c", i + 1), p.clone()));
            }
        }
        for (k, w) in mr.angular_velocity.iter().enumerate() {
            v.push((format!("{m}.omega[{k}]"), w.clone()));
        }
        for (k, w) in mr.velocity.iter().enumerate() {
            v.push((format!("{m}.vC[{k}]"), w.clone()));
        }
        for (i, c) in mr.contacts.iter().enumerate() {
            v.push((format!("{m}.v{}x", i + 1), c.components[0].clone()));
        }
        v.push((format!("{m}.Ep"), mr.lost_velocity_energy.clone()));
        v.push((format!("{m}.dEc"), mr.kinetic_energy_loss.clone()));
        for (k, q) in mr.constraint_impulses.iter().enumerate() {
            v.push((format!("{m}.q[{k}]"), q.clone()));
        }
        // U q as a force and a moment: about each joint's anchor, or about C.
        let joints = r.constraints.as_ref().map_or(0, |c| c.joints.len());
        let wrenches: Vec<(String, &str, &WrenchReport)> = match joints {
            0 => mr
                .constraint_wrench
                .iter()
                .map(|w| (String::new(), "MC", w))
                .collect(),
            _ => (mr.joint_reactions.iter().enumerate())
                .map(|(j, w)| (format!("J{}.", j + 1), "M", w))
                .collect(),
        };
        for (at, moment, w) in wrenches {
            for (k, f) in w.force.iter().enumerate() {
                v.push((format!("{m}.{at}F[{k}]"), f.clone()));
            }
            for (k, x) in w.moment.iter().enumerate() {
                v.push((format!("{m}.{at}{moment}[{k}]"), x.clone()));
            }
        }
        sections.push((format!("{m} (after impact)"), v));
    }
    sections
}

/// The paper's notation for a quantity named as in `inertance check`: `g12xx` → g_{12xx},
/// `newton.P1` → P_{1}^{N}, `poisson.dEc` → \Delta E_{c}^{P}, `newton.vC[0]` → v_{Cx}^{N}.
fn latex_name(name: &str) -> String {
    let (model, q) = match name.split_once('.') {
        Some((m, q)) => (if m == "newton" { "^{N}" } else { "^{P}" }, q),
        None => ("", name),
    };
    let axis = |k: &str| match k {
        "0" => "x",
        "1" => "y",
        _ => "z",
    };
    let index = |q: &str| -> Option<(String, String)> {
        let (base, k) = q.strip_suffix(']')?.split_once('[')?;
        Some((base.to_string(), k.to_string()))
    };
    let body = if q == "det" {
        "\\Delta".to_string()
    } else if q == "Mred" {
        "M_{\\mathrm{red}}".to_string()
    } else if q == "Ep" {
        "E_{p}".to_string()
    } else if q == "dEc" {
        "\\Delta E_{c}".to_string()
    } else if let Some((base, k)) = index(q) {
        match base.as_str() {
            "omega" => format!("\\omega_{{{}}}", axis(&k)),
            "vC" => format!("v_{{C{}}}", axis(&k)),
            "q" => format!(
                "q_{{{}}}",
                k.parse::<usize>()
                    .map_or(k.clone(), |i| (i + 1).to_string())
            ),
            "Mred" => format!("M_{{\\mathrm{{red}},{k}}}"),
            "F" => format!("F_{{{}}}", axis(&k)),
            "MC" => format!("M_{{C{}}}", axis(&k)),
            joint => match joint.strip_prefix('J').and_then(|j| j.split_once('.')) {
                Some((j, "F")) => format!("F_{{J{j},{}}}", axis(&k)),
                Some((j, "M")) => format!("M_{{J{j},{}}}", axis(&k)),
                _ => format!("\\mathrm{{{q}}}"),
            },
        }
    } else if let Some(rest) = q.strip_prefix('g') {
        format!("g_{{{rest}}}")
    } else if let Some(i) = q.strip_prefix('P').and_then(|r| r.split_once('/')) {
        format!("\\hat P_{{{}}}", i.0)
    } else if let Some(i) = q.strip_prefix('P').and_then(|r| r.strip_suffix('c')) {
        return format!("P_{{{i}}}^{{c}}");
    } else if let Some(i) = q.strip_prefix('P') {
        format!("P_{{{i}}}")
    } else if let Some(rest) = q.strip_prefix('v') {
        match rest.strip_suffix('0') {
            Some(r) => return format!("v_{{{r}}}^{{0}}"),
            None => format!("v_{{{rest}}}"),
        }
    } else {
        format!("\\mathrm{{{q}}}")
    };
    format!("{body}{model}")
}

fn text_of(v: &Value) -> String {
    v.exact.clone().unwrap_or_else(|| "(no exact form)".into())
}

fn latex_of(v: &Value) -> String {
    v.latex
        .clone()
        .or_else(|| v.exact.clone())
        .unwrap_or_else(|| "\\text{(no exact form)}".into())
}

fn condition_text(a: &Assumption, latex: bool) -> String {
    let e = if a.expr.numer().display_sign() < 0 && a.kind == AssumptionKind::NonZero {
        -a.expr.clone()
    } else {
        a.expr.clone()
    };
    let t = crate::scalar::symbolic::factor::readable(&e, latex);
    match (a.kind, latex) {
        (AssumptionKind::NonZero, false) => format!("{t} ≠ 0"),
        (AssumptionKind::NonZero, true) => format!("{t} \\neq 0"),
        (AssumptionKind::Positive, _) => format!("{t} > 0"),
    }
}

impl Derived {
    /// Plain text (or LaTeX with `latex`): one `name = expression` per line, quantities named
    /// as in `inertance check` (in LaTeX, as in the paper: g_{12xx}, P_1^N, ΔE_c^P); the
    /// prose lines are `%` comments in LaTeX, so the output pastes into a document.
    pub fn to_text(&self, latex: bool) -> String {
        let mut out = String::new();
        let comment = |t: &str| {
            if latex {
                format!("% {t}\n")
            } else {
                format!("{t}\n")
            }
        };
        let (eq, and) = if latex {
            (" &= ", " \\\\")
        } else {
            (" = ", "")
        };
        let val = |v: &Value| if latex { latex_of(v) } else { text_of(v) };
        out += &comment(&format!("derivation of {}", self.report.scene()));
        out += &comment(&format!("symbols: {}", self.symbols.join(", ")));
        out += &comment(&format!("effects: {}", self.report.effects().join(", ")));
        if latex {
            out += "\\begin{aligned}\n";
        }
        let det = crate::scalar::symbolic::factor::readable(&self.det, latex);
        let det_name = if latex { "\\Delta" } else { "det" };
        out += &format!("{det_name}{eq}{det}{and}\n");
        if let Some(locus) = &self.locus {
            if latex {
                out += &format!(
                    "&\\text{{degenerate ($\\Delta = 0$) where }} {} = 0{and}\n",
                    locus.to_latex()
                );
            } else {
                out += &format!("  degenerate (Δ = 0) where {} = 0\n", locus.to_text());
            }
        }
        for (title, lines) in &self.report.quantities() {
            if latex {
                out += &format!("&\\text{{{title}}}{and}\n");
            } else {
                out += &format!("{title}:\n");
            }
            for (name, v) in lines {
                if latex {
                    out += &format!("{}{eq}{}{and}\n", latex_name(name), val(v));
                } else {
                    out += &format!("  {name}{eq}{}\n", val(v));
                }
            }
        }
        if let Some(s) = &self.singular {
            out += &self.singular_text(s, latex);
        }
        if latex {
            out += "\\end{aligned}\n";
        }
        for (m, ok) in &self.energy_identity {
            out += &comment(&format!(
                "{m}: energy identity ΔE_c = −E_p + Σ P_i v_ix⁰ (eq. 34) {}",
                if *ok { "holds identically" } else { "FAILS" }
            ));
        }
        if self.conditions.is_empty() {
            out += &comment("conditions: none (the formulas hold for every value of the symbols)");
        } else {
            out += &comment("conditions (the formulas hold where all of these do):");
            if latex {
                out += "\\begin{gathered}\n";
                let items: Vec<String> = self
                    .conditions
                    .iter()
                    .map(|c| condition_text(c, true))
                    .collect();
                out += &items.join(", \\\\\n");
                out += "\n\\end{gathered}\n";
            } else {
                for c in &self.conditions {
                    out += &format!("  {}\n", condition_text(c, false));
                }
            }
        }
        out
    }

    /// A twist's components by body: one body's whole (no label), a system's six at a time
    /// labelled with the body's name (`.ball2` in text, `_{\\text{ball2}}` in LaTeX).
    fn per_body<'a>(&'a self, v: &'a [RatFun]) -> Vec<(BodyLabel, &'a [RatFun])> {
        match &self.report {
            Readout::Body(_) => vec![(BodyLabel::default(), v)],
            Readout::System(r) => r
                .bodies
                .iter()
                .zip(v.chunks(6))
                .map(|(name, part)| {
                    let label = BodyLabel {
                        text: format!(".{name}"),
                        latex: format!("_{{\\text{{{name}}}}}"),
                    };
                    (label, part)
                })
                .collect(),
        }
    }

    fn singular_text(&self, s: &Singular, latex: bool) -> String {
        let mut out = String::new();
        let line = |t: String| {
            if latex {
                format!("&\\text{{{t}}} \\\\\n")
            } else {
                format!("{t}\n")
            }
        };
        out += &line(format!(
            "det = 0 identically: rank G = {} of {} for every value of the symbols (§8, eq. 61–68, 98–102)",
            s.rank, s.contacts
        ));
        let ex = |e: &RatFun| crate::scalar::symbolic::factor::readable(e, latex);
        for f in &s.models {
            let m = f.model.name();
            match &f.solution {
                None => {
                    out += &line(format!(
                        "{m}: compatible (rank [G | b] = rank G) only where"
                    ));
                    for fac in &f.factored {
                        let t = if latex { fac.to_latex() } else { fac.to_text() };
                        out += &if latex {
                            format!("&\\quad {t} = 0 \\\\\n")
                        } else {
                            format!("  {t} = 0\n")
                        };
                    }
                }
                Some((x, dirs)) => {
                    out += &line(format!(
                        "{m}: compatible for every value of the symbols; impulses (as multiples of the normals) x + Σ t_k z_k:"
                    ));
                    for (i, xi) in x.iter().enumerate() {
                        out += &if latex {
                            format!("\\hat P_{{{}}} &= {} \\\\\n", i + 1, ex(xi))
                        } else {
                            format!("  {m}.P{}/|n{}| = {}\n", i + 1, i + 1, ex(xi))
                        };
                    }
                    for (k, z) in dirs.iter().enumerate() {
                        let zs: Vec<String> = z.iter().map(ex).collect();
                        out += &if latex {
                            format!(
                                "z_{{{}}} &= \\left[{}\\right] \\\\\n",
                                k + 1,
                                zs.join(",\\ ")
                            )
                        } else {
                            format!("  z{} = [{}]\n", k + 1, zs.join(", "))
                        };
                    }
                    let varies: Vec<&Vec<RatFun>> = f
                        .twist_change
                        .iter()
                        .filter(|d| !d.iter().all(num_traits::Zero::is_zero))
                        .collect();
                    if varies.is_empty() {
                        out += &line(format!(
                            "{m}: the twist after impact and both energies are the same for every member of the family"
                        ));
                    } else {
                        out += &line(format!(
                            "{m}: the twist after impact VARIES along the family (P_i = (1 + k_i) P_i^c with unequal k_i); per unit t_k it changes by:"
                        ));
                        for (k, d) in varies.iter().enumerate() {
                            for (body, part) in self.per_body(d) {
                                let ds: Vec<String> = part.iter().map(ex).collect();
                                out += &if latex {
                                    format!(
                                        "\\delta\\{{v{}\\}}_{{{}}} &= \\left[{}\\right] \\\\\n",
                                        body.latex,
                                        k + 1,
                                        ds.join(",\\ ")
                                    )
                                } else {
                                    format!(
                                        "  d(twist{})/dt{} = [{}]\n",
                                        body.text,
                                        k + 1,
                                        ds.join(", ")
                                    )
                                };
                            }
                        }
                    }
                    if let Some(o) = &f.outcome {
                        for (body, part) in self.per_body(&o.twist) {
                            let tw: Vec<String> = part.iter().map(ex).collect();
                            out += &if latex {
                                format!(
                                    "\\{{v{}\\}} &= \\left[{}\\right] \\\\\n",
                                    body.latex,
                                    tw.join(",\\ ")
                                )
                            } else {
                                format!(
                                    "  {m}{}.twist (particular solution) = [{}]\n",
                                    body.text,
                                    tw.join(", ")
                                )
                            };
                        }
                        if !latex {
                            out += &format!(
                                "  {m}.Ep = {}\n  {m}.dEc = {}\n",
                                ex(&o.lost_velocity_energy),
                                ex(&o.kinetic_energy_loss)
                            );
                        }
                    }
                }
            }
        }
        out
    }

    /// The JSON form: the report's keys (values as expression strings) plus `symbols`,
    /// `det_locus`, `conditions`, `energy_identity` and `singular`.
    pub fn to_json(&self) -> Json {
        let mut j = self.report.to_json();
        let text = |e: &RatFun| crate::scalar::symbolic::factor::readable(e, false);
        let ex = |e: &RatFun| Json::String(text(e));
        if let Json::Object(map) = &mut j {
            map.insert("symbols".into(), json!(self.symbols));
            map.insert("det".into(), ex(&self.det));
            map.insert(
                "det_locus".into(),
                self.locus
                    .as_ref()
                    .map_or(Json::Null, |f| Json::String(f.to_text())),
            );
            map.insert(
                "conditions".into(),
                Json::Array(
                    self.conditions
                        .iter()
                        .map(|c| Json::String(condition_text(c, false)))
                        .collect(),
                ),
            );
            map.insert(
                "energy_identity".into(),
                self.energy_identity
                    .iter()
                    .map(|(m, ok)| (m.name().to_string(), json!(ok)))
                    .collect::<serde_json::Map<_, _>>()
                    .into(),
            );
            map.insert(
                "singular".into(),
                self.singular.as_ref().map_or(Json::Null, |s| {
                    json!({
                        "rank": s.rank,
                        "contacts": s.contacts,
                        "models": s.models.iter().map(|f| json!({
                            "model": f.model.name(),
                            "compatible_identically": f.solution.is_some(),
                            "conditions": f.factored.iter().map(|c| format!("{} = 0", c.to_text())).collect::<Vec<_>>(),
                            "particular_impulse_multiples": f.solution.as_ref().map(|(x, _)| x.iter().map(text).collect::<Vec<_>>()),
                            "null_directions": f.solution.as_ref().map(|(_, z)| z.iter().map(|v| v.iter().map(text).collect::<Vec<_>>()).collect::<Vec<_>>()),
                            "twist_change_per_direction": f.twist_change.iter().map(|v| v.iter().map(text).collect::<Vec<_>>()).collect::<Vec<_>>(),
                        })).collect::<Vec<_>>(),
                    })
                }),
            );
        }
        j
    }
}
