//! The rigid body: mass, central inertia tensor, and the mass matrix in screw coordinates.
//!
//! With the twist {v} = [ω; v_C], the paper's mass matrix (eq. 9) and its inverse are
//!
//! ```text
//! [M] = [[0, m I], [J, 0]],     [M]⁻¹ = [[0, J⁻¹], [m⁻¹ I, 0]],
//! ```
//!
//! with J the central inertia tensor (about C) in the body axes: J = diag(J_x, J_y, J_z) in
//! central principal axes, as in the paper, or any symmetric positive definite matrix in other
//! axes through C ([`Inertia`]). So \[M\]{v} = [m v_C; J ω] is the momentum screw,
//! \[η\]\[M\] = diag(J, m I) and \[η\]\[M\]⁻¹ = diag(m⁻¹ I, J⁻¹) (eq. 56) are symmetric positive
//! definite, and the kinetic energy is T = ½ {v}ᵀ \[η\]\[M\] {v} = ½ (ωᵀ J ω + m v_C²) (eq. 32).
//! The principal path divides by J_k; a full tensor multiplies by its J⁻¹, computed once and
//! exactly (adjugate over determinant, [`crate::mechanics::inertia`]).

use crate::mechanics::inertia::{self, InertiaTensor};
use crate::mechanics::screw::{Screw, Vec3, dot};
use crate::scalar::Scalar;

pub use crate::mechanics::inertia::Inertia;

/// A rigid body: its mass and its central inertia tensor, in the axes Cxyz of the scene
/// (central principal axes when `inertia` is [`Inertia::Principal`]).
#[derive(Debug, PartialEq)]
pub struct RigidBody<T: Scalar> {
    /// The mass m > 0.
    pub mass: T,
    /// The central inertia tensor J: principal moments (J_x, J_y, J_z), each > 0, or a full
    /// symmetric positive definite tensor.
    pub inertia: Inertia<T>,
}

impl<T: Scalar> Clone for RigidBody<T> {
    fn clone(&self) -> Self {
        RigidBody {
            mass: self.mass.clone(),
            inertia: self.inertia.clone(),
        }
    }

    /// Field by field, reusing the inertia in place (see [`Inertia`]'s `clone_from`).
    fn clone_from(&mut self, source: &Self) {
        self.mass.clone_from(&source.mass);
        self.inertia.clone_from(&source.inertia);
    }
}

/// How the body's velocity answers an impulse: the twist change per unit impulse along an
/// axis screw. A free body answers with \[M\]⁻¹ (eq. 11); a constrained one with
/// \[D\]\[M_red\]⁻¹\[D\]ᵀ\[η\] (eq. 85). The solve is written once against this trait.
///
/// A system of bodies answers in the stack of its bodies' screws
/// ([`crate::mechanics::system::SystemScrew`]): `S` is the screw space.
pub trait Mobility<T: Scalar, S = Screw<T>> {
    /// W{E}: the twist produced by a unit impulse along the axis screw {E}.
    fn response(&self, e: &S) -> S;

    /// W{E} into `out`, which a mobility may fill in place reusing its storage (a system's
    /// stack of screws); by default `out` is replaced by [`Mobility::response`].
    fn response_into(&self, e: &S, out: &mut S) {
        *out = self.response(e);
    }
}

impl<T: Scalar> RigidBody<T> {
    /// A body of mass `mass` in its central principal axes, with the principal moments
    /// `moments` = (J_x, J_y, J_z).
    pub fn principal(mass: T, moments: Vec3<T>) -> Self {
        RigidBody {
            mass,
            inertia: Inertia::Principal(moments),
        }
    }

    /// A body of mass `mass` with the full central inertia tensor whose rows are `tensor`
    /// (symmetric; J⁻¹ is computed here, once).
    pub fn with_tensor(mass: T, tensor: [[T; 3]; 3]) -> Self {
        RigidBody {
            mass,
            inertia: Inertia::Tensor(InertiaTensor::new(tensor)),
        }
    }

