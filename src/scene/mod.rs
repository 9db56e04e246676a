//! Scene files (TOML): the public schema, read exactly as written.
//!
//! ```toml
//! name = "planar bar on two supports"
//! [body]
//! mass = 1
//! inertia = [12, 1.6, 12]          # central principal moments Jx, Jy, Jz
//! velocity = [3, 2, 0]             # v_C before impact, body axes
//! angular_velocity = [0, 0, 0.4]   # omega before impact
//! [[contact]]
//! point = [0, -2, 0]
//! normal = [1, 0, 0]               # outward; need not be unit
//! k = 0.3                          # or k_newton = .., k_poisson = ..
//! [[contact]]
//! point = [0, 4, 0]
//! normal = [1, 0, 0]
//! tangent = [0, 1, 0]              # optional axis y_i
//! k = 0.2
//! [solve]
//! models = ["newton", "poisson"]   # either or both
//! ```
//!
//! Every number may be a TOML integer or float, or a string holding a fraction or an
//! expression (`"1/3"`, `"2/sqrt(5)"`, `"cos(30 deg)"`, see [`crate::number`]). The raw text
//! is kept, so in exact mode `0.1` is exactly 1/10; an irrational expression is refused in
//! exact mode and evaluated in floating point otherwise.
//!
//! **Symbols.** Read with [`Scene::load_with`] (as `inertance derive --symbols m,k1,…` does), a
//! value may be an expression in the declared symbols (`mass = "m"`, `point = [0, "-a", 0]`,
//! `normal = ["cos(theta)", "sin(theta)", 0]`); such a scene runs only in the symbolic scalar
//! ([`crate::scalar::symbolic::RatFun`]), and the range checks (mass > 0, k ∈ [0, 1]) are left to the
//! reader of the derived formulas. Undeclared names are errors, so a typo is not a symbol.
//!
//! Keys are addressed as paths, `body.mass`, `contact[1].k` (contacts counted from 0), both
//! in error messages and in [`set_value`], which overrides one value of a scene.

pub mod pipeline;

use std::fmt;

use num_traits::Signed;
use toml_edit::{DocumentMut, Item, Table, TableLike, Value};

use crate::mechanics::body::RigidBody;
use crate::mechanics::constraint::Joint;
use crate::mechanics::contact::Contact;
use crate::number::{Number, parse_number_with};
use crate::impact::restitution::Model;
use crate::scalar::Scalar;
use crate::mechanics::screw::{Screw, Vec3, norm2};
use crate::impact::problem::{InvalidProblem, Problem, Reason};
use crate::mechanics::surface::{Surface, SurfaceError};

/// A scene that failed to read: which file, which key, which value, what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// The file (or `<derivation>#case` for embedded scenes).
    pub file: String,
    /// The key path, e.g. `contact[1].k`; empty for whole-file problems.
    pub key: String,
    /// The offending value as written, if any.
    pub value: Option<String>,
    /// What is wrong, and what to do about it.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if !self.key.is_empty() {
            write!(f, ": key `{}`", self.key)?;
        }
        if let Some(v) = &self.value {
            write!(f, " = {v}")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for SceneError {}

/// One contact of a scene, numbers as written.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactSpec {
    /// A_i.
    pub point: [Number; 3],
    /// The outward normal; `None` when it comes from the `[surface]` (∇f at the point).
    pub normal: Option<[Number; 3]>,
    /// The imposed axis y_i.
    pub tangent: Option<[Number; 3]>,
    /// k_i^N.
    pub k_newton: Number,
    /// k_i^P.
    pub k_poisson: Number,
}

/// The kinds of joint a scene may declare (see [`crate::mechanics::constraint::Joint`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// `kind = "revolute"`: `point`, `axis`.
    Revolute,
    /// `kind = "prismatic"`: `axis`.
    Prismatic,
    /// `kind = "cylindrical"`: `point`, `axis`.
    Cylindrical,
    /// `kind = "spherical"`: `point`.
    Spherical,
    /// `kind = "planar"`: `normal`.
    Planar,
}

impl JointKind {
    const NAMES: [(&'static str, JointKind); 5] = [
        ("revolute", JointKind::Revolute),
        ("prismatic", JointKind::Prismatic),
        ("cylindrical", JointKind::Cylindrical),
        ("spherical", JointKind::Spherical),
        ("planar", JointKind::Planar),
    ];

    /// The vector keys this kind needs, besides `kind`.
    fn keys(self) -> &'static [&'static str] {
        match self {
            JointKind::Revolute | JointKind::Cylindrical => &["point", "axis"],
            JointKind::Prismatic => &["axis"],
            JointKind::Spherical => &["point"],
            JointKind::Planar => &["normal"],
        }
    }
}

/// One `[[constraints.joint]]` table.
#[derive(Clone, Debug, PartialEq)]
pub struct JointSpec {
    /// Its kind.
    pub kind: JointKind,
    /// Its vectors, in the order of the kind's keys (`point`, `axis` / `normal`).
    pub vectors: Vec<[Number; 3]>,
}

