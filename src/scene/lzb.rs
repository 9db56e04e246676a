//! A scene under the LZB law (`[solve] law = "lzb"`, `--law lzb`): each contact's law read from
//! its keys, the impact integrated by [`crate::impact::multiple::solve_lzb`] in f64 (or
//! double-double, [`run_lzb_in`]), and its
//! report.
//!
//! Per contact: `stiffness` K_i (default 1; only the ratios between contacts change the
//! outcome; `"hertz"`: Hertz's (4/3) E* √R* from the shapes and `material`s that touch,
//! [`super::model::hertz`]), `exponent` η_i (default 3/2, Hertz; 1 linear) — Siconos'
//! `MultipleImpactNSL(e, K, η)` — and Stronge's energetic coefficient e_i, read from
//! `k_energetic` when given, else from the contact's `k` (or `k_poisson`), as the energetic
//! restitution of the frictional integration reads it. The scene's numbers must be plain
//! numbers (no symbols); the integration is numerical, so the result is a float (f64, or
//! double-double with `--precision double-double`) whatever the inputs (`--exact` is refused
//! by the command line). Contacts with `mu` > 0 take Coulomb
//! friction along the path; the report then adds each contact's tangential impulse and the
//! energy friction dissipated there (a frictionless report is unchanged).

use crate::impact::multiple::{ContactLaw, Event, LawError, Lzb, Sample, Stats, solve_lzb};
use crate::mechanics::screw::Screws;
use crate::number::Number;
use crate::scalar::{Real, Scalar};

use super::pipeline::{RunError, friction_tolerance, prepare};
use super::schema::ContactSpec;
use super::{Scene, SceneError};

/// The LZB law of every contact of `scene`.
///
/// # Errors
/// A [`SceneError`] naming the contact's key and value: a number with symbols, K ≤ 0, η ≤ 0,
/// e ∉ [0, 1].
pub fn contact_laws(scene: &Scene) -> Result<Vec<ContactLaw>, SceneError> {
    scene
        .contacts
        .iter()
        .enumerate()
        .map(|(i, c)| contact_law(scene, i, c))
        .collect()
}

fn contact_law(scene: &Scene, i: usize, c: &ContactSpec) -> Result<ContactLaw, SceneError> {
    let err = |key: &str, n: &Number, message: String| SceneError {
        file: scene.file.clone(),
        key: format!("contact[{i}].{key}"),
        value: Some(n.text.clone()),
        message,
    };
    let value = |key: &str, n: &Number| -> Result<f64, SceneError> {
        if n.symbols.is_empty() && n.approx.is_finite() {
            Ok(n.approx)
        } else {
            Err(err(
                key,
                n,
                "the LZB law needs a number here (it is integrated numerically)".to_string(),
            ))
        }
    };
    let stiffness = match &c.stiffness {
        Some(n) => value("stiffness", n)?,
        None if c.hertz => {
            return Err(SceneError {
                file: scene.file.clone(),
                key: format!("contact[{i}].stiffness"),
                value: Some("\"hertz\"".to_string()),
                message: "Hertz's stiffness comes from the shapes and materials that touch: \
                          write the scene in the world frame (a `shape` and a `material` for \
                          each body, and the `obstacle` or the bodies the contact joins), or \
                          give `stiffness` as a number"
                    .to_string(),
            });
        }
        None => 1.0,
    };
    let exponent = match &c.exponent {
        Some(n) => value("exponent", n)?,
        None => 1.5,
    };
    let (e_key, e_num) = match &c.k_energetic {
        Some(n) => ("k_energetic", n),
        None => ("k", &c.k_poisson),
    };
    let restitution = value(e_key, e_num)?;
    ContactLaw::new(stiffness, exponent, restitution).map_err(|e| match e {
        LawError::Stiffness { .. } => err(
            "stiffness",
            c.stiffness.as_ref().expect("the default 1 is valid"),
            format!("{e}: give the contact's stiffness K > 0 (only ratios matter)"),
        ),
        LawError::Exponent { .. } => err(
            "exponent",
            c.exponent.as_ref().expect("the default 3/2 is valid"),
            format!("{e}: give η > 0 (1 linear, 1.5 Hertz)"),
        ),
        LawError::Restitution { .. } => err(e_key, e_num, e.to_string()),
    })
}

/// The twist after impact of each body: (name, ω, v_C).
pub type Twists = Vec<(String, [f64; 3], [f64; 3])>;

