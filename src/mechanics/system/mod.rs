//! Systems of rigid bodies in one impact: several bodies, contacts between two of them or
//! between one and an obstacle, and joints between bodies or to the ground.
//!
//! The paper treats one body (§2–13); its machinery extends to a system without a new idea.
//! The convention here: every vector is in **world axes**, and each body's screws are about its
//! own centre of mass C_b, so a body keeps the paper's [ω; v_C] and block \[M\] (eq. 9) and
//! the system's mass matrix is block diagonal. The system's twist, its contact axes, its
//! constraint screws and its wrenches are stacks of one screw per body ([`SystemScrew`]):
//!
//! * a **contact** i joins body a and body b (or a and an obstacle) at the world point A_i,
//!   its normal n_i pointing out of a. Its axis acts on a as {E_a} = [n; (A − C_a) × n] and on
//!   b as −{E_b}, so {Ê_i}ᵀ η {V} = n·(v_a(A) − v_b(A)) is the relative normal velocity
//!   (positive: approaching) and the impulse −P {Ê_i} pushes a along −n and b along +n
//!   (eq. 2–8 on each body);
//! * a **joint** blocks the relative twist of its two bodies along the screws its kind does
//!   not leave free (revolute, prismatic, cylindrical, spherical, planar, fixed; one body: to
//!   the ground), and the system answers impulses through the mobility of
//!   [`mobility`]: W = M⁻¹ for a free system, the Schur complement of the joints' KKT
//!   system otherwise — §9–11's W = D M_red⁻¹ Dᵀ η on the system's 6B-dimensional space.
//!
//! Then G = [{Ê_i}ᵀ η W {Ê_j}], Δ, Newton's and Poisson's laws, E_p and ΔE_c (eq. 12–34) are
//! the paper's, through the same solve ([`crate::impact::mechanism::Mechanism`],
//! implemented for [`System`] in [`crate::impact::system`]). A system of one body with no
//! joints is the paper's body.

mod articulated;
pub mod mobility;
pub mod screw;

use std::sync::Arc;

use crate::impact::problem::{InvalidProblem, validate_body, validate_contact};
use crate::linalg::NotSemidefinite;
use crate::mechanics::body::{Mobility, RigidBody};
use crate::mechanics::constraint::Joint;
use crate::mechanics::contact::Contact;
use crate::mechanics::reaction::Wrench;
use crate::mechanics::screw::{Screw, Screws, Vec3};
use crate::scalar::Scalar;

pub(crate) use articulated::{Articulated, ResponseScratch};
use mobility::{JointRows, Row, free_response};
pub use screw::{SystemScrew, about};

/// The twist `velocity` of `bodies` brought onto the twists `joints` allow: its projection in
/// the kinetic metric, W [M] {V} = {V} − W₀ H K⁺ Hᵀ η {V} ([`mobility`]). For a caller whose
/// twist meets the joints only to its own rounding — a simulation's state, held on them by
/// projections in its own rows ([`crate::simulate::system::joints`]) — which [`System::new`]
/// would refuse in floats: it takes a blocked rate as zero only within the rounding of the
/// impact layer's own rows.
///
/// # Errors
/// [`NotSemidefinite`]: K not positive semidefinite (rounding; cannot happen exactly).
pub fn allowed<T: Scalar>(
    bodies: &[SystemBody<T>],
    joints: &[SystemJoint<T>],
    velocity: &SystemScrew<T>,
) -> Result<SystemScrew<T>, NotSemidefinite> {
    if joints.is_empty() {
        return Ok(velocity.clone());
    }
    let screws = JointScrews::new(joints);
    let rows = JointRows::new(bodies, joints, &screws, false)?;
    let momentum = SystemScrew(
        bodies
            .iter()
            .zip(&velocity.0)
            .map(|(b, v)| b.body.momentum(v))
            .collect(),
    );
    Ok(rows.response(bodies, &momentum))
}

/// One body of a system: its mass and central inertia (world axes) and where its centre of
/// mass is (world).
#[derive(Clone, Debug, PartialEq)]
pub struct SystemBody<T: Scalar> {
    /// Mass and central inertia tensor, in world axes.
    pub body: RigidBody<T>,
    /// C_b, the centre of mass, in the world.
    pub centre: Vec3<T>,
}

/// What a contact of a system joins: its first body a (the normal points out of it) and its
/// second body b, or an obstacle (`None`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pair {
    /// a.
    pub first: usize,
    /// b, or `None` for an obstacle.
    pub second: Option<usize>,
}

