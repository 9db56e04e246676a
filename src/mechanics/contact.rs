//! Contacts and their local frames A_i x_i y_i z_i (eq. 2–4 and §12, eq. 112–123).
//!
//! **No square root.** The axes are kept as the (generally non-unit) directions they are
//! built from: x̂_i = n_i as given, ŷ_i, ẑ_i as below. With E-hat the screw of an unnormalised
//! axis, every quantity of the paper follows from a hatted one by a norm:
//!
//! ```text
//! v_ix = v̂_ix / |x̂_i|,   P_i = P̂_i |x̂_i|,   g_ij = ĝ_ij / (|x̂_i| |x̂_j|)
//! ```
//!
//! and the laws (eq. 14, 21–23) are invariant under this scaling, so the solve runs on hatted
//! quantities in any field and the norms are applied only when results are reported, as
//! exact surds q·√r ([`Surd`]) in exact mode. Velocities after impact and both energies never
//! involve a norm and are exact rationals whenever the inputs are.
//!
//! **Tangent axes.** If the contact gives a tangent y_i (it must be perpendicular to n_i), then
//! ŷ_i = y_i and ẑ_i = x̂_i × ŷ_i. Otherwise §12 builds them from the velocity v_A of the
//! contact point before impact: ẑ_i = n_i × v_A (eq. 113) and ŷ_i = ẑ_i × n_i (eq. 120), so
//! that ŷ_i points along the tangential velocity and v_iz⁰ = 0 (Remark 3). When the tangential
//! velocity is zero (n_i × v_A = 0), the fallback is deterministic: ẑ_i = n_i × e_k, where e_k
//! is the coordinate axis least aligned with n_i (smallest |n_k|, lowest k on ties).

use crate::mechanics::screw::{Screw, Screws, Vec3, dot, norm2, rescaled};
use crate::scalar::Scalar;

/// One contact as given: the point A_i, the outward normal n_i (axis A_i x_i; need not be a
/// unit vector), an optional tangent axis y_i, and the restitution coefficients.
#[derive(Clone, Debug, PartialEq)]
pub struct Contact<T: Scalar> {
    /// Position of A_i from C, body axes.
    pub point: Vec3<T>,
    /// Outward normal of the body at A_i: the direction of A_i x_i.
    pub normal: Vec3<T>,
    /// The axis A_i y_i, if imposed.
    pub tangent: Option<Vec3<T>>,
    /// Newton's coefficient k_i^N (eq. 14).
    pub k_newton: T,
    /// Poisson's coefficient k_i^P (eq. 23).
    pub k_poisson: T,
    /// Stronge's energetic coefficient k_i^E: the restitution work at the contact is k_i^E²
    /// times its compression work ([`crate::impact::friction`]).
    pub k_energetic: T,
    /// Coulomb's coefficient of friction μ_i ≥ 0 (§14; 0: frictionless, the paper's §2–13).
    pub mu: T,
}

impl<T: Scalar> Contact<T> {
    /// A contact at `point` (from C) with the body's outward `normal` there and one
    /// coefficient of restitution `k` for both models; the tangent follows §12.
    pub fn new(point: Vec3<T>, normal: Vec3<T>, k: T) -> Self {
        Contact {
            point,
            normal,
            tangent: None,
            k_newton: k.clone(),
            k_poisson: k.clone(),
            k_energetic: k,
            mu: T::zero(),
        }
    }

    /// The same contact with the axis y_i imposed (perpendicular to the normal).
    pub fn with_tangent(mut self, tangent: Vec3<T>) -> Self {
        self.tangent = Some(tangent);
        self
    }

    /// The same contact with Coulomb friction of coefficient μ_i (§14).
    pub fn with_friction(mut self, mu: T) -> Self {
        self.mu = mu;
        self
    }

    /// The same contact with Stronge's energetic coefficient k_i^E given separately.
    pub fn with_energetic(mut self, k_energetic: T) -> Self {
        self.k_energetic = k_energetic;
        self
    }

    /// The same contact with Newton's k_i^N and Poisson's k_i^P given separately.
    pub fn with_coefficients(mut self, k_newton: T, k_poisson: T) -> Self {
        self.k_newton = k_newton;
        self.k_poisson = k_poisson;
        self
    }
}

/// How the tangent axis y_i of a frame was chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TangentRule {
    /// Given in the scene.
    Given,
    /// Along the tangential velocity of the contact point before impact (§12).
    Velocity,
    /// Tangential velocity zero: ẑ = n × e_k with this coordinate axis k (0 = x, 1 = y, 2 = z).
    Fallback(usize),
}

