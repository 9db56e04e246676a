//! What a solve reports, in the units of the paper: a scalar-free readout of an [`Impact`]
//! and its [`Outcome`]s, rendered as a table or as JSON.
//!
//! Every value carries its f64 approximation and, in exact mode, its exact text: `p/q`, or
//! `c*sqrt(r)` when a non-unit axis puts a norm into it (an impulse P_i = P̂_i |n_i|, a
//! velocity component v_ix = v̂_ix / |n_i|, see [`crate::mechanics::contact`]). Angles are the one
//! exception: α = atan2(v_z, v_y) is transcendental, so it is a number in both modes (its
//! cosine and sine are exact surds).
//!
//! The JSON keys are a public contract (guide/solving.md, "JSON report").
//!
//! Here: the readout itself ([`Report`], [`Value`]) and how it is read out of a solve, undoing
//! the normalisation of the solver's axes; `table` renders it for people ([`Report::to_table`]),
//! `json` for programs ([`Report::to_json`]).

pub mod animation;
pub mod animation_system;
pub mod exact_run;
mod friction;
mod json;
pub mod lzb;
mod plot;
pub mod simulation;
pub mod simulation_system;
pub mod system;
pub mod system_friction;
mod table;
pub mod trajectory;
mod wide;

pub use friction::{FrictionContact, FrictionReport};
pub use trajectory::{TrajectoryContact, TrajectoryPoint};
pub use wide::Wide;

use serde_json::Value as Json;

use crate::impact::admissibility::Inadmissible;
use crate::impact::outputs::Outputs;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::impact::unilateral::{Activity, Law};
use crate::mechanics::constraint::Constrained;
use crate::mechanics::contact::{ContactFrame, Surd, TangentRule};
use crate::mechanics::reaction::{Wrench, joint_reactions};
use crate::mechanics::screw::{Screws, Vec3, rescaled};
use crate::scalar::Scalar;

/// One reported number: f64 always, exact text in exact mode; in a dual-number run (a
/// sensitivity, [`crate::scalar::dual`]) also its derivative with respect to the seeded input.
#[derive(Clone, Debug, PartialEq)]
pub struct Value {
    /// The value (rounded, in exact mode).
    pub f64: f64,
    /// `p/q` or `c*sqrt(r)`, in exact mode; an expression in symbolic mode.
    pub exact: Option<String>,
    /// The LaTeX form, in symbolic mode.
    pub latex: Option<String>,
    /// d(value)/d(seeded input), in a dual-number run (its `exact` text in `Dual<Exact>`; a
    /// `f64` of NaN where the value has no derivative); `None` in every other run.
    pub derivative: Option<Box<Value>>,
    /// A float result beyond the range of f64 (Δ or an inertance of a scene solved in scaled
    /// units, [`crate::scene::scale`]): its exact value as mantissa and power of two, with
    /// [`Value::f64`] what f64 holds of it (±∞, 0 or subnormal). Printed and written as decimal
    /// text from the pair ([`Value::text`], [`Value::json`]); `None` for every value f64 holds.
    pub wide: Option<Wide>,
}

impl Value {
    /// The value of `x`: f64, and its exact text for exact types; its derivative for dual
    /// numbers.
    pub fn of<T: Scalar>(x: &T) -> Self {
        match x.dual_parts() {
            Some((v, d)) => Value {
                derivative: Some(Box::new(Value::plain(&d))),
                ..Value::plain(&v)
            },
            None => Value::plain(x),
        }
    }

    /// The value of `x` without a derivative.
    fn plain<T: Scalar>(x: &T) -> Self {
        Value {
            f64: x.to_f64(),
            exact: x.exact_text(),
            latex: x.latex_text(),
            derivative: None,
            wide: None,
        }
    }

    /// The value of the surd `s` (and its derivative, d(q√r) = (q′ + q r′/(2r))√r, for dual
    /// numbers).
    pub fn surd<T: Scalar>(s: &Surd<T>) -> Self {
        let plain = |s: &Surd<T>| Value {
            f64: s.to_f64(),
            exact: s.exact_text(),
            latex: s.latex_text(),
            derivative: None,
            wide: None,
        };
        let derivative = s.coeff.dual_parts().map(|_| {
            Box::new(match s.derivative() {
                Some(d) => plain(&d),
                None => Value::float(f64::NAN),
            })
        });
        Value {
            derivative,
            ..plain(s)
        }
    }