/// A joint of a system: its kind and geometry (points in the world) and the bodies it joins.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemJoint<T: Scalar> {
    /// The kind, with its anchor and axis in the world.
    pub joint: Joint<T>,
    /// The bodies: the reaction is reported on the first; the second `None` for the ground.
    pub pair: Pair,
}

/// Why a system is not valid. Indices count from 0 in the order given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SystemError {
    /// A body's mass, inertia or twist (named as for one body).
    #[error("body {body}: {error}")]
    Body {
        /// The body.
        body: usize,
        /// What is wrong with it.
        error: InvalidProblem,
    },
    /// A contact's point, normal, tangent or coefficients.
    #[error("contact {contact}: {error}")]
    Contact {
        /// The contact.
        contact: usize,
        /// What is wrong with it.
        error: InvalidProblem,
    },
    /// No contact: nothing collides.
    #[error("a collision needs at least one contact")]
    NoContacts,
    /// Not one pair of bodies per contact.
    #[error(
        "{contacts} contacts but {pairs} pairs of bodies: each contact needs the bodies it joins"
    )]
    PairsMismatch {
        /// How many contacts.
        contacts: usize,
        /// How many pairs.
        pairs: usize,
    },
    /// A contact or joint names a body the system does not have.
    #[error("{what} {index} names body {body}, but the system has {bodies}")]
    UnknownBody {
        /// `"contact"` or `"joint"`.
        what: &'static str,
        /// Its index.
        index: usize,
        /// The body named.
        body: usize,
        /// How many bodies there are.
        bodies: usize,
    },
    /// A contact or joint between a body and itself.
    #[error("{what} {index} joins body {body} to itself")]
    SameBody {
        /// `"contact"` or `"joint"`.
        what: &'static str,
        /// Its index.
        index: usize,
        /// The body.
        body: usize,
    },
    /// The twist before impact moves a joint along a screw it blocks.
    #[error(
        "the velocities before impact violate joint {joint}: its bodies move relative to each \
         other along a screw it blocks ({kind}; relative rate {rate})"
    )]
    JointViolated {
        /// The joint.
        joint: usize,
        /// Its kind.
        kind: &'static str,
        /// H_kᵀ η {V⁰} for the first blocked screw violated, as f64 (`"not identically
        /// zero"` for a symbolic rate).
        rate: String,
    },
    /// K was not positive semidefinite (rounding; cannot happen exactly).
    #[error(transparent)]
    NotSemidefinite(#[from] NotSemidefinite),
}

/// A validated system (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct System<T: Scalar> {
    bodies: Vec<SystemBody<T>>,
    velocity: SystemScrew<T>,
    contacts: Vec<Contact<T>>,
    pairs: Vec<Pair>,
    /// Per contact, A − C_a and A − C_b (`None`: an obstacle).
    levers: Vec<(Vec3<T>, Option<Vec3<T>>)>,
    joints: Vec<SystemJoint<T>>,
    /// The joints' free and blocked screws (shared by the system's copies).
    screws: Arc<JointScrews<T>>,
    rows: Option<JointRows<T>>,
}

