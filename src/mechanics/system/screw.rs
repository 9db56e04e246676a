//! The screws of a system: one screw per body, each about that body's own centre of mass.
//!
//! A system's twist is the stack {V} = [V_1; …; V_B] of its bodies' twists V_b = [ω_b; v_Cb]
//! (world axes, v_Cb the velocity of C_b). A contact axis, a constraint screw and a wrench are
//! stacked the same way: the screw of an axis through A with direction u acts on body b as
//! [u; (A − C_b) × u] ([`Screw::axis`] from C_b), and the mixed product pairs the stacks block
//! by block, {E}ᵀ η {V} = Σ_b {E_b}ᵀ η {V_b} (eq. 6) — the power of a wrench on every body, or
//! the velocity along an axis of a point counted on each body it belongs to.
//!
//! An axis screw written about the world origin O, [u; m] with m = A × u, is the same axis
//! about C_b as [u; m − C_b × u] ([`about`]): positions in the stacks are from each body's C.

use crate::mechanics::screw::{Screw, Screws, Vec3};
use crate::scalar::Scalar;

/// A system's screw: one [`Screw`] per body (module docs). The default is the empty stack, of
/// no body, the placeholder of an outcome not yet solved.
#[derive(Debug, PartialEq)]
pub struct SystemScrew<T: Scalar>(pub Vec<Screw<T>>);

/// `clone_from` reuses the stack's storage (the derived one would allocate a new one): how the
/// solves' buffers of a system are written over without allocating.
impl<T: Scalar> Clone for SystemScrew<T> {
    fn clone(&self) -> Self {
        SystemScrew(self.0.clone())
    }

    fn clone_from(&mut self, source: &Self) {
        // Component by component: a whole screw's clone is a call to memcpy per body.
        self.0.truncate(source.0.len());
        let kept = self.0.len();
        for (to, from) in self.0.iter_mut().zip(&source.0) {
            for k in 0..6 {
                to.0[k].clone_from(&from.0[k]);
            }
        }
        self.0.extend(source.0[kept..].iter().cloned());
    }
}

impl<T: Scalar> Default for SystemScrew<T> {
    fn default() -> Self {
        SystemScrew(Vec::new())
    }
}

impl<T: Scalar> SystemScrew<T> {
    /// The zero screw of `bodies` bodies written over `self`, its storage reused.
    pub fn set_zeros(&mut self, bodies: usize) {
        self.0.truncate(bodies);
        for s in &mut self.0 {
            for x in s.0.iter_mut() {
                x.set_zero();
            }
        }
        let kept = self.0.len();
        self.0.extend((kept..bodies).map(|_| Screw::zero()));
    }

    /// The zero screw of `bodies` bodies.
    pub fn zeros(bodies: usize) -> Self {
        SystemScrew(vec![Screw::zero(); bodies])
    }

    /// Body `b`'s screw.
    pub fn body(&self, b: usize) -> &Screw<T> {
        &self.0[b]
    }

    /// Number of bodies.
    pub fn bodies(&self) -> usize {
        self.0.len()
    }
}

impl<T: Scalar> Screws<T> for SystemScrew<T> {
    fn reciprocal(&self, other: &Self) -> T {
        let mut s = T::zero();
        for (a, b) in self.0.iter().zip(&other.0) {
            s += a.reciprocal(b);
        }
        s
    }

    fn add_scaled(&mut self, c: &T, other: &Self) {
        for (a, b) in self.0.iter_mut().zip(&other.0) {
            a.add_scaled(c, b);
        }
    }

    fn minus(&self, other: &Self) -> Self {
        SystemScrew(
            self.0
                .iter()
                .zip(&other.0)
                .map(|(a, b)| Screws::minus(a, b))
                .collect(),
        )
    }

    fn zero_like(&self) -> Self {
        SystemScrew::zeros(self.0.len())
    }

    fn components(&self) -> Vec<T> {
        self.0
            .iter()
            .flat_map(|s| s.as_slice().iter().cloned())
            .collect()
    }

    fn max_abs_f64(&self) -> f64 {
        self.0.iter().map(Screws::max_abs_f64).fold(0.0, f64::max)
    }

    fn from_single(s: Screw<T>) -> Self {
        SystemScrew(vec![s])
    }

    fn single(&self) -> Option<&Screw<T>> {
        match self.0.as_slice() {
            [s] => Some(s),
            _ => None,
        }
    }
}

/// The axis (or wrench) screw `screw`, written about the world origin, about the point `c`:
/// [u; m] ↦ [u; m − c × u].
pub fn about<T: Scalar>(screw: &Screw<T>, c: &Vec3<T>) -> Screw<T> {
    let u = screw.top();
    Screw::new(u.clone(), screw.bottom() - c.cross(&u))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int};

    fn v(x: i64, y: i64, z: i64) -> Vec3<Exact> {
        Vec3::new(int(x), int(y), int(z))
    }

    #[test]
    fn an_axis_about_the_origin_pairs_with_a_twist_as_about_the_centre() {
        // The axis through A = (1, 2, 3) along u = (0, 0, 1); a body at C = (4, −1, 2).
        let (a, u, c) = (v(1, 2, 3), v(0, 0, 1), v(4, -1, 2));
        let about_origin = Screw::axis(&a, &u);
        let about_c = Screw::axis(&(a.clone() - c.clone()), &u);
        assert_eq!(about(&about_origin, &c), about_c);
        // {E}ᵀ η {V} is u · v(A) for the twist [ω; v_C] of the body.
        let twist = Screw::new(v(1, -2, 5), v(3, 0, -1));
        let at_a = twist.bottom() + twist.top().cross(&(a - c));
        assert_eq!(about_c.reciprocal(&twist), u.dot(&at_a));
    }

    #[test]
    fn stacks_pair_block_by_block() {
        let s = SystemScrew(vec![
            Screw::new(v(1, 0, 0), v(0, 1, 0)),
            Screw::new(v(0, 0, 2), v(1, 1, 1)),
        ]);
        let t = SystemScrew(vec![
            Screw::new(v(2, 3, 4), v(5, 6, 7)),
            Screw::new(v(1, 1, 1), v(0, 0, 3)),
        ]);
        let expected = s.0[0].reciprocal(&t.0[0]) + s.0[1].reciprocal(&t.0[1]);
        assert_eq!(Screws::reciprocal(&s, &t), expected);
        let mut u = s.clone();
        u.add_scaled(&int(2), &t);
        assert_eq!(
            Screws::minus(&u, &s),
            SystemScrew(vec![
                Screw(t.0[0].0.clone() * int::<Exact>(2)),
                Screw(t.0[1].0.clone() * int::<Exact>(2)),
            ])
        );
    }
}