    /// \[M\]{v} = [m v_C; J ω], the momentum screw of the twist {v}.
    pub fn momentum(&self, v: &Screw<T>) -> Screw<T> {
        let w = v.top();
        let vc = v.bottom();
        let jw = match &self.inertia {
            Inertia::Principal(j) => Vec3::new(
                j[0].clone() * &w[0],
                j[1].clone() * &w[1],
                j[2].clone() * &w[2],
            ),
            Inertia::Tensor(t) => inertia::times(t.matrix(), &w),
        };
        Screw::new(vc * self.mass.clone(), jw)
    }

    /// ½ {v}ᵀ \[η\]\[M\] {v} = ½ (ωᵀ J ω + m |v_C|²) (eq. 28, 32), written out.
    #[inline]
    pub fn kinetic_energy(&self, v: &Screw<T>) -> T {
        let s = v.as_slice();
        let rot = match &self.inertia {
            Inertia::Principal(j) => {
                let mut rot = j[0].clone() * &s[0] * &s[0];
                rot += j[1].clone() * &s[1] * &s[1];
                rot += j[2].clone() * &s[2] * &s[2];
                rot
            }
            Inertia::Tensor(t) => {
                // ωᵀ J ω = Σ_i ω_i (J ω)_i.
                let j = t.matrix();
                let mut rot = T::zero();
                for i in 0..3 {
                    let mut row = j[(i, 0)].clone() * &s[0];
                    row += j[(i, 1)].clone() * &s[1];
                    row += j[(i, 2)].clone() * &s[2];
                    rot += row * &s[i];
                }
                rot
            }
        };
        let trans = s[3].clone() * &s[3] + s[4].clone() * &s[4] + s[5].clone() * &s[5];
        (rot + self.mass.clone() * trans) / (T::one() + T::one())
    }
}

impl<T: Scalar> Mobility<T> for RigidBody<T> {
    /// \[M\]⁻¹{E} = [J⁻¹ (r × u); u / m] (eq. 9, 11).
    fn response(&self, e: &Screw<T>) -> Screw<T> {
        let u = e.top();
        let mu = e.bottom();
        match &self.inertia {
            Inertia::Principal(j) => Screw::new(
                Vec3::new(
                    mu[0].clone() / &j[0],
                    mu[1].clone() / &j[1],
                    mu[2].clone() / &j[2],
                ),
                u / self.mass.clone(),
            ),
            Inertia::Tensor(t) => tensor_response(t, &mu, u, &self.mass),
        }
    }
}

/// [J⁻¹ μ; u / m], out of line: were u / m shared by both arms of [`RigidBody::response`], the
/// compiler would move it after the branch, and the principal arm could no longer pair its
/// six f64 divisions into three vector ones as it did before the tensor existed.
#[inline(never)]
fn tensor_response<T: Scalar>(t: &InertiaTensor<T>, mu: &Vec3<T>, u: Vec3<T>, m: &T) -> Screw<T> {
    Screw::new(t.solve(mu), u / m.clone())
}

/// The inertance g = {E_a}ᵀ \[η\] W {E_b} (eq. 12, 86): the velocity along axis a produced by a
/// unit impulse along axis b.
pub fn inertance<T: Scalar>(mobility: &impl Mobility<T>, a: &Screw<T>, b: &Screw<T>) -> T {
    a.reciprocal(&mobility.response(b))
}