/// A `[surface]` effect: the body's surface f(x, y, z) = 0 in body axes (f < 0 inside, so
/// ∇f points outward).
#[derive(Clone, Debug)]
pub struct SurfaceSpec {
    /// f as written.
    pub text: String,
    /// f parsed, with its symbolic gradient.
    pub surface: Surface,
}

impl PartialEq for SurfaceSpec {
    fn eq(&self, other: &Self) -> bool {
        self.text == other.text
    }
}

/// A `[constraints]` effect, as written.
#[derive(Clone, Debug, PartialEq)]
pub enum ConstraintsSpec {
    /// The paper's form: the free screws (columns of D, eq. 78) and optionally the blocked
    /// ones (columns of U, eq. 75), each [ω; v] or [direction; moment].
    Screws {
        /// D.
        free: Vec<[Number; 6]>,
        /// U, if given.
        blocked: Option<Vec<[Number; 6]>>,
    },
    /// Joints; D is the union of their free screws, U derived.
    Joints(Vec<JointSpec>),
}

/// A scene, validated, with every number as written (exact value when rational, f64 always).
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Where it came from, for messages.
    pub file: String,
    /// Its `name`, or the file name.
    pub name: String,
    /// m.
    pub mass: Number,
    /// (J_x, J_y, J_z).
    pub inertia: [Number; 3],
    /// v_C⁰.
    pub velocity: [Number; 3],
    /// ω⁰.
    pub angular_velocity: [Number; 3],
    /// The contacts.
    pub contacts: Vec<ContactSpec>,
    /// The restitution models asked for, in the order given.
    pub models: Vec<Model>,
    /// The `[constraints]` effect, if declared.
    pub constraints: Option<ConstraintsSpec>,
    /// The `[surface]` effect, if declared.
    pub surface: Option<SurfaceSpec>,
}

impl Scene {
    /// Read and validate the scene file at `path`.
    pub fn load(path: &std::path::Path) -> Result<Scene, SceneError> {
        Scene::load_with(path, &[])
    }