/// A solved LZB scene: the outcome's numbers, flattened out of the mechanism's screw space.
#[derive(Clone, Debug)]
pub struct LzbReport {
    /// The scene's name.
    pub name: String,
    /// The float type the law was integrated in ([`Scalar::NAME`]: `"f64"`, `"double-double"`).
    pub scalar: &'static str,
    /// The law of every contact.
    pub laws: Vec<ContactLaw>,
    /// v_i⁰ per contact (positive approaching).
    pub before: Vec<f64>,
    /// P_i per contact, along the unit normal.
    pub impulses: Vec<f64>,
    /// v_i after impact.
    pub after: Vec<f64>,
    /// Each body's name and twist after impact (ω, v_C).
    pub twists: Twists,
    /// W_c,i: the energy each contact stored over its compression phases.
    pub work_compression: Vec<f64>,
    /// W_r,i: the energy each contact gave back.
    pub work_expansion: Vec<f64>,
    /// τ_i per contact along its unit tangent axes (none without friction).
    pub tangential: Vec<Vec<f64>>,
    /// ∫ v_it · dτ_i per contact: the energy friction dissipated there.
    pub friction_dissipation: Vec<f64>,
    /// Whether any contact has friction (the report's tangential columns).
    pub friction: bool,
    /// The largest potential energy each contact held.
    pub max_energy: Vec<f64>,
    /// ΔE_c = T⁰ − T.
    pub kinetic_energy_loss: f64,
    /// ΔE_c − Σ (W_c,i − W_r,i + W_f,i).
    pub energy_residual: f64,
    /// The events, in order.
    pub events: Vec<Event>,
    /// Steps and events.
    pub stats: Stats,
    /// The order in which the contacts last ended their expansion.
    pub ending_order: Vec<usize>,
    /// The impulses' estimated error.
    pub error_estimate: f64,
    /// The relative tolerance.
    pub tolerance: f64,
    /// τ at the end of the impact.
    pub end: f64,
    /// The impulse history: the path at every accepted step ([`Sample`]).
    pub samples: Vec<Sample>,
}

/// Solve `scene` under the LZB law, in f64, to the relative tolerance of the scene's
/// `[solve] tolerance`, else ε^(2/3) ([`run_lzb_in`] in another float type).
///
/// # Errors
/// [`RunError`]: the scene's bad input, or the integration's [`crate::impact::multiple::LzbError`].
pub fn run_lzb(scene: &Scene) -> Result<LzbReport, RunError> {
    run_lzb_in::<f64>(scene)
}

/// Solve `scene` under the LZB law in the float type `T` (`f64` or double-double), to the
/// relative tolerance of the scene's `[solve] tolerance`, else ε^(2/3) of `T` (3.7·10⁻¹¹ in
/// f64, 1.3·10⁻²¹ in double-double). The mechanism is built in `T` from the
/// scene's exact numbers; the laws' K, η, e are their `f64` values, taken exactly into `T`.
/// The report's numbers are the outcome's rounded to `f64`.
///
/// # Errors
/// As [`run_lzb`].
pub fn run_lzb_in<T: Real>(scene: &Scene) -> Result<LzbReport, RunError> {
    let laws = contact_laws(scene)?;
    let tolerance = scene.tolerance.unwrap_or_else(friction_tolerance::<T>);
    if scene.system.is_some() {
        let system = scene.system::<T>()?;
        let out = solve_lzb(&system, &laws, tolerance)?;
        let names = super::system_pipeline::body_names(scene);
        Ok(report(scene, out, &names))
    } else {
        let problem = prepare::<T>(scene)?;
        let out = solve_lzb(&problem, &laws, tolerance)?;
        Ok(report(scene, out, &["body".to_string()]))
    }
}

fn report<T: Real, S: Screws<T>>(scene: &Scene, out: Lzb<S, T>, names: &[String]) -> LzbReport {
    let c: Vec<f64> = out
        .velocity
        .components()
        .iter()
        .map(Scalar::to_f64)
        .collect();
    let twists = names
        .iter()
        .enumerate()
        .filter(|(b, _)| 6 * b + 5 < c.len())
        .map(|(b, name)| {
            let at = |k: usize| c[6 * b + k];
            (name.clone(), [at(0), at(1), at(2)], [at(3), at(4), at(5)])
        })
        .collect();
    let f = |x: &[T]| -> Vec<f64> { x.iter().map(Scalar::to_f64).collect() };
    LzbReport {
        name: scene.name.clone(),
        scalar: T::NAME,
        before: f(&out.before),
        ending_order: out.ending_order(),
        friction: out.has_friction(),
        laws: out.laws,
        impulses: f(&out.impulses),
        after: f(&out.after),
        twists,
        work_compression: f(&out.work_compression),
        work_expansion: f(&out.work_expansion),
        tangential: out.tangential.iter().map(|t| f(t)).collect(),
        friction_dissipation: f(&out.friction_dissipation),
        max_energy: f(&out.max_energy),
        kinetic_energy_loss: out.kinetic_energy_loss.to_f64(),
        energy_residual: out.energy_residual.to_f64(),
        events: out.events,
        stats: out.stats,
        error_estimate: out.error_estimate,
        tolerance: out.tolerance,
        end: out.end,
        samples: out.samples,
    }
}

