//! Ideal constraints (§9–11): a body whose twists are restricted to the span of the free
//! screws D = [D_1 … D_d] (eq. 78), held by the constraint screws U = [U_1 … U_{6−d}] (eq. 75)
//! with Dᵀ η U = 0 (eq. 82).
//!
//! **The mobility.** With {v} = D ξ (eq. 79), multiplying the momentum balance
//! M({v} − {v⁰}) = −Σ P_i {E_ix} + U q (eq. 76) by Dᵀ η kills U q and gives
//!
//! ```text
//! M_red = Dᵀ η M D (eq. 83),    {v} − {v⁰} = −Σ P_i D M_red⁻¹ Dᵀ η {E_ix} (eq. 85)
//! ```
//!
//! so W = D M_red⁻¹ Dᵀ η takes the place of M⁻¹ everywhere: the inertances (eq. 86, 94), the
//! impulses (eq. 88–89), the contact velocities (eq. 95), and E_p, ΔE_c (eq. 96–97). This is
//! [`Constrained`]'s [`Mobility`] implementation; the solve is unchanged.
//!
//! **The constraint impulses.** The OCR'd eq. (93) is garbled; we derive q from the momentum
//! balance itself. Once P is known, the wrench the constraints must supply is
//!
//! ```text
//! U q = r,   r = M({v} − {v⁰}) + Σ P_i {E_ix}.
//! ```
//!
//! Multiplying by Uᵀ η M⁻¹ (eq. 90–92) gives the (6−d)×(6−d) system
//! (Uᵀ η M⁻¹ U) q = Uᵀ η M⁻¹ r, whose matrix is a Gram matrix under the positive definite
//! η M⁻¹ (eq. 57–58) and so is invertible when the columns of U are independent. Since
//! M⁻¹ r = Δv + Σ P_i M⁻¹{E_ix} and Uᵀ η Δv = Uᵀ η D Δξ = 0, this is eq. (92):
//! (Uᵀ η M⁻¹ U) q = Σ P_i Uᵀ η M⁻¹ {E_ix}. The solution satisfies U q = r exactly (r lies in
//! the span of U because Dᵀ η r = 0 by eq. 85), which the tests check in exact arithmetic.
//! q_a is the multiplier of the screw U_a as written.
//!
//! **Orthogonal screws, not Gram matrices.** M_red and Uᵀ η M⁻¹ U are Gram matrices, and
//! forming them squares the conditioning of the screws in the body's metric: a body of mass m
//! and moment J on a revolute joint about z through (0, −l, 0) and a prismatic one along x has
//! M_red = [[J + m l², −m l], [−m l, m]], of condition about m l²/J, while its motion space
//! is as well conditioned as the body (a rotation about C and a translation, kinetic energies
//! J and m). So D is orthogonalised in ⟨a, b⟩ = {a}ᵀ η M {b} = ω_a·J ω_b + m v_a·v_b
//! (eq. 32; [`RigidBody::momentum`], [`Screw::reciprocal`]) by modified Gram–Schmidt on the
//! screws themselves, without normalising (field operations only, as
//! [`crate::impact::gram_schmidt`] does for the contact wrenches):
//!
//! ```text
//! D_k = b_k + Σ_{i<k} r_ik b_i,   ⟨b_i, b_k⟩ = d_k δ_ik,   W = Σ_a b_a b_aᵀ η / d_a
//! ```
//!
//! (M_red = Rᵀ diag(d) R, and W = D M_red⁻¹ Dᵀ η does not depend on the basis of span D), and
//! {v⁰} is checked by removing its components along the b_a from {v⁰} itself. U is
//! orthogonalised the same way in ⟨a, b⟩ = {a}ᵀ η M⁻¹ {b} ([`Mobility::response`] of the
//! body), U = C R, and q solves R q = y with y_a = ⟨r, c_a⟩/e_a. Exact types compute the
//! same W, the same q and the same first dependent screw as the Gram matrices did (a screw is
//! dependent iff its orthogonalised q_k is 0).
//!
//! *Passes.* A pass that removes more than half of the squared norm is repeated (Kahan and
//! Parlett's test; "twice is enough", Giraud, Langou and Rozložník 2005, when the metric is
//! well scaled). In a badly scaled metric (m l² ≫ J) the first pass leaves rounding of order
//! ε in the heavy coordinates v, worth m ε² against the d_k ≈ J that is sought; each repeat
//! removes that rounding's component along the earlier b_i, down by a factor of order ε, so
//! the loop goes on while it matters and stops when a pass removes at most half (the computed
//! b_k is then orthogonal to working precision in this metric) or leaves only rounding (a
//! screw in the span: dependent, or {v⁰} allowed). Measured: two passes for the joints above
//! at every m/J from 10⁻³⁰⁰ to 10³⁰⁰, also where the coordinates round (a revolute through
//! (−0.3, 0.7, 0) with the prismatic along (0.7, 0.3, 0)), and the f64 solves then agree with
//! the exact ones to a few ε (tests/regression_constrained_heavy_body.rs).
//!
//! *Dependence.* A screw is dependent when every coordinate of its orthogonalised q_k is
//! within the rounding bound of its own computation: the coordinate j is x_j − Σ_t c_t b_tj
//! over the p·k subtractions of p passes, within γ_(pk+1) (|x_j| + Σ_t |c_t| |b_tj|) of its
//! exact value for the computed c_t (Higham, *Accuracy and Stability of Numerical
//! Algorithms*, Lemma 3.1, γ_n ≈ n ε/2), and the test is [`Scalar::is_negligible`] with
//! n = p·k + 1 against that sum of magnitudes, twice γ to cover the rounding of the c_t. The
//! test is componentwise, so it does not depend on the units or on the metric: the M-norm of
//! q_k relative to that of D_k would call the prismatic joint above dependent once
//! J/(m l²) < ε² (its orthogonalised screw is the rotation about C, of kinetic energy J beside
//! the translation's m), though its coordinates are those of a unit rotation, far from zero.