/// g_ij for the free body written out as eq. (57), an independent formula used to test
/// [`inertance`]: (u_i·u_j)/m + Σ_k μ_ik μ_jk / J_k in principal axes, and in general
/// (u_i·u_j)/m + μ_iᵀ J⁻¹ μ_j, here μ_iᵀ adj(J) μ_j / det J (not the stored J⁻¹).
pub fn inertance_eq57<T: Scalar>(body: &RigidBody<T>, a: &Screw<T>, b: &Screw<T>) -> T {
    let (ua, ma) = (a.top(), a.bottom());
    let (ub, mb) = (b.top(), b.bottom());
    let mut g = dot(&ua, &ub) / body.mass.clone();
    match &body.inertia {
        Inertia::Principal(j) => {
            for k in 0..3 {
                g += ma[k].clone() * &mb[k] / j[k].clone();
            }
        }
        Inertia::Tensor(t) => {
            let adj = inertia::adjugate(t.matrix());
            g += dot(&ma, &inertia::times(&adj, &mb)) / inertia::determinant(t.matrix());
        }
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int};

    fn v(x: i64, y: i64, z: i64) -> Vec3<Exact> {
        Vec3::new(int(x), int(y), int(z))
    }

    #[test]
    fn inertance_matches_eq57_and_is_symmetric() {
        let body = RigidBody::principal(int::<Exact>(3), v(2, 5, 7));
        let a = Screw::axis(&v(1, -2, 3), &v(2, 1, -1));
        let b = Screw::axis(&v(0, 4, -1), &v(1, 0, 3));
        assert_eq!(inertance(&body, &a, &b), inertance_eq57(&body, &a, &b));
        assert_eq!(inertance(&body, &a, &b), inertance(&body, &b, &a));
    }

    #[test]
    fn kinetic_energy_is_half_m_v2_plus_half_w_j_w() {
        let body = RigidBody::principal(int::<Exact>(2), v(1, 3, 5));
        let twist = Screw::new(v(1, 1, 2), v(3, 0, -1));
        // ½(1·1 + 3·1 + 5·4) + ½·2·(9 + 1) = 12 + 10.
        assert_eq!(body.kinetic_energy(&twist), int(22));
    }

    fn tensor_body() -> RigidBody<Exact> {
        // Positive definite: minors 4, 11, 18.
        let rows = [[4, 1, 0], [1, 3, 1], [0, 1, 2]].map(|r| r.map(int));
        RigidBody::with_tensor(int(3), rows)
    }

    #[test]
    fn a_diagonal_tensor_is_the_principal_body() {
        let principal = RigidBody::principal(int::<Exact>(3), v(2, 5, 7));
        let diagonal = [[2, 0, 0], [0, 5, 0], [0, 0, 7]].map(|r| r.map(int));
        let tensor = RigidBody::with_tensor(int(3), diagonal);
        let e = Screw::axis(&v(1, -2, 3), &v(2, 1, -1));
        let twist = Screw::new(v(1, 1, 2), v(3, 0, -1));
        assert_eq!(tensor.response(&e), principal.response(&e));
        assert_eq!(tensor.momentum(&twist), principal.momentum(&twist));
        assert_eq!(
            tensor.kinetic_energy(&twist),
            principal.kinetic_energy(&twist)
        );
    }

    #[test]
    fn a_full_tensor_answers_with_its_inverse() {
        let body = tensor_body();
        let a = Screw::axis(&v(1, -2, 3), &v(2, 1, -1));
        let b = Screw::axis(&v(0, 4, -1), &v(1, 0, 3));
        // [M][M]⁻¹{E} = {E}: [m · u/m; J J⁻¹ μ] = [u; μ], exactly.
        let p = body.momentum(&body.response(&a));
        assert_eq!((p.top(), p.bottom()), (a.top(), a.bottom()));
        assert_eq!(inertance(&body, &a, &b), inertance_eq57(&body, &a, &b));
        assert_eq!(inertance(&body, &a, &b), inertance(&body, &b, &a));
        // ½ ωᵀJω + ½ m v²: ω = (1, 1, 2): Jω = (5, 6, 5), ωᵀJω = 21; ½·21 + ½·3·10 = 51/2.
        let twist = Screw::new(v(1, 1, 2), v(3, 0, -1));
        assert_eq!(body.kinetic_energy(&twist), crate::scalar::ratio(51, 2));
    }
}
