//! Scene files (TOML): the public schema, read exactly as written.
//!
//! ```toml
//! name = "planar bar on two supports"
//! [body]
//! mass = 1
//! inertia = [12, 1.6, 12]          # central principal moments Jx, Jy, Jz, or the 3×3
//!                                  # tensor [[Jxx, Jxy, Jxz], [Jxy, Jyy, Jyz], [Jxz, Jyz, Jzz]]
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
//! **Friction.** `mu = 0.5` on a contact (default 0) and, optionally, `[solve] restitution =
//! "newton" | "poisson" | "energetic"` (with `k_energetic` per contact, default `k_poisson`)
//! integrate the impact in impulse space ([`crate::impact::friction`]) instead of solving the
//! paper's algebraic system; `[solve] tolerance = 1e-12` sets the relative tolerance of a
//! spatial scene's integration.
//!
//! **The LZB law.** `[solve] law = "lzb"` (or `--law lzb`) solves a frictionless scene by the
//! multiple-impact law of Liu, Zhao and Brogliato ([`crate::impact::multiple`], [`lzb`]): per
//! contact `stiffness = 1` (K, only ratios matter), `exponent = 1.5` (η: 1 linear, 1.5 Hertz)
//! and the energetic restitution from `k_energetic`, else `k`.
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
//!
//! Here: [`Scene`] and its conversion to a [`Problem`] in a scalar type. `read` walks a
//! document and holds the reader's primitives, `schema` the tables a scene may have
//! ([`ContactSpec`], [`ConstraintsSpec`], …) and how each is read, `path` the key paths and
//! [`set_value`]; [`pipeline`] runs a scene from assembly to report; [`limits`] names the
//! sizes refused at once; [`seed`] marks the input a sensitivity run differentiates with
//! respect to.

mod exact;
mod law;
pub mod limits;
pub mod lzb;
pub mod model;
mod notes;
mod path;
pub mod pipeline;
mod read;
pub mod scale;
mod schema;
pub mod seed;
mod system;
pub mod system_pipeline;

pub use model::Axes;
pub use model::params::ParamSpec;
pub use path::{set_axes, set_param, set_value};
pub use read::parse_document;
pub use schema::{ConstraintsSpec, ContactSpec, JointKind, JointSpec, SurfaceSpec};

use std::fmt;

use toml_edit::DocumentMut;

use crate::impact::friction::Restitution;
use crate::impact::outputs::Outputs;
use crate::impact::problem::{InvalidProblem, Problem, Reason};
use crate::impact::restitution::Model;
use crate::impact::unilateral::Law;
use crate::mechanics::body::RigidBody;
use crate::mechanics::constraint::Joint;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Vec3, norm2};
use crate::mechanics::surface::SurfaceError;
use crate::number::Number;
use crate::scalar::Scalar;

/// The keys of the inertia tensor's entries off the diagonal, in the order of
/// [`Scene::inertia_products`]: J_xy, J_xz, J_yz.
pub const PRODUCT_KEYS: [&str; 3] = [
    "body.inertia[0][1]",
    "body.inertia[0][2]",
    "body.inertia[1][2]",
];

/// The end of the message for a number a float type cannot hold (the pipeline recognises it).
pub const OUT_OF_RANGE: &str = "`--exact` solves the scene exactly";

/// What a tolerance of the spatial frictional integration must be (`[solve] tolerance`,
/// `--tolerance`): the rule, for messages.
pub const TOLERANCE_RULE: &str = "must be a number between 0 and 1 (exclusive): the relative \
                                  tolerance of the spatial frictional integration, e.g. 1e-10";

/// Whether `x` is a tolerance of the spatial frictional integration: 0 < x < 1.
pub fn valid_tolerance(x: f64) -> bool {
    x > 0.0 && x < 1.0
}

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