    /// A number without exact form (an angle, a float result).
    pub fn float(x: f64) -> Self {
        Value {
            f64: x,
            exact: None,
            latex: None,
            derivative: None,
            wide: None,
        }
    }

    /// The JSON value: the exact string in exact mode, a number otherwise; a value beyond
    /// f64 ([`Value::wide`]) as a string in decimal scientific notation with 17 significant
    /// digits (`"1.2345678901234567e600"`: enough to give back its f64 mantissa), never `null`.
    pub fn json(&self) -> Json {
        match (&self.exact, &self.wide) {
            (Some(t), _) => Json::String(t.clone()),
            (None, Some(w)) => Json::String(w.decimal(17)),
            (None, None) => json_f64(self.f64),
        }
    }

    /// Readable text: the exact value (with ≈ decimals when not a short decimal), or the f64.
    ///
    /// An exact value beyond the range of f64 (or too small for it) gets its decimals from the
    /// exact text, never `≈ inf` or `≈ 0`.
    pub fn text(&self) -> String {
        if let (None, Some(w)) = (&self.exact, &self.wide) {
            return w.decimal(7);
        }
        match &self.exact {
            Some(t) if self.f64.is_nan() => t.clone(),
            Some(t) if !self.f64.is_finite() || (self.f64 == 0.0 && t != "0") => {
                match approx_exact(t) {
                    Some(a) => format!("{t} ≈ {a}"),
                    None => t.clone(),
                }
            }
            Some(t) if t.parse::<f64>().is_err() || t.len() > 14 => {
                format!("{} ≈ {}", t, fmt_f64(self.f64))
            }
            Some(t) => t.clone(),
            None => fmt_f64(self.f64),
        }
    }
}

/// Seven significant digits of an exact text `p`, `p/q`, `c*sqrt(r)` or `sqrt(r)` (signed) in
/// scientific notation, computed in integers so that it holds far beyond the range of f64;
/// `None` for any other text.
fn approx_exact(text: &str) -> Option<String> {
    use num_bigint::BigInt;
    use num_traits::{Signed, Zero};
    let (neg, t) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text),
    };
    let (coef, radicand) = match t.split_once("sqrt(") {
        Some((c, r)) => {
            let r: f64 = r.strip_suffix(')')?.parse().ok()?;
            let c = match c.strip_suffix('*') {
                Some(c) => c,
                None if c.is_empty() => "1",
                None => return None,
            };
            (c, r)
        }
        None => (t, 1.0),
    };
    let (p, q) = match coef.split_once('/') {
        Some((p, q)) => (p.parse::<BigInt>().ok()?, q.parse::<BigInt>().ok()?),
        None => (coef.parse::<BigInt>().ok()?, BigInt::from(1)),
    };
    if q.is_zero() || p.is_negative() || q.is_negative() || !radicand.is_finite() {
        return None;
    }
    if p.is_zero() {
        return Some("0".into());
    }
    // p·10^s / q has about 9 digits; the value is that times 10^-s.
    let digits = |x: &BigInt| x.to_string().len() as i64;
    let s = 9 - (digits(&p) - digits(&q));
    let ten = |k: i64| num_traits::pow(BigInt::from(10), k as usize);
    let scaled = if s >= 0 {
        p * ten(s) / q
    } else {
        p / (q * ten(-s))
    };
    let mut m: f64 = scaled.to_string().parse().ok()?;
    m *= radicand.sqrt();
    let mut e = -s;
    while m >= 10.0 {
        m /= 10.0;
        e += 1;
    }
    while m > 0.0 && m < 1.0 {
        m *= 10.0;
        e -= 1;
    }
    // Seven significant digits may round the mantissa up to 10 (9.9999999… → 10.000000).
    if format!("{m:.6}").starts_with("10") {
        m /= 10.0;
        e += 1;
    }
    Some(format!("{}{m:.6}e{e}", if neg { "-" } else { "" }))
}

