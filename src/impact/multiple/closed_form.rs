//! Where the LZB law has a closed form: every contact alike (derivations/lzb.md, "Exact
//! limits").
//!
//! **Claim.** Let every contact have the same law (K, η, e), every contact approach at the same
//! speed (v_i⁰ = v > 0), and every row of G (the inertance matrix of the unit normals) have the
//! same sum g = Σ_j g_ij > 0. Then the LZB impact ends with
//!
//! ```text
//! P_i = (1 + e) v / g,   v_i = −e v,   W_c,i = v² / (2g),   W_r,i = e² W_c,i   (every i)
//! ```
//!
//! whatever K and η — the one-contact law of Newton (and Stronge), applied to a contact of
//! inertance g.
//!
//! **Proof.** The equations in τ (module docs of [`super::lzb`]) are dP_i/dτ = F(u_i),
//! du_i/dτ = c v_i (÷ e² in expansion), v = v⁰ − G P, the same F and c at every contact. On the
//! set where every P_i is one p and every u_i one u, v_i = v − g p is the same at every contact,
//! so every right-hand side is the same: the set is invariant, and the solution from P = 0,
//! u = 0 (on it) stays on it — the equations in (P, u) have a unique solution from there (u
//! grows linearly from 0, and u ↦ u^η is Lipschitz away from 0). On it the impact is that of one
//! contact of inertance g approaching at v: compression ends at v − g p = 0 (p = v/g, energy
//! stored ∫ (v − g p) dp = v²/(2g)), expansion releases e² of it, ∫ (g p − v) dp = e² v²/(2g),
//! which ends at g p − v = e v. With n = 1 the claim is the one-contact law; a body landing flat
//! on its corners (a bar on two supports, a box on four, centred) satisfies it by symmetry.
//!
//! The same impulses solve the simultaneous Newton law with k = e (G P = (1 + e) v⁰ holds, as
//! G 1 = g 1), so there the multiple-impact law and the paper's agree exactly.
//!
//! Generic over the scalar: in rationals the outcome is exact. The inputs may be the hatted
//! ones (normals not unit) when every normal has the same length s: Ĝ = s² G, v̂ = s v, so the
//! conditions hold for both alike and P̂ = P/s.

use crate::scalar::{Scalar, int};

use super::law::ContactLaw;

/// The closed-form outcome of an LZB impact whose contacts are all alike.
#[derive(Clone, Debug, PartialEq)]
pub struct Alike<T: Scalar> {
    /// g: every row sum of G.
    pub inertance: T,
    /// v: every contact's approach speed before impact.
    pub speed: T,
    /// P_i = (1 + e) v / g, every i.
    pub impulses: Vec<T>,
    /// v_i = −e v after impact, every i.
    pub after: Vec<T>,
    /// W_c,i = v²/(2g): the energy each contact stores.
    pub work_compression: T,
    /// W_r,i = e² W_c,i: the energy each contact gives back.
    pub work_expansion: T,
}

/// The closed form when every contact is alike (module docs), else `None`: `g` is G (n × n,
/// row-major), `v0` the normal velocities before impact (positive approaching), `laws` each
/// contact's law and `e` their common coefficient of restitution in the scalar.
///
/// `None` when the laws differ, a speed differs or is not positive, or the row sums differ or
/// are not positive.
pub fn alike<T: Scalar>(g: &[T], v0: &[T], laws: &[ContactLaw], e: &T) -> Option<Alike<T>> {
    let n = v0.len();
    if n == 0 || g.len() != n * n || laws.len() != n || laws.iter().any(|l| *l != laws[0]) {
        return None;
    }
    let speed = v0[0].clone();
    if speed.signum_i8() <= 0 || v0.iter().any(|v| *v != speed) {
        return None;
    }
    let row = |i: usize| g[i * n..(i + 1) * n].iter().fold(T::zero(), |s, x| s + x);
    let inertance = row(0);
    if inertance.signum_i8() <= 0 || (1..n).any(|i| row(i) != inertance) {
        return None;
    }
    let one = T::one();
    let p = (one + e.clone()) * speed.clone() / inertance.clone();
    let after = -(e.clone() * speed.clone());
    let work_compression = speed.clone() * speed.clone() / (int::<T>(2) * inertance.clone());
    let work_expansion = e.clone() * e.clone() * work_compression.clone();
    Some(Alike {
        inertance,
        speed,
        impulses: vec![p; n],
        after: vec![after; n],
        work_compression,
        work_expansion,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Exact;
    use num_traits::Zero;

    fn q(n: i64, d: i64) -> Exact {
        int::<Exact>(n) / int::<Exact>(d)
    }

    #[test]
    fn four_corners_alike_take_newtons_impulses_exactly() {
        // G of a box landing flat: each row a permutation of (a, b, c, d).
        let (a, b, c, d) = (q(7, 3), q(1, 6), q(-1, 2), q(1, 6));
        let g = vec![
            a.clone(),
            b.clone(),
            c.clone(),
            d.clone(), //
            b.clone(),
            a.clone(),
            d.clone(),
            c.clone(), //
            c.clone(),
            d.clone(),
            a.clone(),
            b.clone(), //
            d.clone(),
            c.clone(),
            b.clone(),
            a.clone(),
        ];
        let v0 = vec![q(3, 2); 4];
        let laws = vec![ContactLaw::default(); 4];
        let out = alike(&g, &v0, &laws, &q(1, 2)).expect("alike");
        // g = 7/3 + 1/6 − 1/2 + 1/6 = 13/6; P = (3/2)(3/2)/(13/6) = 27/26.
        assert_eq!(out.inertance, q(13, 6));
        assert_eq!(out.impulses, vec![q(27, 26); 4]);
        assert_eq!(out.after, vec![q(-3, 4); 4]);
        // v⁰ − G P = −e v⁰ at every contact: the simultaneous Newton law's equations.
        for i in 0..4 {
            let gp = (0..4).fold(Exact::zero(), |s, j| s + g[i * 4 + j].clone() * q(27, 26));
            assert_eq!(v0[i].clone() - gp, q(-3, 4));
        }
        assert_eq!(out.work_compression, q(27, 52));
        assert_eq!(out.work_expansion, q(27, 208));
    }

    #[test]
    fn contacts_not_alike_have_no_closed_form() {
        let g = vec![q(2, 1), q(1, 1), q(1, 1), q(2, 1)];
        let laws = vec![ContactLaw::default(); 2];
        let e = q(1, 1);
        assert!(alike(&g, &[q(1, 1), q(1, 1)], &laws, &e).is_some());
        assert!(alike(&g, &[q(1, 1), q(1, 2)], &laws, &e).is_none());
        assert!(alike(&g, &[q(0, 1), q(0, 1)], &laws, &e).is_none());
        let uneven = vec![q(2, 1), q(1, 1), q(1, 1), q(3, 1)];
        assert!(alike(&uneven, &[q(1, 1), q(1, 1)], &laws, &e).is_none());
        let other = [
            ContactLaw::default(),
            ContactLaw {
                stiffness: 2.0,
                ..ContactLaw::default()
            },
        ];
        assert!(alike(&g, &[q(1, 1), q(1, 1)], &other, &e).is_none());
    }
}
