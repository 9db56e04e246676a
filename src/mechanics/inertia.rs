//! The central inertia tensor J (about the centre of mass C), in the axes the scene is
//! written in.
//!
//! In central principal axes J = diag(J_x, J_y, J_z), the paper's setting (eq. 9), and
//! J⁻¹ = diag(1/J_x, 1/J_y, 1/J_z). In any other axes through C — a body posed in world axes,
//! J_world = R J Rᵀ — J is a full symmetric matrix
//!
//! ```text
//!     [ J_xx  J_xy  J_xz ]
//! J = [ J_xy  J_yy  J_yz ],       J_xy = −∫ x y dm, …  (the tensor's entries, not the
//!     [ J_xz  J_yz  J_zz ]                               products of inertia ∫ x y dm)
//! ```
//!
//! and its inverse is exact in any field, by the adjugate (the transposed cofactors):
//!
//! ```text
//! J⁻¹ = adj(J) / det J,
//! adj(J)_ik = J_{k+1,i+1} J_{k+2,i+2} − J_{k+1,i+2} J_{k+2,i+1}   (indices mod 3),
//! det J = J_xx adj(J)_xx + J_xy adj(J)_yx + J_xz adj(J)_zx,
//! ```
//!
//! computed once, when the tensor is built — no square root, no eigen-decomposition, so
//! exact rationals and the symbolic scalar hold it exactly. J is physical when it is
//! symmetric positive definite, which Sylvester's criterion decides from the signs of the
//! leading principal minors
//!
//! ```text
//! Δ₁ = J_xx > 0,    Δ₂ = J_xx J_yy − J_xy² > 0,    Δ₃ = det J > 0,
//! ```
//!
//! exactly in exact types ([`crate::impact::problem::Problem::new`] checks them).

use nalgebra::Matrix3;

use crate::mechanics::screw::Vec3;
use crate::scalar::Scalar;

/// The central inertia tensor of a body: principal moments, or a full symmetric tensor.
#[derive(Debug, PartialEq)]
pub enum Inertia<T: Scalar> {
    /// J = diag(J_x, J_y, J_z): the axes are central principal axes (the paper's setting,
    /// and the fast path: J⁻¹ μ is three divisions).
    Principal(Vec3<T>),
    /// A full symmetric tensor, with its inverse.
    Tensor(InertiaTensor<T>),
}

impl<T: Scalar> Clone for Inertia<T> {
    fn clone(&self) -> Self {
        match self {
            Inertia::Principal(j) => Inertia::Principal(j.clone()),
            Inertia::Tensor(t) => Inertia::Tensor(t.clone()),
        }
    }

    /// In place when both are of one kind, so that re-assembling a problem
    /// ([`crate::impact::solve::Impact::reassemble`]) copies three moments, not a whole tensor.
    fn clone_from(&mut self, source: &Self) {
        match (self, source) {
            (Inertia::Principal(a), Inertia::Principal(b)) => a.clone_from(b),
            (Inertia::Tensor(a), Inertia::Tensor(b)) => a.clone_from(b),
            (this, source) => *this = source.clone(),
        }
    }
}

impl<T: Scalar> From<Vec3<T>> for Inertia<T> {
    /// The central principal moments (J_x, J_y, J_z).
    fn from(moments: Vec3<T>) -> Self {
        Inertia::Principal(moments)
    }
}

impl<T: Scalar> From<[[T; 3]; 3]> for Inertia<T> {
    /// A full tensor, given by its rows.
    fn from(rows: [[T; 3]; 3]) -> Self {
        Inertia::Tensor(InertiaTensor::new(rows))
    }
}

impl<T: Scalar> Inertia<T> {
    /// J as a matrix (diagonal for principal moments).
    pub fn matrix(&self) -> Matrix3<T> {
        match self {
            Inertia::Principal(j) => Matrix3::from_diagonal(j),
            Inertia::Tensor(t) => t.matrix.clone(),
        }
    }

    /// The entry J_ik.
    pub fn entry(&self, i: usize, k: usize) -> T {
        match self {
            Inertia::Principal(j) if i == k => j[i].clone(),
            Inertia::Principal(_) => T::zero(),
            Inertia::Tensor(t) => t.matrix[(i, k)].clone(),
        }
    }
}

/// A full symmetric inertia tensor J and its inverse J⁻¹ = adj(J) / det J, computed once.
///
/// Built from any 3×3 matrix, so that an invalid one can be named when it is refused:
/// [`crate::impact::problem::Problem::new`] refuses a tensor that is not symmetric positive
/// definite, so every validated body has one with an inverse.
#[derive(Clone, Debug, PartialEq)]
pub struct InertiaTensor<T: Scalar> {
    matrix: Matrix3<T>,
    inverse: Option<Matrix3<T>>,
}