/// An f64 as JSON: a number, or `null` when it is not finite.
pub(crate) fn json_f64(x: f64) -> Json {
    serde_json::Number::from_f64(x)
        .map(Json::Number)
        .unwrap_or(Json::Null)
}

/// An f64 for people: six decimals without trailing zeros, or scientific notation when very
/// small or large.
fn fmt_f64(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x.abs() >= 1e-4 && x.abs() < 1e7 {
        let s = format!("{x:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" { "0".into() } else { s.into() }
    } else {
        format!("{x:.6e}")
    }
}

/// The direction of a tangential velocity: α with cos α = v_y/|v_t|, sin α = v_z/|v_t| (eq. 27).
#[derive(Clone, Debug, PartialEq)]
pub struct Angle {
    /// α in degrees, in [0, 360).
    pub degrees: f64,
    /// cos α.
    pub cos: Value,
    /// sin α.
    pub sin: Value,
}

/// A contact point's velocity in its own frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PointVelocity {
    /// (v_ix, v_iy, v_iz).
    pub components: [Value; 3],
    /// α_i, or `None` when the tangential velocity is zero.
    pub angle: Option<Angle>,
}

/// The readout of one restitution model.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelReport {
    /// Which model.
    pub model: Model,
    /// P_i.
    pub impulses: Vec<Value>,
    /// P̂_i = P_i / |n_i| as given: the impulse as a multiple of the normal as written.
    pub impulse_multiples: Vec<Value>,
    /// P_i^c (Poisson).
    pub compression_impulses: Option<Vec<Value>>,
    /// ω after impact.
    pub angular_velocity: [Value; 3],
    /// v_C after impact.
    pub velocity: [Value; 3],
    /// Contact-point velocities after impact.
    pub contacts: Vec<PointVelocity>,
    /// E_p.
    pub lost_velocity_energy: Value,
    /// ΔE_c.
    pub kinetic_energy_loss: Value,
    /// {q}, the constraint impulses (empty for a free body).
    pub constraint_impulses: Vec<Value>,
    /// U q = [F; M_C], about the centre of mass C (constrained bodies, when the constraint
    /// impulses are asked for).
    pub constraint_wrench: Option<WrenchReport>,
    /// Per joint, its reaction about its anchor (bodies held by joints; as `constraint_wrench`).
    pub joint_reactions: Vec<WrenchReport>,
    /// The impact law the outcome obeys.
    pub law: Law,
    /// Why a simultaneous outcome is not physical; empty when it is admissible.
    pub inadmissible: Vec<Inadmissible>,
    /// The unilateral law's activity: which contacts take an impulse, and whether G is
    /// singular (velocities unique, impulses possibly a set).
    pub activity: Option<Activity>,
    /// The unilateral law: per contact, whether it takes an impulse (empty otherwise).
    pub active: Vec<bool>,
    /// When Poisson's law does not decide the outcome: the least and greatest value of each
    /// twist component [ω; v_C] over the vertices of the set of compression impulses.
    pub outcome_range: Option<[(Value, Value); 6]>,
}

/// An impulsive wrench reduced to a point ([`crate::mechanics::reaction::Wrench`]).
#[derive(Clone, Debug, PartialEq)]
pub struct WrenchReport {
    /// The point the moment is taken about, from C.
    pub point: [Value; 3],
    /// The force, N s.
    pub force: [Value; 3],
    /// The moment about `point`, N m s.
    pub moment: [Value; 3],
}

impl WrenchReport {
    fn of<T: Scalar>(w: &Wrench<T>) -> Self {
        let each = |v: &Vec3<T>| [0, 1, 2].map(|k| Value::of(&v[k]));
        WrenchReport {
            point: each(&w.point),
            force: each(&w.force),
            moment: each(&w.moment),
        }
    }
}

/// A joint of a constrained body: its kind and where its reaction is reduced to.
#[derive(Clone, Debug, PartialEq)]
pub struct JointReport {
    /// `"revolute"`, `"prismatic"`, …
    pub kind: &'static str,
    /// Whether its reaction is about its own point (else about C: prismatic, planar).
    pub has_point: bool,
}