use nalgebra::SVector;

use crate::linalg::null_space;
use crate::mechanics::body::{Mobility, RigidBody};
use crate::mechanics::screw::{Screw, Vec3, norm2};
use crate::scalar::Scalar;

/// A joint, as users write constraints: each contributes the free screws of its motion.
#[derive(Clone, Debug, PartialEq)]
pub enum Joint<T: Scalar> {
    /// Rotation about the axis through `point` (from C) with direction `axis`: [a; p × a].
    Revolute {
        /// A point of the axis.
        point: Vec3<T>,
        /// Its direction.
        axis: Vec3<T>,
    },
    /// Translation along `axis`: [0; a].
    Prismatic {
        /// The direction of sliding.
        axis: Vec3<T>,
    },
    /// Rotation about and translation along one axis.
    Cylindrical {
        /// A point of the axis.
        point: Vec3<T>,
        /// Its direction.
        axis: Vec3<T>,
    },
    /// Rotation about every axis through `point` (a ball joint).
    Spherical {
        /// The centre of the ball.
        point: Vec3<T>,
    },
    /// Motion in the plane with normal `normal`: rotation about it and translations in it.
    Planar {
        /// The plane's normal.
        normal: Vec3<T>,
    },
    /// No relative motion at all (a weld): two bodies of a system move as one
    /// ([`crate::mechanics::system`]); `point` is where its reaction is reported.
    Fixed {
        /// The anchor of its reaction.
        point: Vec3<T>,
    },
}

