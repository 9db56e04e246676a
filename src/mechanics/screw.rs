//! Screw (Plücker) coordinates, with the paper's conventions (§2.2).
//!
//! A screw is a column of six numbers `[top; bottom]`:
//!
//! * a **velocity screw** (twist) is {v} = [ω; v_C]: angular velocity, then the velocity of
//!   the centre of mass C;
//! * the screw of an **axis** through the point A (position **r** from C) with direction **u**
//!   is {E} = [u; r × u] (eq. 3–4, with \[S\] the matrix of r×);
//! * a **wrench** (an impulse and its moment about C) has the same layout, [P; r × P].
//!
//! The mixed product of eq. (6), {a} * {b} = {a}ᵀ \[η\] {b} with \[η\] = [[0, I], [I, 0]]
//! (eq. 5), pairs a twist with an axis: {E}ᵀ η {v} = u · (v_C + ω × r) is the velocity of
//! the point A along **u** (eq. 8).

use nalgebra::{SVector, Vector3};

use crate::scalar::Scalar;

/// A 3-vector of the body frame Cxyz (central axes: principal ones, unless the body has a full
/// inertia tensor).
pub type Vec3<T> = Vector3<T>;

/// A screw in Plücker coordinates, `[top; bottom]` (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Screw<T: Scalar>(pub SVector<T, 6>);

impl<T: Scalar> Screw<T> {
    /// The screw [top; bottom].
    #[inline]
    pub fn new(top: Vec3<T>, bottom: Vec3<T>) -> Self {
        let [a, b, c] = <[T; 3]>::from(top);
        let [d, e, f] = <[T; 3]>::from(bottom);
        Screw(SVector::<T, 6>::new(a, b, c, d, e, f))
    }

    /// The zero screw.
    pub fn zero() -> Self {
        Screw(SVector::<T, 6>::zeros())
    }

    /// The screw of the axis through `point` with direction `direction`: [u; r × u] (eq. 3–4).
    #[inline]
    pub fn axis(point: &Vec3<T>, direction: &Vec3<T>) -> Self {
        Self::new(direction.clone(), point.cross(direction))
    }

    /// The first three coordinates (ω of a twist, the direction of an axis).
    #[inline]
    pub fn top(&self) -> Vec3<T> {
        self.0.fixed_rows::<3>(0).into_owned()
    }

    /// The last three coordinates (v_C of a twist, the moment of an axis about C).
    #[inline]
    pub fn bottom(&self) -> Vec3<T> {
        self.0.fixed_rows::<3>(3).into_owned()
    }

    /// The mixed product {self}ᵀ \[η\] {other} of eq. (6): top·bottom' + bottom·top'.
    #[inline]
    pub fn reciprocal(&self, other: &Screw<T>) -> T {
        let mut s = T::zero();
        for i in 0..3 {
            s += self.0[i].clone() * &other.0[i + 3];
            s += self.0[i + 3].clone() * &other.0[i];
        }
        s
    }

    /// `self + c · other`, in place (the update {v} ← {v} − P M⁻¹{E} of eq. 24).
    #[inline]
    pub fn add_scaled(&mut self, c: &T, other: &Screw<T>) {
        for i in 0..6 {
            self.0[i] += c.clone() * &other.0[i];
        }
    }

    /// The coordinates as a slice, top first.
    pub fn as_slice(&self) -> &[T] {
        self.0.as_slice()
    }
}

/// The screws a mechanism's twists and contact axes live in, paired by η (eq. 6): one body's
/// [`Screw`], or the stack of a system's, one screw per body
/// ([`crate::mechanics::system::SystemScrew`]). The impact is solved once against this trait
/// ([`crate::impact::mechanism::Mechanism`]).
pub trait Screws<T: Scalar>: Clone + std::fmt::Debug + PartialEq + Default {
    /// {self}ᵀ η {other}: the velocity along an axis, the power of a wrench on a twist.
    fn reciprocal(&self, other: &Self) -> T;
    /// `self + c · other`, in place.
    fn add_scaled(&mut self, c: &T, other: &Self);
    /// `self − other`.
    fn minus(&self, other: &Self) -> Self;
    /// The zero of `self`'s space.
    fn zero_like(&self) -> Self;
    /// The components in order: [ω; v] for one screw, each body's in turn for a stack.
    fn components(&self) -> Vec<T>;
    /// The largest |coordinate|, as f64: the scale of a response, for error bounds.
    fn max_abs_f64(&self) -> f64;
    /// One body's screw as a member of this space (a stack of one for a system): how the
    /// one-body float lane ([`crate::impact::solve`]) serves a system of one body.
    fn from_single(s: Screw<T>) -> Self;
    /// The one body's screw, when the space is one body's.
    fn single(&self) -> Option<&Screw<T>>;
}

impl<T: Scalar> Default for Screw<T> {
    fn default() -> Self {
        Screw::zero()
    }
}