impl<T: Scalar> System<T> {
    /// The system of `bodies` moving with `velocity` (one twist per body, world axes, about
    /// its centre), hit at `contacts` (world points; the normal out of the pair's first body)
    /// joining `pairs`, held by `joints`.
    ///
    /// # Errors
    /// The first [`SystemError`]: a body or contact as [`crate::impact::problem::Problem::new`]
    /// checks them, a reference to a body that does not exist or to the same body twice, a
    /// twist before impact that a joint forbids.
    pub fn new(
        bodies: Vec<SystemBody<T>>,
        velocity: SystemScrew<T>,
        contacts: Vec<Contact<T>>,
        pairs: Vec<Pair>,
        joints: Vec<SystemJoint<T>>,
    ) -> Result<Self, SystemError> {
        let count = bodies.len();
        for (b, (body, v)) in bodies.iter().zip(&velocity.0).enumerate() {
            validate_body(&body.body, v).map_err(|error| SystemError::Body { body: b, error })?;
        }
        if contacts.is_empty() {
            return Err(SystemError::NoContacts);
        }
        if pairs.len() != contacts.len() {
            return Err(SystemError::PairsMismatch {
                contacts: contacts.len(),
                pairs: pairs.len(),
            });
        }
        for (i, c) in contacts.iter().enumerate() {
            validate_contact(i, c).map_err(|error| SystemError::Contact { contact: i, error })?;
        }
        let check = |what: &'static str, index: usize, pair: &Pair| {
            for body in std::iter::once(pair.first).chain(pair.second) {
                if body >= count {
                    return Err(SystemError::UnknownBody {
                        what,
                        index,
                        body,
                        bodies: count,
                    });
                }
            }
            if pair.second == Some(pair.first) {
                return Err(SystemError::SameBody {
                    what,
                    index,
                    body: pair.first,
                });
            }
            Ok(())
        };
        for (i, p) in pairs.iter().enumerate() {
            check("contact", i, p)?;
        }
        for (j, joint) in joints.iter().enumerate() {
            check("joint", j, &joint.pair)?;
        }
        let screws = JointScrews::new(&joints);
        let levers = contacts
            .iter()
            .zip(&pairs)
            .map(|(c, p)| {
                let arm = |b: usize| c.point.clone() - bodies[b].centre.clone();
                (arm(p.first), p.second.map(arm))
            })
            .collect();
        let system = System {
            rows: None,
            levers,
            bodies,
            screws: Arc::new(screws),
            velocity,
            contacts,
            pairs,
            joints,
        };
        system.check_allowed()?;
        let mut system = system;
        if !system.joints.is_empty() {
            system.rows = Some(JointRows::new(
                &system.bodies,
                &system.joints,
                &system.screws,
                false,
            )?);
        }
        Ok(system)
    }

    /// The same system with its contacts' lever arms A − C_a and A − C_b (`None` for an
    /// obstacle) given rather than formed in `T` from the rounded world points and centres:
    /// a scene reader computes them exactly and rounds each once, as it does a `[body]`'s
    /// r = A − C, so that a one-body system away from the origin is the one-body problem bit
    /// for bit in floats (issue 24). In exact types they are the differences [`System::new`]
    /// forms.
    ///
    /// # Errors
    /// [`SystemError::PairsMismatch`] when `levers` has not one entry per contact, or names a
    /// second body where the contact has none (or none where it has one).
    pub fn with_lever_arms(
        mut self,
        levers: Vec<(Vec3<T>, Option<Vec3<T>>)>,
    ) -> Result<Self, SystemError> {
        let fits = levers.len() == self.pairs.len()
            && levers
                .iter()
                .zip(&self.pairs)
                .all(|((_, b), p)| b.is_some() == p.second.is_some());
        if !fits {
            return Err(SystemError::PairsMismatch {
                contacts: self.contacts.len(),
                pairs: levers.len(),
            });
        }
        self.levers = levers;
        Ok(self)
    }

    /// Contact `i`'s lever arm A − C_b on `body`, one of the two bodies it joins.
    ///
    /// # Panics
    /// When the contact does not touch `body`.
    pub fn lever_arm(&self, i: usize, body: usize) -> &Vec3<T> {
        let (pair, (first, second)) = (self.pairs[i], &self.levers[i]);
        match (body == pair.first, second) {
            (true, _) => first,
            (false, Some(r)) if pair.second == Some(body) => r,
            _ => panic!("contact {i} does not touch body {body}"),
        }
    }

    /// The same system with its joints' system factored densely whatever their graph (the
    /// path closed loops take, [`mobility`]): for tests, which compare it with the tree's.
    ///
    /// # Errors
    /// [`SystemError::NotSemidefinite`], as [`System::new`].
    #[doc(hidden)]
    pub fn with_dense_joints(mut self) -> Result<Self, SystemError> {
        if self.rows.is_some() {
            self.rows = Some(JointRows::new(
                &self.bodies,
                &self.joints,
                &self.screws,
                true,
            )?);
        }
        Ok(self)
    }

    /// Whether the joints' system is factored along a tree, in time linear in the bodies (the
    /// joints form a forest; the articulated-body recursion, [`mobility`]), rather than
    /// densely.
    pub fn joints_factored_along_tree(&self) -> bool {
        self.rows.as_ref().is_some_and(JointRows::is_tree)
    }

    /// The bodies.
    pub fn bodies(&self) -> &[SystemBody<T>] {
        &self.bodies
    }

    /// {V⁰}: each body's twist before impact.
    pub fn velocity(&self) -> &SystemScrew<T> {
        &self.velocity
    }

    /// The contacts (world points).
    pub fn contacts(&self) -> &[Contact<T>] {
        &self.contacts
    }

    /// What each contact joins.
    pub fn pairs(&self) -> &[Pair] {
        &self.pairs
    }

    /// The joints.
    pub fn joints(&self) -> &[SystemJoint<T>] {
        &self.joints
    }

    /// Whether some joints are redundant (their reactions are then not all determined).
    pub fn redundant_joints(&self) -> bool {
        self.rows
            .as_ref()
            .is_some_and(|r| r.rank < self.screws.rows())
    }

    /// The screw of the axis through contact `i`'s point with direction `u` (module docs).
    pub fn contact_axis(&self, i: usize, u: &Vec3<T>) -> SystemScrew<T> {
        let mut s = SystemScrew(Vec::new());
        self.contact_axis_into(i, u, &mut s);
        s
    }

    /// [`System::contact_axis`] into `s`, its storage reused.
    pub fn contact_axis_into(&self, i: usize, u: &Vec3<T>, s: &mut SystemScrew<T>) {
        let (pair, (first, second)) = (self.pairs[i], &self.levers[i]);
        s.set_zeros(self.bodies.len());
        s.0[pair.first] = Screw::axis(first, u);
        if let (Some(b), Some(r)) = (pair.second, second) {
            s.0[b] = Screw(-Screw::axis(r, u).0);
        }
    }

    /// The articulated-body factorization of the joints, when they form a forest with
    /// independent free screws ([`articulated`]); a system without joints is a forest of
    /// free roots.
    pub(crate) fn articulated(&self) -> Option<Articulated<T>> {
        Articulated::new(&self.bodies, &self.joints, &self.screws)
    }

    /// `tree` factored again for this system (of the shape it was built for).
    pub(crate) fn refactor(&self, tree: &mut Articulated<T>) -> Option<()> {
        tree.refactor(&self.bodies, &self.screws)
    }

    /// The velocity of contact `i`'s point on its first body relative to its second, before
    /// impact: v_a(A) − v_b(A).
    pub fn relative_velocity(&self, i: usize) -> Vec3<T> {
        let pair = self.pairs[i];
        let at = |b: usize| {
            let v = &self.velocity.0[b];
            v.bottom() + v.top().cross(self.lever_arm(i, b))
        };
        match pair.second {
            Some(b) => at(pair.first) - at(b),
            None => at(pair.first),
        }
    }

    /// ½ Σ_b {V_b}ᵀ η M_b {V_b} (eq. 28, 32 on each body).
    pub fn kinetic_energy(&self, v: &SystemScrew<T>) -> T {
        let mut t = T::zero();
        for (b, s) in self.bodies.iter().zip(&v.0) {
            t += b.body.kinetic_energy(s);
        }
        t
    }

    /// Each body's kinetic energy ½ {V_b}ᵀ η M_b {V_b}.
    pub fn kinetic_energies(&self, v: &SystemScrew<T>) -> Vec<T> {
        self.bodies
            .iter()
            .zip(&v.0)
            .map(|(b, s)| b.body.kinetic_energy(s))
            .collect()
    }

    /// The system's momentum screw about the world origin: [Σ m_b v_Cb; Σ (J_b ω_b + C_b × m_b
    /// v_Cb)] — linear momentum and angular momentum about O.
    pub fn momentum(&self, v: &SystemScrew<T>) -> (Vec3<T>, Vec3<T>) {
        let mut linear = Vec3::zeros();
        let mut angular = Vec3::zeros();
        for (b, s) in self.bodies.iter().zip(&v.0) {
            // [M]{v} = [m v_C; J ω] (RigidBody::momentum).
            let m = b.body.momentum(s);
            let p = m.top();
            angular += m.bottom() + b.centre.cross(&p);
            linear += p;
        }
        (linear, angular)
    }

    /// The joints' impulses λ (one per blocked screw) for the twist change `dv` and the
    /// contact impulses `impulses` along the axes `axes` (hatted): K λ = Hᵀ η W₀ (M Δ{V} + Σ
    /// P̂_i {Ê_i}) ([`mobility`]). Empty without joints.
    pub fn joint_impulses<'a>(
        &self,
        dv: &SystemScrew<T>,
        impulses: impl Iterator<Item = (&'a T, &'a SystemScrew<T>)>,
    ) -> Vec<T>
    where
        T: 'a,
    {
        let Some(rows) = &self.rows else {
            return Vec::new();
        };
        let mut wrench = dv.zero_like();
        for (p, e) in impulses {
            wrench.add_scaled(p, e);
        }
        rows.multipliers(&self.bodies, &self.screws, dv, &wrench)
    }

    /// Each joint's reaction on its first body from the joints' impulses `lambda`, reduced to
    /// its anchor (the origin for a joint without one), world axes ([`mobility`]).
    pub fn joint_reactions(&self, lambda: &[T]) -> Vec<Wrench<T>> {
        if self.rows.is_none() {
            return Vec::new();
        }
        let mut lambda = lambda.iter();
        self.joints
            .iter()
            .enumerate()
            .map(|(j, joint)| {
                let mut w = Screw::zero();
                for (u, l) in self.screws.blocked(j).iter().zip(lambda.by_ref()) {
                    w.add_scaled(l, u);
                }
                let p = joint.joint.anchor().cloned().unwrap_or_else(Vec3::zeros);
                Wrench::about(&w, p)
            })
            .collect()
    }

    /// The twist before impact must satisfy every joint (module docs).
    fn check_allowed(&self) -> Result<(), SystemError> {
        // Body b's twist as a field about the world origin: [ω; v_O], v_O = v_C + ω × (O − C).
        let at_origin = |b: usize| {
            let (v, c) = (&self.velocity.0[b], &self.bodies[b].centre);
            let w = v.top();
            Screw::new(w.clone(), v.bottom() - w.cross(c))
        };
        for (j, joint) in self.joints.iter().enumerate() {
            let (a, b) = (joint.pair.first, joint.pair.second);
            // The relative twist, about the origin: H_kᵀ η {V} = u_kᵀ η (V_a − V_b).
            let mut relative = at_origin(a);
            if let Some(b) = b {
                relative = Screws::minus(&relative, &at_origin(b));
            }
            for u in self.screws.blocked(j) {
                if u.reciprocal(&relative).is_zero() {
                    continue;
                }
                // Not zero (exactly, or in floats perhaps by rounding): the rate as the row
                // gives it, body by body about each centre, and in floats its test against
                // the row's largest term.
                let h = Row::new(u, joint, &self.bodies);
                let rate = h.rate(&self.velocity);
                if T::IS_EXACT || !self.negligible(&rate, &h) {
                    // Exactly zero or not (a symbolic rate must vanish identically: no sign
                    // is assumed).
                    return Err(SystemError::JointViolated {
                        joint: j,
                        kind: joint.joint.name(),
                        rate: rate_text(&rate),
                    });
                }
            }
        }
        Ok(())
    }

    /// Whether the rate `rate` of the twist before impact along the row `h` is rounding:
    /// negligible against the largest product it sums.
    fn negligible(&self, rate: &T, h: &Row<T>) -> bool {
        let mut scale = T::zero();
        for (b, a) in h.entries() {
            let b = &self.velocity.0[b];
            for k in 0..6 {
                let t = a.0[k].clone() * &b.0[(k + 3) % 6];
                if t.abs_gt(&scale) {
                    scale = if t.signum_i8() < 0 { -t } else { t };
                }
            }
        }
        rate.is_negligible(&scale, 12 * self.bodies.len())
    }
}