    /// As [`Scene::load`], with values allowed to name the `symbols` (for `inertance derive`):
    /// such a value runs only in the symbolic scalar.
    pub fn load_with(path: &std::path::Path, symbols: &[String]) -> Result<Scene, SceneError> {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| SceneError {
            file: file.clone(),
            key: String::new(),
            value: None,
            message: format!("cannot read the file: {e}"),
        })?;
        Scene::parse_with(&text, &file, symbols)
    }

    /// Parse and validate scene text; `file` names it in messages.
    pub fn parse(text: &str, file: &str) -> Result<Scene, SceneError> {
        Scene::parse_with(text, file, &[])
    }

    /// As [`Scene::parse`], with values allowed to name the `symbols`.
    pub fn parse_with(text: &str, file: &str, symbols: &[String]) -> Result<Scene, SceneError> {
        let doc = parse_document(text, file)?;
        Scene::from_document_with(&doc, file, symbols)
    }

    /// Validate a parsed document.
    pub fn from_document(doc: &DocumentMut, file: &str) -> Result<Scene, SceneError> {
        Scene::from_document_with(doc, file, &[])
    }

    /// As [`Scene::from_document`], with values allowed to name the `symbols`.
    pub fn from_document_with(
        doc: &DocumentMut,
        file: &str,
        symbols: &[String],
    ) -> Result<Scene, SceneError> {
        let r = Reader { file, symbols };
        let root = doc.as_table();
        r.only_keys(root, "", TOP_KEYS)?;
        let name = match root.get("name") {
            None => file.rsplit('/').next().unwrap_or(file).to_string(),
            Some(item) => r.string(item, "name")?,
        };
        if let Some(item) = root.get("description") {
            r.string(item, "description")?;
        }
        let body = r.table(root, "body", "")?;
        r.only_keys(
            body,
            "body",
            &["mass", "inertia", "velocity", "angular_velocity"],
        )?;
        let mass = r.number(r.get(body, "mass", "body")?, "body.mass")?;
        r.positive(&mass, "body.mass", "a mass must be positive")?;
        let inertia = r.triple(r.get(body, "inertia", "body")?, "body.inertia")?;
        for (i, j) in inertia.iter().enumerate() {
            r.positive(
                j,
                &format!("body.inertia[{i}]"),
                "central principal moments must be positive",
            )?;
        }
        let velocity = r.triple(r.get(body, "velocity", "body")?, "body.velocity")?;
        let angular_velocity = r.triple(
            r.get(body, "angular_velocity", "body")?,
            "body.angular_velocity",
        )?;

        let contacts = match root.get("contact") {
            Some(Item::ArrayOfTables(arr)) => arr
                .iter()
                .enumerate()
                .map(|(i, t)| r.contact(t, i))
                .collect::<Result<Vec<_>, _>>()?,
            Some(other) => {
                return Err(r.err("contact", Some(short(other)), "must be [[contact]] tables"));
            }
            None => Vec::new(),
        };
        if contacts.is_empty() {
            return Err(r.err("contact", None, "a scene needs at least one [[contact]]"));
        }

        let models = match root.get("solve") {
            None => Model::ALL.to_vec(),
            Some(item) => {
                let t = item
                    .as_table()
                    .ok_or_else(|| r.err("solve", Some(short(item)), "must be a table: [solve]"))?;
                r.only_keys(t, "solve", &["models"])?;
                match t.get("models") {
                    None => Model::ALL.to_vec(),
                    Some(m) => r.models(m, "solve.models")?,
                }
            }
        };
        let constraints = match root.get("constraints") {
            None => None,
            Some(item) => Some(r.constraints(item)?),
        };
        let surface = match root.get("surface") {
            None => None,
            Some(item) => Some(r.surface(item)?),
        };
        Ok(Scene {
            file: file.to_string(),
            name,
            mass,
            inertia,
            velocity,
            angular_velocity,
            contacts,
            models,
            constraints,
            surface,
        })
    }

    /// The effects the scene declares, in report order.
    pub fn effects(&self, models: &[Model]) -> Vec<String> {
        let mut e: Vec<String> = Vec::new();
        if self.constraints.is_some() {
            e.push("constraints".into());
        }
        if self.surface.is_some() {
            e.push("surface".into());
        }
        e.extend(models.iter().map(|m| m.name().to_string()));
        e
    }

    /// Whether the scene can run in exact rationals: every number rational, and the surface
    /// (if any) exact at its contact points.
    pub fn is_rational(&self) -> bool {
        self.numbers().all(|(_, n)| n.exact.is_ok())
            && self.problem::<crate::scalar::Exact>().is_ok()
    }

    /// Every number with its key path.
    pub fn numbers(&self) -> impl Iterator<Item = (String, &Number)> {
        let mut v: Vec<(String, &Number)> = vec![("body.mass".into(), &self.mass)];
        let triples = [
            ("body.inertia", &self.inertia),
            ("body.velocity", &self.velocity),
            ("body.angular_velocity", &self.angular_velocity),
        ];
        for (k, t) in triples {
            for (i, n) in t.iter().enumerate() {
                v.push((format!("{k}[{i}]"), n));
            }
        }
        for (c, spec) in self.contacts.iter().enumerate() {
            for (i, n) in spec.point.iter().enumerate() {
                v.push((format!("contact[{c}].point[{i}]"), n));
            }
            for (i, n) in spec.normal.iter().flatten().enumerate() {
                v.push((format!("contact[{c}].normal[{i}]"), n));
            }
            if let Some(t) = &spec.tangent {
                for (i, n) in t.iter().enumerate() {
                    v.push((format!("contact[{c}].tangent[{i}]"), n));
                }
            }
            v.push((format!("contact[{c}].k_newton"), &spec.k_newton));
            v.push((format!("contact[{c}].k_poisson"), &spec.k_poisson));
        }
        match &self.constraints {
            None => {}
            Some(ConstraintsSpec::Screws { free, blocked }) => {
                let lists = [("free", Some(free)), ("blocked", blocked.as_ref())];
                for (name, list) in lists {
                    for (i, screw) in list.into_iter().flatten().enumerate() {
                        for (k, n) in screw.iter().enumerate() {
                            v.push((format!("constraints.{name}[{i}][{k}]"), n));
                        }
                    }
                }
            }
            Some(ConstraintsSpec::Joints(joints)) => {
                for (j, joint) in joints.iter().enumerate() {
                    for (key, vec) in joint.kind.keys().iter().zip(&joint.vectors) {
                        for (k, n) in vec.iter().enumerate() {
                            v.push((format!("constraints.joint[{j}].{key}[{k}]"), n));
                        }
                    }
                }
            }
        }
        v.into_iter()
    }

    /// The problem in the scalar type `T`. Exact types take each number's exact value and
    /// refuse irrational ones (naming the key and the value); floats take the rounded value.
    pub fn problem<T: Scalar>(&self) -> Result<Problem<T>, SceneError> {
        let num = |n: &Number, key: &str| -> Result<T, SceneError> { self.value::<T>(n, key) };
        let vec3 = |t: &[Number; 3], key: &str| -> Result<Vec3<T>, SceneError> {
            Ok(Vec3::new(
                num(&t[0], &format!("{key}[0]"))?,
                num(&t[1], &format!("{key}[1]"))?,
                num(&t[2], &format!("{key}[2]"))?,
            ))
        };
        let body = RigidBody {
            mass: num(&self.mass, "body.mass")?,
            inertia: vec3(&self.inertia, "body.inertia")?,
        };
        let velocity = Screw::new(
            vec3(&self.angular_velocity, "body.angular_velocity")?,
            vec3(&self.velocity, "body.velocity")?,
        );
        let mut contacts = Vec::with_capacity(self.contacts.len());
        for (i, c) in self.contacts.iter().enumerate() {
            let key = |k: &str| format!("contact[{i}].{k}");
            let point = vec3(&c.point, &key("point"))?;
            let normal = match (&c.normal, &self.surface) {
                (Some(n), _) => vec3(n, &key("normal"))?,
                (None, Some(surface)) => self.surface_normal(surface, &point, c, i)?,
                (None, None) => {
                    return Err(self.error(
                        &key("normal"),
                        None,
                        "missing: give the outward normal, or declare a [surface] to take it from",
                    ));
                }
            };
            contacts.push(Contact {
                point,
                normal,
                tangent: match &c.tangent {
                    Some(t) => Some(vec3(t, &key("tangent"))?),
                    None => None,
                },
                k_newton: num(&c.k_newton, &key("k_newton"))?,
                k_poisson: num(&c.k_poisson, &key("k_poisson"))?,
            });
        }
        Problem::new(body, velocity, contacts).map_err(|e| self.invalid(e))
    }

    /// A problem the validated constructor refused (what the reader's own checks let
    /// through: a tangent not perpendicular to its normal), as an error naming the key.
    fn invalid(&self, e: InvalidProblem) -> SceneError {
        let message = match &e.reason {
            Reason::NotPerpendicular { dot } => format!(
                "not perpendicular to the normal (n·y = {dot}); give a tangent in the contact \
                 plane or omit it to follow §12"
            ),
            reason => reason.to_string(),
        };
        self.error(&e.field.to_string(), None, &message)
    }
}