/// The constraints of a constrained body, as used.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstraintsReport {
    /// D, the free screws.
    pub free: Vec<[Value; 6]>,
    /// U, the blocked screws.
    pub blocked: Vec<[Value; 6]>,
    /// Whether U was derived as the η-orthogonal complement of D.
    pub blocked_derived: bool,
    /// M_red = Dᵀ η M D (eq. 83), row by row.
    pub reduced_mass: Vec<Vec<Value>>,
    /// The joints D was built from, in order (empty for the paper's form).
    pub joints: Vec<JointReport>,
}

/// The readout of a solve.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// The scene's name.
    pub scene: String,
    /// `"f64"`, `"exact"`, …
    pub scalar: &'static str,
    /// The effects simulated, e.g. `["newton", "poisson"]`.
    pub effects: Vec<String>,
    /// G = \[g_ij,xx\].
    pub inertance: Vec<Vec<Value>>,
    /// \[g_ij,yx\].
    pub inertance_yx: Vec<Vec<Value>>,
    /// \[g_ij,zx\].
    pub inertance_zx: Vec<Vec<Value>>,
    /// Δ = det G.
    pub det: Value,
    /// Unit axes (x_i, y_i, z_i) of each contact frame, and how y_i was chosen.
    pub frames: Vec<([[Value; 3]; 3], TangentRule)>,
    /// Contact-point velocities before impact.
    pub contacts_before: Vec<PointVelocity>,
    /// One readout per model solved.
    pub models: Vec<ModelReport>,
    /// The constraints, for a constrained body.
    pub constraints: Option<ConstraintsReport>,
    /// The surface f = 0 and its gradient as text, when contact normals come from it.
    pub surface: Option<(String, [String; 3])>,
    /// One readout per frictional law solved (a scene with friction or an energetic law:
    /// then `models` is empty).
    pub friction: Vec<FrictionReport>,
    /// The frictional laws that have no answer for this scene: the law, why, and the short
    /// status (`no-continuation`, `undetermined`, `never-ends`).
    pub friction_failures: Vec<(crate::impact::friction::Restitution, String, &'static str)>,
    /// The models that have no answer under the scene's law while others do (a body jammed
    /// under Newton's unilateral law, say): the model, why, and the short status (`jammed`).
    pub model_failures: Vec<(Model, String, &'static str)>,
    /// The axes of a modelled scene's vectors (`"world"` or `"body"`, origin at the centre of
    /// mass); `None` for the paper's body-axes scenes.
    pub axes: Option<&'static str>,
    /// The outputs printed (`[solve] outputs`, `--outputs`): the table and the JSON leave
    /// the others out. Without [`Outputs::TANGENTIAL`] the frames' tangent axes, the
    /// tangential inertances and velocities and the angles were not computed (zero here).
    pub outputs: Outputs,
}

impl Report {
    /// Read out an assembled impact and the outcomes of its models.
    pub fn new<T: Scalar>(
        scene: &str,
        effects: Vec<String>,
        impact: &Impact<T>,
        outcomes: &[(Model, Outcome<T>)],
        constraints: Option<&Constrained<T>>,
    ) -> Report {
        let n = impact.contacts();
        let frames = impact.frames();
        let tangential = impact.outputs().needs().contains(Outputs::TANGENTIAL);
        let velocities = |hats: &[[T; 3]]| point_velocities(hats, frames, tangential);
        let constrained = impact.outputs().contains(Outputs::CONSTRAINT_IMPULSES);
        Report {
            axes: None,
            outputs: impact.outputs(),
            scene: scene.to_string(),
            scalar: T::NAME,
            effects,
            inertance: inertances(impact.g_hat(), frames, n, 0),
            inertance_yx: match tangential {
                true => inertances(impact.g_yx_hat(), frames, n, 1),
                false => Vec::new(),
            },
            inertance_zx: match tangential {
                true => inertances(impact.g_zx_hat(), frames, n, 2),
                false => Vec::new(),
            },
            det: determinant(impact.det_hat(), frames),
            frames: frames.iter().map(|f| unit_axes(f, tangential)).collect(),
            contacts_before: velocities(impact.before_hat()),
            models: outcomes
                .iter()
                .map(|(m, o)| {
                    let mut r = ModelReport::new(*m, o, frames, &velocities);
                    if let (Some(c), true) = (constraints, constrained) {
                        r.constraint_wrench = Some(WrenchReport::of(&Wrench::about(
                            &o.constraint_wrench,
                            Vec3::zeros(),
                        )));
                        r.joint_reactions = joint_reactions(&o.constraint_wrench, &c.joints)
                            .iter()
                            .map(WrenchReport::of)
                            .collect();
                    }
                    r
                })
                .collect(),
            constraints: constraints.map(ConstraintsReport::new),
            surface: None,
            friction: Vec::new(),
            friction_failures: Vec::new(),
            model_failures: Vec::new(),
        }
    }

    /// Whether some model or frictional law has no answer while others are reported.
    pub fn partial(&self) -> bool {
        !self.model_failures.is_empty() || !self.friction_failures.is_empty()
    }

    /// The report of one model, if it was solved.
    pub fn model(&self, m: Model) -> Option<&ModelReport> {
        self.models.iter().find(|r| r.model == m)
    }
}

/// One block of inertances in physical units, row by row: g_ij,ax = ĝ_ij,ax / (|â_i| |x̂_j|)
/// = (ĝ / (â_i² x̂_j²)) · √(â_i² x̂_j²), â the axis `a` of contact i's frame.
fn inertances<T: Scalar, S: Screws<T>>(
    m: &[T],
    frames: &[ContactFrame<T, S>],
    n: usize,
    a: usize,
) -> Vec<Vec<Value>> {
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let r2 = frames[i].norm2[a].clone() * &frames[j].norm2[0];
                    Value::surd(&Surd::over_norm(&m[i * n + j], &r2))
                })
                .collect()
        })
        .collect()
}