impl<T: Scalar> Mobility<T, SystemScrew<T>> for System<T> {
    /// W{E}: each body's \[M\]⁻¹ (eq. 11), then the joints' correction ([`mobility`]).
    fn response(&self, e: &SystemScrew<T>) -> SystemScrew<T> {
        match &self.rows {
            Some(rows) => rows.response(&self.bodies, e),
            None => free_response(&self.bodies, e),
        }
    }
}

/// A violated joint's rate for the message: its f64 value, or for a symbolic one that it is not
/// zero for every value of the symbols.
fn rate_text<T: Scalar>(rate: &T) -> String {
    let x = rate.to_f64();
    if x.is_finite() {
        format!("{x:e}")
    } else {
        "not identically zero".into()
    }
}

/// Every joint's free screws (about the world origin, as [`Joint::free_screws`] gives them)
/// and the screws it blocks ([`blocked_screws`]), all joints' in one vector each.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointScrews<T: Scalar> {
    free: Vec<Screw<T>>,
    /// Joint j's free screws are `free[free_starts[j]..free_starts[j + 1]]`.
    free_starts: Vec<usize>,
    blocked: Vec<Screw<T>>,
    /// Per blocked screw: the column where it is 1 and its joint's other blocked screws 0.
    columns: Vec<u8>,
    /// Joint j's blocked screws are `blocked[blocked_starts[j]..blocked_starts[j + 1]]`.
    blocked_starts: Vec<usize>,
    /// Whether every joint's free screws are independent.
    pub(crate) independent: bool,
}