impl<T: Scalar> Joint<T> {
    /// Its kind, as named in scene files (`revolute`, …).
    pub fn name(&self) -> &'static str {
        match self {
            Joint::Revolute { .. } => "revolute",
            Joint::Prismatic { .. } => "prismatic",
            Joint::Cylindrical { .. } => "cylindrical",
            Joint::Spherical { .. } => "spherical",
            Joint::Planar { .. } => "planar",
            Joint::Fixed { .. } => "fixed",
        }
    }

    /// The point its reaction is reduced to ([`crate::mechanics::reaction`]): its `point`;
    /// `None` for a prismatic or planar joint, which has none.
    pub fn anchor(&self) -> Option<&Vec3<T>> {
        match self {
            Joint::Revolute { point, .. }
            | Joint::Cylindrical { point, .. }
            | Joint::Spherical { point }
            | Joint::Fixed { point } => Some(point),
            Joint::Prismatic { .. } | Joint::Planar { .. } => None,
        }
    }

    /// The free screws (twists [ω; v_C]) this joint allows.
    pub fn free_screws(&self) -> Vec<Screw<T>> {
        let mut out = Vec::with_capacity(3);
        self.free_screws_into(&mut out);
        out
    }

    /// [`Joint::free_screws`] appended to `out` (a system's joints fill one vector).
    pub fn free_screws_into(&self, out: &mut Vec<Screw<T>>) {
        let revolute = |p: &Vec3<T>, a: &Vec3<T>| Screw::new(a.clone(), p.cross(a));
        let prismatic = |a: &Vec3<T>| Screw::new(Vec3::zeros(), a.clone());
        match self {
            Joint::Revolute { point, axis } => out.push(revolute(point, axis)),
            Joint::Prismatic { axis } => out.push(prismatic(axis)),
            Joint::Cylindrical { point, axis } => {
                out.extend([revolute(point, axis), prismatic(axis)]);
            }
            Joint::Spherical { point } => out.extend((0..3).map(|k| {
                let mut e = Vec3::zeros();
                e[k] = T::one();
                revolute(point, &e)
            })),
            Joint::Planar { normal } => {
                // Two in-plane directions, rational: n × e_k for the axis e_k least aligned
                // with n, then n × that.
                let mut k = 0;
                for i in 1..3 {
                    if normal[k].abs_gt(&normal[i]) {
                        k = i;
                    }
                }
                let mut e = Vec3::zeros();
                e[k] = T::one();
                let t1 = normal.cross(&e);
                let t2 = normal.cross(&t1);
                out.extend([
                    revolute(&Vec3::zeros(), normal),
                    prismatic(&t1),
                    prismatic(&t2),
                ]);
            }
            Joint::Fixed { .. } => {}
        }
    }
}

/// Why a set of constraints is not valid. Indices count from 0 in the order given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ConstraintError {
    /// No free screw: the body cannot move, so no collision happens.
    #[error("no free screws: the body cannot move at all")]
    Immobile,
    /// More than six free screws, or a free screw is a combination of the others (D is not of
    /// full column rank).
    #[error(
        "free screw {index} is a linear combination of the ones before it (D must have full column rank)"
    )]
    DependentFree {
        /// The screw found dependent.
        index: usize,
    },
    /// A constraint screw is a combination of the others.
    #[error(
        "blocked screw {index} is a linear combination of the ones before it (U must have full column rank)"
    )]
    DependentBlocked {
        /// The screw found dependent.
        index: usize,
    },
    /// D_iᵀ η U_j ≠ 0 (eq. 82): the constraint would do work on an allowed motion.
    #[error(
        "free screw {free} and blocked screw {blocked} are not reciprocal: D_{free}ᵀ η U_{blocked} = {value} ≠ 0 (eq. 82)"
    )]
    NotReciprocal {
        /// Index in D.
        free: usize,
        /// Index in U.
        blocked: usize,
        /// The product, as f64.
        value: f64,
    },
    /// dim D + dim U ≠ 6.
    #[error("{free} free + {blocked} blocked screws = {} ≠ 6: together they must span all six dimensions", free + blocked)]
    Dimension {
        /// dim D.
        free: usize,
        /// dim U.
        blocked: usize,
    },
    /// The twist before impact is not a combination of the free screws.
    #[error(
        "the velocity before impact is not allowed by the constraints: it leaves {residual:e} (relative) outside the span of D"
    )]
    VelocityNotAllowed {
        /// ‖{v⁰} − D ξ⁰‖ / ‖{v⁰}‖ (Euclidean, f64).
        residual: f64,
    },
}

/// A body with ideal constraints: the [`Mobility`] W = D M_red⁻¹ Dᵀ η, and what is needed for
/// the constraint impulses, both from the screws orthogonalised in the body's metric (module
/// docs). Small fixed-size buffers: no allocation per response.
#[derive(Clone, Debug)]
pub struct Constrained<T: Scalar> {
    body: RigidBody<T>,
    /// D, the free screws.
    pub free: Vec<Screw<T>>,
    /// U, the constraint screws (given, or the η-orthogonal complement of D).
    pub blocked: Vec<Screw<T>>,
    /// Whether U was derived rather than given.
    pub derived_blocked: bool,
    /// The joints D was built from (empty for the paper's form): their anchors are where
    /// the reactions are reported ([`crate::mechanics::reaction`]).
    pub joints: Vec<Joint<T>>,
    /// D orthogonalised in ⟨a, b⟩ = {a}ᵀ η M {b}: M_red is diagonal in this basis.
    free_basis: Orthogonal<T>,
    /// U orthogonalised in ⟨a, b⟩ = {a}ᵀ η M⁻¹ {b}: so is Uᵀ η M⁻¹ U.
    blocked_basis: Orthogonal<T>,
}

