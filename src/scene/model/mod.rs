//! Scenes as a user thinks of them: a world frame, the body's pose, its shape, obstacles and
//! named parameters — brought to the solver's frame.
//!
//! The paper writes every vector in the body's central principal axes. A modelled scene writes
//! them where the user sees them:
//!
//! * `[params]`: named values usable in every expression (`params.rs`);
//! * `[body] shape` (or `mass` with `inertia` — three principal moments or a full tensor —
//!   about `inertia_about`, with `centre_of_mass`), all in body axes (`shape.rs`);
//! * `[body] pose` (R, body → world, `pose.rs`) and `position` (the body origin in the world);
//!   `velocity` (of the centre of mass C) and `angular_velocity` in the world frame;
//! * contacts at a world `point`, a `body_point` (body axes) or a box `corner`, against an
//!   `[[obstacle]]` plane (`obstacle.rs`) or with a world `normal` and `tangent`.
//!
//! The solver then works with its origin at C, in world axes (the default: results come back in
//! the world frame) or in body axes (`[solve] axes = "body"`):
//!
//! ```text
//! C_w = position + R c                  r_i = Q (A_i − C_w)          n_i, y_i, v_C, ω ↦ Q ·
//! J = R J_C Rᵀ (world)  or  J_C (body)   with Q = I (world) or Rᵀ (body)
//! J_C = J_A − m (|d|² I − d dᵀ),  d = A − c   (the parallel-axis theorem, `inertia_about` A)
//! ```
//!
//! Every value is combined as an expression (`term.rs`) and read again like a written number,
//! so exact scenes stay exact (a rational rotation gives fractions, `30 deg` radicals) and a
//! parameter is a symbol for `derive` and carries its derivative in a sensitivity run. A scene
//! that uses none of these keys is read exactly as before.

pub(crate) mod exact_sphere;
pub(crate) mod hertz;
pub(crate) mod obstacle;
pub(crate) mod params;
pub(crate) mod pose;
pub(crate) mod shape;
pub(crate) mod simulated_system;
pub(crate) mod simulation;
pub(crate) mod system;
pub(crate) mod term;

use toml_edit::{Item, Table};

use super::SceneError;
use super::read::{Reader, short};
use super::schema::{BodyTable, ConstraintsSpec, ContactSpec};
use crate::number::Number;
use obstacle::{Obstacle, touching_corners, world};
use shape::Shape;
use term::{Mat3, Term, Vec3, apply, dot, product, sub, transpose, zero};

/// The axes a modelled scene is solved and reported in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axes {
    /// World axes, origin at the centre of mass (the default).
    World,
    /// The body's axes, origin at the centre of mass.
    Body,
}

impl Axes {
    /// Its name in scene files and reports.
    pub fn name(self) -> &'static str {
        match self {
            Axes::World => "world",
            Axes::Body => "body",
        }
    }
}

/// Body keys only a modelled scene has.
const BODY_KEYS: [&str; 6] = [
    "shape",
    "density",
    "pose",
    "position",
    "centre_of_mass",
    "inertia_about",
];
/// Contact keys only a modelled scene has.
const CONTACT_KEYS: [&str; 3] = ["body_point", "corner", "obstacle"];

/// Whether the document uses the modelling keys (else it is read as the paper's body-axes scene).
pub(crate) fn declared(root: &Table) -> bool {
    let body = root.get("body").and_then(Item::as_table_like);
    let in_body = body.is_some_and(|b| BODY_KEYS.iter().any(|k| b.contains_key(k)));
    let contacts = match root.get("contact") {
        Some(Item::ArrayOfTables(a)) => a
            .iter()
            .any(|t| CONTACT_KEYS.iter().any(|k| t.contains_key(k))),
        _ => false,
    };
    let axes = root
        .get("solve")
        .and_then(Item::as_table_like)
        .is_some_and(|s| s.contains_key("axes"));
    in_body || contacts || axes || root.contains_key("obstacle")
}

/// What the lowering gives the scene besides its contacts and constraints.
pub(crate) struct Lowered {
    pub(crate) body: BodyTable,
    pub(crate) axes: Axes,
}

/// The touching corners a read has found, by box, pose and plane normal: each contact on an
/// obstacle and the check that every touching corner is named ask again (three times for a box
/// on two corners), and each time the eight corners' heights were combined and compared anew.
/// Only answers are kept: a comparison that fails fails again, naming its own contact.
#[derive(Default)]
pub(crate) struct LowestCorners(std::cell::RefCell<Vec<(LowestKey, Lowest)>>);

/// The touching corners found: their sign patterns, `None` when a comparison depends on symbols.
type Lowest = Option<Vec<[i64; 3]>>;

/// The touching corners a read keeps at most (the last found): a scene of many boxes asks
/// about each once or twice in a row, and a longer list would only lengthen the search.
const LOWEST_KEPT: usize = 16;

/// What the touching corners depend on: the box's edges, its pose R and the plane's normal.
type LowestKey = (Vec3, Mat3, Vec3);

/// A body whose central inertia tensor is singular.
enum Degenerate {
    /// No moment about the line through C along u (body axes).
    Line(Vec3),
    /// No moment at all.
    Point,
}

/// The frame of a modelled scene: R, the body origin, C, and the output axes.
struct Frame {
    r: Mat3,
    position: Vec3,
    centre_body: Vec3,
    centre: Vec3,
    axes: Axes,
}

