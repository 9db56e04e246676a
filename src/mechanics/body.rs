//! The rigid body: mass, central principal moments, and the mass matrix in screw coordinates.
//!
//! With the twist {v} = [ω; v_C], the paper's mass matrix (eq. 9) and its inverse are
//!
//! ```text
//! [M] = [[0, m I], [J, 0]],     [M]⁻¹ = [[0, J⁻¹], [m⁻¹ I, 0]],     J = diag(J_x, J_y, J_z),
//! ```
//!
//! so \[M\]{v} = [m v_C; J ω] is the momentum screw, \[η\]\[M\] = diag(J, m I) and
//! \[η\]\[M\]⁻¹ = diag(m⁻¹ I, J⁻¹) (eq. 56) are symmetric positive definite, and the kinetic
//! energy is T = ½ {v}ᵀ \[η\]\[M\] {v} = ½ (ωᵀ J ω + m v_C²) (eq. 32).

use crate::mechanics::screw::{Screw, Vec3, dot};
use crate::scalar::Scalar;

/// A rigid body in its central principal frame Cxyz.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidBody<T: Scalar> {
    /// The mass m > 0.
    pub mass: T,
    /// The central principal moments (J_x, J_y, J_z), each > 0.
    pub inertia: Vec3<T>,
}

/// How the body's velocity answers an impulse: the twist change per unit impulse along an
/// axis screw. A free body answers with \[M\]⁻¹ (eq. 11); a constrained one with
/// \[D\]\[M_red\]⁻¹\[D\]ᵀ\[η\] (eq. 85). The solve is written once against this trait.
pub trait Mobility<T: Scalar> {
    /// W{E}: the twist produced by a unit impulse along the axis screw {E}.
    fn response(&self, e: &Screw<T>) -> Screw<T>;
}

impl<T: Scalar> RigidBody<T> {
    /// \[M\]{v} = [m v_C; J ω], the momentum screw of the twist {v}.
    pub fn momentum(&self, v: &Screw<T>) -> Screw<T> {
        let w = v.top();
        let vc = v.bottom();
        Screw::new(
            vc * self.mass.clone(),
            Vec3::new(
                self.inertia[0].clone() * &w[0],
                self.inertia[1].clone() * &w[1],
                self.inertia[2].clone() * &w[2],
            ),
        )
    }

    /// ½ {v}ᵀ \[η\]\[M\] {v} = ½ (ωᵀ J ω + m |v_C|²) (eq. 28, 32), written out (J is diagonal).
    #[inline]
    pub fn kinetic_energy(&self, v: &Screw<T>) -> T {
        let s = v.as_slice();
        let mut rot = self.inertia[0].clone() * &s[0] * &s[0];
        rot += self.inertia[1].clone() * &s[1] * &s[1];
        rot += self.inertia[2].clone() * &s[2] * &s[2];
        let trans = s[3].clone() * &s[3] + s[4].clone() * &s[4] + s[5].clone() * &s[5];
        (rot + self.mass.clone() * trans) / (T::one() + T::one())
    }
}

impl<T: Scalar> Mobility<T> for RigidBody<T> {
    /// \[M\]⁻¹{E} = [J⁻¹ (r × u); u / m] (eq. 9, 11).
    fn response(&self, e: &Screw<T>) -> Screw<T> {
        let u = e.top();
        let mu = e.bottom();
        Screw::new(
            Vec3::new(
                mu[0].clone() / &self.inertia[0],
                mu[1].clone() / &self.inertia[1],
                mu[2].clone() / &self.inertia[2],
            ),
            u / self.mass.clone(),
        )
    }
}

/// The inertance g = {E_a}ᵀ \[η\] W {E_b} (eq. 12, 86): the velocity along axis a produced by a
/// unit impulse along axis b.
pub fn inertance<T: Scalar>(mobility: &impl Mobility<T>, a: &Screw<T>, b: &Screw<T>) -> T {
    a.reciprocal(&mobility.response(b))
}

/// g_ij for the free body written out as eq. (57): (u_i·u_j)/m + Σ_k μ_ik μ_jk / J_k, an
/// independent formula used to test [`inertance`].
pub fn inertance_eq57<T: Scalar>(body: &RigidBody<T>, a: &Screw<T>, b: &Screw<T>) -> T {
    let (ua, ma) = (a.top(), a.bottom());
    let (ub, mb) = (b.top(), b.bottom());
    let mut g = dot(&ua, &ub) / body.mass.clone();
    for k in 0..3 {
        g += ma[k].clone() * &mb[k] / body.inertia[k].clone();
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
        let body = RigidBody {
            mass: int::<Exact>(3),
            inertia: v(2, 5, 7),
        };
        let a = Screw::axis(&v(1, -2, 3), &v(2, 1, -1));
        let b = Screw::axis(&v(0, 4, -1), &v(1, 0, 3));
        assert_eq!(inertance(&body, &a, &b), inertance_eq57(&body, &a, &b));
        assert_eq!(inertance(&body, &a, &b), inertance(&body, &b, &a));
    }

    #[test]
    fn kinetic_energy_is_half_m_v2_plus_half_w_j_w() {
        let body = RigidBody {
            mass: int::<Exact>(2),
            inertia: v(1, 3, 5),
        };
        let twist = Screw::new(v(1, 1, 2), v(3, 0, -1));
        // ½(1·1 + 3·1 + 5·4) + ½·2·(9 + 1) = 12 + 10.
        assert_eq!(body.kinetic_energy(&twist), int(22));
    }
}