/// At most this many passes of Gram–Schmidt per screw. A pass is repeated only while it
/// removes more than half of the squared norm and leaves more than rounding, and each
/// repetition shrinks the rounding left along the earlier screws by about the working
/// precision (module docs): measured, two passes for the joints of the module docs at every
/// m/J from 10⁻³⁰⁰ to 10³⁰⁰ and for joints whose coordinates round (0.3, 0.7), one for
/// well-conditioned screws; the cap only bounds a loop no scene has needed.
const MAX_PASSES: usize = 64;

/// Screws orthogonalised by modified Gram–Schmidt, without normalising, in a metric
/// ⟨a, b⟩ = {a}ᵀ η G {b} with η G symmetric positive definite (G = M for twists, M⁻¹ for
/// wrenches): s_k = b_k + Σ_{i<k} r_ik b_i, ⟨b_i, b_k⟩ = d_k δ_ik.
#[derive(Clone, Debug)]
struct Orthogonal<T: Scalar> {
    /// b_k.
    vectors: Vec<Screw<T>>,
    /// G b_k, so that ⟨x, b_k⟩ = {x}ᵀ η (G b_k) costs six products.
    images: Vec<Screw<T>>,
    /// d_k = ⟨b_k, b_k⟩ > 0.
    norms2: Vec<T>,
    /// r_ik, n×n row-major above the diagonal (unit diagonal and zeros below, not used).
    r: Vec<T>,
}

/// Whether every coordinate of q, the result of `terms` − 1 subtractions x_j − Σ_t c_t b_tj,
/// is within the rounding bound of that computation: γ_terms times `noise` = |x| + Σ_t |c_t| |b_t|
/// (Higham, Lemma 3.1, one product and one subtraction per term), doubled to cover the
/// rounding of the c_t: [`Scalar::is_negligible`] with n = `terms`, n ε ≈ 2 γ_n.
fn within<T: Scalar>(q: &Screw<T>, noise: &Screw<T>, terms: usize) -> bool {
    (0..6).all(|j| q.0[j].is_negligible(&noise.0[j], terms))
}

/// |s|, componentwise.
fn magnitude<T: Scalar>(s: &Screw<T>) -> Screw<T> {
    Screw(s.0.map(|x| if x.signum_i8() < 0 { -x } else { x }))
}

impl<T: Scalar> Orthogonal<T> {
    /// Orthogonalise `screws` in turn in the metric `g` (x ↦ G x); `Err(k)` for the first
    /// screw that is a combination of the ones before it, to working precision: every
    /// coordinate of its orthogonalised q_k within the rounding bound of its own computation
    /// (module docs; exactly q_k = 0 in exact types).
    fn new(screws: &[Screw<T>], g: &impl Fn(&Screw<T>) -> Screw<T>) -> Result<Self, usize> {
        let n = screws.len();
        let mut basis = Orthogonal {
            vectors: Vec::with_capacity(n),
            images: Vec::with_capacity(n),
            norms2: Vec::with_capacity(n),
            r: vec![T::zero(); n * n],
        };
        let mut coefficients = vec![T::zero(); n];
        for (k, s) in screws.iter().enumerate() {
            let mut q = s.clone();
            let mut noise = (!T::IS_EXACT).then(|| magnitude(s));
            coefficients.iter_mut().for_each(|c| *c = T::zero());
            let (image, d, passes) =
                basis.orthogonalise(&mut q, g, &mut coefficients[..k], noise.as_mut());
            let negligible = match &noise {
                Some(noise) => within(&q, noise, passes * k + 1),
                None => q.0.iter().all(|x| x.is_negligible(&T::zero(), 1)),
            };
            if negligible || d.signum_i8() <= 0 {
                return Err(k);
            }
            for (i, c) in coefficients[..k].iter().enumerate() {
                basis.r[i * n + k] = c.clone();
            }
            basis.vectors.push(q);
            basis.images.push(image);
            basis.norms2.push(d);
        }
        Ok(basis)
    }

    /// Number of screws.
    fn len(&self) -> usize {
        self.norms2.len()
    }