impl<T: Scalar> JointScrews<T> {
    fn new(joints: &[SystemJoint<T>]) -> Self {
        let mut s = JointScrews {
            free: Vec::with_capacity(joints.len()),
            free_starts: Vec::with_capacity(joints.len() + 1),
            blocked: Vec::with_capacity(5 * joints.len()),
            columns: Vec::with_capacity(5 * joints.len()),
            blocked_starts: Vec::with_capacity(joints.len() + 1),
            independent: true,
        };
        s.free_starts.push(0);
        s.blocked_starts.push(0);
        for joint in joints {
            let from = s.free.len();
            joint.joint.free_screws_into(&mut s.free);
            let rank = blocked_screws(&s.free[from..], &mut s.blocked, &mut s.columns);
            s.independent &= rank == s.free.len() - from;
            s.free_starts.push(s.free.len());
            s.blocked_starts.push(s.blocked.len());
        }
        s
    }

    /// Joint `j`'s free screws.
    pub(crate) fn free(&self, j: usize) -> &[Screw<T>] {
        &self.free[self.free_starts[j]..self.free_starts[j + 1]]
    }

    /// Joint `j`'s blocked screws.
    pub(crate) fn blocked(&self, j: usize) -> &[Screw<T>] {
        &self.blocked[self.blocked_starts[j]..self.blocked_starts[j + 1]]
    }