impl Frame {
    /// A world vector in the output axes.
    fn out(&self, v: &Vec3) -> Vec3 {
        match self.axes {
            Axes::World => v.clone(),
            Axes::Body => apply(&transpose(&self.r), v),
        }
    }
}

impl Reader<'_> {
    /// A term read back as a number of the scene, at `key` (for messages).
    pub(super) fn term_number(&self, t: &Term, key: &str) -> Result<Number, SceneError> {
        self.params
            .number(&t.to_string())
            .map_err(|e| self.err(key, None, format!("the derived value cannot be read: {e}")))
    }

    /// Three terms as numbers at `key[i]`.
    fn numbers3(&self, v: &Vec3, key: &str) -> Result<[Number; 3], SceneError> {
        Ok([
            self.term_number(&v[0], &format!("{key}[0]"))?,
            self.term_number(&v[1], &format!("{key}[1]"))?,
            self.term_number(&v[2], &format!("{key}[2]"))?,
        ])
    }

    /// The value of a term for messages: exact when it is, else a decimal.
    pub(super) fn approx(&self, t: &Term) -> String {
        match self.params.number(&t.to_string()) {
            Ok(n) => match &n.exact {
                Ok(q) => crate::number::format_rational(q),
                Err(_) if !n.symbols.is_empty() => n.text.clone(),
                Err(_) => format!("{:.6e}", n.approx),
            },
            Err(_) => t.to_string(),
        }
    }

    /// The sign of a term: exact for rationals and radicals (`cos(30 deg)`), to 2⁻⁴⁰ relative
    /// to `scale` for other irrational values (`cos(3 deg)`, read in f64), `None` when it names
    /// a symbol (its sign is the reader's to assume).
    pub(super) fn sign_at(
        &self,
        t: &Term,
        scale: f64,
        key: &str,
    ) -> Result<Option<i8>, SceneError> {
        if let Term::Rat(q) = t {
            return Ok(Some(sign_of(q)));
        }
        // Far from zero — beyond twice the error bound carried along — the f64 value decides.
        let (x, e) = (t.approx(), t.error());
        if x.is_finite() && e.is_finite() && x.abs() > 2.0 * e {
            return Ok(Some(if x > 0.0 { 1 } else { -1 }));
        }
        let n = self.term_number(t, key)?;
        if let Ok(q) = &n.exact {
            return Ok(Some(sign_of(q)));
        }
        if !n.symbols.is_empty() {
            return Ok(None);
        }
        if let Ok(x) = crate::scalar::symbolic::symbolic(&n.text, &[]) {
            return Ok(crate::scalar::Scalar::known_sign(&x));
        }
        // Transcendental: an f64 value. Its error is a few rounding errors of the terms that
        // make it (each of the size of `scale`); 2⁻⁴⁰ leaves room for long expressions.
        Ok(Some(if n.approx.abs() <= scale.abs() * 2f64.powi(-40) {
            0
        } else if n.approx > 0.0 {
            1
        } else {
            -1
        }))
    }

    /// The sign of a − b (see [`Reader::sign_at`]), 0 at once when a and b are the [same
    /// term](same): reading `(a) - (a)` back would decide it only after parsing and evaluating
    /// the text (and, for an irrational a, trying its radical form) — most of the cost of
    /// reading a posed box, whose corners at one height have one text.
    pub(super) fn sign_of_difference(
        &self,
        a: &Term,
        b: &Term,
        scale: f64,
        key: &str,
    ) -> Result<Option<i8>, SceneError> {
        if same(a, b) {
            return Ok(Some(0));
        }
        self.sign_at(&(a - b), scale, key)
    }

    /// The sign of (a − b)·n (see [`Reader::sign_at`]), 0 at once when each component of a − b
    /// is a difference of the [same term](same) or meets a zero component of n.
    fn sign_of_height(
        &self,
        (a, b): (&Vec3, &Vec3),
        n: &Vec3,
        scale: f64,
        key: &str,
    ) -> Result<Option<i8>, SceneError> {
        if (0..3).all(|i| same(&a[i], &b[i]) || n[i].is_zero()) {
            return Ok(Some(0));
        }
        self.sign_at(&dot(&sub(a, b), n), scale, key)
    }

    /// [`Reader::sign_at`] with the scale 1.
    pub(super) fn sign(&self, t: &Term, key: &str) -> Result<Option<i8>, SceneError> {
        self.sign_at(t, 1.0, key)
    }

    /// Whether a term is zero (see [`Reader::sign_at`]).
    pub(super) fn decide_zero(&self, t: &Term, key: &str) -> Result<Option<bool>, SceneError> {
        Ok(self.sign(t, key)?.map(|s| s == 0))
    }

    /// The magnitude of a term in f64 (for tolerances).
    pub(super) fn magnitude(&self, t: &Term) -> f64 {
        let x = t.approx().abs();
        if x.is_finite() { x } else { 1.0 }
    }

    /// Read a modelled scene's body, and bring its contacts and constraints to the solver's
    /// frame.
    pub(crate) fn lower(
        &self,
        root: &Table,
        contacts: &mut [ContactSpec],
        constraints: &mut Option<ConstraintsSpec>,
    ) -> Result<Lowered, SceneError> {
        if root.contains_key("surface") {
            return Err(self.err(
                "surface",
                None,
                "a [surface] is read in the paper's body axes at the centre of mass; it cannot be \
                 combined with shape, pose, position, centre_of_mass, obstacles or body points yet — \
                 write the scene in body axes, or give each contact its normal",
            ));
        }
        let body = self.table(root, "body", "")?;
        let mut keys = vec!["mass", "inertia", "velocity", "angular_velocity"];
        keys.extend(BODY_KEYS);
        keys.push("material");
        self.only_keys(body, "body", &keys)?;
        let material = self.material(body, "body")?;
        let (mut props, shape) = self.mass_properties(body, "body")?;
        let degenerate = self.degenerate(&mut props, shape.as_ref(), "body")?;
        let r = self.pose(body.get("pose"), "body")?;
        let position = match body.get("position") {
            None => zero(),
            Some(p) => self.triple(p, "body.position")?.each_ref().map(Term::of),
        };
        let axes = self.axes(root)?;
        let centre = world(&position, &r, &props.centre);
        let frame = Frame {
            r,
            position,
            centre_body: props.centre.clone(),
            centre,
            axes,
        };
        let obstacles = self.obstacles(root)?;
        self.place_contacts(
            root,
            contacts,
            &frame,
            &obstacles,
            (shape.as_ref(), material),
        )?;
        if let Some(c) = constraints {
            self.lower_constraints(c, &frame)?;
        }
        if let Some(d) = &degenerate {
            self.check_degenerate(d, contacts, constraints.is_some(), &frame)?;
        }
        let velocity = self.triple(self.get(body, "velocity", "body")?, "body.velocity")?;
        let omega = self.triple(
            self.get(body, "angular_velocity", "body")?,
            "body.angular_velocity",
        )?;
        let velocity = self.numbers3(
            &frame.out(&velocity.each_ref().map(Term::of)),
            "body.velocity",
        )?;
        let angular_velocity = self.numbers3(
            &frame.out(&omega.each_ref().map(Term::of)),
            "body.angular_velocity",
        )?;
        let j = match axes {
            Axes::World => product(&product(&frame.r, &props.inertia), &transpose(&frame.r)),
            Axes::Body => props.inertia.clone(),
        };
        let mass = self.term_number(&props.mass, "body.mass")?;
        self.positive(&mass, "body.mass", "a mass must be positive")?;
        let inertia = [
            self.term_number(&j[0][0], "body.inertia[0]")?,
            self.term_number(&j[1][1], "body.inertia[1]")?,
            self.term_number(&j[2][2], "body.inertia[2]")?,
        ];
        let off = [&j[0][1], &j[0][2], &j[1][2]];
        let inertia_products = if off.iter().all(|t| t.is_zero()) {
            None
        } else {
            Some([
                self.term_number(off[0], "body.inertia[0][1]")?,
                self.term_number(off[1], "body.inertia[0][2]")?,
                self.term_number(off[2], "body.inertia[1][2]")?,
            ])
        };
        Ok(Lowered {
            body: BodyTable {
                mass,
                inertia,
                inertia_products,
                velocity,
                angular_velocity,
            },
            axes,
        })
    }

    /// A body with no moment of inertia about a line through C (a thin rod, point masses on a
    /// line) or about any (one point mass): J_C is singular, with null space spanned by the
    /// axis u (or everything). No contact on that line has a moment about it, so the impact does
    /// not depend on the missing moment: J_C is completed to J_C + c·P (P the projector on the
    /// null space, c = tr J_C / 2, the rod's transverse moment) — any c > 0 gives the same
    /// impulses, twist and energies, since J⁻¹ never acts along u — and each contact is then
    /// checked to have no moment about u ([`Reader::check_degenerate`]).
    fn degenerate(
        &self,
        props: &mut shape::MassProperties,
        shape: Option<&Shape>,
        prefix: &str,
    ) -> Result<Option<Degenerate>, SceneError> {
        let j = &mut props.inertia;
        let found = match shape {
            Some(Shape::Rod(_)) => {
                Some(Degenerate::Line([Term::int(0), Term::int(0), Term::int(1)]))
            }
            Some(Shape::Points(points)) => {
                let d: Vec<Vec3> = points.iter().map(|(_, p)| sub(p, &props.centre)).collect();
                let mut axis: Option<Vec3> = None;
                for di in &d {
                    if dot(di, di).is_zero()
                        || self.decide_zero(&dot(di, di), &format!("{prefix}.shape.points"))?
                            == Some(true)
                    {
                        continue;
                    }
                    match &axis {
                        None => axis = Some(di.clone()),
                        Some(u) => {
                            let c = term::cross(u, di);
                            let off = dot(&c, &c);
                            if self.decide_zero(&off, &format!("{prefix}.shape.points"))?
                                != Some(true)
                            {
                                return Ok(None);
                            }
                        }
                    }
                }
                Some(match axis {
                    Some(u) => Degenerate::Line(u),
                    None => Degenerate::Point,
                })
            }
            _ => None,
        };
        let Some(found) = found else {
            return Ok(None);
        };
        let trace = &(&j[0][0] + &j[1][1]) + &j[2][2];
        let c = match &found {
            Degenerate::Line(_) => &trace / &Term::int(2),
            // One point mass: no moment at all; any c serves, c = m (in units of kg m²).
            Degenerate::Point => props.mass.clone(),
        };
        for a in 0..3 {
            for b in 0..3 {
                let p = match &found {
                    Degenerate::Line(u) => &(&u[a] * &u[b]) / &dot(u, u),
                    Degenerate::Point => Term::int(i64::from(a == b)),
                };
                j[a][b] = &j[a][b] + &(&c * &p);
            }
        }
        Ok(Some(found))
    }

    /// A body without a moment about u (or at all): every contact must have none either —
    /// (r × n)·u = 0, and with friction r × u = 0 (the tangential impulses too) — and
    /// constraints are refused (their screws may have one).
    fn check_degenerate(
        &self,
        d: &Degenerate,
        contacts: &[ContactSpec],
        constrained: bool,
        frame: &Frame,
    ) -> Result<(), SceneError> {
        let what = match d {
            Degenerate::Line(_) => "about its own axis (a thin rod, or point masses on a line)",
            Degenerate::Point => "at all (a single point mass)",
        };
        if constrained {
            return Err(self.err(
                "constraints",
                None,
                format!("the body has no moment of inertia {what}; constraints on such a body are not supported — give it a thickness (a cylinder, or masses off the line)"),
            ));
        }
        let axis = match d {
            Degenerate::Line(u) => Some(match frame.axes {
                Axes::World => apply(&frame.r, u),
                Axes::Body => u.clone(),
            }),
            Degenerate::Point => None,
        };
        for (i, c) in contacts.iter().enumerate() {
            let r = c.point.each_ref().map(Term::of);
            let Some(n) = &c.normal else { continue };
            let n = n.each_ref().map(Term::of);
            let moment = term::cross(&r, &n);
            let rough = !matches!(&c.mu.exact, Ok(q) if num_traits::Zero::is_zero(q));
            let (bad, reason) = match &axis {
                Some(u) => {
                    let about = dot(&moment, u);
                    let off = term::cross(&r, u);
                    let off_axis =
                        rough && self.decide_zero(&dot(&off, &off), "contact")? == Some(false);
                    (
                        self.decide_zero(&about, "contact")? == Some(false) || off_axis,
                        "a moment about the body's axis",
                    )
                }
                None => (
                    self.decide_zero(&dot(&moment, &moment), "contact")? == Some(false),
                    "a moment about the centre of mass",
                ),
            };
            if bad {
                return Err(self.err(
                    &format!("contact[{i}]"),
                    None,
                    format!(
                        "its impulse has {reason}, but the body has no moment of inertia {what}: touch it on \
                         its axis (for a rod, `body_point = [0, 0, z]`), or give it a thickness"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// `[solve] axes`.
    fn axes(&self, root: &Table) -> Result<Axes, SceneError> {
        let item = root
            .get("solve")
            .and_then(Item::as_table_like)
            .and_then(|s| s.get("axes"));
        match item {
            None => Ok(Axes::World),
            Some(a) => match a.as_str() {
                Some("world") => Ok(Axes::World),
                Some("body") => Ok(Axes::Body),
                _ => Err(self.err(
                    "solve.axes",
                    Some(short(a)),
                    "expected \"world\" (results in world axes) or \"body\" (in the body's axes)",
                )),
            },
        }
    }

    /// m, c and J_C in body axes, from the shape or from `mass`, `inertia`, `inertia_about`
    /// and `centre_of_mass`.
    fn mass_properties(
        &self,
        body: &Table,
        prefix: &str,
    ) -> Result<(shape::MassProperties, Option<Shape>), SceneError> {
        let refuse = |key: &str, why: &str| -> Result<(), SceneError> {
            match body.get(key) {
                Some(v) => {
                    Err(self.err(&format!("{prefix}.{key}"), Some(short(v)), why.to_string()))
                }
                None => Ok(()),
            }
        };
        if let Some(s) = body.get("shape") {
            let shape = self.shape(s, &format!("{prefix}.shape"))?;
            for key in ["inertia", "centre_of_mass", "inertia_about"] {
                refuse(
                    key,
                    "the shape gives the mass properties; give either a shape or the mass properties",
                )?;
            }
            let mass = if let Shape::Points(_) = shape {
                for key in ["mass", "density"] {
                    refuse(key, "point masses carry their own masses")?;
                }
                Term::int(0)
            } else {
                match (body.get("mass"), body.get("density")) {
                    (Some(m), None) => {
                        let m = self.number(m, &format!("{prefix}.mass"))?;
                        self.positive(&m, &format!("{prefix}.mass"), "a mass must be positive")?;
                        let density = shape.volume().map(|v| m.approx / v.approx());
                        if let Some(rho) = density.filter(|d| d.is_finite()) {
                            self.observed
                                .borrow_mut()
                                .density
                                .push((prefix.to_string(), rho));
                        }
                        Term::of(&m)
                    }
                    (None, Some(rho)) => {
                        let rho = self.number(rho, &format!("{prefix}.density"))?;
                        self.positive(
                            &rho,
                            &format!("{prefix}.density"),
                            "a density must be positive",
                        )?;
                        let volume = shape.volume().ok_or_else(|| {
                            self.err(
                                &format!("{prefix}.density"),
                                Some(rho.text.clone()),
                                "a thin rod has no volume: give its `mass`",
                            )
                        })?;
                        &Term::of(&rho) * &volume
                    }
                    (Some(_), Some(_)) => {
                        return Err(self.err(
                            &format!("{prefix}.density"),
                            None,
                            "give `mass` or `density`, not both",
                        ));
                    }
                    (None, None) => {
                        return Err(self.err(
                            &format!("{prefix}.mass"),
                            None,
                            "missing: give the body's `mass` or `density`",
                        ));
                    }
                }
            };
            let props = shape.mass_properties(&mass);
            return Ok((props, Some(shape)));
        }
        refuse("density", "a density needs a `shape` to give the volume")?;
        let m = self.number(self.get(body, "mass", prefix)?, &format!("{prefix}.mass"))?;
        self.positive(&m, &format!("{prefix}.mass"), "a mass must be positive")?;
        let mass = Term::of(&m);
        let (diagonal, products) = self.inertia(
            self.get(body, "inertia", prefix)?,
            &format!("{prefix}.inertia"),
        )?;
        let d = diagonal.each_ref().map(Term::of);
        let p = products.as_ref().map(|p| p.each_ref().map(Term::of));
        // (J_xy, J_xz, J_yz) at (0, 1), (0, 2), (1, 2), mirrored.
        let j_a: Mat3 = std::array::from_fn(|i| {
            std::array::from_fn(|k| match (i == k, &p) {
                (true, _) => d[i].clone(),
                (false, None) => Term::int(0),
                (false, Some(p)) => p[i + k - 1].clone(),
            })
        });
        let centre = match body.get("centre_of_mass") {
            None => zero(),
            Some(c) => self
                .triple(c, &format!("{prefix}.centre_of_mass"))?
                .each_ref()
                .map(Term::of),
        };
        let j_c = match body.get("inertia_about") {
            None => j_a,
            Some(a) => {
                // J_C = J_A − m (|d|² I − d dᵀ), d = A − c.
                let about = self
                    .triple(a, &format!("{prefix}.inertia_about"))?
                    .each_ref()
                    .map(Term::of);
                let d = sub(&about, &centre);
                let d2 = dot(&d, &d);
                std::array::from_fn(|i| {
                    std::array::from_fn(|k| {
                        let shift = if i == k {
                            &d2 - &(&d[i] * &d[k])
                        } else {
                            -&(&d[i] * &d[k])
                        };
                        &j_a[i][k] - &(&mass * &shift)
                    })
                })
            }
        };
        Ok((
            shape::MassProperties {
                mass,
                centre,
                inertia: j_c,
            },
            None,
        ))
    }

    /// Each contact's point, normal and tangent in the solver's frame.
    fn place_contacts(
        &self,
        root: &Table,
        contacts: &mut [ContactSpec],
        frame: &Frame,
        obstacles: &[Obstacle],
        (shape, material): (Option<&Shape>, Option<hertz::Material>),
    ) -> Result<(), SceneError> {
        let Some(Item::ArrayOfTables(tables)) = root.get("contact") else {
            return Ok(());
        };
        let mut heights: Vec<Option<(usize, usize, Term)>> = Vec::new();
        let mut named: Vec<(usize, usize, Vec3)> = Vec::new();
        for (i, (t, spec)) in tables.iter().zip(contacts.iter_mut()).enumerate() {
            let at = format!("contact[{i}]");
            let given: Vec<&str> = ["point", "body_point", "corner"]
                .into_iter()
                .filter(|k| t.contains_key(k))
                .collect();
            if given.len() > 1 {
                return Err(self.err(
                    &format!("{at}.{}", given[1]),
                    None,
                    format!("give one of `point` (world), `body_point` (body axes) or `corner`, not `{}` and `{}`", given[0], given[1]),
                ));
            }
            let obstacle = match t.get("obstacle") {
                None => None,
                Some(o) => {
                    if let Some(n) = t.get("normal") {
                        return Err(self.err(
                            &format!("{at}.normal"),
                            Some(short(n)),
                            "the contact names an obstacle, whose normal gives the body's (n = −N); drop `normal`",
                        ));
                    }
                    Some(self.obstacle_ref(o, &format!("{at}.obstacle"), obstacles)?)
                }
            };
            // The point in body axes when known, and in the world.
            let (body_point, world_point): (Option<Vec3>, Vec3) = match given.first().copied() {
                Some("point") => (None, spec.point.each_ref().map(Term::of)),
                Some("body_point") => {
                    let p = self.triple(
                        t.get("body_point").expect("given"),
                        &format!("{at}.body_point"),
                    )?;
                    let p = p.each_ref().map(Term::of);
                    (Some(p.clone()), world(&frame.position, &frame.r, &p))
                }
                Some(_) => {
                    let p = self.corner(
                        t.get("corner").expect("given"),
                        &format!("{at}.corner"),
                        shape,
                    )?;
                    (Some(p.clone()), world(&frame.position, &frame.r, &p))
                }
                None => {
                    let Some(o) = obstacle else {
                        return Err(self.err(&format!("{at}.point"), None, "missing (required): give `point` (world), `body_point` (body axes) or `corner`"));
                    };
                    let p = self.touch_point(&obstacles[o], o, shape, frame, &at)?;
                    (Some(p.clone()), world(&frame.position, &frame.r, &p))
                }
            };
            let r = match (&body_point, frame.axes) {
                (Some(p), Axes::Body) => sub(p, &frame.centre_body),
                _ => frame.out(&sub(&world_point, &frame.centre)),
            };
            spec.point = self.numbers3(&r, &format!("{at}.point"))?;
            if let Some(t) = &spec.tangent {
                spec.tangent = Some(self.numbers3(
                    &frame.out(&t.each_ref().map(Term::of)),
                    &format!("{at}.tangent"),
                )?);
            }
            match obstacle {
                Some(o) => {
                    let ob = &obstacles[o];
                    let n = ob.normal.each_ref().map(|x| -x);
                    spec.normal = Some(self.numbers3(&frame.out(&n), &format!("{at}.normal"))?);
                    let h = self.check_obstacle(
                        ob,
                        o,
                        &world_point,
                        body_point.as_ref(),
                        frame,
                        shape,
                        &at,
                    )?;
                    heights.push(Some((i, o, h)));
                    named.push((i, o, world_point.clone()));
                    if spec.hertz {
                        let body = self.hertz_surface(shape, None);
                        self.set_hertz(
                            &at,
                            &mut spec.stiffness,
                            &mut spec.exponent,
                            [
                                (body, material, "the body"),
                                (hertz::Surface::Flat, ob.material, &ob.label(o)),
                            ],
                        )?;
                    }
                }
                None => {
                    if spec.hertz {
                        return Err(self.err(
                            &format!("{at}.stiffness"),
                            Some("\"hertz\"".to_string()),
                            "Hertz's stiffness needs the surface the body strikes: name its \
                             `obstacle` (with a `material`), or give `stiffness` as a number",
                        ));
                    }
                    if let Some(n) = &spec.normal {
                        spec.normal = Some(self.numbers3(
                            &frame.out(&n.each_ref().map(Term::of)),
                            &format!("{at}.normal"),
                        )?);
                    }
                    heights.push(None);
                }
            }
        }
        // Contacts on one plane without a given point must be at one height along N.
        let on: Vec<(usize, usize, Term)> = heights.into_iter().flatten().collect();
        for (a, (i, o, h)) in on.iter().enumerate() {
            for (j, p, g) in &on[a + 1..] {
                if o == p && obstacles[*o].point.is_none() {
                    let diff = g - h;
                    if self
                        .sign_at(
                            &diff,
                            self.magnitude(h).max(self.magnitude(g)),
                            &format!("contact[{j}].obstacle"),
                        )?
                        .is_some_and(|s| s != 0)
                    {
                        return Err(self.err(
                            &format!("contact[{j}]"),
                            None,
                            format!(
                                "contacts {i} and {j} both touch {} but lie {} apart along its normal: \
                                 both cannot touch the plane; check the pose and the points",
                                obstacles[*o].label(*o),
                                self.approx(&diff)
                            ),
                        ));
                    }
                }
            }
        }
        if let Some(Shape::Box(dims)) = shape {
            self.every_touching_corner_named(&named, obstacles, frame, dims)?;
        }
        Ok(())
    }

    /// A box that touches an obstacle along an edge or a face must have a contact at each
    /// touching corner: with only some named, the solve would let the others pass through the
    /// plane (a box lying flat with two of its four corners named spins into the floor). The
    /// obstacle's `partial = true` says the omission is deliberate. `named` holds each contact
    /// that names an obstacle: its index, the obstacle's and its world point.
    fn every_touching_corner_named(
        &self,
        named: &[(usize, usize, Vec3)],
        obstacles: &[Obstacle],
        frame: &Frame,
        dims: &Vec3,
    ) -> Result<(), SceneError> {
        for (o, ob) in obstacles.iter().enumerate() {
            let on: Vec<&(usize, usize, Vec3)> = named.iter().filter(|c| c.1 == o).collect();
            let Some(&&(first, _, ref plane)) = on.first() else {
                continue;
            };
            if ob.partial {
                continue;
            }
            let at = format!("contact[{first}]");
            let Some(lowest) = self.touching(dims, frame, &ob.normal, &at)? else {
                continue;
            };
            // The lowest corners touch when they lie on the plane (through the contacts).
            let plane = ob.point.as_ref().unwrap_or(plane);
            let mut touching = Vec::new();
            let mut corners = Vec::new();
            for s in &lowest {
                let corner = world(&frame.position, &frame.r, &Shape::corner(dims, *s));
                let scale = corner
                    .iter()
                    .chain(plane.iter())
                    .map(|x| self.magnitude(x))
                    .fold(0.0, f64::max)
                    .max(1e-300)
                    * ob.normal
                        .iter()
                        .map(|x| self.magnitude(x))
                        .fold(0.0, f64::max);
                if self.sign_of_height((&corner, plane), &ob.normal, scale, &at)? == Some(0) {
                    touching.push(*s);
                    corners.push(corner);
                }
            }
            if touching.len() < 2 {
                continue;
            }
            let mut missing = Vec::new();
            for (s, corner) in touching.iter().zip(&corners) {
                let scale = corner
                    .iter()
                    .map(|x| self.magnitude(x))
                    .fold(0.0, f64::max)
                    .max(1e-300);
                let mut found = false;
                for (_, _, p) in &on {
                    let mut same = true;
                    for (a, b) in p.iter().zip(corner) {
                        same &= self.sign_of_difference(a, b, scale, &at)? == Some(0);
                    }
                    found |= same;
                }
                if !found {
                    missing.push(*s);
                }
            }
            if missing.is_empty() {
                continue;
            }
            let list = |corners: &[[i64; 3]]| {
                corners
                    .iter()
                    .map(|s| format!("{s:?}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            return Err(self.err(
                &format!("obstacle[{o}]"),
                None,
                format!(
                    "the box touches {} at {} corners in this pose ({}), but the contacts name \
                     {} of them: the others would pass through the plane. Add a contact for each \
                     missing corner (`corner = {}`), or set `partial = true` on the obstacle if \
                     leaving them out is deliberate",
                    ob.label(o),
                    touching.len(),
                    list(&touching),
                    touching.len() - missing.len(),
                    list(&missing).replace("], [", "]`, `corner = ["),
                ),
            ));
        }
        Ok(())
    }

    /// `corner = [±1, ±1, ±1]` of a box shape, in body axes.
    fn corner(&self, item: &Item, key: &str, shape: Option<&Shape>) -> Result<Vec3, SceneError> {
        let Some(Shape::Box(dims)) = shape else {
            return Err(self.err(
                key,
                Some(short(item)),
                "a corner needs `[body] shape = { box = [a, b, c] }`; give `body_point` otherwise",
            ));
        };
        let signs: Option<Vec<i64>> = item.as_array().filter(|a| a.len() == 3).and_then(|a| {
            a.iter()
                .map(|v| v.as_integer().filter(|s| s.abs() == 1))
                .collect()
        });
        let s = signs.ok_or_else(|| {
            self.err(
                key,
                Some(short(item)),
                "must be three signs, e.g. [1, -1, -1]: the corner (±a/2, ±b/2, ±c/2)",
            )
        })?;
        Ok(Shape::corner(dims, [s[0], s[1], s[2]]))
    }

    /// The point where a sphere touches a plane, or a box's one lowest corner, in body axes.
    fn touch_point(
        &self,
        ob: &Obstacle,
        o: usize,
        shape: Option<&Shape>,
        frame: &Frame,
        at: &str,
    ) -> Result<Vec3, SceneError> {
        match shape {
            Some(Shape::Sphere(radius)) => {
                // C − r N/|N| in the world, i.e. c − r Rᵀ N/|N| in body axes.
                let n2 = dot(&ob.normal, &ob.normal);
                let norm = self.root(&n2);
                let down = apply(&transpose(&frame.r), &ob.normal).map(|x| &(&(-&x) * radius) / &norm);
                Ok(term::add(&frame.centre_body, &down))
            }
            Some(Shape::Box(dims)) => {
                let Some(lowest) = self.touching(dims, frame, &ob.normal, at)? else {
                    return Err(self.err(
                        &format!("{at}.corner"),
                        None,
                        "which corner touches depends on the symbols: name it with `corner`",
                    ));
                };
                match lowest.as_slice() {
                    [s] => Ok(Shape::corner(dims, *s)),
                    many => Err(self.err(
                        &format!("{at}.corner"),
                        None,
                        format!(
                            "{} corners of the box touch {} in this pose ({}): name each with `corner`, one contact per corner",
                            many.len(),
                            ob.label(o),
                            many.iter().map(|s| format!("{s:?}")).collect::<Vec<_>>().join(", ")
                        ),
                    )),
                }
            }
            _ => Err(self.err(
                &format!("{at}.body_point"),
                None,
                "missing: name the body's point that touches the obstacle (`body_point`, or `corner` for a box)",
            )),
        }
    }

    /// A box's touching corners against the plane normal `n`; `None` when a comparison
    /// depends on symbols (then the reader of the derived formulas answers for it).
    fn touching(
        &self,
        dims: &Vec3,
        frame: &Frame,
        n: &Vec3,
        at: &str,
    ) -> Result<Option<Vec<[i64; 3]>>, SceneError> {
        let found = self
            .lowest
            .0
            .borrow()
            .iter()
            .find_map(|((d, r, m), lowest)| {
                (d == dims && *r == frame.r && m == n).then(|| lowest.clone())
            });
        if let Some(lowest) = found {
            return Ok(lowest);
        }
        let lowest = self.touching_anew(dims, frame, n, at)?;
        let mut kept = self.lowest.0.borrow_mut();
        if kept.len() == LOWEST_KEPT {
            kept.remove(0);
        }
        kept.push(((dims.clone(), frame.r.clone(), n.clone()), lowest.clone()));
        Ok(lowest)
    }

    /// [`Reader::touching`], comparing the corners' heights.
    fn touching_anew(
        &self,
        dims: &Vec3,
        frame: &Frame,
        n: &Vec3,
        at: &str,
    ) -> Result<Option<Vec<[i64; 3]>>, SceneError> {
        let scale = dims.iter().map(|d| self.magnitude(d)).fold(0.0, f64::max)
            * n.iter().map(|d| self.magnitude(d)).fold(0.0, f64::max);
        let mut failure = None;
        let mut undecided = false;
        let result = touching_corners(dims, &frame.r, n, |a, b| {
            match self.sign_of_difference(a, b, scale, at) {
                Ok(Some(s)) => Some(s.cmp(&0)),
                Ok(None) => {
                    undecided = true;
                    None
                }
                Err(e) => {
                    failure = Some(e);
                    None
                }
            }
        });
        match failure {
            Some(e) => Err(e),
            None => Ok((!undecided).then_some(result)),
        }
    }

    /// The checks of a contact against its obstacle; returns the point's height along N.
    #[allow(clippy::too_many_arguments)]
    fn check_obstacle(
        &self,
        ob: &Obstacle,
        o: usize,
        point: &Vec3,
        body_point: Option<&Vec3>,
        frame: &Frame,
        shape: Option<&Shape>,
        at: &str,
    ) -> Result<Term, SceneError> {
        let n = &ob.normal;
        let label = ob.label(o);
        let scale = point
            .iter()
            .chain(frame.centre.iter())
            .map(|x| self.magnitude(x))
            .fold(0.0, f64::max)
            .max(1e-300)
            * n.iter().map(|x| self.magnitude(x)).fold(0.0, f64::max);
        let height = dot(point, n);
        if let Some(p) = &ob.point {
            let d = &height - &dot(p, n);
            if self.sign_at(&d, scale, at)?.is_some_and(|s| s != 0) {
                return Err(self.err(
                    at,
                    None,
                    format!(
                        "the contact point is off the plane of {label}: (A − P)·N = {} ({}); move the body \
                         (`[body] position`) or drop the obstacle's `point` to take the plane through the contact",
                        self.approx(&d),
                        if self.sign_at(&d, scale, at)? == Some(1) { "above it: no contact" } else { "inside the obstacle" }
                    ),
                ));
            }
        }
        let flip = |value: &Term| {
            self.err(
                &format!("{at}.obstacle"),
                None,
                format!(
                    "the body is on the wrong side of {label} ((C − A)·N = {}): an obstacle's normal \
                     points out of the obstacle, toward the body — flip its sign",
                    self.approx(value)
                ),
            )
        };
        let above = dot(&sub(&frame.centre, point), n);
        if let (Some(Shape::Box(dims)), Some(bp)) = (shape, body_point) {
            let h_here = dot(&apply(&frame.r, bp), n);
            let lowest = self.touching(dims, frame, n, at)?.unwrap_or_default();
            if let Some(s) = lowest.first() {
                let min = dot(&apply(&frame.r, &Shape::corner(dims, *s)), n);
                if self
                    .sign_of_difference(&h_here, &min, scale, at)?
                    .is_some_and(|s| s > 0)
                {
                    let gap = &h_here - &min;
                    // Lowest along −N instead: the normal points the wrong way.
                    let down = n.each_ref().map(|x| -x);
                    let highest = self.touching(dims, frame, &down, at)?.unwrap_or_default();
                    if highest.iter().any(|s| Shape::corner(dims, *s) == *bp) {
                        // A top corner: either it cannot touch, or the normal points into the
                        // obstacle. Say both, the corners that can touch first.
                        return Err(self.err(
                            &format!("{at}.obstacle"),
                            None,
                            format!(
                                "this point is the box's highest along {label}'s normal, so it \
                                 cannot touch {label}: the corners that can touch it in this pose \
                                 are {} (the lowest along the normal). If this point is right, \
                                 the obstacle's normal points into the obstacle ((C − A)·N = {}): \
                                 flip its sign",
                                lowest
                                    .iter()
                                    .map(|s| format!("{s:?}"))
                                    .collect::<Vec<_>>()
                                    .join(", "),
                                self.approx(&above)
                            ),
                        ));
                    }
                    return Err(self.err(
                        at,
                        None,
                        format!(
                            "this point is {} above the box's lowest corner along {label}'s normal, so the box \
                             would pass through the plane; the corners touching in this pose are {}",
                            self.approx(&gap),
                            lowest.iter().map(|s| format!("{s:?}")).collect::<Vec<_>>().join(", ")
                        ),
                    ));
                }
            }
        }
        // C must not lie inside the obstacle (on the plane is allowed: a bar's contacts on its axis).
        if self.sign_at(&above, scale, at)?.is_some_and(|s| s < 0) {
            return Err(flip(&above));
        }
        Ok(height)
    }

    /// Joints' points and axes, and screws, in the solver's frame.
    fn lower_constraints(&self, c: &mut ConstraintsSpec, frame: &Frame) -> Result<(), SceneError> {
        match c {
            ConstraintsSpec::Screws { free, blocked } => {
                let lists = [("free", Some(free)), ("blocked", blocked.as_mut())];
                for (name, list) in lists {
                    for (i, s) in list.into_iter().flatten().enumerate() {
                        let key = format!("constraints.{name}[{i}]");
                        let top = frame.out(&[Term::of(&s[0]), Term::of(&s[1]), Term::of(&s[2])]);
                        let bottom =
                            frame.out(&[Term::of(&s[3]), Term::of(&s[4]), Term::of(&s[5])]);
                        let [a, b, cc] = self.numbers3(&top, &key)?;
                        let [d, e, f] = self.numbers3(&bottom, &key)?;
                        *s = [a, b, cc, d, e, f];
                    }
                }
            }
            ConstraintsSpec::Joints(joints) => {
                for (j, joint) in joints.iter_mut().enumerate() {
                    let keys = joint.kind.keys();
                    for (key, v) in keys.iter().zip(joint.vectors.iter_mut()) {
                        let path = format!("constraints.joint[{j}].{key}");
                        let t = v.each_ref().map(Term::of);
                        let out = if *key == "point" {
                            frame.out(&sub(&t, &frame.centre))
                        } else {
                            frame.out(&t)
                        };
                        *v = self.numbers3(&out, &path)?;
                    }
                }
            }
        }
        Ok(())
    }
}

/// Whether two terms are the same: one exact rational, or one text with one finite value — so
/// that their difference is exactly zero. A text naming a symbol (its value NaN) is not the
/// same as itself here: its sign is the reader's to assume, as [`Reader::sign_at`] leaves it.
pub(super) fn same(a: &Term, b: &Term) -> bool {
    a == b && a.approx().is_finite()
}

fn sign_of(q: &num_rational::BigRational) -> i8 {
    use num_traits::Signed;
    if q.is_positive() {
        1
    } else if q.is_negative() {
        -1
    } else {
        0
    }
}