    /// One pass of modified Gram–Schmidt: q ← q − c_i b_i for each i in turn, with
    /// c_i = ⟨q, b_i⟩/d_i of the current q; adds c_i to `coefficients[i]` and |c_i| |b_i| to
    /// `noise`, and returns Σ c_i² d_i, the squared norm removed (Pythagoras).
    fn pass(
        &self,
        q: &mut Screw<T>,
        coefficients: &mut [T],
        mut noise: Option<&mut Screw<T>>,
    ) -> T {
        let mut removed = T::zero();
        for (i, c_total) in coefficients.iter_mut().enumerate() {
            let c = q.reciprocal(&self.images[i]) / &self.norms2[i];
            q.add_scaled(&-c.clone(), &self.vectors[i]);
            if let Some(noise) = noise.as_deref_mut() {
                let size = if c.signum_i8() < 0 {
                    -c.clone()
                } else {
                    c.clone()
                };
                noise.add_scaled(&size, &magnitude(&self.vectors[i]));
            }
            removed += c.clone() * &c * &self.norms2[i];
            *c_total += c;
        }
        removed
    }

    /// q orthogonalised against the first `coefficients.len()` screws, in place: passes are
    /// repeated while one removes more than half of q's squared norm (Kahan and Parlett's
    /// test, as in [`crate::impact::gram_schmidt`]; module docs), unless q is already zero to
    /// working precision (with `noise`: then what a pass removes is rounding, and repeating
    /// would chase it). Returns G q, ⟨q, q⟩ and the passes made (one in exact types, where a
    /// second would remove nothing).
    fn orthogonalise(
        &self,
        q: &mut Screw<T>,
        g: &impl Fn(&Screw<T>) -> Screw<T>,
        coefficients: &mut [T],
        mut noise: Option<&mut Screw<T>>,
    ) -> (Screw<T>, T, usize) {
        let mut image = g(q);
        let mut norm2 = q.reciprocal(&image);
        if coefficients.is_empty() {
            return (image, norm2, 0);
        }
        let two = T::one() + T::one();
        let mut passes = 0;
        while passes < MAX_PASSES {
            let removed = self.pass(q, coefficients, noise.as_deref_mut());
            passes += 1;
            image = g(q);
            let before = std::mem::replace(&mut norm2, q.reciprocal(&image));
            if T::IS_EXACT
                || !(removed * &two).abs_gt(&before)
                || noise
                    .as_deref()
                    .is_some_and(|n| within(q, n, passes * coefficients.len() + 1))
            {
                break;
            }
        }
        (image, norm2, passes)
    }
}

impl<T: Scalar> Constrained<T> {
    /// Validate D (and U, if given; otherwise derive it) for `body`, and orthogonalise D in
    /// η M and U in η M⁻¹ (module docs).
    pub fn new(
        body: &RigidBody<T>,
        free: Vec<Screw<T>>,
        blocked: Option<Vec<Screw<T>>>,
    ) -> Result<Self, ConstraintError> {
        let d = free.len();
        if d == 0 {
            return Err(ConstraintError::Immobile);
        }
        if d > 6 {
            return Err(ConstraintError::DependentFree { index: 6 });
        }
        // M_red = Dᵀ η M D (eq. 83) is the Gram matrix of D in η M: diagonal in this basis,
        // and D is of full column rank iff no orthogonalised screw vanishes.
        let free_basis = Orthogonal::new(&free, &|s: &Screw<T>| body.momentum(s))
            .map_err(|index| ConstraintError::DependentFree { index })?;

        let (blocked, derived_blocked) = match blocked {
            Some(u) => {
                for (a, da) in free.iter().enumerate() {
                    for (b, ub) in u.iter().enumerate() {
                        let p = da.reciprocal(ub);
                        let reference = screw_norm2(da) * screw_norm2(ub);
                        if !(p.clone() * &p).is_negligible(&reference, 6) {
                            return Err(ConstraintError::NotReciprocal {
                                free: a,
                                blocked: b,
                                value: p.to_f64(),
                            });
                        }
                    }
                }
                (u, false)
            }
            None => (complement(&free), true),
        };
        let u = blocked.len();
        if d + u != 6 {
            return Err(ConstraintError::Dimension {
                free: d,
                blocked: u,
            });
        }
        let blocked_basis = Orthogonal::new(&blocked, &|s: &Screw<T>| body.response(s))
            .map_err(|index| ConstraintError::DependentBlocked { index })?;
        Ok(Constrained {
            body: body.clone(),
            free,
            blocked,
            derived_blocked,
            joints: Vec::new(),
            free_basis,
            blocked_basis,
        })
    }