/// A number as the reports print floats: 6 decimals, or scientific below 10⁻⁴ or above 10⁶.
pub(crate) fn num(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 {
        "0".to_string()
    } else if !(1e-4..1e6).contains(&a) {
        format!("{x:.6e}")
    } else {
        let t = format!("{x:.6}");
        let t = t.trim_end_matches('0').trim_end_matches('.');
        t.to_string()
    }
}

impl LzbReport {
    /// The readable report.
    pub fn to_table(&self) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        let n = self.impulses.len();
        let _ = writeln!(s, "{} — {} (lzb)\n", self.name, self.scalar);
        let _ = writeln!(
            s,
            "LZB law (Liu, Zhao & Brogliato 2008): per contact stiffness K, exponent η, \
             energetic restitution e."
        );
        let _ = writeln!(
            s,
            "Impulses along the unit normals; velocities positive approaching.\n"
        );
        if self.friction {
            let _ = writeln!(
                s,
                "Coulomb friction along the path (Zhao, Liu & Brogliato 2009): τ along the unit \
                 tangents (in the plane, the contact's y sense), opposing the slip; W_f the \
                 energy friction dissipated.\n"
            );
        }
        let mut rows = vec![vec![
            String::new(),
            "K".to_string(),
            "η".to_string(),
            "e".to_string(),
            "v⁰ [m/s]".to_string(),
            "P [N s]".to_string(),
            "v [m/s]".to_string(),
            "E_max [J]".to_string(),
            "W_c [J]".to_string(),
            "W_r [J]".to_string(),
            "dissipated [J]".to_string(),
        ]];
        if self.friction {
            rows[0].push("τ [N s]".to_string());
            rows[0].push("W_f [J]".to_string());
        }
        for i in 0..n {
            let l = &self.laws[i];
            rows.push(vec![
                format!("A{}", i + 1),
                num(l.stiffness),
                num(l.exponent),
                num(l.restitution),
                num(self.before[i]),
                num(self.impulses[i]),
                num(self.after[i]),
                num(self.max_energy[i]),
                num(self.work_compression[i]),
                num(self.work_expansion[i]),
                num(self.work_compression[i] - self.work_expansion[i]),
            ]);
            if self.friction {
                let t: Vec<String> = self.tangential[i].iter().map(|x| num(*x)).collect();
                let row = rows.last_mut().expect("just pushed");
                row.push(match t.len() {
                    0 => "—".to_string(),
                    1 => t[0].clone(),
                    _ => format!("({})", t.join(", ")),
                });
                row.push(num(self.friction_dissipation[i]));
            }
        }
        let widths: Vec<usize> = (0..rows[0].len())
            .map(|k| rows.iter().map(|r| r[k].chars().count()).max().unwrap_or(0))
            .collect();
        for r in &rows {
            let mut line = String::from(" ");
            for (k, cell) in r.iter().enumerate() {
                let pad = widths[k] - cell.chars().count();
                line.push_str("  ");
                line.push_str(&" ".repeat(pad));
                line.push_str(cell);
            }
            let _ = writeln!(s, "{}", line.trim_end());
        }
        let _ = writeln!(s, "\nAfter impact:");
        for (name, w, v) in &self.twists {
            let _ = writeln!(
                s,
                "  {name}: ω = [{}, {}, {}] rad/s, v_C = [{}, {}, {}] m/s",
                num(w[0]),
                num(w[1]),
                num(w[2]),
                num(v[0]),
                num(v[1]),
                num(v[2])
            );
        }
        let dissipated: f64 = (0..n)
            .map(|i| self.work_compression[i] - self.work_expansion[i])
            .sum();
        if self.friction {
            let friction: f64 = self.friction_dissipation.iter().sum();
            let _ = writeln!(
                s,
                "  ΔE_c [J] = {} (dissipated at the contacts: {} normal, {} by friction)",
                num(self.kinetic_energy_loss),
                num(dissipated),
                num(friction)
            );
        } else {
            let _ = writeln!(
                s,
                "  ΔE_c [J] = {} (dissipated at the contacts: {})",
                num(self.kinetic_energy_loss),
                num(dissipated)
            );
        }
        let order: Vec<String> = self
            .ending_order
            .iter()
            .map(|i| format!("A{}", i + 1))
            .collect();
        let _ = writeln!(
            s,
            "\nIntegration: {} steps ({} rejected), {} events; contacts ended in the order {}; \
             tolerance {:.1e}, impulse error estimate {:.1e} N s.",
            self.stats.accepted,
            self.stats.rejected,
            self.stats.events,
            order.join(", "),
            self.tolerance,
            self.error_estimate
        );
        s
    }
}