/// A contact's frame: three unnormalised axes, their screws and their squared norms.
///
/// The screws live in the mechanism's space `S`: a body's [`Screw`] about its centre of mass,
/// or for a contact between two bodies of a system the axis's screw on the first minus its
/// screw on the second ([`crate::mechanics::system`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ContactFrame<T: Scalar, S: Screws<T> = Screw<T>> {
    /// {Ê_x}, {Ê_y}, {Ê_z}: screws of the unnormalised axes x̂, ŷ, ẑ through A_i.
    pub axes: [S; 3],
    /// x̂, ŷ, ẑ: the axes' directions (the report's unit axes are these over their norms).
    pub directions: [Vec3<T>; 3],
    /// |x̂|², |ŷ|², |ẑ|².
    pub norm2: [T; 3],
    /// How ŷ was chosen.
    pub rule: TangentRule,
}

/// A contact whose imposed tangent is not perpendicular to its normal.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("contact {index}: the tangent is not perpendicular to the normal (n·y = {dot})")]
pub struct TangentNotPerpendicular {
    /// The contact's index (0-based).
    pub index: usize,
    /// n·y, as f64, for the message.
    pub dot: f64,
}

impl<T: Scalar> ContactFrame<T> {
    /// Build the frame of `contact` (number `index`) for a body moving with the twist
    /// `v0` = [ω⁰; v_C⁰] before impact.
    pub fn new(
        index: usize,
        contact: &Contact<T>,
        v0: &Screw<T>,
    ) -> Result<Self, TangentNotPerpendicular> {
        // eq. 112: the velocity of A_i.
        let point_velocity = || v0.bottom() + v0.top().cross(&contact.point);
        ContactFrame::with_axes(index, contact, point_velocity, |u| {
            Screw::axis(&contact.point, u)
        })
    }

    /// The frame of `contact` reduced to its normal: x̂ = n_i and |x̂|², the tangent axes and
    /// their norms zero (for a solve that reports nothing tangential,
    /// [`crate::impact::outputs::Outputs::TANGENTIAL`]).
    pub fn normal(contact: &Contact<T>) -> Self {
        ContactFrame::normal_with(contact, |u| Screw::axis(&contact.point, u))
    }
}

impl<T: Scalar, S: Screws<T>> ContactFrame<T, S> {
    /// Build the frame of `contact` (number `index`) whose point moves at `point_velocity`
    /// before impact (relative to the other body, for a contact between two), the screw of
    /// each axis given by `axis` from its direction. The tangent is the contact's, or follows
    /// §12 (eq. 112–123): ẑ = n × v_A, ŷ = ẑ × n.
    pub fn with_axes(
        index: usize,
        contact: &Contact<T>,
        point_velocity: impl FnOnce() -> Vec3<T>,
        axis: impl Fn(&Vec3<T>) -> S,
    ) -> Result<Self, TangentNotPerpendicular> {
        let x = contact.normal.clone();
        let nx2 = norm2(&x);
        let (y, rule) = match &contact.tangent {
            Some(t) => {
                let d = dot(&x, t);
                let reference = nx2.clone() * norm2(t);
                if !(d.clone() * &d).is_negligible(&reference, 3) {
                    return Err(TangentNotPerpendicular {
                        index,
                        dot: d.to_f64(),
                    });
                }
                (t.clone(), TangentRule::Given)
            }
            None => {
                // eq. 112: velocity of A_i (a direction here, kept within range: `rescaled`);
                // eq. 113: n × v_A.
                let va = rescaled(&point_velocity());
                let z = x.cross(&va);
                let reference = nx2.clone() * norm2(&va);
                if norm2(&z).is_negligible(&reference, 3) {
                    let k = least_aligned_axis(&x);
                    let mut e = Vec3::<T>::zeros();
                    e[k] = T::one();
                    (x.cross(&e).cross(&x), TangentRule::Fallback(k))
                } else {
                    (z.cross(&x), TangentRule::Velocity)
                }
            }
        };
        let z = x.cross(&y);
        let norm2 = [nx2, norm2(&y), norm2(&z)];
        let axes = [axis(&x), axis(&y), axis(&z)];
        Ok(ContactFrame {
            axes,
            directions: [x, y, z],
            norm2,
            rule,
        })
    }

    /// The frame of `contact` reduced to its normal, the screw of an axis given by `axis`.
    pub fn normal_with(contact: &Contact<T>, axis: impl Fn(&Vec3<T>) -> S) -> Self {
        let zero = Vec3::zeros();
        ContactFrame {
            axes: [axis(&contact.normal), axis(&zero), axis(&zero)],
            directions: [contact.normal.clone(), zero.clone(), zero],
            norm2: [norm2(&contact.normal), T::zero(), T::zero()],
            rule: TangentRule::Given,
        }
    }