    /// The body held by `joints`: D the union of their free screws, U derived.
    pub fn from_joints(
        body: &RigidBody<T>,
        joints: Vec<Joint<T>>,
    ) -> Result<Self, ConstraintError> {
        let free = joints.iter().flat_map(Joint::free_screws).collect();
        Ok(Constrained {
            joints,
            ..Constrained::new(body, free, None)?
        })
    }

    /// The number of degrees of freedom, d = dim D.
    pub fn dof(&self) -> usize {
        self.free.len()
    }

    /// M_red = Dᵀ η M D (eq. 83), d×d row-major (recomputed; for reports and tests).
    pub fn reduced_mass(&self) -> Vec<T> {
        let d = self.dof();
        let mut m = Vec::with_capacity(d * d);
        for a in 0..d {
            for b in 0..d {
                m.push(self.free[a].reciprocal(&self.body.momentum(&self.free[b])));
            }
        }
        m
    }

    /// Check that {v⁰} is a twist the constraints allow: {v⁰} = D ξ⁰ (eq. 79). Its η-M
    /// orthogonal projection on the span of D is removed screw by screw from {v⁰} itself
    /// (Gram–Schmidt against the orthogonalised D), and what is left must be negligible.
    pub fn check_allowed(&self, v0: &Screw<T>) -> Result<(), ConstraintError> {
        let mut r = v0.clone();
        let mut coefficients = [(); 6].map(|_| T::zero());
        let mut noise = (!T::IS_EXACT).then(|| magnitude(v0));
        self.free_basis.orthogonalise(
            &mut r,
            &|s: &Screw<T>| self.body.momentum(s),
            &mut coefficients[..self.dof()],
            noise.as_mut(),
        );
        let (res, scale) = (screw_norm2(&r), screw_norm2(v0));
        if res.is_negligible(&scale, 36) {
            Ok(())
        } else {
            let relative = if scale.to_f64() > 0.0 {
                (res.to_f64() / scale.to_f64()).sqrt()
            } else {
                f64::INFINITY
            };
            Err(ConstraintError::VelocityNotAllowed { residual: relative })
        }
    }

    /// The constraint impulses q, U q = M({v} − {v⁰}) + Σ P̂_i {Ê_ix} (see the module docs),
    /// written into `q` (length 6 − d); returns the wrench U q = [F; M_C]
    /// ([`crate::mechanics::reaction`]) as that right-hand side: U plays no part in it, so it
    /// does not depend on the basis U is written in (in floats either).
    pub fn impulses_into<'a>(
        &self,
        dv: &Screw<T>,
        impulses: impl IntoIterator<Item = (&'a T, &'a Screw<T>)>,
        q: &mut Vec<T>,
    ) -> Screw<T>
    where
        T: 'a,
    {
        let u = self.blocked.len();
        let mut r = self.body.momentum(dv);
        for (p, e) in impulses {
            r.add_scaled(p, e);
        }
        // r = Σ_a y_a c_a over the orthogonalised U (one pass: r lies in their span), and
        // U = C R with R unit upper triangular, so R q = y.
        q.clear();
        q.resize(u, T::zero());
        let wrench = r.clone();
        self.blocked_basis.pass(&mut r, q, None);
        let rr = &self.blocked_basis.r;
        for i in (0..u).rev() {
            for k in i + 1..u {
                let t = rr[i * u + k].clone() * &q[k];
                q[i] -= t;
            }
        }
        wrench
    }
}

impl<T: Scalar> Mobility<T> for Constrained<T> {
    /// W{E} = D M_red⁻¹ Dᵀ η {E} = Σ_a b_a ({b_a}ᵀ η {E}) / d_a (eq. 85) over D orthogonalised
    /// in η M, in which M_red = diag(d_a).
    fn response(&self, e: &Screw<T>) -> Screw<T> {
        let basis = &self.free_basis;
        let mut out = Screw::zero();
        for a in 0..basis.len() {
            let y = basis.vectors[a].reciprocal(e) / &basis.norms2[a];
            out.add_scaled(&y, &basis.vectors[a]);
        }
        out
    }
}