/// Δ = Δ̂ / Π |x̂_i|², rational.
fn determinant<T: Scalar, S: Screws<T>>(det: &T, frames: &[ContactFrame<T, S>]) -> Value {
    let mut norms = T::one();
    for f in frames {
        norms *= &f.norm2[0];
    }
    Value::of(&(det.clone() / &norms))
}

/// A contact frame's unit axes (x_i, y_i, z_i), and how y_i was chosen; y_i and z_i zero when
/// they were not built (`tangential` false).
fn unit_axes<T: Scalar, S: Screws<T>>(
    f: &ContactFrame<T, S>,
    tangential: bool,
) -> ([[Value; 3]; 3], TangentRule) {
    let unit = |a: usize| -> [Value; 3] {
        let d = &f.directions[a];
        [0, 1, 2].map(|k| match a == 0 || tangential {
            true => Value::surd(&Surd::over_norm(&d[k], &f.norm2[a])),
            false => Value::of(&T::zero()),
        })
    };
    ([unit(0), unit(1), unit(2)], f.rule)
}

/// Each contact point's velocity in its own frame; along the normal only (the rest zero, no
/// angle) when the tangent axes were not built (`tangential` false).
fn point_velocities<T: Scalar, S: Screws<T>>(
    hats: &[[T; 3]],
    frames: &[ContactFrame<T, S>],
    tangential: bool,
) -> Vec<PointVelocity> {
    hats.iter()
        .zip(frames)
        .map(|(v, f)| match tangential {
            true => point_velocity(v, f),
            false => PointVelocity {
                components: [
                    Value::surd(&Surd::over_norm(&v[0], &f.norm2[0])),
                    Value::of(&T::zero()),
                    Value::of(&T::zero()),
                ],
                angle: None,
            },
        })
        .collect()
}

/// Impulses along the normals as written: P_i = P̂_i |x̂_i|.
fn impulses<T: Scalar, S: Screws<T>>(hats: &[T], frames: &[ContactFrame<T, S>]) -> Vec<Value> {
    hats.iter()
        .zip(frames)
        .map(|(p, f)| Value::surd(&Surd::times_norm(p, &f.norm2[0])))
        .collect()
}