/// The free screws, the blocked screws if given, and for each free screw the key that
/// declared it (for messages), in the scalar type `T`.
pub type ConstraintScrews<T> = (Vec<Screw<T>>, Option<Vec<Screw<T>>>, Vec<String>);

impl Scene {
    /// The declared constraints in the scalar type `T` (`None` for a free body).
    pub fn constraint_screws<T: Scalar>(&self) -> Result<Option<ConstraintScrews<T>>, SceneError> {
        let num = |n: &Number, key: String| -> Result<T, SceneError> { self.value::<T>(n, &key) };
        let screw = |c: &[Number; 6], key: &str| -> Result<Screw<T>, SceneError> {
            let mut out = Vec::with_capacity(6);
            for (k, n) in c.iter().enumerate() {
                out.push(num(n, format!("{key}[{k}]"))?);
            }
            let top = Vec3::new(out[0].clone(), out[1].clone(), out[2].clone());
            let bottom = Vec3::new(out[3].clone(), out[4].clone(), out[5].clone());
            Ok(Screw::new(top, bottom))
        };
        match &self.constraints {
            None => Ok(None),
            Some(ConstraintsSpec::Screws { free, blocked }) => {
                let keys: Vec<String> = (0..free.len())
                    .map(|i| format!("constraints.free[{i}]"))
                    .collect();
                let d = free
                    .iter()
                    .zip(&keys)
                    .map(|(c, k)| screw(c, k))
                    .collect::<Result<Vec<_>, _>>()?;
                let u = match blocked {
                    None => None,
                    Some(b) => Some(
                        b.iter()
                            .enumerate()
                            .map(|(i, c)| screw(c, &format!("constraints.blocked[{i}]")))
                            .collect::<Result<Vec<_>, _>>()?,
                    ),
                };
                Ok(Some((d, u, keys)))
            }
            Some(ConstraintsSpec::Joints(joints)) => {
                let (mut d, mut keys) = (Vec::new(), Vec::new());
                for (j, joint) in joints.iter().enumerate() {
                    let key = format!("constraints.joint[{j}]");
                    let mut vecs = Vec::with_capacity(2);
                    for (name, v) in joint.kind.keys().iter().zip(&joint.vectors) {
                        vecs.push(Vec3::new(
                            num(&v[0], format!("{key}.{name}[0]"))?,
                            num(&v[1], format!("{key}.{name}[1]"))?,
                            num(&v[2], format!("{key}.{name}[2]"))?,
                        ));
                    }
                    let joint_t = match joint.kind {
                        JointKind::Revolute => Joint::Revolute {
                            point: vecs[0].clone(),
                            axis: vecs[1].clone(),
                        },
                        JointKind::Prismatic => Joint::Prismatic {
                            axis: vecs[0].clone(),
                        },
                        JointKind::Cylindrical => Joint::Cylindrical {
                            point: vecs[0].clone(),
                            axis: vecs[1].clone(),
                        },
                        JointKind::Spherical => Joint::Spherical {
                            point: vecs[0].clone(),
                        },
                        JointKind::Planar => Joint::Planar {
                            normal: vecs[0].clone(),
                        },
                    };
                    for s in joint_t.free_screws() {
                        d.push(s);
                        keys.push(key.clone());
                    }
                }
                Ok(Some((d, None, keys)))
            }
        }
    }