    /// The hatted velocity components (Ê_x, Ê_y, Ê_z)·{v} of the contact point (eq. 8).
    pub fn velocity(&self, v: &S) -> [T; 3] {
        [
            self.axes[0].reciprocal(v),
            self.axes[1].reciprocal(v),
            self.axes[2].reciprocal(v),
        ]
    }
}

/// The index of the coordinate axis least aligned with `n` (smallest |n_k|, lowest k on ties).
fn least_aligned_axis<T: Scalar>(n: &Vec3<T>) -> usize {
    let mut k = 0;
    for i in 1..3 {
        if n[k].abs_gt(&n[i]) {
            k = i;
        }
    }
    k
}

/// A value q·√r with q, r in the scalar type (r ≥ 0): how a quantity that involves an axis
/// norm is reported. For exact types it renders canonically (`3/17*sqrt(17)`); for floats it
/// is evaluated.
#[derive(Clone, Debug, PartialEq)]
pub struct Surd<T: Scalar> {
    /// q.
    pub coeff: T,
    /// r ≥ 0.
    pub radicand: T,
}

impl<T: Scalar> Surd<T> {
    /// raw · |a| for an axis with |a|² = `norm2`: raw·√(norm2) (an impulse, P = P̂ |x̂|).
    pub fn times_norm(raw: &T, norm2: &T) -> Self {
        Surd {
            coeff: raw.clone(),
            radicand: norm2.clone(),
        }
    }

    /// raw / |a| for an axis with |a|² = `norm2`: (raw/norm2)·√(norm2) (a velocity component
    /// or an inertance, v = v̂ / |x̂|).
    pub fn over_norm(raw: &T, norm2: &T) -> Self {
        Surd {
            coeff: raw.clone() / norm2,
            radicand: norm2.clone(),
        }
    }

    /// q·√r as one value of the type: rounded in floats, exact in exact types when √r is
    /// (a perfect square in rationals, any r in the symbolic type); `None` otherwise — then
    /// [`Surd::to_f64`] and [`Surd::exact_text`] still give it.
    pub fn value(&self) -> Option<T> {
        Some(self.coeff.clone() * &self.radicand.sqrt_value()?)
    }

    /// The value in f64.
    pub fn to_f64(&self) -> f64 {
        match (self.coeff.to_rational(), self.radicand.to_rational()) {
            (Some(q), Some(r)) => crate::number::surd_to_f64(&q, &r),
            _ => self.coeff.to_f64() * self.radicand.to_f64().sqrt(),
        }
    }

    /// The exact text `p/q` or `c*sqrt(r)`, for exact types.
    ///
    /// Beyond rationals (the symbolic type), the value q·√r is formed exactly when √r is
    /// (a rational r becomes a radical); otherwise `None`.
    ///
    /// When √r is not a value of the type (a symbolic norm such as √(a² + 1)), the product is
    /// written as it stands, `(q)*sqrt(r)` — still exact, never "no exact form".
    pub fn exact_text(&self) -> Option<String> {
        if let (Some(q), Some(r)) = (self.coeff.to_rational(), self.radicand.to_rational()) {
            return Some(crate::number::format_surd(&q, &r));
        }
        if let Some(v) = self.exact_value() {
            return v.exact_text();
        }
        let (q, r) = (self.coeff.exact_text()?, self.radicand.exact_text()?);
        Some(if self.coeff.is_zero() {
            "0".into()
        } else {
            format!("({q})*sqrt({r})")
        })
    }

    /// The exact value in LaTeX, for types with a LaTeX form of their own (`q\sqrt{r}` when
    /// √r is not a value of the type).
    pub fn latex_text(&self) -> Option<String> {
        if let Some(v) = self.exact_value() {
            return v.latex_text();
        }
        let (q, r) = (self.coeff.latex_text()?, self.radicand.latex_text()?);
        Some(if self.coeff.is_zero() {
            "0".into()
        } else {
            format!("\\left({q}\\right)\\sqrt{{{r}}}")
        })
    }

    /// For dual numbers ([`crate::scalar::dual`]): the derivative of q·√r, again a surd with
    /// the radicand r — d(q√r) = q′√r + q r′/(2√r) = (q′ + q r′/(2r))√r — so it stays exact
    /// in `Dual<Exact>` whatever |n_i| is. `None` for other types, and at r = 0 with r′ ≠ 0
    /// (no derivative; never for an axis norm).
    pub fn derivative(&self) -> Option<Surd<T>> {
        let (q, dq) = self.coeff.dual_parts()?;
        let (r, dr) = self.radicand.dual_parts()?;
        let coeff = if dr.is_zero() {
            dq
        } else if r.is_zero() {
            return None;
        } else {
            dq + &(q * &dr / (r.clone() + &r))
        };
        Some(Surd { coeff, radicand: r })
    }

