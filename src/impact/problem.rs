//! A collision problem, validated on construction: the body, its twist before impact, the
//! contacts and, optionally, ideal constraints (§9–11).
//!
//! [`Problem::new`] refuses what has no physical meaning — a mass or principal moment that is
//! not positive, an inertia tensor that is not symmetric positive definite, a number that is
//! not finite, a zero normal or tangent, a tangent not perpendicular to its normal, a
//! coefficient of restitution outside [0, 1], no contact at all — with an [`InvalidProblem`]
//! naming the field (`body.mass`, `contact[1].normal`, keys as in scene files, contacts
//! counted from 0). Everything downstream may then rely on m > 0, J positive definite (J_k > 0,
//! or det J > 0 with J⁻¹ formed) and n_i ≠ 0, so [`crate::impact::solve::Impact`] cannot be
//! handed a problem it would divide by zero on.
//!
//! A full inertia tensor J ([`crate::mechanics::inertia`]) must be symmetric — exactly in
//! exact types, to 2ε of the larger entry in floats — and positive definite, which Sylvester's
//! criterion decides from the signs of its leading principal minors: its diagonal entries
//! J_kk > 0 (necessary, and named like principal moments), then Δ₂ = J_xx J_yy − J_xy² > 0 and
//! Δ₃ = det J > 0. Exact types decide these signs exactly.
//!
//! A value whose sign is not decided without assumptions (a symbol `m` in the symbolic type)
//! passes the range checks: they are left to the reader of the derived formulas, as `derive`
//! documents.

use std::fmt;

use crate::impact::friction::blocks::plane_normals;
use crate::impact::mechanism::Mechanism;
use crate::impact::route::{self, Route};
use crate::impact::solve::Outcome;
use crate::mechanics::body::{Inertia, Mobility, RigidBody};
use crate::mechanics::constraint::{Constrained, ConstraintError, Joint};
use crate::mechanics::contact::{Contact, ContactFrame, TangentNotPerpendicular};
use crate::mechanics::inertia::InertiaTensor;
use crate::mechanics::screw::{Screw, Vec3, dot, norm2};
use crate::scalar::Scalar;

/// A validated collision problem. Build it with [`Problem::new`] (and
/// [`Problem::with_constraints`] or [`Problem::with_joints`] for a constrained body).
#[derive(Debug)]
pub struct Problem<T: Scalar> {
    body: RigidBody<T>,
    velocity: Screw<T>,
    contacts: Vec<Contact<T>>,
    constraints: Option<Constrained<T>>,
}

impl<T: Scalar> Clone for Problem<T> {
    fn clone(&self) -> Self {
        Problem {
            body: self.body.clone(),
            velocity: self.velocity.clone(),
            contacts: self.contacts.clone(),
            constraints: self.constraints.clone(),
        }
    }

    /// Field by field, so that [`crate::impact::solve::Impact::reassemble`] reuses the
    /// contact buffer (the derived `clone_from` would allocate a new one).
    ///
    /// A free body's `None` and a principal-axes body's moments are copied in place: the
    /// derived `clone_from` of an enum or an `Option` writes the whole value, hundreds of
    /// bytes for the tensor and constrained variants, even when both sides hold the small one.
    fn clone_from(&mut self, source: &Self) {
        self.body.mass.clone_from(&source.body.mass);
        match (&mut self.body.inertia, &source.body.inertia) {
            (Inertia::Principal(to), Inertia::Principal(from)) => to.clone_from(from),
            (to, from) => *to = from.clone(),
        }
        self.velocity.clone_from(&source.velocity);
        self.contacts.clone_from(&source.contacts);
        match (&mut self.constraints, &source.constraints) {
            (None, None) => {}
            (Some(to), Some(from)) => to.clone_from(from),
            (to, from) => *to = from.clone(),
        }
    }
}

