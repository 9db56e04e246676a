//! What a solve reports, in the units of the paper: a scalar-free readout of an [`Impact`]
//! and its [`Outcome`]s, rendered as a table or as JSON.
//!
//! Every value carries its f64 approximation and, in exact mode, its exact text: `p/q`, or
//! `c*sqrt(r)` when a non-unit axis puts a norm into it (an impulse P_i = P̂_i |n_i|, a
//! velocity component v_ix = v̂_ix / |n_i|, see [`crate::mechanics::contact`]). Angles are the one
//! exception: α = atan2(v_z, v_y) is transcendental, so it is a number in both modes (its
//! cosine and sine are exact surds).
//!
//! The JSON keys are a public contract (README, "JSON report").

use serde_json::{Map, Value as Json, json};

use crate::mechanics::constraint::Constrained;
use crate::mechanics::contact::{ContactFrame, Surd, TangentRule};
use crate::impact::restitution::Model;
use crate::scalar::Scalar;
use crate::impact::solve::{Impact, Outcome};

/// One reported number: f64 always, exact text in exact mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Value {
    /// The value (rounded, in exact mode).
    pub f64: f64,
    /// `p/q` or `c*sqrt(r)`, in exact mode; an expression in symbolic mode.
    pub exact: Option<String>,
    /// The LaTeX form, in symbolic mode.
    pub latex: Option<String>,
}

impl Value {
    /// The value of `x`: f64, and its exact text for exact types.
    pub fn of<T: Scalar>(x: &T) -> Self {
        Value {
            f64: x.to_f64(),
            exact: x.exact_text(),
            latex: x.latex_text(),
        }
    }

    /// The value of the surd `s`.
    pub fn surd<T: Scalar>(s: &Surd<T>) -> Self {
        Value {
            f64: s.to_f64(),
            exact: s.exact_text(),
            latex: s.latex_text(),
        }
    }

    /// A number without exact form (an angle, a float result).
    pub fn float(x: f64) -> Self {
        Value {
            f64: x,
            exact: None,
            latex: None,
        }
    }

    /// The JSON value: the exact string in exact mode, a number otherwise.
    pub fn json(&self) -> Json {
        match &self.exact {
            Some(t) => Json::String(t.clone()),
            None => json_f64(self.f64),
        }
    }

    /// Readable text: the exact value (with ≈ decimals when not a short decimal), or the f64.
    pub fn text(&self) -> String {
        match &self.exact {
            Some(t) if self.f64.is_nan() => t.clone(),
            Some(t) if t.parse::<f64>().is_err() || t.len() > 14 => {
                format!("{} ≈ {}", t, fmt_f64(self.f64))
            }
            Some(t) => t.clone(),
            None => fmt_f64(self.f64),
        }
    }
}