    fn error(&self, key: &str, value: Option<String>, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.clone(),
            key: key.to_string(),
            value,
            message: message.into(),
        }
    }

    /// The outward normal of a contact on the surface: ∇f at its point (eq. 103–107), after
    /// checking that the point lies on f = 0 (exactly in exact types; in floats, the distance
    /// estimate |f|/|∇f| must be ≤ 10⁻⁹ of max(|p|, 1)) and that ∇f ≠ 0 there.
    fn surface_normal<T: Scalar>(
        &self,
        surface: &SurfaceSpec,
        p: &Vec3<T>,
        c: &ContactSpec,
        i: usize,
    ) -> Result<Vec3<T>, SceneError> {
        let key = format!("contact[{i}].point");
        let shown = format!(
            "[{}, {}, {}]",
            c.point[0].text, c.point[1].text, c.point[2].text
        );
        let at = [p[0].clone(), p[1].clone(), p[2].clone()];
        let fail = |e: SurfaceError| {
            self.error(
                "surface.f",
                Some(format!("\"{}\"", surface.text)),
                format!("at {key} = {shown}: {}", e.message),
            )
        };
        let g = surface.surface.gradient::<T>(&at).map_err(fail)?;
        let grad = Vec3::new(g[0].clone(), g[1].clone(), g[2].clone());
        let g2 = norm2(&grad);
        if g2.is_zero() {
            return Err(self.error(
                &key,
                Some(shown),
                "∇f = 0 there: the surface has no normal at this point; give `normal` explicitly",
            ));
        }
        let f = surface.surface.value::<T>(&at).map_err(fail)?;
        let on = if T::IS_EXACT {
            f.is_zero()
        } else {
            let (f, g, r) = (
                f.to_f64().abs(),
                g2.to_f64().sqrt(),
                norm2(p).to_f64().sqrt().max(1.0),
            );
            f <= 1e-9 * g * r
        };
        if !on {
            return Err(self.error(
                &key,
                Some(shown),
                format!(
                    "not on the surface f = {}: f(point) = {} ≠ 0",
                    surface.text,
                    f.exact_text().unwrap_or_else(|| f.to_f64().to_string())
                ),
            ));
        }
        Ok(grad)
    }

    /// One number in `T`: exact types refuse irrational values, naming the key and value.
    fn value<T: Scalar>(&self, n: &Number, key: &str) -> Result<T, SceneError> {
        T::from_number(n).map_err(|message| SceneError {
            file: self.file.clone(),
            key: key.to_string(),
            value: Some(n.text.clone()),
            message,
        })
    }
}

/// Parse TOML text into a document (syntax errors name the file and the position).
pub fn parse_document(text: &str, file: &str) -> Result<DocumentMut, SceneError> {
    text.parse::<DocumentMut>().map_err(|e| SceneError {
        file: file.to_string(),
        key: String::new(),
        value: None,
        message: format!("not valid TOML: {}", e.to_string().trim()),
    })
}

/// Override one value of a scene document: `path` like `body.mass`, `contact[1].k`,
/// `body.velocity[0]`; `value` is TOML text (`0.5`, `"1/3"`, `[1, 0, 0]`). Used by
/// derivations (`set` lines) and parameter sweeps.
pub fn set_value(doc: &mut DocumentMut, path: &str, value: &str) -> Result<(), String> {
    let new: Value = value
        .trim()
        .parse::<Value>()
        .map_err(|e| format!("`{value}` is not a TOML value: {}", e.to_string().trim()))?;
    let segments: Vec<&str> = path.split('.').collect();
    let mut table: &mut dyn TableLike = doc.as_table_mut();
    for (depth, seg) in segments.iter().enumerate() {
        let (name, index) =
            split_index(seg).ok_or_else(|| format!("bad key `{seg}` in `{path}`"))?;
        if depth + 1 == segments.len() {
            match index {
                None => {
                    table.insert(name, Item::Value(new));
                    if name == "k" {
                        table.remove("k_newton");
                        table.remove("k_poisson");
                    } else if name == "k_newton" || name == "k_poisson" {
                        split_k(table);
                    }
                }
                Some(i) => {
                    let slot = table
                        .get_mut(name)
                        .and_then(Item::as_array_mut)
                        .and_then(|a| a.get_mut(i))
                        .ok_or_else(|| format!("`{path}`: there is no {name}[{i}]"))?;
                    *slot = new;
                }
            }
            return Ok(());
        }
        let child = table
            .get_mut(name)
            .ok_or_else(|| format!("`{path}`: no key `{name}`"))?;
        table = match (child, index) {
            (Item::Table(t), None) => t,
            (Item::Value(Value::InlineTable(t)), None) => t,
            (Item::ArrayOfTables(arr), Some(i)) => arr
                .get_mut(i)
                .ok_or_else(|| format!("`{path}`: there is no {name}[{i}]"))?,
            _ => return Err(format!("`{path}`: `{seg}` is not a table")),
        };
    }
    Err(format!("`{path}`: nothing to set"))
}