/// Which input an [`InvalidProblem`] is about. Its `Display` is the key of a scene file
/// (`body.inertia[2]`, `contact[0].k_newton`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// `body.mass`.
    Mass,
    /// `body.inertia[k]`: the central principal moment J_k, or the diagonal entry J_kk of a
    /// full tensor.
    Inertia(usize),
    /// `body.inertia[i][k]`, i ≠ k: an entry of a full inertia tensor off its diagonal (J_xy,
    /// J_xz, J_yz and their mirrors).
    InertiaProduct(usize, usize),
    /// `body.inertia`: the inertia tensor as a whole (its leading principal minors).
    InertiaTensor,
    /// `body.angular_velocity[k]`: ω⁰_k.
    AngularVelocity(usize),
    /// `body.velocity[k]`: v_C⁰_k.
    Velocity(usize),
    /// `contact`: the list of contacts.
    Contacts,
    /// `contact[i].point`.
    Point(usize),
    /// `contact[i].normal`.
    Normal(usize),
    /// `contact[i].tangent`.
    Tangent(usize),
    /// `contact[i].k_newton`: Newton's coefficient k_i^N.
    KNewton(usize),
    /// `contact[i].k_poisson`: Poisson's coefficient k_i^P.
    KPoisson(usize),
    /// `contact[i].k_energetic`: Stronge's energetic coefficient k_i^E.
    KEnergetic(usize),
    /// `contact[i].mu`: Coulomb's coefficient of friction μ_i.
    Mu(usize),
    /// `constraints`: the free and blocked screws, or the joints.
    Constraints,
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Field::Mass => write!(f, "body.mass"),
            Field::Inertia(k) => write!(f, "body.inertia[{k}]"),
            Field::InertiaProduct(i, k) => write!(f, "body.inertia[{i}][{k}]"),
            Field::InertiaTensor => write!(f, "body.inertia"),
            Field::AngularVelocity(k) => write!(f, "body.angular_velocity[{k}]"),
            Field::Velocity(k) => write!(f, "body.velocity[{k}]"),
            Field::Contacts => write!(f, "contact"),
            Field::Point(i) => write!(f, "contact[{i}].point"),
            Field::Normal(i) => write!(f, "contact[{i}].normal"),
            Field::Tangent(i) => write!(f, "contact[{i}].tangent"),
            Field::KNewton(i) => write!(f, "contact[{i}].k_newton"),
            Field::KPoisson(i) => write!(f, "contact[{i}].k_poisson"),
            Field::KEnergetic(i) => write!(f, "contact[{i}].k_energetic"),
            Field::Mu(i) => write!(f, "contact[{i}].mu"),
            Field::Constraints => write!(f, "constraints"),
        }
    }
}

/// What is wrong with the field.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Reason {
    /// NaN or an infinity.
    #[error("is not a finite number")]
    NotFinite,
    /// A mass or moment of inertia ≤ 0.
    #[error("must be positive")]
    NotPositive,
    /// An inertia tensor whose entry differs from its mirror across the diagonal.
    #[error(
        "is {value} but its mirror across the diagonal is {mirror}: an inertia tensor is symmetric"
    )]
    NotSymmetric {
        /// The entry, in f64.
        value: f64,
        /// The mirrored entry, in f64.
        mirror: f64,
    },
    /// An inertia tensor with a leading principal minor ≤ 0 (Sylvester's criterion).
    #[error(
        "is not positive definite: its leading principal minor {} = {value} is not positive \
         (Sylvester's criterion); a physical inertia tensor must be positive definite",
        minor_formula(.minor)
    )]
    NotPositiveDefinite {
        /// Which leading principal minor fails: 1, 2 or 3.
        minor: usize,
        /// Its value, in f64.
        value: f64,
    },
    /// A normal or tangent that is the zero vector.
    #[error("is the zero vector: an axis needs a direction")]
    ZeroVector,
    /// A coefficient of friction < 0.
    #[error("must not be negative (0: frictionless)")]
    Negative,
    /// A coefficient of restitution outside [0, 1].
    #[error("must lie in [0, 1] (0: plastic, 1: elastic)")]
    OutsideUnitInterval,
    /// An imposed tangent not perpendicular to its normal.
    #[error("is not perpendicular to the normal (n·y = {dot})")]
    NotPerpendicular {
        /// n·y, in f64.
        dot: f64,
    },
    /// No contact: there is no collision to solve.
    #[error("is empty: a collision needs at least one contact")]
    NoContacts,
    /// The constraints are inconsistent, or the twist before impact violates them.
    #[error("{0}")]
    Constraint(ConstraintError),
}