/// A scene, validated, with every number as written (exact value when rational, f64 always).
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Where it came from, for messages.
    pub file: String,
    /// Its `name`, or the file name.
    pub name: String,
    /// m.
    pub mass: Number,
    /// The diagonal of the central inertia tensor in the solver's axes, (J_xx, J_yy, J_zz):
    /// the central principal moments (J_x, J_y, J_z) when the axes are principal.
    pub inertia: [Number; 3],
    /// The tensor's entries off the diagonal, (J_xy, J_xz, J_yz), when the axes are not
    /// principal (a full tensor, or a posed body reported in world axes); `None` when they vanish.
    pub inertia_products: Option<[Number; 3]>,
    /// v_C⁰.
    pub velocity: [Number; 3],
    /// ω⁰.
    pub angular_velocity: [Number; 3],
    /// The contacts.
    pub contacts: Vec<ContactSpec>,
    /// The restitution models asked for, in the order given.
    pub models: Vec<Model>,
    /// The impact law (`[solve] law`): the paper's simultaneous one unless `"unilateral"`.
    pub law: Law,
    /// `[solve] restitution`: one restitution law for the frictional integration
    /// ([`crate::impact::friction`]), `"newton"`, `"poisson"` or `"energetic"`.
    pub restitution: Option<Restitution>,
    /// `[solve] outputs`: the outputs the report prints ([`Outputs::ALL`] unless listed); the
    /// solve computes those and what its checks read (impulses, velocities along the
    /// normals, energies), not the tangential ones or the constraint impulses unless asked.
    pub outputs: Outputs,
    /// `[solve] tolerance`: the relative tolerance of the spatial frictional integration
    /// ([`crate::impact::friction::spatial`]) and of the LZB law's ([`lzb`]), in (0, 1);
    /// `None`: the scalar's default
    /// ([`crate::scene::pipeline::friction_tolerance`]). Planar scenes are solved event by
    /// event and do not read it.
    pub tolerance: Option<f64>,
    /// The `[constraints]` effect, if declared.
    pub constraints: Option<ConstraintsSpec>,
    /// The `[surface]` effect, if declared.
    pub surface: Option<SurfaceSpec>,
    /// The `[params]`, in order.
    pub params: Vec<ParamSpec>,
    /// The axes of a modelled scene (world frame, pose, shape, obstacles: [`model`]); `None`
    /// for a scene written in the paper's body axes.
    pub axes: Option<Axes>,
    /// The angles of a modelled scene's pose, each with its key as written
    /// (`body.pose.angle`, `body.pose[1].angle`): the notes and the exact solver's refusals
    /// name them rather than the numbers computed from them.
    pub angles: Vec<(String, Number)>,
    /// The density m / V (kg/m³) of each shape given its mass, with its body's key (`body`,
    /// `body[i]`), for the units note.
    pub density: Vec<(String, f64)>,
    /// A scene of several bodies (`[[body]]` tables, [`crate::mechanics::system`]): its bodies,
    /// what each contact joins, and its joints. The one-body fields then hold the first body's
    /// numbers, and the contacts' points are in the world.
    pub system: Option<model::system::SystemSpec>,
}

/// The text of the scene file at `path`, with its name for messages.
fn read_text(path: &std::path::Path) -> Result<(String, String), SceneError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| SceneError {
        file: file.clone(),
        key: String::new(),
        value: None,
        message: format!("cannot read the file: {e}"),
    })?;
    Ok((file, text))
}

/// A scene to simulate (`inertance simulate`, [`crate::simulate`]): its name, its file and
/// what to run ([`model::simulation`] documents the keys).
#[derive(Clone, Debug, PartialEq)]
pub struct SimulationScene {
    /// Where it came from, for messages.
    pub file: String,
    /// Its `name`, or the file name.
    pub name: String,
    /// The body, obstacles, law and options.
    pub setup: crate::simulate::Setup,
}

/// A scene of several bodies (spheres, boxes and thin rods) to simulate ([`model::simulated_system`] documents the keys).
#[derive(Clone, Debug, PartialEq)]
pub struct SimulatedSystemScene {
    /// Where it came from, for messages.
    pub file: String,
    /// Its `name`, or the file name.
    pub name: String,
    /// The spheres, obstacles, contacts, law and options.
    pub setup: crate::simulate::system::SystemSetup,
}

