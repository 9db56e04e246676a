//! The tables of a scene, with every number as written: what `[body]`, `[[contact]]`,
//! `[solve]`, `[constraints]` and `[surface]` hold, and how each is read and checked (ranges,
//! zero vectors, which keys go together).

use crate::impact::friction::Restitution;
use toml_edit::{Item, Table};

use super::SceneError;
use super::read::{Reader, short};
use crate::impact::outputs::Outputs;
use crate::impact::restitution::Model;
use crate::impact::unilateral::Law;
use crate::mechanics::surface::Surface;
use crate::number::Number;

/// The `[body]` table, before it is spread over the [`super::Scene`]'s fields.
pub(crate) struct BodyTable {
    /// m.
    pub(super) mass: Number,
    /// (J_x, J_y, J_z), or the diagonal (J_xx, J_yy, J_zz) of a 3×3 tensor.
    pub(super) inertia: [Number; 3],
    /// A 3×3 tensor's entries off the diagonal (J_xy, J_xz, J_yz); `None` for principal
    /// moments, or when they are all 0.
    pub(super) inertia_products: Option<[Number; 3]>,
    /// v_C⁰.
    pub(super) velocity: [Number; 3],
    /// ω⁰.
    pub(super) angular_velocity: [Number; 3],
}

/// The `[solve]` table, read.
pub(crate) struct SolveTable {
    /// `models`.
    pub(super) models: Vec<Model>,
    /// `law`.
    pub(super) law: Law,
    /// `restitution`.
    pub(super) restitution: Option<Restitution>,
    /// `outputs`.
    pub(super) outputs: Outputs,
    /// `tolerance`.
    pub(super) tolerance: Option<f64>,
}

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
    /// k_i^E (Stronge's energetic coefficient), when given; otherwise k_i^P (which is `k` when
    /// one `k` is given) stands for it.
    pub k_energetic: Option<Number>,
    /// μ_i, Coulomb's coefficient of friction (`mu`, default 0).
    pub mu: Number,
    /// K_i, the contact stiffness of the LZB law (`stiffness`, default 1; read only under
    /// `[solve] law = "lzb"`).
    pub stiffness: Option<Number>,
    /// η_i, the compliance exponent of the LZB law (`exponent`, default 3/2; read only under
    /// `[solve] law = "lzb"`).
    pub exponent: Option<Number>,
    /// `stiffness = "hertz"`: K_i is Hertz's, from the shapes and materials that touch; the
    /// modelling layer ([`super::model::hertz`]) sets `stiffness` to it, or refuses the scene.
    pub hertz: bool,
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
    pub(super) fn keys(self) -> &'static [&'static str] {
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

/// Whether two numbers are the same value: exactly when both are rational, as expressions
/// when either names a symbol, and to 4 ulps of the larger in f64 otherwise (irrational
/// values, evaluated in floating point).
fn same_value(a: &Number, b: &Number) -> bool {
    if let (Ok(x), Ok(y)) = (&a.exact, &b.exact) {
        return x == y;
    }
    if !a.symbols.is_empty() || !b.symbols.is_empty() {
        let symbolic = |n: &Number| crate::scalar::symbolic::symbolic(&n.text, &n.symbols);
        return match (symbolic(a), symbolic(b)) {
            (Ok(x), Ok(y)) => num_traits::Zero::is_zero(&(x - y)),
            _ => false,
        };
    }
    (a.approx - b.approx).abs() <= 4.0 * f64::EPSILON * a.approx.abs().max(b.approx.abs())
}

impl Reader<'_> {
    /// The `[body]` table: m and J (positive), v_C⁰ and ω⁰.
    pub(super) fn body(&self, root: &Table) -> Result<BodyTable, SceneError> {
        let body = self.table(root, "body", "")?;
        self.only_keys(
            body,
            "body",
            &["mass", "inertia", "velocity", "angular_velocity"],
        )?;
        let mass = self.number(self.get(body, "mass", "body")?, "body.mass")?;
        self.positive(&mass, "body.mass", "a mass must be positive")?;
        let (inertia, inertia_products) =
            self.inertia(self.get(body, "inertia", "body")?, "body.inertia")?;
        for (i, j) in inertia.iter().enumerate() {
            self.positive(
                j,
                &format!("body.inertia[{i}]"),
                "central principal moments must be positive",
            )?;
        }
        let velocity = self.triple(self.get(body, "velocity", "body")?, "body.velocity")?;
        let angular_velocity = self.triple(
            self.get(body, "angular_velocity", "body")?,
            "body.angular_velocity",
        )?;
        Ok(BodyTable {
            mass,
            inertia,
            inertia_products,
            velocity,
            angular_velocity,
        })
    }

    /// `inertia`: the central principal moments `[Jx, Jy, Jz]`, or the full tensor as a 3×3
    /// array `[[Jxx, Jxy, Jxz], [Jxy, Jyy, Jyz], [Jxz, Jyz, Jzz]]` — symmetric (exactly when
    /// both entries are rational or symbolic, to 4 ulps in f64 otherwise) with a positive
    /// diagonal. Returns the diagonal and the entries off it (J_xy, J_xz, J_yz), `None` when
    /// those are all exactly 0. Positive definiteness is checked with the problem
    /// ([`crate::impact::problem::Problem::new`]), in the scalar it runs in.
    pub(super) fn inertia(
        &self,
        item: &Item,
        key: &str,
    ) -> Result<([Number; 3], Option<[Number; 3]>), SceneError> {
        let rows = match item.as_array() {
            Some(a) if a.len() == 3 && a.iter().all(|v| v.as_array().is_some()) => a,
            Some(a) if a.iter().any(|v| v.as_array().is_some()) => {
                return Err(self.err(
                    key,
                    Some(short(item)),
                    "must be the three central principal moments [Jx, Jy, Jz] or a 3×3 tensor \
                     [[Jxx, Jxy, Jxz], [Jxy, Jyy, Jyz], [Jxz, Jyz, Jzz]] (three rows of three)",
                ));
            }
            _ => return Ok((self.triple(item, key)?, None)),
        };
        let mut j: Vec<Vec<Number>> = Vec::with_capacity(3);
        for (i, row) in rows.iter().enumerate() {
            let row_key = format!("{key}[{i}]");
            let row = row.as_array().filter(|r| r.len() == 3).ok_or_else(|| {
                self.err(
                    &row_key,
                    Some(row.to_string().trim().to_string()),
                    "must be a row of three numbers: a 3×3 tensor has three rows of three",
                )
            })?;
            let mut entries = Vec::with_capacity(3);
            for (k, v) in row.iter().enumerate() {
                entries.push(self.number_value(v, &format!("{key}[{i}][{k}]"))?);
            }
            j.push(entries);
        }
        for (i, k) in [(1, 0), (2, 0), (2, 1)] {
            let (a, b) = (&j[i][k], &j[k][i]);
            if !same_value(a, b) {
                return Err(self.err(
                    &format!("{key}[{i}][{k}]"),
                    Some(a.text.clone()),
                    format!(
                        "differs from `{key}[{k}][{i}]` = {}: an inertia tensor is symmetric, \
                         so the entries mirrored across the diagonal must be equal",
                        b.text
                    ),
                ));
            }
        }
        for k in 0..3 {
            self.positive(
                &j[k][k],
                &format!("{key}[{k}][{k}]"),
                "the diagonal entries of an inertia tensor must be positive",
            )?;
        }
        let diagonal = [j[0][0].clone(), j[1][1].clone(), j[2][2].clone()];
        let products = [j[0][1].clone(), j[0][2].clone(), j[1][2].clone()];
        let vanish = products
            .iter()
            .all(|n| matches!(&n.exact, Ok(q) if num_traits::Zero::is_zero(q)));
        Ok((diagonal, (!vanish).then_some(products)))
    }

    /// The `[solve]` table: the models asked for (all of them when absent), the impact law
    /// (the paper's simultaneous one when absent), the outputs reported (all when absent) and
    /// the spatial frictional integration's tolerance.
    pub(super) fn solve(&self, root: &Table) -> Result<SolveTable, SceneError> {
        let Some(item) = root.get("solve") else {
            return Ok(SolveTable {
                models: Model::ALL.to_vec(),
                law: Law::default(),
                restitution: None,
                outputs: Outputs::ALL,
                tolerance: None,
            });
        };
        let t = item
            .as_table()
            .ok_or_else(|| self.err("solve", Some(short(item)), "must be a table: [solve]"))?;
        self.only_keys(
            t,
            "solve",
            &[
                "models",
                "law",
                "restitution",
                "axes",
                "outputs",
                "tolerance",
            ],
        )?;
        let restitution = match t.get("restitution") {
            None => None,
            Some(r) => Some(r.as_str().and_then(Restitution::from_name).ok_or_else(|| {
                self.err(
                    "solve.restitution",
                    Some(short(r)),
                    "unknown restitution law; expected \"newton\", \"poisson\" or \"energetic\"",
                )
            })?),
        };
        let models = match t.get("models") {
            None => Model::ALL.to_vec(),
            Some(m) => self.models(m, "solve.models")?,
        };
        let law = match t.get("law") {
            None => Law::default(),
            Some(l) => l.as_str().and_then(Law::from_name).ok_or_else(|| {
                self.err(
                    "solve.law",
                    Some(short(l)),
                    "unknown law; expected \"simultaneous\" (the paper's), \"unilateral\" or \"lzb\"",
                )
            })?,
        };
        let outputs = match t.get("outputs") {
            None => Outputs::ALL,
            Some(o) => self.outputs(o, "solve.outputs")?,
        };
        let tolerance = match t.get("tolerance") {
            None => None,
            Some(item) => Some(self.tolerance(item, "solve.tolerance")?),
        };
        Ok(SolveTable {
            models,
            law,
            restitution,
            outputs,
            tolerance,
        })
    }

    /// `[solve] tolerance`: a number strictly between 0 and 1 ([`super::valid_tolerance`]).
    fn tolerance(&self, item: &Item, key: &str) -> Result<f64, SceneError> {
        let n = self
            .number(item, key)
            .map_err(|_| self.err(key, Some(short(item)), super::TOLERANCE_RULE))?;
        if n.symbols.is_empty() && super::valid_tolerance(n.approx) {
            Ok(n.approx)
        } else {
            Err(self.err(key, Some(n.text), super::TOLERANCE_RULE))
        }
    }

    /// A `[[contact]]` table: its point, normal, tangent and coefficients.
    pub(super) fn contact(&self, t: &Table, i: usize) -> Result<ContactSpec, SceneError> {
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
                "k_energetic",
                "mu",
                "stiffness",
                "exponent",
                "name",
                "body_point",
                "corner",
                "obstacle",
                "bodies",
                "body",
            ],
        )?;
        // A modelled contact may be placed by `body_point`, `corner` or its obstacle instead
        // (see `model`), which then sets the point.
        let placed = ["body_point", "corner", "obstacle"]
            .iter()
            .any(|k| t.contains_key(k));
        let point = match t.get("point") {
            None if placed => {
                std::array::from_fn(|_| crate::number::parse_number("0").expect("0 is a number"))
            }
            item => self.triple(
                item.ok_or_else(|| self.err(&format!("{at}.point"), None, "missing (required)"))?,
                &format!("{at}.point"),
            )?,
        };
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
        let ke = k_of("k_energetic")?;
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
        let k_energetic = ke;
        let mu = match t.get("mu") {
            None => crate::number::parse_number("0").expect("0 is a number"),
            Some(item) => {
                let path = format!("{at}.mu");
                self.friction(self.number(item, &path)?, &path)?
            }
        };
        let lzb_of = |key: &str| -> Result<Option<Number>, SceneError> {
            t.get(key)
                .map(|item| self.number(item, &format!("{at}.{key}")))
                .transpose()
        };
        let hertz = match t.get("stiffness").and_then(Item::as_str) {
            Some("hertz") => true,
            Some(other) => {
                return Err(self.err(
                    &format!("{at}.stiffness"),
                    Some(format!("\"{other}\"")),
                    "must be a number K > 0, or \"hertz\": Hertz's stiffness from the shapes and \
                     the `material` of the two bodies (or body and obstacle) that touch",
                ));
            }
            None => false,
        };
        Ok(ContactSpec {
            point,
            normal,
            tangent,
            k_newton,
            k_poisson,
            k_energetic,
            mu,
            stiffness: if hertz { None } else { lzb_of("stiffness")? },
            exponent: lzb_of("exponent")?,
            hertz,
        })
    }

    /// The `[surface]` table: f, parsed with its gradient.
    pub(super) fn surface(&self, item: &Item) -> Result<SurfaceSpec, SceneError> {
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
        let expanded = self
            .params
            .expand(text, &["x", "y", "z"])
            .map_err(|e| self.err("surface.f", Some(short(f)), e.to_string()))?;
        let surface = Surface::parse_with(&expanded, self.symbols)
            .map_err(|e| self.err("surface.f", Some(short(f)), e.message))?;
        Ok(SurfaceSpec {
            text: text.to_string(),
            surface,
        })
    }

    /// The `[constraints]` table: the paper's screws, or joints.
    pub(super) fn constraints(&self, item: &Item) -> Result<ConstraintsSpec, SceneError> {
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

    /// A list of six-number screws, none zero.
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

    /// A `[[constraints.joint]]` table: its kind and the vectors the kind needs.
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

    /// The outputs listed in `[solve] outputs` ([`Outputs::NAMED`], or `"all"`).
    fn outputs(&self, item: &Item, key: &str) -> Result<Outputs, SceneError> {
        let arr = item.as_array().ok_or_else(|| {
            self.err(
                key,
                Some(short(item)),
                "must be an array such as [\"impulses\", \"twist\"]",
            )
        })?;
        let mut outputs = Outputs::NONE;
        for v in arr.iter() {
            let shown = v.to_string().trim().to_string();
            let name = v.as_str().unwrap_or(&shown);
            outputs |= Outputs::parse([name])
                .map_err(|e| self.err(key, Some(shown.clone()), e.to_string()))?;
        }
        if outputs.is_empty() {
            return Err(self.err(key, Some("[]".into()), "list at least one output"));
        }
        Ok(outputs)
    }

    /// The models listed in `[solve] models`, each once.
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