/// The blocked screws U derived from the free ones: a basis of the η-orthogonal complement
/// {x : D_aᵀ η x = 0 for every a} (eq. 82), from the rows [D_a bottom; D_a top] by reduced row
/// echelon form, one screw per free column with a 1 there ([`null_space`]). The metric plays
/// no part, so the pivoted elimination on D's own coordinates is as accurate for any mass and
/// moments.
pub fn complement<T: Scalar>(free: &[Screw<T>]) -> Vec<Screw<T>> {
    let mut rows = Vec::with_capacity(6 * free.len());
    for s in free {
        rows.extend(s.bottom().iter().cloned());
        rows.extend(s.top().iter().cloned());
    }
    let (_, basis) = null_space(&rows, free.len(), 6);
    basis
        .into_iter()
        .map(|x| Screw(SVector::<T, 6>::from_iterator(x)))
        .collect()
}

/// The Euclidean |s|² of a screw's six coordinates (a scale for zero tests only).
fn screw_norm2<T: Scalar>(s: &Screw<T>) -> T {
    norm2(&s.top()) + norm2(&s.bottom())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int};

    fn v(x: i64, y: i64, z: i64) -> Vec3<Exact> {
        Vec3::new(int(x), int(y), int(z))
    }

    fn s(c: [i64; 6]) -> Screw<Exact> {
        Screw::new(v(c[0], c[1], c[2]), v(c[3], c[4], c[5]))
    }

    fn body() -> RigidBody<Exact> {
        RigidBody::principal(int(10), v(1, 2, 3))
    }

    #[test]
    fn example_6_joints_give_the_papers_d_and_u() {
        // A revolute joint about OZ at O = (0, −l, 0) (CO × k = −l i, l = 1) and a prismatic
        // joint along OX: D = {[0 0 1 −1 0 0], [0 0 0 1 0 0]} (Example 6).
        let joints = [
            Joint::Revolute {
                point: v(0, -1, 0),
                axis: v(0, 0, 1),
            },
            Joint::Prismatic { axis: v(1, 0, 0) },
        ];
        let free: Vec<_> = joints.iter().flat_map(Joint::free_screws).collect();
        assert_eq!(free, vec![s([0, 0, 1, -1, 0, 0]), s([0, 0, 0, 1, 0, 0])]);
        let c = Constrained::new(&body(), free, None).unwrap();
        assert_eq!(c.blocked.len(), 4);
        for d in &c.free {
            for u in &c.blocked {
                assert_eq!(d.reciprocal(u), int(0));
            }
        }
        // M_red = [[J_z + m l², −m l], [−m l, m]] (Example 6).
        assert_eq!(c.reduced_mass(), vec![int(13), int(-10), int(-10), int(10)]);
    }

    #[test]
    fn all_free_is_the_free_body() {
        let free: Vec<_> = (0..6)
            .map(|k| {
                let mut c = [0; 6];
                c[k] = 1;
                s(c)
            })
            .collect();
        let c = Constrained::new(&body(), free, None).unwrap();
        assert!(c.blocked.is_empty());
        let e = Screw::axis(&v(1, 2, 3), &v(4, 1, 0));
        assert_eq!(c.response(&e), body().response(&e));
    }

    #[test]
    fn invalid_constraints_are_named() {
        let d = vec![s([0, 0, 1, -1, 0, 0]), s([0, 0, 2, -2, 0, 0])];
        assert_eq!(
            Constrained::new(&body(), d, None).unwrap_err(),
            ConstraintError::DependentFree { index: 1 }
        );
        let d = vec![s([0, 0, 1, 0, 0, 0])];
        let u = vec![s([0, 0, 0, 0, 0, 1])];
        assert!(matches!(
            Constrained::new(&body(), d.clone(), Some(u)),
            Err(ConstraintError::NotReciprocal {
                free: 0,
                blocked: 0,
                ..
            })
        ));
        let u = vec![s([1, 0, 0, 0, 0, 0])];
        assert_eq!(
            Constrained::new(&body(), d, Some(u)).unwrap_err(),
            ConstraintError::Dimension {
                free: 1,
                blocked: 1
            }
        );
        assert_eq!(
            Constrained::new(&body(), vec![], None).unwrap_err(),
            ConstraintError::Immobile
        );
    }

    #[test]
    fn velocity_outside_d_is_refused() {
        let c = Constrained::new(&body(), vec![s([0, 0, 1, -1, 0, 0])], None).unwrap();
        assert!(c.check_allowed(&s([0, 0, 2, -2, 0, 0])).is_ok());
        assert!(matches!(
            c.check_allowed(&s([0, 0, 1, 0, 0, 0])),
            Err(ConstraintError::VelocityNotAllowed { .. })
        ));
    }
}