/// A scene to simulate: one body or several bodies.
#[derive(Clone, Debug, PartialEq)]
pub enum AnySimulation {
    /// One body.
    Body(Box<SimulationScene>),
    /// Several bodies.
    System(Box<SimulatedSystemScene>),
}

impl AnySimulation {
    /// Read the scene to simulate at `path`: one `[body]` or several `[[body]]` spheres.
    ///
    /// # Errors
    /// A [`SceneError`] naming the file, the key and the value.
    pub fn load(path: &std::path::Path) -> Result<AnySimulation, SceneError> {
        let (file, text) = read_text(path)?;
        AnySimulation::parse(&text, &file)
    }

    /// Parse scene text to simulate; `file` names it in messages.
    ///
    /// # Errors
    /// As [`AnySimulation::load`].
    pub fn parse(text: &str, file: &str) -> Result<AnySimulation, SceneError> {
        let doc = parse_document(text, file)?;
        let (name, what) = read::simulation(&doc, file)?;
        let file = file.to_string();
        Ok(match what {
            read::Simulated::Body(setup) => AnySimulation::Body(Box::new(SimulationScene {
                file,
                name,
                setup: *setup,
            })),
            read::Simulated::System(setup) => {
                AnySimulation::System(Box::new(SimulatedSystemScene {
                    file,
                    name,
                    setup: *setup,
                }))
            }
        })
    }
}

impl SimulationScene {
    /// Read the scene to simulate at `path`.
    ///
    /// # Errors
    /// A [`SceneError`] naming the file, the key and the value; a scene of several bodies is
    /// refused here (read it with [`AnySimulation::load`]).
    pub fn load(path: &std::path::Path) -> Result<SimulationScene, SceneError> {
        let (file, text) = read_text(path)?;
        SimulationScene::parse(&text, &file)
    }

    /// Read the scene to simulate at `path` and its exact form: a frictionless sphere among
    /// planes, every number exact in `T` ([`crate::simulate::exact`]).
    ///
    /// # Errors
    /// As [`SimulationScene::load`], and a scene that has no exact form (not a sphere, friction,
    /// a normal whose length is not exact in `T`).
    pub fn load_exact<T: crate::scalar::Scalar>(
        path: &std::path::Path,
    ) -> Result<(SimulationScene, crate::simulate::exact::ExactSphere<T>), SceneError> {
        let (file, text) = read_text(path)?;
        let scene = SimulationScene::parse(&text, &file)?;
        let doc = parse_document(&text, &file)?;
        let exact = read::exact_sphere::<T>(&doc, &file, &scene.setup)?;
        Ok((scene, exact))
    }

    /// Parse scene text to simulate; `file` names it in messages.
    ///
    /// # Errors
    /// As [`SimulationScene::load`].
    pub fn parse(text: &str, file: &str) -> Result<SimulationScene, SceneError> {
        match AnySimulation::parse(text, file)? {
            AnySimulation::Body(s) => Ok(*s),
            AnySimulation::System(_) => Err(SceneError {
                file: file.to_string(),
                key: "body".to_string(),
                value: None,
                message: "a scene of several [[body]] spheres: it is simulated as a system \
                          (`inertance simulate` without --exact; AnySimulation in the library), \
                          not as one body"
                    .to_string(),
            }),
        }
    }
}

impl Scene {
    /// Read and validate the scene file at `path`.
    pub fn load(path: &std::path::Path) -> Result<Scene, SceneError> {
        Scene::load_with(path, &[])
    }

    /// As [`Scene::load`], with values allowed to name the `symbols` (for `inertance derive`):
    /// such a value runs only in the symbolic scalar.
    pub fn load_with(path: &std::path::Path, symbols: &[String]) -> Result<Scene, SceneError> {
        let (file, text) = read_text(path)?;
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
        read::scene(doc, file, symbols, None)
    }

    /// As [`Scene::from_document_with`], with the parameter `seed` seeded: every number
    /// carries its derivative with respect to it ([`Number::tangent`]), for a sensitivity run.
    pub fn from_document_seeded(
        doc: &DocumentMut,
        file: &str,
        symbols: &[String],
        seed: &str,
    ) -> Result<Scene, SceneError> {
        read::scene(doc, file, symbols, Some(seed))
    }