/// Why a problem was refused: the field and the reason.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{field} {reason}")]
pub struct InvalidProblem {
    /// The offending input.
    pub field: Field,
    /// What is wrong with it.
    pub reason: Reason,
}

/// The leading principal minor Δ_k of the inertia tensor, written out.
fn minor_formula(k: &usize) -> &'static str {
    match k {
        1 => "Δ₁ = J_xx",
        2 => "Δ₂ = J_xx J_yy − J_xy²",
        _ => "Δ₃ = det J",
    }
}

fn invalid(field: Field, reason: Reason) -> InvalidProblem {
    InvalidProblem { field, reason }
}

/// Refuse a non-finite value.
fn finite<T: Scalar>(x: &T, field: Field) -> Result<(), InvalidProblem> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(invalid(field, Reason::NotFinite))
    }
}

/// Refuse a value that is not finite and positive (an undecided symbolic sign passes).
fn positive<T: Scalar>(x: &T, field: Field) -> Result<(), InvalidProblem> {
    finite(x, field)?;
    match x.known_sign() {
        Some(s) if s <= 0 => Err(invalid(field, Reason::NotPositive)),
        _ => Ok(()),
    }
}

/// Refuse an inertia tensor that is not symmetric positive definite (see the module docs).
fn tensor<T: Scalar>(t: &InertiaTensor<T>) -> Result<(), InvalidProblem> {
    let j = t.matrix();
    let field = |i: usize, k: usize| {
        if i == k {
            Field::Inertia(i)
        } else {
            Field::InertiaProduct(i, k)
        }
    };
    for i in 0..3 {
        for k in 0..3 {
            finite(&j[(i, k)], field(i, k))?;
        }
    }
    for (i, k) in [(1, 0), (2, 0), (2, 1)] {
        let (a, b) = (&j[(i, k)], &j[(k, i)]);
        let larger = if a.abs_gt(b) { a } else { b };
        if !(a.clone() - b).is_negligible(larger, 2) {
            let reason = Reason::NotSymmetric {
                value: a.to_f64(),
                mirror: b.to_f64(),
            };
            return Err(invalid(field(i, k), reason));
        }
    }
    for k in 0..3 {
        positive(&j[(k, k)], Field::Inertia(k))?;
    }
    for (m, minor) in t.leading_minors().iter().enumerate() {
        if matches!(minor.known_sign(), Some(s) if s <= 0) {
            let reason = Reason::NotPositiveDefinite {
                minor: m + 1,
                value: minor.to_f64(),
            };
            return Err(invalid(Field::InertiaTensor, reason));
        }
    }
    Ok(())
}

/// Refuse a coefficient of restitution outside [0, 1].
fn coefficient<T: Scalar>(k: &T, field: Field) -> Result<(), InvalidProblem> {
    finite(k, field)?;
    let below = k.known_sign() == Some(-1);
    let above = (T::one() - k).known_sign() == Some(-1);
    if below || above {
        return Err(invalid(field, Reason::OutsideUnitInterval));
    }
    Ok(())
}

/// Refuse a vector with a non-finite component; `field(k)` names component k.
fn finite_vector<T: Scalar>(
    v: &Vec3<T>,
    field: impl Fn(usize) -> Field,
) -> Result<(), InvalidProblem> {
    for k in 0..3 {
        finite(&v[k], field(k))?;
    }
    Ok(())
}

/// Refuse an axis that is not finite or is the zero vector.
fn axis<T: Scalar>(v: &Vec3<T>, field: Field) -> Result<(), InvalidProblem> {
    finite_vector(v, |_| field)?;
    if norm2(v).known_sign() == Some(0) {
        return Err(invalid(field, Reason::ZeroVector));
    }
    Ok(())
}