    /// Where joint `j`'s blocked screws start among all joints', and the column where each
    /// is 1 (and the others 0).
    pub(crate) fn columns(&self, j: usize) -> (usize, &[u8]) {
        let (a, b) = (self.blocked_starts[j], self.blocked_starts[j + 1]);
        (a, &self.columns[a..b])
    }

    /// All joints' blocked screws: the rows of H.
    pub(crate) fn rows(&self) -> usize {
        self.blocked.len()
    }
}

/// A basis of the screws u with uᵀ η f = 0 for every free screw f, appended to `blocked`:
/// what the joint blocks — the null space of the rows (η f)ᵀ by reduced row echelon form
/// (partial pivoting, as [`crate::linalg::gauss::rref`], here on a fixed 6 × 6 array without
/// allocating), one screw per column that is not a pivot, with a 1 there and 0 in the other
/// such columns (appended to `columns`). Returns the rank of the free screws.
fn blocked_screws<T: Scalar>(
    free: &[Screw<T>],
    blocked: &mut Vec<Screw<T>>,
    columns: &mut Vec<u8>,
) -> usize {
    // Rows (η f)ᵀ: [f_bottom; f_top].
    let rows = free.len().min(6);
    let mut a: [T; 36] = std::array::from_fn(|_| T::zero());
    for (r, f) in free.iter().take(rows).enumerate() {
        for k in 0..6 {
            a[6 * r + k] = f.0[(k + 3) % 6].clone();
        }
    }
    let mut scale = T::zero();
    for x in &a[..6 * rows] {
        if x.abs_gt(&scale) {
            scale = x.clone();
        }
    }
    let mut pivots = [0usize; 6];
    let mut r = 0;
    for c in 0..6 {
        if r == rows {
            break;
        }
        let mut p = r;
        for i in r + 1..rows {
            if a[6 * i + c].abs_gt(&a[6 * p + c]) {
                p = i;
            }
        }
        if a[6 * p + c].is_negligible(&scale, 6) {
            continue;
        }
        for j in 0..6 {
            a.swap(6 * r + j, 6 * p + j);
        }
        let piv = a[6 * r + c].clone();
        for j in 0..6 {
            a[6 * r + j] /= &piv;
        }
        for i in 0..rows {
            if i != r && !a[6 * i + c].is_zero() {
                let f = a[6 * i + c].clone();
                for j in 0..6 {
                    let t = f.clone() * &a[6 * r + j];
                    a[6 * i + j] -= t;
                }
            }
        }
        pivots[r] = c;
        r += 1;
    }
    let pivots = &pivots[..r];
    for free in (0..6).filter(|c| !pivots.contains(c)) {
        let mut u = Screw::zero();
        u.0[free] = T::one();
        for (k, &pc) in pivots.iter().enumerate() {
            u.0[pc] = -a[6 * k + free].clone();
        }
        blocked.push(u);
        columns.push(free as u8);
    }
    r
}