/// When `k` is replaced by one of `k_newton`/`k_poisson`, keep the other at the old `k`.
fn split_k(table: &mut dyn TableLike) {
    if let Some(k) = table.remove("k") {
        for key in ["k_newton", "k_poisson"] {
            if table.get(key).is_none() {
                table.insert(key, k.clone());
            }
        }
    }
}

/// `contact[1]` → ("contact", Some(1)); `mass` → ("mass", None).
fn split_index(seg: &str) -> Option<(&str, Option<usize>)> {
    match seg.find('[') {
        None => Some((seg, None)),
        Some(open) => {
            let close = seg.strip_suffix(']')?;
            let idx = close[open + 1..].parse().ok()?;
            Some((&seg[..open], Some(idx)))
        }
    }
}

fn short(item: &Item) -> String {
    let s = item.to_string();
    let s = s.trim();
    if s.len() > 60 {
        format!("{}…", &s[..s.floor_char_boundary(60)])
    } else {
        s.to_string()
    }
}

/// The keys a scene may have at its top level.
const TOP_KEYS: &[&str] = &[
    "name",
    "description",
    "body",
    "contact",
    "solve",
    "constraints",
    "surface",
];

/// Whether a value in symbols is identically zero (`"m - m"`).
fn symbolic_zero(n: &Number) -> bool {
    crate::scalar::symbolic::symbolic(&n.text, &n.symbols).is_ok_and(|x| num_traits::Zero::is_zero(&x))
}

/// Reads values out of a document, turning every problem into a [`SceneError`].
struct Reader<'a> {
    file: &'a str,
    /// Names values may use as symbols.
    symbols: &'a [String],
}