impl ModelReport {
    /// Read out one model's outcome.
    fn new<T: Scalar>(
        model: Model,
        o: &Outcome<T>,
        frames: &[ContactFrame<T>],
        velocities: &dyn Fn(&[[T; 3]]) -> Vec<PointVelocity>,
    ) -> ModelReport {
        ModelReport {
            model,
            impulses: impulses(&o.impulses_hat, frames),
            impulse_multiples: o.impulses_hat.iter().map(Value::of).collect(),
            compression_impulses: match model {
                Model::Newton => None,
                Model::Poisson => Some(impulses(&o.compression_hat, frames)),
            },
            angular_velocity: {
                let w = o.velocity.top();
                [0, 1, 2].map(|k| Value::of(&w[k]))
            },
            velocity: {
                let v = o.velocity.bottom();
                [0, 1, 2].map(|k| Value::of(&v[k]))
            },
            contacts: velocities(&o.after_hat),
            lost_velocity_energy: Value::of(&o.lost_velocity_energy),
            kinetic_energy_loss: Value::of(&o.kinetic_energy_loss),
            constraint_impulses: o.constraint_impulses.iter().map(Value::of).collect(),
            constraint_wrench: None,
            joint_reactions: Vec::new(),
            law: Law::Simultaneous,
            inadmissible: Vec::new(),
            activity: None,
            active: Vec::new(),
            outcome_range: None,
        }
    }
}

impl ConstraintsReport {
    /// Read out the constraints as used: D, U and M_red.
    fn new<T: Scalar>(c: &Constrained<T>) -> ConstraintsReport {
        let screw = |s: &crate::mechanics::screw::Screw<T>| -> [Value; 6] {
            std::array::from_fn(|k| Value::of(&s.0[k]))
        };
        let d = c.dof();
        let m = c.reduced_mass();
        ConstraintsReport {
            free: c.free.iter().map(screw).collect(),
            blocked: c.blocked.iter().map(screw).collect(),
            blocked_derived: c.derived_blocked,
            reduced_mass: (0..d)
                .map(|a| (0..d).map(|b| Value::of(&m[a * d + b])).collect())
                .collect(),
            joints: c
                .joints
                .iter()
                .map(|j| JointReport {
                    kind: j.name(),
                    has_point: j.anchor().is_some(),
                })
                .collect(),
        }
    }
}

/// Velocity components in the unit frame, and the tangential angle (eq. 8, 27).
fn point_velocity<T: Scalar, S: Screws<T>>(
    hat: &[T; 3],
    frame: &ContactFrame<T, S>,
) -> PointVelocity {
    let s: [Surd<T>; 3] = [0, 1, 2].map(|k| Surd::over_norm(&hat[k], &frame.norm2[k]));
    // v_y = a√r, v_z = b√s ⇒ |v_t|² = a²r + b²s = Q, cos α = a√(r/Q), sin α = b√(s/Q): the
    // same for a and b times one power of two, which in floats keeps Q within range (a
    // tangential velocity of 10³⁰⁸ m/s gave Q = ∞ and α = 0 whatever its direction).
    let ab = rescaled(&Vec3::new(
        s[1].coeff.clone(),
        s[2].coeff.clone(),
        T::zero(),
    ));
    let q = ab[0].clone() * &ab[0] * &s[1].radicand + ab[1].clone() * &ab[1] * &s[2].radicand;
    let zero_tangential = q.is_negligible(&T::zero(), 1);
    let angle = if zero_tangential {
        None
    } else {
        let cos = Surd {
            coeff: ab[0].clone(),
            radicand: s[1].radicand.clone() / &q,
        };
        let sin = Surd {
            coeff: ab[1].clone(),
            radicand: s[2].radicand.clone() / &q,
        };
        let (c, si) = (cos.to_f64(), sin.to_f64());
        let mut deg = si.atan2(c).to_degrees();
        if deg < 0.0 {
            deg += 360.0;
        }
        if deg >= 360.0 {
            deg -= 360.0;
        }
        Some(Angle {
            degrees: deg,
            cos: Value::surd(&cos),
            sin: Value::surd(&sin),
        })
    };
    PointVelocity {
        components: [Value::surd(&s[0]), Value::surd(&s[1]), Value::surd(&s[2])],
        angle,
    }
}