impl<T: Scalar> InertiaTensor<T> {
    /// The tensor with these rows, and its inverse when det J ≠ 0.
    pub fn new(rows: [[T; 3]; 3]) -> Self {
        let matrix = Matrix3::from_fn(|i, k| rows[i][k].clone());
        let det = determinant(&matrix);
        let inverse = (!det.is_zero()).then(|| adjugate(&matrix).map(|a| a / &det));
        InertiaTensor { matrix, inverse }
    }

    /// J.
    pub fn matrix(&self) -> &Matrix3<T> {
        &self.matrix
    }

    /// J⁻¹; `None` when J is singular (refused by [`crate::impact::problem::Problem::new`]).
    pub fn inverse(&self) -> Option<&Matrix3<T>> {
        self.inverse.as_ref()
    }

    /// The leading principal minors (Δ₁, Δ₂, Δ₃) = (J_xx, J_xx J_yy − J_xy J_yx, det J) of
    /// Sylvester's criterion: J (symmetric) is positive definite iff all three are > 0.
    pub fn leading_minors(&self) -> [T; 3] {
        let j = &self.matrix;
        let d2 = j[(0, 0)].clone() * &j[(1, 1)] - j[(0, 1)].clone() * &j[(1, 0)];
        [j[(0, 0)].clone(), d2, determinant(j)]
    }

    /// J⁻¹ μ.
    ///
    /// # Panics
    /// If J is singular (never for a validated problem's body).
    #[inline]
    pub fn solve(&self, mu: &Vec3<T>) -> Vec3<T> {
        let inv = self
            .inverse
            .as_ref()
            .expect("a singular inertia tensor has no inverse; Problem::new refuses it");
        times(inv, mu)
    }
}

/// A ω for a 3×3 matrix A, by reference (no big rational cloned needlessly).
#[inline]
pub fn times<T: Scalar>(a: &Matrix3<T>, w: &Vec3<T>) -> Vec3<T> {
    Vec3::from_fn(|i, _| {
        let mut s = a[(i, 0)].clone() * &w[0];
        s += a[(i, 1)].clone() * &w[1];
        s += a[(i, 2)].clone() * &w[2];
        s
    })
}

/// adj(A), the transposed matrix of cofactors: A adj(A) = det(A) I.
pub fn adjugate<T: Scalar>(a: &Matrix3<T>) -> Matrix3<T> {
    Matrix3::from_fn(|i, k| {
        let (k1, k2, i1, i2) = ((k + 1) % 3, (k + 2) % 3, (i + 1) % 3, (i + 2) % 3);
        a[(k1, i1)].clone() * &a[(k2, i2)] - a[(k1, i2)].clone() * &a[(k2, i1)]
    })
}

/// det A, expanded along the first row.
pub fn determinant<T: Scalar>(a: &Matrix3<T>) -> T {
    let adj = adjugate(a);
    a[(0, 0)].clone() * &adj[(0, 0)]
        + a[(0, 1)].clone() * &adj[(1, 0)]
        + a[(0, 2)].clone() * &adj[(2, 0)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int};

    fn rows(r: [[i64; 3]; 3]) -> [[Exact; 3]; 3] {
        r.map(|row| row.map(int))
    }

    #[test]
    fn the_inverse_is_the_adjugate_over_the_determinant() {
        // det = 4(6 − 1) − 1(2 − 0) + 0 = 18.
        let t = InertiaTensor::new(rows([[4, 1, 0], [1, 3, 1], [0, 1, 2]]));
        assert_eq!(determinant(t.matrix()), int(18));
        assert_eq!(t.leading_minors(), [int(4), int(11), int(18)]);
        let product = t.matrix() * t.inverse().unwrap();
        assert_eq!(product, Matrix3::identity());
        let mu = Vec3::new(int(1), int(-2), int(5));
        assert_eq!(times(t.matrix(), &t.solve(&mu)), mu);
    }

    #[test]
    fn a_singular_tensor_has_no_inverse() {
        let t = InertiaTensor::new(rows([[1, 2, 3], [2, 4, 6], [3, 6, 10]]));
        assert_eq!(t.inverse(), None);
        assert_eq!(t.leading_minors()[1], int(0));
    }

    #[test]
    fn principal_moments_are_the_diagonal() {
        let j: Inertia<Exact> = Vec3::new(int(2), int(3), int(5)).into();
        assert_eq!(j.entry(1, 1), int(3));
        assert_eq!(j.entry(0, 2), int(0));
        assert_eq!(
            j.matrix(),
            Matrix3::from_diagonal(&Vec3::new(int(2), int(3), int(5)))
        );
    }
}