impl Reader<'_> {
    fn err(&self, key: &str, value: Option<String>, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.to_string(),
            key: key.to_string(),
            value,
            message: message.into(),
        }
    }

    fn only_keys(&self, t: &dyn TableLike, at: &str, known: &[&str]) -> Result<(), SceneError> {
        for (k, v) in t.iter() {
            if !known.contains(&k) {
                let key = if at.is_empty() {
                    k.to_string()
                } else {
                    format!("{at}.{k}")
                };
                return Err(self.err(
                    &key,
                    Some(short(v)),
                    format!("unknown key; expected one of: {}", known.join(", ")),
                ));
            }
        }
        Ok(())
    }

    fn get<'t>(
        &self,
        t: &'t dyn toml_edit::TableLike,
        key: &str,
        at: &str,
    ) -> Result<&'t Item, SceneError> {
        t.get(key)
            .ok_or_else(|| self.err(&format!("{at}.{key}"), None, "missing (required)"))
    }

    fn table<'t>(&self, t: &'t Table, key: &str, at: &str) -> Result<&'t Table, SceneError> {
        let path = if at.is_empty() {
            key.to_string()
        } else {
            format!("{at}.{key}")
        };
        match t.get(key) {
            None => Err(self.err(
                &path,
                None,
                format!("missing (required): add a [{path}] table"),
            )),
            Some(item) => item.as_table().ok_or_else(|| {
                self.err(
                    &path,
                    Some(short(item)),
                    format!("must be a table: [{path}]"),
                )
            }),
        }
    }

    fn string(&self, item: &Item, key: &str) -> Result<String, SceneError> {
        item.as_str()
            .map(str::to_string)
            .ok_or_else(|| self.err(key, Some(short(item)), "must be a string"))
    }

    fn number_value(&self, v: &Value, key: &str) -> Result<Number, SceneError> {
        let text: String = match v {
            Value::Integer(f) => f.display_repr().into_owned(),
            Value::Float(f) => f.display_repr().into_owned(),
            Value::String(s) => s.value().clone(),
            other => {
                return Err(self.err(
                    key,
                    Some(other.to_string().trim().to_string()),
                    "must be a number (or a string such as \"1/3\")",
                ));
            }
        };
        let shown = v.to_string().trim().to_string();
        parse_number_with(&text, self.symbols).map_err(|e| {
            let mut message = e.to_string();
            if self.symbols.is_empty() && message.contains("unknown name") {
                message += "; a symbolic scene is for `inertance derive SCENE --symbols NAME,…`";
            }
            self.err(key, Some(shown), message)
        })
    }

    fn number(&self, item: &Item, key: &str) -> Result<Number, SceneError> {
        match item.as_value() {
            Some(v) => self.number_value(v, key),
            None => Err(self.err(key, Some(short(item)), "must be a number")),
        }
    }

    fn triple(&self, item: &Item, key: &str) -> Result<[Number; 3], SceneError> {
        let arr = item.as_array().filter(|a| a.len() == 3).ok_or_else(|| {
            self.err(
                key,
                Some(short(item)),
                "must be an array of three numbers [x, y, z]",
            )
        })?;
        let mut out = Vec::with_capacity(3);
        for (i, v) in arr.iter().enumerate() {
            out.push(self.number_value(v, &format!("{key}[{i}]"))?);
        }
        let [a, b, c]: [Number; 3] = out
            .try_into()
            .map_err(|_| self.err(key, None, "must have three numbers"))?;
        Ok([a, b, c])
    }

    fn positive(&self, n: &Number, key: &str, why: &str) -> Result<(), SceneError> {
        let ok = match &n.exact {
            Ok(q) => q.is_positive(),
            // A symbolic value's sign is the reader's assumption, but not when it is 0.
            Err(_) if !n.symbols.is_empty() => !symbolic_zero(n),
            Err(_) => n.approx > 0.0,
        };
        if ok {
            Ok(())
        } else {
            Err(self.err(key, Some(n.text.clone()), format!("{why} (> 0)")))
        }
    }

    fn coefficient(&self, n: Number, key: &str) -> Result<Number, SceneError> {
        let ok = match &n.exact {
            Ok(q) => !q.is_negative() && *q <= num_traits::One::one(),
            Err(_) => !n.symbols.is_empty() || (0.0..=1.0).contains(&n.approx),
        };
        if ok {
            Ok(n)
        } else {
            Err(self.err(
                key,
                Some(n.text.clone()),
                "a coefficient of restitution must lie in [0, 1]",
            ))
        }
    }

    fn nonzero(&self, t: &[Number; 3], key: &str, what: &str) -> Result<(), SceneError> {
        let zero = t.iter().all(|n| match &n.exact {
            Ok(q) => num_traits::Zero::is_zero(q),
            Err(_) if !n.symbols.is_empty() => symbolic_zero(n),
            Err(_) => n.approx == 0.0,
        });
        if zero {
            let shown = format!("[{}, {}, {}]", t[0].text, t[1].text, t[2].text);
            Err(self.err(
                key,
                Some(shown),
                format!("{what} must not be the zero vector"),
            ))
        } else {
            Ok(())
        }
    }

    fn contact(&self, t: &Table, i: usize) -> Result<ContactSpec, SceneError> {
        let at = format!("contact[{i}]");
        self.only_keys(
            t,
            &at,
            &[
                "point",
                "normal",
                "tangent",
                "k",
                "k_newton",
                "k_poisson",
                "name",
            ],
        )?;
        let point = self.triple(self.get(t, "point", &at)?, &format!("{at}.point"))?;
        let normal = match t.get("normal") {
            None => None,
            Some(item) => {
                let n = self.triple(item, &format!("{at}.normal"))?;
                self.nonzero(&n, &format!("{at}.normal"), "a normal")?;
                Some(n)
            }
        };
        let tangent = match t.get("tangent") {
            None => None,
            Some(item) => {
                let tan = self.triple(item, &format!("{at}.tangent"))?;
                self.nonzero(&tan, &format!("{at}.tangent"), "a tangent")?;
                Some(tan)
            }
        };
        let k_of = |key: &str| -> Result<Option<Number>, SceneError> {
            match t.get(key) {
                None => Ok(None),
                Some(item) => {
                    let path = format!("{at}.{key}");
                    Ok(Some(self.coefficient(self.number(item, &path)?, &path)?))
                }
            }
        };
        let (k, kn, kp) = (k_of("k")?, k_of("k_newton")?, k_of("k_poisson")?);
        let (k_newton, k_poisson) = match (k, kn, kp) {
            (Some(k), None, None) => (k.clone(), k),
            (None, Some(n), Some(p)) => (n, p),
            (Some(_), _, _) => {
                return Err(self.err(
                    &format!("{at}.k"),
                    None,
                    "give either `k` or both `k_newton` and `k_poisson`, not both forms",
                ));
            }
            (None, n, p) => {
                let missing = if n.is_none() { "k_newton" } else { "k_poisson" };
                let _ = p;
                return Err(self.err(
                    &format!("{at}.{missing}"),
                    None,
                    "missing: give `k` (both models), or both `k_newton` and `k_poisson`",
                ));
            }
        };
        Ok(ContactSpec {
            point,
            normal,
            tangent,
            k_newton,
            k_poisson,
        })
    }

    fn surface(&self, item: &Item) -> Result<SurfaceSpec, SceneError> {
        let t = item
            .as_table_like()
            .ok_or_else(|| self.err("surface", Some(short(item)), "must be a table: [surface]"))?;
        self.only_keys(t, "surface", &["f"])?;
        let f = self.get(t, "f", "surface")?;
        let text = f.as_str().ok_or_else(|| {
            self.err(
                "surface.f",
                Some(short(f)),
                "must be a string, e.g. \"x^2 + y^2/4 + z^2/9 - 1\"",
            )
        })?;
        let surface = Surface::parse_with(text, self.symbols)
            .map_err(|e| self.err("surface.f", Some(short(f)), e.message))?;
        Ok(SurfaceSpec {
            text: text.to_string(),
            surface,
        })
    }

    fn constraints(&self, item: &Item) -> Result<ConstraintsSpec, SceneError> {
        let t = item.as_table_like().ok_or_else(|| {
            self.err(
                "constraints",
                Some(short(item)),
                "must be a table: [constraints]",
            )
        })?;
        self.only_keys(t, "constraints", &["free", "blocked", "joint"])?;
        let has_screws = t.get("free").is_some() || t.get("blocked").is_some();
        match (t.get("joint"), has_screws) {
            (Some(_), true) => Err(self.err(
                "constraints",
                None,
                "give either the paper's form (`free`, optionally `blocked`) or `[[constraints.joint]]` tables, not both",
            )),
            (Some(Item::ArrayOfTables(arr)), false) => {
                let joints = arr.iter().enumerate().map(|(j, t)| self.joint(t, j)).collect::<Result<Vec<_>, _>>()?;
                Ok(ConstraintsSpec::Joints(joints))
            }
            (Some(other), false) => Err(self.err("constraints.joint", Some(short(other)), "must be [[constraints.joint]] tables")),
            (None, _) => {
                let free_item = t.get("free").ok_or_else(|| {
                    self.err("constraints.free", None, "missing: give the free screws [ω; v] (columns of D), or [[constraints.joint]] tables")
                })?;
                let free = self.screws(free_item, "constraints.free")?;
                let blocked = match t.get("blocked") {
                    None => None,
                    Some(b) => Some(self.screws(b, "constraints.blocked")?),
                };
                Ok(ConstraintsSpec::Screws { free, blocked })
            }
        }
    }

    fn screws(&self, item: &Item, key: &str) -> Result<Vec<[Number; 6]>, SceneError> {
        let arr = item.as_array().ok_or_else(|| {
            self.err(
                key,
                Some(short(item)),
                "must be an array of six-number screws [[ωx, ωy, ωz, vx, vy, vz], …]",
            )
        })?;
        let mut out = Vec::with_capacity(arr.len());
        for (i, v) in arr.iter().enumerate() {
            let path = format!("{key}[{i}]");
            let inner = v.as_array().filter(|a| a.len() == 6).ok_or_else(|| {
                self.err(
                    &path,
                    Some(v.to_string().trim().to_string()),
                    "must be a screw of six numbers [ωx, ωy, ωz, vx, vy, vz]",
                )
            })?;
            let mut nums = Vec::with_capacity(6);
            for (k, x) in inner.iter().enumerate() {
                nums.push(self.number_value(x, &format!("{path}[{k}]"))?);
            }
            let zero = nums.iter().all(|n| match &n.exact {
                Ok(q) => num_traits::Zero::is_zero(q),
                Err(_) => n.approx == 0.0,
            });
            if zero {
                return Err(self.err(
                    &path,
                    Some(v.to_string().trim().to_string()),
                    "a screw must not be zero",
                ));
            }
            let arr6: [Number; 6] = nums
                .try_into()
                .map_err(|_| self.err(&path, None, "must have six numbers"))?;
            out.push(arr6);
        }
        if out.is_empty() {
            return Err(self.err(key, Some("[]".into()), "list at least one screw"));
        }
        Ok(out)
    }

    fn joint(&self, t: &Table, j: usize) -> Result<JointSpec, SceneError> {
        let at = format!("constraints.joint[{j}]");
        let kind_item = self.get(t, "kind", &at)?;
        let names: Vec<&str> = JointKind::NAMES.iter().map(|(n, _)| *n).collect();
        let kind = kind_item
            .as_str()
            .and_then(|k| {
                JointKind::NAMES
                    .iter()
                    .find(|(n, _)| *n == k)
                    .map(|(_, kind)| *kind)
            })
            .ok_or_else(|| {
                self.err(
                    &format!("{at}.kind"),
                    Some(short(kind_item)),
                    format!("unknown joint; expected one of: {}", names.join(", ")),
                )
            })?;
        let mut known = vec!["kind"];
        known.extend_from_slice(kind.keys());
        self.only_keys(t, &at, &known)?;
        let mut vectors = Vec::new();
        for key in kind.keys() {
            let path = format!("{at}.{key}");
            let v = self.triple(self.get(t, key, &at)?, &path)?;
            if *key != "point" {
                self.nonzero(&v, &path, "a joint direction")?;
            }
            vectors.push(v);
        }
        Ok(JointSpec { kind, vectors })
    }

    fn models(&self, item: &Item, key: &str) -> Result<Vec<Model>, SceneError> {
        let arr = item.as_array().ok_or_else(|| {
            self.err(
                key,
                Some(short(item)),
                "must be an array such as [\"newton\", \"poisson\"]",
            )
        })?;
        let mut models = Vec::new();
        for v in arr.iter() {
            let shown = v.to_string().trim().to_string();
            let m = v.as_str().and_then(Model::from_name).ok_or_else(|| {
                self.err(
                    key,
                    Some(shown.clone()),
                    "unknown model; expected \"newton\" or \"poisson\"",
                )
            })?;
            if models.contains(&m) {
                return Err(self.err(key, Some(shown), "model listed twice"));
            }
            models.push(m);
        }
        if models.is_empty() {
            return Err(self.err(key, Some("[]".into()), "list at least one model"));
        }
        Ok(models)
    }
}