/// Is the tangent `t` perpendicular to the normal `n`? (n·t)² negligible against |n|²|t|²:
/// exactly zero in exact types, to 3ε in floats. The test [`crate::mechanics::contact`]
/// applies when it builds the frame.
pub fn perpendicular<T: Scalar>(n: &Vec3<T>, t: &Vec3<T>) -> Result<(), T> {
    let d = dot(n, t);
    let reference = norm2(n) * norm2(t);
    if (d.clone() * &d).is_negligible(&reference, 3) {
        Ok(())
    } else {
        Err(d)
    }
}

impl<T: Scalar> Problem<T> {
    /// A free body of mass and central inertia tensor `body`, moving with the twist
    /// `velocity` = {v⁰} = [ω⁰; v_C⁰] (body axes) before impact, hit at `contacts`.
    ///
    /// # Errors
    /// [`InvalidProblem`] for m ≤ 0, J_k ≤ 0, an inertia tensor that is not symmetric positive
    /// definite, a non-finite number, a zero normal or tangent, a tangent not perpendicular to
    /// its normal, k outside [0, 1], or no contact.
    pub fn new(
        body: RigidBody<T>,
        velocity: Screw<T>,
        contacts: Vec<Contact<T>>,
    ) -> Result<Self, InvalidProblem> {
        validate_body(&body, &velocity)?;
        if contacts.is_empty() {
            return Err(invalid(Field::Contacts, Reason::NoContacts));
        }
        for (i, c) in contacts.iter().enumerate() {
            validate_contact(i, c)?;
        }
        Ok(Problem {
            body,
            velocity,
            contacts,
            constraints: None,
        })
    }

    /// The same body held by ideal constraints (§9–11): its twists restricted to the span of
    /// the `free` screws D (eq. 78), held by the constraint screws `blocked` U (eq. 75) or,
    /// when `None`, by the η-orthogonal complement of D. The twist before impact must be
    /// allowed by them.
    ///
    /// # Errors
    /// [`Field::Constraints`] with the [`ConstraintError`]: dependent or non-reciprocal
    /// screws, a body that cannot move, or a twist before impact the constraints forbid.
    pub fn with_constraints(
        self,
        free: Vec<Screw<T>>,
        blocked: Option<Vec<Screw<T>>>,
    ) -> Result<Self, InvalidProblem> {
        let c = Constrained::new(&self.body, free, blocked)
            .map_err(|e| invalid(Field::Constraints, Reason::Constraint(e)))?;
        self.with_constrained(c)
    }

    /// The same body held by `joints` (their free screws together; U derived).
    ///
    /// # Errors
    /// As [`Problem::with_constraints`].
    pub fn with_joints(self, joints: &[Joint<T>]) -> Result<Self, InvalidProblem> {
        let c = Constrained::from_joints(&self.body, joints.to_vec())
            .map_err(|e| invalid(Field::Constraints, Reason::Constraint(e)))?;
        self.with_constrained(c)
    }

    /// The same body held by constraints already validated for it.
    ///
    /// # Errors
    /// [`Field::Constraints`] when the twist before impact is not allowed by them.
    pub fn with_constrained(mut self, constraints: Constrained<T>) -> Result<Self, InvalidProblem> {
        constraints
            .check_allowed(&self.velocity)
            .map_err(|e| invalid(Field::Constraints, Reason::Constraint(e)))?;
        self.constraints = Some(constraints);
        Ok(self)
    }

    /// Mass and central inertia tensor.
    pub fn body(&self) -> &RigidBody<T> {
        &self.body
    }

    /// {v⁰} = [ω⁰; v_C⁰], the twist before impact.
    pub fn velocity(&self) -> &Screw<T> {
        &self.velocity
    }

    /// The contacts A_1 … A_N.
    pub fn contacts(&self) -> &[Contact<T>] {
        &self.contacts
    }

    /// Body, twist and contacts, to change one and validate again with [`Problem::new`]
    /// (constraints are dropped: add them again).
    pub fn into_parts(self) -> (RigidBody<T>, Screw<T>, Vec<Contact<T>>) {
        (self.body, self.velocity, self.contacts)
    }

    /// The ideal constraints, for a constrained body.
    pub fn constraints(&self) -> Option<&Constrained<T>> {
        self.constraints.as_ref()
    }
}