impl<T: Scalar> Screws<T> for Screw<T> {
    #[inline]
    fn reciprocal(&self, other: &Self) -> T {
        Screw::reciprocal(self, other)
    }

    #[inline]
    fn add_scaled(&mut self, c: &T, other: &Self) {
        Screw::add_scaled(self, c, other);
    }

    #[inline]
    fn minus(&self, other: &Self) -> Self {
        Screw(self.0.clone() - other.0.clone())
    }

    #[inline]
    fn zero_like(&self) -> Self {
        Screw::zero()
    }

    fn components(&self) -> Vec<T> {
        self.as_slice().to_vec()
    }

    fn max_abs_f64(&self) -> f64 {
        self.0.iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max)
    }

    #[inline]
    fn from_single(s: Screw<T>) -> Self {
        s
    }

    #[inline]
    fn single(&self) -> Option<&Screw<T>> {
        Some(self)
    }
}

/// u · w, field-only.
pub fn dot<T: Scalar>(u: &Vec3<T>, w: &Vec3<T>) -> T {
    u[0].clone() * &w[0] + u[1].clone() * &w[1] + u[2].clone() * &w[2]
}

/// |u|², the squared norm (no square root is taken anywhere in the solver).
pub fn norm2<T: Scalar>(u: &Vec3<T>) -> T {
    dot(u, u)
}

/// `u` times a power of two that brings its largest component near 1, in float types: a
/// direction, which any length serves, whose squared norm then neither overflows nor
/// underflows (the velocity of a point of a body spinning at 10³⁰⁸ rad/s squares to ∞ in f64,
/// and a contact frame built on it fell back to a coordinate axis). The scaling is exact, so
/// every quantity normalised by |u| comes out bit for bit as from `u`. Exact types, which
/// cannot overflow, return `u` as it is.
pub fn rescaled<T: Scalar>(u: &Vec3<T>) -> Vec3<T> {
    if T::IS_EXACT {
        return u.clone();
    }
    let largest = u
        .iter()
        .map(|x| x.to_f64().abs())
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    if largest == 0.0 {
        return u.clone();
    }
    let k = largest.log2().floor() as i32;
    if k == 0 {
        return u.clone();
    }
    // In two halves, each a power of two f64 holds (2^1074 is not one); and only factors the
    // type holds exactly.
    let mut out = u.clone();
    for half in [k / 2, k - k / 2] {
        let power = 2f64.powi(-half);
        match T::from_f64(power) {
            Some(f) if f.to_f64() == power => out = out.map(|x| x * &f),
            _ => return u.clone(),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int};

    fn v(x: i64, y: i64, z: i64) -> Vec3<Exact> {
        Vec3::new(int(x), int(y), int(z))
    }

    #[test]
    fn axis_screw_is_direction_and_moment() {
        // Example 3: A_1 = (0, −2, 0), x_1 = i  ⇒  {E_1x} = [1 0 0 0 0 2]ᵀ.
        let e = Screw::axis(&v(0, -2, 0), &v(1, 0, 0));
        assert_eq!(e.top(), v(1, 0, 0));
        assert_eq!(e.bottom(), v(0, 0, 2));
    }

    #[test]
    fn reciprocal_product_is_the_point_velocity_along_the_axis() {
        // {E}ᵀη{v} = u · (v_C + ω × r) for any r, u, ω, v_C.
        let (r, u) = (v(1, -2, 3), v(2, 1, -1));
        let (w, vc) = (v(-1, 4, 2), v(5, 0, -3));
        let e = Screw::axis(&r, &u);
        let twist = Screw::new(w.clone(), vc.clone());
        assert_eq!(e.reciprocal(&twist), dot(&u, &(vc + w.cross(&r))));
        assert_eq!(e.reciprocal(&twist), twist.reciprocal(&e));
    }

    #[test]
    fn rescaled_keeps_the_direction_exactly_and_the_square_in_range() {
        // Scaled by a power of two: every ratio of components is kept bit for bit.
        for u in [
            Vec3::<f64>::new(1e308, -3e307, 0.0),
            Vec3::new(3e-320, 1e-321, -2e-322),
            Vec3::new(0.3, 0.0, 7.0),
        ] {
            let r = rescaled(&u);
            for i in 0..3 {
                for j in 0..3 {
                    if u[j] != 0.0 {
                        assert_eq!(r[i] / r[j], u[i] / u[j], "{u:?}");
                    }
                }
            }
            let square = norm2(&r);
            assert!(square.is_normal() && (1.0..64.0).contains(&square), "{u:?}");
        }
        // f32's least subnormal, 2^−149, in two factors f32 holds (2^74, 2^75).
        let tiny = Vec3::new(1e-45f32, 0.0, 0.0);
        assert_eq!(rescaled(&tiny), Vec3::new(1.0, 0.0, 0.0));
        // Exact types cannot overflow: unchanged.
        assert_eq!(rescaled(&v(4, -8, 2)), v(4, -8, 2));
    }
}