    /// q·√r as one value of the type, when √r is exactly representable.
    fn exact_value(&self) -> Option<T> {
        Some(self.coeff.clone() * &self.radicand.sqrt_exact()?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int};

    fn v(x: i64, y: i64, z: i64) -> Vec3<Exact> {
        Vec3::new(int(x), int(y), int(z))
    }

    fn contact(p: Vec3<Exact>, n: Vec3<Exact>, t: Option<Vec3<Exact>>) -> Contact<Exact> {
        Contact {
            point: p,
            normal: n,
            tangent: t,
            k_newton: int(0),
            k_poisson: int(0),
            k_energetic: int(0),
            mu: int(0),
        }
    }

    #[test]
    fn velocity_rule_reproduces_example_8() {
        // §13: A_1 = (R,0,0), A_2 = (0,R,0), v_C⁰ = (v⁰, 2v⁰, 0), ω⁰ = 0 (R = 1, v⁰ = 1).
        let v0 = Screw::new(v(0, 0, 0), v(1, 2, 0));
        let f1 = ContactFrame::new(0, &contact(v(1, 0, 0), v(1, 0, 0), None), &v0).unwrap();
        let f2 = ContactFrame::new(1, &contact(v(0, 1, 0), v(0, 1, 0), None), &v0).unwrap();
        // The paper: y_1 ∝ (0,1,0), z_1 = (0,0,1); y_2 ∝ (1,0,0), z_2 = (0,0,−1).
        assert_eq!(
            f1.axes[1].top() / f1.norm2[1].clone(),
            v(0, 1, 0) / int::<Exact>(2)
        );
        assert_eq!(f2.axes[2].top(), v(0, 0, -1));
        assert_eq!(f2.axes[1].top(), v(1, 0, 0));
        assert_eq!(f1.rule, TangentRule::Velocity);
        // Remark 3: v_iz⁰ = 0 by construction.
        assert_eq!(f1.velocity(&v0)[2], int(0));
        assert_eq!(f2.velocity(&v0)[2], int(0));
    }

    #[test]
    fn zero_tangential_velocity_falls_back_deterministically() {
        let v0 = Screw::new(v(0, 0, 0), v(3, 0, 0));
        let f = ContactFrame::new(0, &contact(v(1, 0, 0), v(2, 0, 0), None), &v0).unwrap();
        assert_eq!(f.rule, TangentRule::Fallback(1));
        // ẑ = n × e_y ∝ e_z, ŷ = ẑ × n ∝ e_y: a right-handed orthogonal frame.
        assert_eq!(dot(&f.axes[0].top(), &f.axes[1].top()), int(0));
        assert_eq!(f.axes[0].top().cross(&f.axes[1].top()), f.axes[2].top());
    }

    #[test]
    fn skew_tangent_is_refused() {
        let v0 = Screw::zero();
        let err = ContactFrame::new(3, &contact(v(0, 0, 0), v(1, 0, 0), Some(v(1, 1, 0))), &v0);
        assert_eq!(err, Err(TangentNotPerpendicular { index: 3, dot: 1.0 }));
    }

    #[test]
    fn non_unit_normal_norms() {
        let v0 = Screw::new(v(0, 0, 1), v(1, 1, 0));
        let f = ContactFrame::new(0, &contact(v(1, 1, 0), v(4, 1, 0), None), &v0).unwrap();
        assert_eq!(f.norm2[0], int(17));
        assert_eq!(f.norm2[2], f.norm2[0].clone() * &f.norm2[1]);
    }

    #[test]
    fn the_derivative_of_a_dual_surd_is_a_surd_of_the_same_radicand() {
        use crate::scalar::dual::Dual;
        let d = |v: i64, t: i64| Dual::new(int::<Exact>(v), int::<Exact>(t));
        // (3 + ε)·√(4 + 4ε) = (3 + ε)(2 + ε) = 6 + 5ε: the derivative 5/2·√4.
        let s = Surd::times_norm(&d(3, 1), &d(4, 4));
        let ds = s.derivative().unwrap();
        assert_eq!(ds.exact_text().as_deref(), Some("5"));
        assert_eq!(ds.radicand, d(4, 0));
        // (1 + 0ε)·√(2 + ε): d = 1/(2√2) = √2/4, exactly.
        let s = Surd::times_norm(&d(1, 0), &d(2, 1));
        assert_eq!(
            s.derivative().unwrap().exact_text().as_deref(),
            Some("1/4*sqrt(2)")
        );
        assert_eq!(
            Surd::times_norm(&int::<Exact>(1), &int(2)).derivative(),
            None
        );
    }
}