    /// Whether the impact is integrated in impulse space ([`crate::impact::friction`]): some
    /// μ_i ≠ 0, or `[solve] restitution` given. A μ_i = 0 seeded with a derivative (a
    /// sensitivity run) counts as frictional: the derivative with respect to μ at 0 is that of
    /// the frictional integration (μ ≥ 0, one-sided), not of the frictionless model.
    pub fn frictional(&self) -> bool {
        self.restitution.is_some()
            || self.contacts.iter().any(|c| match &c.mu.exact {
                Ok(q) => !num_traits::Zero::is_zero(q) || c.mu.tangent != 0.0,
                Err(_) => true,
            })
    }

    /// How the frictional integration holds the contacts: the unilateral law's release and
    /// re-engagement under `law = "unilateral"`, else the simultaneous hypothesis.
    pub fn hypothesis(&self) -> crate::impact::friction::Hypothesis {
        match self.law {
            Law::Unilateral => crate::impact::friction::Hypothesis::Unilateral,
            Law::Simultaneous | Law::Lzb => crate::impact::friction::Hypothesis::Simultaneous,
        }
    }

    /// The restitution laws of the frictional integration: `[solve] restitution`, else the
    /// models asked for (`models`, or the scene's).
    pub fn restitutions(&self, models: Option<&[Model]>) -> Vec<Restitution> {
        match self.restitution {
            Some(r) => vec![r],
            None => models
                .unwrap_or(&self.models)
                .iter()
                .map(|&m| Restitution::from(m))
                .collect(),
        }
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
        if self.law == Law::Unilateral {
            e.push(self.law.name().into());
        }
        e.extend(models.iter().map(|m| m.name().to_string()));
        e
    }

    /// Whether the scene can run in exact rationals: every number rational, and the surface
    /// (if any) exact at its contact points.
    pub fn is_rational(&self) -> bool {
        if let Some(spec) = &self.system {
            return self.numbers().all(|(_, n)| n.exact.is_ok())
                && spec.numbers().iter().all(|(_, n)| n.exact.is_ok())
                && self.system::<crate::scalar::Exact>().is_ok();
        }
        self.numbers().all(|(_, n)| n.exact.is_ok())
            && self.problem::<crate::scalar::Exact>().is_ok()
    }