fn json_f64(x: f64) -> Json {
    serde_json::Number::from_f64(x)
        .map(Json::Number)
        .unwrap_or(Json::Null)
}

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
        // g_ij,ax = ĝ_ij,ax / (|â_i| |x̂_j|) = (ĝ / (â_i² x̂_j²)) · √(â_i² x̂_j²).
        let inert = |m: &[T], a: usize| -> Vec<Vec<Value>> {
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
        };
        // Δ = Δ̂ / Π |x̂_i|², rational.
        let mut norms = T::one();
        for f in frames {
            norms *= &f.norm2[0];
        }
        let det = Value::of(&(impact.det_hat().clone() / &norms));
        let frames_out = frames
            .iter()
            .map(|f| {
                let unit = |a: usize| -> [Value; 3] {
                    let d = f.axes[a].top();
                    [0, 1, 2].map(|k| Value::surd(&Surd::over_norm(&d[k], &f.norm2[a])))
                };
                ([unit(0), unit(1), unit(2)], f.rule)
            })
            .collect();
        let contacts_before = impact
            .before_hat()
            .iter()
            .zip(frames)
            .map(|(v, f)| point_velocity(v, f))
            .collect();
        let models = outcomes
            .iter()
            .map(|(m, o)| ModelReport {
                model: *m,
                impulses: o
                    .impulses_hat
                    .iter()
                    .zip(frames)
                    .map(|(p, f)| Value::surd(&Surd::times_norm(p, &f.norm2[0])))
                    .collect(),
                impulse_multiples: o.impulses_hat.iter().map(Value::of).collect(),
                compression_impulses: match m {
                    Model::Newton => None,
                    Model::Poisson => Some(
                        o.compression_hat
                            .iter()
                            .zip(frames)
                            .map(|(p, f)| Value::surd(&Surd::times_norm(p, &f.norm2[0])))
                            .collect(),
                    ),
                },
                angular_velocity: {
                    let w = o.velocity.top();
                    [0, 1, 2].map(|k| Value::of(&w[k]))
                },
                velocity: {
                    let v = o.velocity.bottom();
                    [0, 1, 2].map(|k| Value::of(&v[k]))
                },
                contacts: o
                    .after_hat
                    .iter()
                    .zip(frames)
                    .map(|(v, f)| point_velocity(v, f))
                    .collect(),
                lost_velocity_energy: Value::of(&o.lost_velocity_energy),
                kinetic_energy_loss: Value::of(&o.kinetic_energy_loss),
                constraint_impulses: o.constraint_impulses.iter().map(Value::of).collect(),
            })
            .collect();
        let screw = |s: &crate::mechanics::screw::Screw<T>| -> [Value; 6] {
            std::array::from_fn(|k| Value::of(&s.0[k]))
        };
        let constraints = constraints.map(|c| {
            let d = c.dof();
            let m = c.reduced_mass();
            ConstraintsReport {
                free: c.free.iter().map(screw).collect(),
                blocked: c.blocked.iter().map(screw).collect(),
                blocked_derived: c.derived_blocked,
                reduced_mass: (0..d)
                    .map(|a| (0..d).map(|b| Value::of(&m[a * d + b])).collect())
                    .collect(),
            }
        });
        Report {
            scene: scene.to_string(),
            scalar: T::NAME,
            effects,
            inertance: inert(impact.g_hat(), 0),
            inertance_yx: inert(impact.g_yx_hat(), 1),
            inertance_zx: inert(impact.g_zx_hat(), 2),
            det,
            frames: frames_out,
            contacts_before,
            models,
            constraints,
            surface: None,
        }
    }

    /// The report of one model, if it was solved.
    pub fn model(&self, m: Model) -> Option<&ModelReport> {
        self.models.iter().find(|r| r.model == m)
    }

    /// The JSON report (keys documented in the README).
    pub fn to_json(&self) -> Json {
        let mat = |m: &Vec<Vec<Value>>| -> Json {
            Json::Array(
                m.iter()
                    .map(|r| Json::Array(r.iter().map(Value::json).collect()))
                    .collect(),
            )
        };
        let vec = |v: &[Value]| -> Json { Json::Array(v.iter().map(Value::json).collect()) };
        let mut models = Map::new();
        for r in &self.models {
            let mut o = Map::new();
            o.insert("impulses".into(), vec(&r.impulses));
            o.insert("impulses_per_normal".into(), vec(&r.impulse_multiples));
            if let Some(c) = &r.compression_impulses {
                o.insert("compression_impulses".into(), vec(c));
            }
            o.insert("velocity".into(), vec(&r.velocity));
            o.insert("angular_velocity".into(), vec(&r.angular_velocity));
            o.insert(
                "contacts".into(),
                Json::Array(
                    self.contacts_before
                        .iter()
                        .zip(&r.contacts)
                        .map(|(b, a)| {
                            json!({
                                "velocity_before": vec(&b.components),
                                "velocity_after": vec(&a.components),
                                "angle_before_deg": b.angle.as_ref().map(|x| json_f64(x.degrees)),
                                "angle_after_deg": a.angle.as_ref().map(|x| json_f64(x.degrees)),
                            })
                        })
                        .collect(),
                ),
            );
            o.insert("lost_velocity_energy".into(), r.lost_velocity_energy.json());
            o.insert("kinetic_energy_loss".into(), r.kinetic_energy_loss.json());
            if self.constraints.is_some() {
                o.insert("constraint_impulses".into(), vec(&r.constraint_impulses));
            }
            models.insert(r.model.name().into(), Json::Object(o));
        }
        let mut top = json!({
            "scene": self.scene,
            "scalar": self.scalar,
            "effects": self.effects,
            "inertance": mat(&self.inertance),
            "inertance_yx": mat(&self.inertance_yx),
            "inertance_zx": mat(&self.inertance_zx),
            "det": self.det.json(),
            "frames": self.frames.iter().map(|(axes, rule)| json!({
                "x": vec(&axes[0]), "y": vec(&axes[1]), "z": vec(&axes[2]),
                "tangent": match rule {
                    TangentRule::Given => "given".to_string(),
                    TangentRule::Velocity => "velocity".to_string(),
                    TangentRule::Fallback(k) => format!("fallback-{}", ["x", "y", "z"][*k]),
                },
            })).collect::<Vec<_>>(),
            "models": Json::Object(models),
        });
        if let (Some((f, grad)), Some(obj)) = (&self.surface, top.as_object_mut()) {
            obj.insert("surface".into(), json!({ "f": f, "gradient": grad }));
        }
        if let (Some(c), Some(obj)) = (&self.constraints, top.as_object_mut()) {
            obj.insert(
                "constraints".into(),
                json!({
                    "free": c.free.iter().map(|s| vec(s)).collect::<Vec<_>>(),
                    "blocked": c.blocked.iter().map(|s| vec(s)).collect::<Vec<_>>(),
                    "blocked_derived": c.blocked_derived,
                    "reduced_mass": mat(&c.reduced_mass),
                }),
            );
        }
        top
    }

    /// A readable table: models side by side, SI units.
    pub fn to_table(&self) -> String {
        let mut rows: Vec<(String, Vec<String>)> = Vec::new();
        let n = self.inertance.len();
        let header: Vec<String> = self
            .models
            .iter()
            .map(|m| m.model.name().to_string())
            .collect();
        let each = |f: &dyn Fn(&ModelReport) -> String| -> Vec<String> {
            self.models.iter().map(f).collect()
        };
        for i in 0..n {
            rows.push((format!("P{} [N s]", i + 1), each(&|m| m.impulses[i].text())));
        }
        for i in 0..n {
            if self.models.iter().any(|m| m.compression_impulses.is_some()) {
                rows.push((
                    format!("P{}c [N s]", i + 1),
                    each(&|m| {
                        m.compression_impulses
                            .as_ref()
                            .map_or("—".into(), |c| c[i].text())
                    }),
                ));
            }
        }
        let axes = ["x", "y", "z"];
        for (k, a) in axes.iter().enumerate() {
            rows.push((
                format!("ω{a} [rad/s]"),
                each(&|m| m.angular_velocity[k].text()),
            ));
        }
        for (k, a) in axes.iter().enumerate() {
            rows.push((format!("vC{a} [m/s]"), each(&|m| m.velocity[k].text())));
        }
        for i in 0..n {
            for (k, a) in axes.iter().enumerate() {
                rows.push((
                    format!("v{}{a} [m/s]", i + 1),
                    each(&|m| m.contacts[i].components[k].text()),
                ));
            }
            rows.push((
                format!("α{} [deg]", i + 1),
                each(&|m| {
                    m.contacts[i]
                        .angle
                        .as_ref()
                        .map_or("—".into(), |x| fmt_f64(x.degrees))
                }),
            ));
        }
        if let Some(c) = &self.constraints {
            for a in 0..c.blocked.len() {
                rows.push((
                    format!("q{} [N s]", a + 1),
                    each(&|m| m.constraint_impulses[a].text()),
                ));
            }
        }
        rows.push(("E_p [J]".into(), each(&|m| m.lost_velocity_energy.text())));
        rows.push(("ΔE_c [J]".into(), each(&|m| m.kinetic_energy_loss.text())));

        let mut out = format!(
            "{} — {} ({})\n\n",
            self.scene,
            self.scalar,
            self.effects.join(", ")
        );
        out += "Inertances G = [g_ij,xx] [1/kg]:\n";
        for r in &self.inertance {
            out += &format!(
                "  {}\n",
                r.iter().map(Value::text).collect::<Vec<_>>().join("  ")
            );
        }
        out += &format!("Δ = det G = {}\n", self.det.text());
        if let Some((f, g)) = &self.surface {
            out += &format!(
                "Surface: f = {f} = 0, ∇f = ({}, {}, {})\n",
                g[0], g[1], g[2]
            );
        }
        if let Some(c) = &self.constraints {
            let screws = |l: &[[Value; 6]]| -> String {
                l.iter()
                    .map(|s| {
                        format!(
                            "[{}]",
                            s.iter().map(Value::text).collect::<Vec<_>>().join(", ")
                        )
                    })
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            out += &format!(
                "Constraints: {} degree(s) of freedom\n  D = {}\n  U = {}{}\n",
                c.free.len(),
                screws(&c.free),
                screws(&c.blocked),
                if c.blocked_derived {
                    " (derived: η-orthogonal complement of D)"
                } else {
                    ""
                }
            );
            let m = c
                .reduced_mass
                .iter()
                .map(|r| {
                    format!(
                        "[{}]",
                        r.iter().map(Value::text).collect::<Vec<_>>().join(", ")
                    )
                })
                .collect::<Vec<_>>()
                .join(" ");
            out += &format!("  M_red = Dᵀ η M D = {m}\n");
        }
        out += "\nBefore impact:\n";
        for (i, b) in self.contacts_before.iter().enumerate() {
            out += &format!(
                "  A{}: v = ({}, {}, {}) m/s, α⁰ = {}\n",
                i + 1,
                b.components[0].text(),
                b.components[1].text(),
                b.components[2].text(),
                b.angle
                    .as_ref()
                    .map_or("— (no tangential velocity)".into(), |x| format!(
                        "{}°",
                        fmt_f64(x.degrees)
                    ))
            );
        }
        out += "\nAfter impact:\n";
        let w0 = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(0);
        let cols: Vec<usize> = (0..header.len())
            .map(|c| {
                rows.iter()
                    .map(|r| r.1[c].chars().count())
                    .chain([header[c].len()])
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let line = |name: &str, cells: &[String]| -> String {
            let mut s = format!("  {name}{}", " ".repeat(w0 - name.chars().count()));
            for (c, cell) in cells.iter().enumerate() {
                s += &format!("  {}{}", " ".repeat(cols[c] - cell.chars().count()), cell);
            }
            s + "\n"
        };
        out += &line("", &header);
        for (name, cells) in &rows {
            out += &line(name, cells);
        }
        out
    }
}

/// Velocity components in the unit frame, and the tangential angle (eq. 8, 27).
fn point_velocity<T: Scalar>(hat: &[T; 3], frame: &ContactFrame<T>) -> PointVelocity {
    let s: [Surd<T>; 3] = [0, 1, 2].map(|k| Surd::over_norm(&hat[k], &frame.norm2[k]));
    // v_y = a√r, v_z = b√s ⇒ |v_t|² = a²r + b²s = Q, cos α = a√(r/Q), sin α = b√(s/Q).
    let q = s[1].coeff.clone() * &s[1].coeff * &s[1].radicand
        + s[2].coeff.clone() * &s[2].coeff * &s[2].radicand;
    let zero_tangential = q.is_negligible(&T::zero(), 1);
    let angle = if zero_tangential {
        None
    } else {
        let cos = Surd {
            coeff: s[1].coeff.clone(),
            radicand: s[1].radicand.clone() / &q,
        };
        let sin = Surd {
            coeff: s[2].coeff.clone(),
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
