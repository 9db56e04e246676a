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

use nalgebra::SVector;

use crate::linalg::{self, factor_psd, null_space};
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
}

impl<T: Scalar> Joint<T> {
    /// The free screws (twists [ω; v_C]) this joint allows.
    pub fn free_screws(&self) -> Vec<Screw<T>> {
        let revolute = |p: &Vec3<T>, a: &Vec3<T>| Screw::new(a.clone(), p.cross(a));
        let prismatic = |a: &Vec3<T>| Screw::new(Vec3::zeros(), a.clone());
        match self {
            Joint::Revolute { point, axis } => vec![revolute(point, axis)],
            Joint::Prismatic { axis } => vec![prismatic(axis)],
            Joint::Cylindrical { point, axis } => vec![revolute(point, axis), prismatic(axis)],
            Joint::Spherical { point } => (0..3)
                .map(|k| {
                    let mut e = Vec3::zeros();
                    e[k] = T::one();
                    revolute(point, &e)
                })
                .collect(),
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
                vec![
                    revolute(&Vec3::zeros(), normal),
                    prismatic(&t1),
                    prismatic(&t2),
                ]
            }
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
/// the constraint impulses. Small fixed-size buffers: no allocation per response.
#[derive(Clone, Debug)]
pub struct Constrained<T: Scalar> {
    body: RigidBody<T>,
    /// D, the free screws.
    pub free: Vec<Screw<T>>,
    /// U, the constraint screws (given, or the η-orthogonal complement of D).
    pub blocked: Vec<Screw<T>>,
    /// Whether U was derived rather than given.
    pub derived_blocked: bool,
    /// D's columns equilibrated: D_a · 2^(k_a), with 2^(k_a) bringing their diagonal entry of
    /// M_red near 1 (floats; k_a = 0 in exact types). W = D M_red⁻¹ Dᵀ η is the same for every
    /// scaling of D's columns, so the solve uses these; the zero tests of rank then compare each
    /// screw with its own size, whatever the units (a body of 10⁻³⁰⁰ kg and 3.3 kg·m² on a
    /// revolute and a prismatic joint has M_red = diag(3.3, 10⁻³⁰⁰), which the unscaled test,
    /// relative to the largest entry, took for rank 1).
    basis: Vec<Screw<T>>,
    /// U's columns equilibrated the same way in Uᵀ η M⁻¹ U, with their powers of two: q is
    /// reported per column of U as given, q_a = 2^(k_a) q′_a.
    blocked_basis: Vec<(Screw<T>, T)>,
    m_red: SVector<T, 36>,
    m_red_perm: [usize; 6],
    u_gram: SVector<T, 36>,
    u_gram_perm: [usize; 6],
}

/// 2^k, the power of two nearest 1/√g for a positive float g (1 in exact types, and for g = 0
/// or a non-finite g): a screw times it has a Gram entry g·4^k within [½, 2).
fn equilibrator<T: Scalar>(g: &T) -> T {
    let x = g.to_f64();
    if T::IS_EXACT || !(x.is_finite() && x > 0.0) {
        return T::one();
    }
    let k = -(x.log2() / 2.0).round();
    T::from_f64(k.exp2())
        .filter(|s| s.to_f64().is_normal())
        .unwrap_or_else(T::one)
}

/// The screw s times the scalar c.
fn times<T: Scalar>(s: &Screw<T>, c: &T) -> Screw<T> {
    let mut out = Screw::zero();
    out.add_scaled(c, s);
    out
}

impl<T: Scalar> Constrained<T> {
    /// Validate D (and U, if given; otherwise derive it) for `body`, and factor M_red and
    /// Uᵀ η M⁻¹ U.
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
        // M_red = Dᵀ η M D (eq. 83): a Gram matrix, so rank-deficient iff D is; formed on
        // the equilibrated columns (see `basis`).
        let basis: Vec<Screw<T>> = free
            .iter()
            .map(|s| times(s, &equilibrator(&s.reciprocal(&body.momentum(s)))))
            .collect();
        let mut m_red = SVector::<T, 36>::zeros();
        let momenta: Vec<Screw<T>> = basis.iter().map(|s| body.momentum(s)).collect();
        for a in 0..d {
            for b in 0..d {
                m_red[a * d + b] = basis[a].reciprocal(&momenta[b]);
            }
        }
        if let Some(index) = first_dependent(&m_red.as_slice()[..d * d], d) {
            return Err(ConstraintError::DependentFree { index });
        }
        let mut m_red_perm = [0; 6];
        factor_psd(&mut m_red.as_mut_slice()[..d * d], d, &mut m_red_perm[..d])
            .map_err(|e| ConstraintError::DependentFree { index: e.index })?;

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
            None => {
                // x ∈ U ⇔ D_aᵀ η x = 0 for every a: rows [D_a bottom; D_a top].
                let mut rows = Vec::with_capacity(6 * d);
                for s in &free {
                    rows.extend(s.bottom().iter().cloned());
                    rows.extend(s.top().iter().cloned());
                }
                let (_, basis) = null_space(&rows, d, 6);
                let u = basis
                    .into_iter()
                    .map(|x| Screw(SVector::<T, 6>::from_iterator(x)))
                    .collect();
                (u, true)
            }
        };
        let u = blocked.len();
        if d + u != 6 {
            return Err(ConstraintError::Dimension {
                free: d,
                blocked: u,
            });
        }
        let blocked_basis: Vec<(Screw<T>, T)> = blocked
            .iter()
            .map(|s| {
                let k = equilibrator(&s.reciprocal(&body.response(s)));
                (times(s, &k), k)
            })
            .collect();
        let mut u_gram = SVector::<T, 36>::zeros();
        for a in 0..u {
            let r = body.response(&blocked_basis[a].0);
            for b in 0..u {
                u_gram[b * u + a] = blocked_basis[b].0.reciprocal(&r);
            }
        }
        if let Some(index) = first_dependent(&u_gram.as_slice()[..u * u], u) {
            return Err(ConstraintError::DependentBlocked { index });
        }
        let mut u_gram_perm = [0; 6];
        factor_psd(
            &mut u_gram.as_mut_slice()[..u * u],
            u,
            &mut u_gram_perm[..u],
        )
        .map_err(|e| ConstraintError::DependentBlocked { index: e.index })?;
        Ok(Constrained {
            body: body.clone(),
            free,
            blocked,
            derived_blocked,
            basis,
            blocked_basis,
            m_red,
            m_red_perm,
            u_gram,
            u_gram_perm,
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

    /// ξ with D ξ the η-M-orthogonal projection of `v` on the span of D:
    /// M_red ξ = Dᵀ η M {v} (exactly ξ⁰ of eq. 79 when {v} is allowed), for D's equilibrated
    /// columns (`basis`).
    fn coordinates(&self, v: &Screw<T>) -> SVector<T, 6> {
        let d = self.dof();
        let p = self.body.momentum(v);
        let mut xi = SVector::<T, 6>::zeros();
        for a in 0..d {
            xi[a] = self.basis[a].reciprocal(&p);
        }
        let mut work = SVector::<T, 6>::zeros();
        linalg::solve_factored(
            &self.m_red.as_slice()[..d * d],
            d,
            &self.m_red_perm[..d],
            &mut xi.as_mut_slice()[..d],
            &mut work.as_mut_slice()[..d],
        );
        xi
    }

    /// Check that {v⁰} is a twist the constraints allow: {v⁰} = D ξ⁰ (eq. 79).
    pub fn check_allowed(&self, v0: &Screw<T>) -> Result<(), ConstraintError> {
        let xi = self.coordinates(v0);
        let mut r = v0.clone();
        for (a, s) in self.basis.iter().enumerate() {
            r.add_scaled(&-xi[a].clone(), s);
        }
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
    /// written into `q` (length 6 − d).
    pub fn impulses_into<'a>(
        &self,
        dv: &Screw<T>,
        impulses: impl IntoIterator<Item = (&'a T, &'a Screw<T>)>,
        q: &mut Vec<T>,
    ) where
        T: 'a,
    {
        let u = self.blocked.len();
        let mut r = self.body.momentum(dv);
        for (p, e) in impulses {
            r.add_scaled(p, e);
        }
        let w = self.body.response(&r);
        q.clear();
        for (ua, _) in &self.blocked_basis {
            q.push(ua.reciprocal(&w));
        }
        let mut work = SVector::<T, 6>::zeros();
        linalg::solve_factored(
            &self.u_gram.as_slice()[..u * u],
            u,
            &self.u_gram_perm[..u],
            q,
            &mut work.as_mut_slice()[..u],
        );
        // q′ multiplies the equilibrated columns U_a·2^(k_a): q_a = 2^(k_a) q′_a.
        for (qa, (_, k)) in q.iter_mut().zip(&self.blocked_basis) {
            *qa *= k;
        }
    }
}

impl<T: Scalar> Mobility<T> for Constrained<T> {
    /// W{E} = D M_red⁻¹ Dᵀ η {E} (eq. 85).
    fn response(&self, e: &Screw<T>) -> Screw<T> {
        let d = self.dof();
        let mut y = SVector::<T, 6>::zeros();
        for a in 0..d {
            y[a] = self.basis[a].reciprocal(e);
        }
        let mut work = SVector::<T, 6>::zeros();
        linalg::solve_factored(
            &self.m_red.as_slice()[..d * d],
            d,
            &self.m_red_perm[..d],
            &mut y.as_mut_slice()[..d],
            &mut work.as_mut_slice()[..d],
        );
        let mut out = Screw::zero();
        for a in 0..d {
            out.add_scaled(&y[a], &self.basis[a]);
        }
        out
    }
}

/// The first k whose screw is a combination of screws 0..k, from their Gram matrix `g`
/// (n×n): the leading k+1 block is then singular. n ≤ 6, so factoring each block is cheap.
fn first_dependent<T: Scalar>(g: &[T], n: usize) -> Option<usize> {
    (0..n).find(|&k| {
        let m = k + 1;
        let mut block: SVector<T, 36> = SVector::zeros();
        for i in 0..m {
            for j in 0..m {
                block[i * m + j] = g[i * n + j].clone();
            }
        }
        let mut perm = [0; 6];
        factor_psd(&mut block.as_mut_slice()[..m * m], m, &mut perm[..m])
            .map_or(true, |f| f.rank < m)
    })
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