    /// Every number with its key path. The inertia tensor's diagonal is `body.inertia[k]`
    /// (whether written as moments or as a 3×3 array), its entries off the diagonal
    /// `body.inertia[0][1]`, `body.inertia[0][2]`, `body.inertia[1][2]` ([`PRODUCT_KEYS`]).
    /// [`Scene::numbers_mut`] lists the same keys: a number added here must be added there
    /// too (or a sensitivity cannot be seeded on it).
    pub fn numbers(&self) -> impl Iterator<Item = (String, &Number)> {
        let mut v: Vec<(String, &Number)> = vec![("body.mass".into(), &self.mass)];
        for (i, n) in self.inertia.iter().enumerate() {
            v.push((format!("body.inertia[{i}]"), n));
        }
        for (key, n) in PRODUCT_KEYS
            .iter()
            .zip(self.inertia_products.iter().flatten())
        {
            v.push((key.to_string(), n));
        }
        let triples = [
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
            if let Some(k) = &spec.k_energetic {
                v.push((format!("contact[{c}].k_energetic"), k));
            }
            v.push((format!("contact[{c}].mu"), &spec.mu));
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

    /// Every number with its key path, mutable: the keys of [`Scene::numbers`], in the same
    /// order (tested). How a sensitivity run seeds a number's [`Number::tangent`] ([`seed`]).
    pub fn numbers_mut(&mut self) -> impl Iterator<Item = (String, &mut Number)> {
        let mut v: Vec<(String, &mut Number)> = vec![("body.mass".into(), &mut self.mass)];
        for (i, n) in self.inertia.iter_mut().enumerate() {
            v.push((format!("body.inertia[{i}]"), n));
        }
        for (key, n) in PRODUCT_KEYS
            .iter()
            .zip(self.inertia_products.iter_mut().flatten())
        {
            v.push((key.to_string(), n));
        }
        let triples = [
            ("body.velocity", &mut self.velocity),
            ("body.angular_velocity", &mut self.angular_velocity),
        ];
        for (k, t) in triples {
            for (i, n) in t.iter_mut().enumerate() {
                v.push((format!("{k}[{i}]"), n));
            }
        }
        for (c, spec) in self.contacts.iter_mut().enumerate() {
            for (i, n) in spec.point.iter_mut().enumerate() {
                v.push((format!("contact[{c}].point[{i}]"), n));
            }
            for (i, n) in spec.normal.iter_mut().flatten().enumerate() {
                v.push((format!("contact[{c}].normal[{i}]"), n));
            }
            if let Some(t) = &mut spec.tangent {
                for (i, n) in t.iter_mut().enumerate() {
                    v.push((format!("contact[{c}].tangent[{i}]"), n));
                }
            }
            v.push((format!("contact[{c}].k_newton"), &mut spec.k_newton));
            v.push((format!("contact[{c}].k_poisson"), &mut spec.k_poisson));
            if let Some(k) = &mut spec.k_energetic {
                v.push((format!("contact[{c}].k_energetic"), k));
            }
            v.push((format!("contact[{c}].mu"), &mut spec.mu));
        }
        match &mut self.constraints {
            None => {}
            Some(ConstraintsSpec::Screws { free, blocked }) => {
                let lists = [("free", Some(free)), ("blocked", blocked.as_mut())];
                for (name, list) in lists {
                    for (i, screw) in list.into_iter().flatten().enumerate() {
                        for (k, n) in screw.iter_mut().enumerate() {
                            v.push((format!("constraints.{name}[{i}][{k}]"), n));
                        }
                    }
                }
            }
            Some(ConstraintsSpec::Joints(joints)) => {
                for (j, joint) in joints.iter_mut().enumerate() {
                    for (key, vec) in joint.kind.keys().iter().zip(&mut joint.vectors) {
                        for (k, n) in vec.iter_mut().enumerate() {
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
        if self.system.is_some() {
            return Err(self.error(
                "body",
                None,
                "a scene of several bodies is solved by `inertance solve` and Python's \
                 `inertance.solve` (simultaneous and unilateral laws, exactly and in floats); \
                 `analyze`, `derive`, `sweep`, `bench` and friction take one body yet",
            ));
        }
        let num = |n: &Number, key: &str| -> Result<T, SceneError> { self.value::<T>(n, key) };
        let vec3 = |t: &[Number; 3], key: &str| -> Result<Vec3<T>, SceneError> {
            Ok(Vec3::new(
                num(&t[0], &format!("{key}[0]"))?,
                num(&t[1], &format!("{key}[1]"))?,
                num(&t[2], &format!("{key}[2]"))?,
            ))
        };
        let mass = num(&self.mass, "body.mass")?;
        let body = match &self.inertia_products {
            None => RigidBody::principal(mass, vec3(&self.inertia, "body.inertia")?),
            Some(products) => {
                let d = |k: usize| num(&self.inertia[k], &format!("body.inertia[{k}]"));
                let p = |k: usize| num(&products[k], PRODUCT_KEYS[k]);
                let (xy, xz, yz) = (p(0)?, p(1)?, p(2)?);
                RigidBody::with_tensor(
                    mass,
                    [
                        [d(0)?, xy.clone(), xz.clone()],
                        [xy, d(1)?, yz.clone()],
                        [xz, yz, d(2)?],
                    ],
                )
            }
        };
        let velocity = Screw::new(
            vec3(&self.angular_velocity, "body.angular_velocity")?,
            vec3(&self.velocity, "body.velocity")?,
        );
        if let Some(surface) = &self.surface {
            self.centre_inside::<T>(surface)?;
        }
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
            contacts.push(self.contact(i, c, point, normal)?);
        }
        Problem::new(body, velocity, contacts).map_err(|e| self.invalid(e))
    }

    /// Contact `i` in `T`, at `point` with `normal` (already read): its tangent and
    /// coefficients.
    pub(crate) fn contact<T: Scalar>(
        &self,
        i: usize,
        c: &ContactSpec,
        point: Vec3<T>,
        normal: Vec3<T>,
    ) -> Result<Contact<T>, SceneError> {
        let num = |n: &Number, key: &str| -> Result<T, SceneError> { self.value::<T>(n, key) };
        let key = |k: &str| format!("contact[{i}].{k}");
        Ok(Contact {
            point,
            normal,
            tangent: match &c.tangent {
                Some(t) => Some(self.vec3(t, &key("tangent"))?),
                None => None,
            },
            k_newton: num(&c.k_newton, &key("k_newton"))?,
            k_poisson: num(&c.k_poisson, &key("k_poisson"))?,
            k_energetic: match &c.k_energetic {
                Some(k) => num(k, &key("k_energetic"))?,
                None => num(&c.k_poisson, &key("k_poisson"))?,
            },
            mu: num(&c.mu, &key("mu"))?,
        })
    }

    /// Three numbers at `key[0..3]` in `T`.
    pub(crate) fn vec3<T: Scalar>(
        &self,
        t: &[Number; 3],
        key: &str,
    ) -> Result<Vec3<T>, SceneError> {
        Ok(Vec3::new(
            self.value::<T>(&t[0], &format!("{key}[0]"))?,
            self.value::<T>(&t[1], &format!("{key}[1]"))?,
            self.value::<T>(&t[2], &format!("{key}[2]"))?,
        ))
    }

    /// §12: the outward normal is ∇f, which points outward only if f < 0 inside the body — so
    /// f at the centre of mass C (the origin of the body axes) must be negative. A surface
    /// written the other way round would give every contact the inward normal and negative
    /// impulses; refuse it with the fix. (An undecided symbolic sign passes.)
    fn centre_inside<T: Scalar>(&self, surface: &SurfaceSpec) -> Result<(), SceneError> {
        let origin = [T::zero(), T::zero(), T::zero()];
        let Ok(f) = surface.surface.value::<T>(&origin) else {
            return Ok(());
        };
        match f.known_sign() {
            Some(s) if s >= 0 => Err(self.error(
                "surface.f",
                Some(format!("\"{}\"", surface.text)),
                format!(
                    "f(C) = f(0, 0, 0) = {} ≥ 0, but the centre of mass lies inside the body, where \
                     f must be negative (the outward normal is ∇f, §12); write the surface with f < 0 \
                     inside, e.g. \"-({})\"",
                    f.exact_text().unwrap_or_else(|| f.to_f64().to_string()),
                    surface.text
                ),
            )),
            _ => Ok(()),
        }
    }

    /// The value at `key` as written: a number, or a vector `[x, y, z]` of the numbers at
    /// `key[0]`, `key[1]`, … (for messages that show what was given); for a joint, its vectors.
    pub fn text_of(&self, key: &str) -> Option<String> {
        if let ("body.inertia", Some([xy, xz, yz])) = (key, &self.inertia_products) {
            let [x, y, z] = &self.inertia;
            let rows = [[x, xy, xz], [xy, y, yz], [xz, yz, z]]
                .map(|r| format!("[{}, {}, {}]", r[0].text, r[1].text, r[2].text));
            return Some(format!("[{}]", rows.join(", ")));
        }
        let prefix = format!("{key}[");
        let joint = format!("{key}.");
        let mut parts = Vec::new();
        for (k, n) in self.numbers() {
            if k == key {
                return Some(n.text.clone());
            }
            if k.starts_with(&prefix) && !k[prefix.len()..].contains('[') || k.starts_with(&joint) {
                parts.push((k, n.text.clone()));
            }
        }
        if parts.is_empty() {
            return None;
        }
        if parts.iter().all(|(k, _)| k.starts_with(&prefix)) {
            return Some(format!(
                "[{}]",
                parts
                    .into_iter()
                    .map(|(_, t)| t)
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        // A joint: `point = [..], axis = [..]`.
        let mut groups: Vec<(String, Vec<String>)> = Vec::new();
        for (k, t) in parts {
            let name = k[joint.len()..]
                .split('[')
                .next()
                .unwrap_or_default()
                .to_string();
            match groups.last_mut() {
                Some((g, v)) if *g == name => v.push(t),
                _ => groups.push((name, vec![t])),
            }
        }
        Some(
            groups
                .into_iter()
                .map(|(g, v)| format!("{g} = [{}]", v.join(", ")))
                .collect::<Vec<_>>()
                .join(", "),
        )
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
        let key = e.field.to_string();
        self.error(&key, self.text_of(&key), &message)
    }
}

/// A scene's constraints in the scalar type `T`.
#[derive(Clone, Debug)]
pub struct ConstraintScrews<T: Scalar> {
    /// The free screws D.
    pub free: Vec<Screw<T>>,
    /// The blocked screws U, if given.
    pub blocked: Option<Vec<Screw<T>>>,
    /// For each free screw, the key that declared it (for messages).
    pub keys: Vec<String>,
    /// The joints D comes from (empty for the paper's form).
    pub joints: Vec<Joint<T>>,
}

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
                Ok(Some(ConstraintScrews {
                    free: d,
                    blocked: u,
                    keys,
                    joints: Vec::new(),
                }))
            }
            Some(ConstraintsSpec::Joints(joints)) => {
                let (mut d, mut keys, mut held) = (Vec::new(), Vec::new(), Vec::new());
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
                    held.push(joint_t);
                }
                Ok(Some(ConstraintScrews {
                    free: d,
                    blocked: None,
                    keys,
                    joints: held,
                }))
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
    /// estimate |f|/|∇f| must be ≤ 10⁻⁹ of max(|p|, 1) — f at a point typed exactly is
    /// evaluated with an error of a few ε times its terms, far below 10⁻⁹, while a coordinate
    /// typed to nine or fewer significant digits of an irrational value misses by more, and is
    /// refused with a hint to write it exactly or give `normal`) and that ∇f ≠ 0 there.
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
            // |f|/|∇f| estimates the distance to the surface; a small one is a rounded
            // coordinate, not a wrong point.
            let distance = f.to_f64().abs() / g2.to_f64().sqrt();
            let scale = norm2(p).to_f64().sqrt().max(1.0);
            let hint = if distance <= 1e-3 * scale {
                format!(
                    " — the point is about {distance:.1e} from it, a rounded coordinate? Write it \
                     exactly (a fraction, or an expression such as \"0.108*cos(30 deg)\"), or give \
                     `normal` explicitly"
                )
            } else {
                String::new()
            };
            return Err(self.error(
                &key,
                Some(shown),
                format!(
                    "not on the surface f = {}: f(point) = {} ≠ 0{hint}",
                    surface.text,
                    f.exact_text().unwrap_or_else(|| f.to_f64().to_string())
                ),
            ));
        }
        Ok(grad)
    }

    /// One number in `T`: exact types refuse irrational values, naming the key and value.
    pub(crate) fn value<T: Scalar>(&self, n: &Number, key: &str) -> Result<T, SceneError> {
        let error = |message: String| SceneError {
            file: self.file.clone(),
            key: key.to_string(),
            value: Some(n.text.clone()),
            message,
        };
        let x = T::from_number(n).map_err(error)?;
        // A nonzero number that rounds to zero or to ±∞ in a float type is out of its range,
        // not zero or infinite: say so (the pipeline scales scenes first; see `scale`).
        if let Ok(q) = &n.exact
            && !num_traits::Zero::is_zero(q)
            && (!x.is_finite() || x.is_zero())
        {
            return Err(error(format!(
                "{}{} is outside the range of {}; {OUT_OF_RANGE}",
                if num_traits::Signed::is_negative(q) {
                    "−"
                } else {
                    ""
                },
                scale::magnitude(q),
                T::NAME
            )));
        }
        Ok(x)
    }
}