impl<T: Scalar> Mobility<T> for Problem<T> {
    /// \[M\]⁻¹{E} for a free body (eq. 11), D M_red⁻¹ Dᵀ η {E} for a constrained one (eq. 85).
    fn response(&self, e: &Screw<T>) -> Screw<T> {
        match &self.constraints {
            Some(c) => c.response(e),
            None => self.body.response(e),
        }
    }
}

/// A body and its twist as [`Problem::new`] checks them (a system checks each of its bodies
/// so): m > 0, J positive definite, the twist finite.
///
/// # Errors
/// The first field that fails, named as for a single body.
pub(crate) fn validate_body<T: Scalar>(
    body: &RigidBody<T>,
    velocity: &Screw<T>,
) -> Result<(), InvalidProblem> {
    positive(&body.mass, Field::Mass)?;
    match &body.inertia {
        Inertia::Principal(j) => {
            for k in 0..3 {
                positive(&j[k], Field::Inertia(k))?;
            }
        }
        Inertia::Tensor(t) => tensor(t)?,
    }
    finite_vector(&velocity.top(), Field::AngularVelocity)?;
    finite_vector(&velocity.bottom(), Field::Velocity)
}

/// Contact `i` as [`Problem::new`] checks it: a finite point, nonzero normal and tangent, the
/// tangent perpendicular, coefficients of restitution in [0, 1], μ ≥ 0.
///
/// # Errors
/// The first field that fails.
pub(crate) fn validate_contact<T: Scalar>(i: usize, c: &Contact<T>) -> Result<(), InvalidProblem> {
    finite_vector(&c.point, |_| Field::Point(i))?;
    axis(&c.normal, Field::Normal(i))?;
    if let Some(t) = &c.tangent {
        axis(t, Field::Tangent(i))?;
        perpendicular(&c.normal, t).map_err(|d| {
            invalid(
                Field::Tangent(i),
                Reason::NotPerpendicular { dot: d.to_f64() },
            )
        })?;
    }
    coefficient(&c.k_newton, Field::KNewton(i))?;
    coefficient(&c.k_poisson, Field::KPoisson(i))?;
    coefficient(&c.k_energetic, Field::KEnergetic(i))?;
    finite(&c.mu, Field::Mu(i))?;
    if c.mu.known_sign() == Some(-1) {
        return Err(invalid(Field::Mu(i), Reason::Negative));
    }
    Ok(())
}

/// The paper's mechanism: one body, free or held by ideal constraints (§9–11), its contacts'
/// axes about its centre of mass.
impl<T: Scalar> Mechanism<T> for Problem<T> {
    type Screw = Screw<T>;

    fn contacts(&self) -> &[Contact<T>] {
        &self.contacts
    }

    fn velocity(&self) -> &Screw<T> {
        &self.velocity
    }

    fn frame(
        &self,
        i: usize,
        tangential: bool,
    ) -> Result<ContactFrame<T>, TangentNotPerpendicular> {
        let c = &self.contacts[i];
        if tangential {
            ContactFrame::new(i, c, &self.velocity)
        } else {
            Ok(ContactFrame::normal(c))
        }
    }

    fn contact_axis(&self, i: usize, u: &Vec3<T>) -> Screw<T> {
        Screw::axis(&self.contacts[i].point, u)
    }

    /// The planes of rational unit normal built from the contacts' points and normals, v_C⁰
    /// and ω⁰ ([`plane_normals`]).
    fn planes(&self) -> Vec<Vec3<T>> {
        let (w0, v0) = (self.velocity.top(), self.velocity.bottom());
        let mut vectors: Vec<Vec3<T>> = self
            .contacts
            .iter()
            .flat_map(|c| [c.point.clone(), c.normal.clone()])
            .collect();
        vectors.extend([v0, w0.clone()]);
        plane_normals(&self.contacts, &[w0], &vectors)
    }

    fn kinetic_energy(&self, v: &Screw<T>) -> T {
        self.body.kinetic_energy(v)
    }

    fn route(&self, g_hat: &[T], n: usize) -> Route {
        route::route(self, g_hat, n)
    }

    fn constraint_impulses(&self, dv: &Screw<T>, frames: &[ContactFrame<T>], out: &mut Outcome<T>) {
        match &self.constraints {
            Some(c) => {
                let axes = frames.iter().map(|f| &f.axes[0]);
                out.constraint_wrench = c.impulses_into(
                    dv,
                    out.impulses_hat.iter().zip(axes),
                    &mut out.constraint_impulses,
                );
            }
            None => out.clear_constraint_impulses(),
        }
    }

    /// The body, when no constraint holds it.
    fn lane_body(&self) -> Option<&RigidBody<T>> {
        self.constraints.is_none().then_some(&self.body)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int};

    fn v(x: i64, y: i64, z: i64) -> Vec3<Exact> {
        Vec3::new(int(x), int(y), int(z))
    }

    fn contact() -> Contact<Exact> {
        Contact {
            point: v(0, -2, 0),
            normal: v(1, 0, 0),
            tangent: None,
            k_newton: int(0),
            k_poisson: int(1),
            k_energetic: int(1),
            mu: int(0),
        }
    }

    fn body(mass: i64) -> RigidBody<Exact> {
        RigidBody::principal(int(mass), v(12, 2, 12))
    }

    fn refused(p: Result<Problem<Exact>, InvalidProblem>) -> (String, Reason) {
        let e = p.expect_err("refused");
        (e.field.to_string(), e.reason)
    }

    #[test]
    fn field_names_are_scene_keys() {
        let twist = Screw::new(v(0, 0, 0), v(3, 0, 0));
        assert_eq!(
            refused(Problem::new(body(0), twist.clone(), vec![contact()])),
            ("body.mass".into(), Reason::NotPositive)
        );
        let mut c = contact();
        c.tangent = Some(v(1, 1, 0));
        assert_eq!(
            refused(Problem::new(body(1), twist.clone(), vec![contact(), c])),
            (
                "contact[1].tangent".into(),
                Reason::NotPerpendicular { dot: 1.0 }
            )
        );
        let mut c = contact();
        c.k_poisson = int(2);
        assert_eq!(
            refused(Problem::new(body(1), twist, vec![c])),
            ("contact[0].k_poisson".into(), Reason::OutsideUnitInterval)
        );
    }

    fn tensor(rows: [[i64; 3]; 3]) -> RigidBody<Exact> {
        RigidBody::with_tensor(int(1), rows.map(|r| r.map(int)))
    }

    #[test]
    fn a_tensor_must_be_symmetric_positive_definite() {
        let twist = Screw::new(v(0, 0, 0), v(3, 0, 0));
        let refuse = |rows| refused(Problem::new(tensor(rows), twist.clone(), vec![contact()]));
        assert!(
            Problem::new(
                tensor([[4, 1, 0], [1, 3, 1], [0, 1, 2]]),
                twist.clone(),
                vec![contact()]
            )
            .is_ok()
        );
        assert_eq!(
            refuse([[4, 1, 0], [2, 3, 1], [0, 1, 2]]),
            (
                "body.inertia[1][0]".into(),
                Reason::NotSymmetric {
                    value: 2.0,
                    mirror: 1.0
                }
            )
        );
        assert_eq!(
            refuse([[4, 1, 0], [1, 0, 1], [0, 1, 2]]),
            ("body.inertia[1]".into(), Reason::NotPositive)
        );
        // Δ₂ = 1·1 − 2² = −3.
        assert_eq!(
            refuse([[1, 2, 0], [2, 1, 0], [0, 0, 1]]),
            (
                "body.inertia".into(),
                Reason::NotPositiveDefinite {
                    minor: 2,
                    value: -3.0
                }
            )
        );
        // Δ₂ = 1 > 0 but Δ₃ = det J = −1: a positive diagonal, and still indefinite.
        let (key, reason) = refuse([[1, 0, 1], [0, 1, 1], [1, 1, 1]]);
        assert_eq!(key, "body.inertia");
        assert_eq!(
            reason,
            Reason::NotPositiveDefinite {
                minor: 3,
                value: -1.0
            }
        );
        assert_eq!(
            reason.to_string(),
            "is not positive definite: its leading principal minor Δ₃ = det J = -1 is not \
             positive (Sylvester's criterion); a physical inertia tensor must be positive definite"
        );
    }
}
