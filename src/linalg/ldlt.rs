//! Field-only linear algebra for the inertance matrix G.
//!
//! G = \[g_ij\] is a Gram matrix, g_ij = {E_i}ᵀ η W {E_j} with η W symmetric positive definite
//! (eq. 57–58), so G is symmetric positive **semi**definite. We factor it as
//!
//! ```text
//! Π G Πᵀ = L D Lᵀ,   L unit lower triangular,  D = diag(d_1 … d_r, 0 … 0)
//! ```
//!
//! with *diagonal* pivoting: at each step the largest remaining diagonal entry becomes the pivot.
//! No square root is taken (so it runs in exact rationals), the determinant is Δ = Π d_k, the
//! rank is the number of nonzero pivots, and for a semidefinite matrix diagonal pivoting is
//! backward stable in floating point (Higham, *Accuracy and Stability of Numerical Algorithms*,
//! §10.3). Since |g_ij|² ≤ g_ii g_jj, a zero largest diagonal means the whole remaining
//! block is zero: the rank decision is one comparison.
//!
//! The routines work in caller-owned buffers so that the f64 solve performs no allocation.

use crate::scalar::Scalar;

/// The result of [`factor_psd`]: the rank found and the magnitude the zero test was relative to.
#[derive(Clone, Debug, PartialEq)]
pub struct Factorization<T> {
    /// Number of nonzero pivots.
    pub rank: usize,
    /// Largest diagonal entry of the input: the reference of every zero test.
    pub scale: T,
}

/// The matrix was not positive semidefinite (a negative pivot, or a zero pivot beside a
/// nonzero entry) — impossible for an inertance matrix, so it signals a bug or corrupt input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("matrix is not positive semidefinite (pivot {index})")]
pub struct NotSemidefinite {
    /// The elimination step at which it showed.
    pub index: usize,
}

/// Factor the symmetric positive semidefinite `n × n` matrix `a` (row-major, both triangles
/// stored) in place into Π A Πᵀ = L D Lᵀ.
///
/// On return the strict lower triangle of `a` holds L, its diagonal holds D (zeros past the
/// rank), and `perm[k]` is the original index of the k-th pivot.
pub fn factor_psd<T: Scalar>(
    a: &mut [T],
    n: usize,
    perm: &mut [usize],
) -> Result<Factorization<T>, NotSemidefinite> {
    debug_assert_eq!(a.len(), n * n);
    for (k, p) in perm.iter_mut().enumerate().take(n) {
        *p = k;
    }
    let mut scale = T::zero();
    for i in 0..n {
        if a[i * n + i].abs_gt(&scale) {
            scale = a[i * n + i].clone();
        }
    }
    if n == 2 {
        return factor_2x2(a, perm, scale);
    }
    for k in 0..n {
        // Diagonal pivoting: the largest remaining diagonal entry.
        let mut p = k;
        for i in k + 1..n {
            if a[i * n + i].abs_gt(&a[p * n + p]) {
                p = i;
            }
        }
        if a[p * n + p].is_negligible(&scale, n) {
            // Semidefinite: the remaining block must be (negligibly) zero.
            for i in k..n {
                for j in k..=i {
                    if !a[i * n + j].is_negligible(&scale, n) {
                        return Err(NotSemidefinite { index: k });
                    }
                }
            }
            for i in k..n {
                for j in k..n {
                    a[i * n + j] = T::zero();
                }
            }
            return Ok(Factorization { rank: k, scale });
        }
        if a[p * n + p].signum_i8() < 0 {
            return Err(NotSemidefinite { index: k });
        }
        if p != k {
            swap_symmetric(a, n, k, p);
            perm.swap(k, p);
        }
        let d = a[k * n + k].clone();
        for i in k + 1..n {
            // Column k below the pivot becomes L; update the trailing block with the
            // symmetric rank-one correction a_ij -= a_ik a_jk / d.
            let aik = a[i * n + k].clone();
            if aik.is_zero() {
                continue;
            }
            let lik = aik.clone() / &d;
            // Row k (upper part) still holds the unscaled a_kj = a_jk.
            for j in k + 1..=i {
                let upd = lik.clone() * &a[k * n + j];
                a[i * n + j] -= upd;
            }
            a[i * n + k] = lik;
        }
        // Mirror the trailing block's lower triangle to the upper one (pivot search reads
        // only diagonals, but the zero test above reads the lower triangle; keep them equal).
        for i in k + 1..n {
            for j in k + 1..i {
                a[j * n + i] = a[i * n + j].clone();
            }
        }
    }
    Ok(Factorization { rank: n, scale })
}

/// The same factorization written out for N = 2, the paper's case (its general loop costs
/// more in bookkeeping than in arithmetic there): pivot on the larger diagonal g_pp, then
/// l = g_qp / g_pp and d_2 = g_qq − l·g_qp. Same decisions as the loop; tested against it.
fn factor_2x2<T: Scalar>(
    a: &mut [T],
    perm: &mut [usize],
    scale: T,
) -> Result<Factorization<T>, NotSemidefinite> {
    let (p, q) = if a[3].abs_gt(&a[0]) { (1, 0) } else { (0, 1) };
    perm[0] = p;
    perm[1] = q;
    let (gpp, gqq, gqp) = (a[3 * p].clone(), a[3 * q].clone(), a[2 * q + p].clone());
    if gpp.is_negligible(&scale, 2) {
        // The larger diagonal is zero: a semidefinite matrix is then zero.
        if !gqp.is_negligible(&scale, 2) || !gqq.is_negligible(&scale, 2) {
            return Err(NotSemidefinite { index: 0 });
        }
        a.iter_mut().for_each(|x| *x = T::zero());
        return Ok(Factorization { rank: 0, scale });
    }
    if gpp.signum_i8() < 0 {
        return Err(NotSemidefinite { index: 0 });
    }
    let l = gqp.clone() / &gpp;
    let d2 = gqq - l.clone() * &gqp;
    let rank = if d2.is_negligible(&scale, 2) {
        1
    } else if d2.signum_i8() < 0 {
        return Err(NotSemidefinite { index: 1 });
    } else {
        2
    };
    a[0] = gpp;
    a[1] = gqp;
    a[2] = l;
    a[3] = if rank == 2 { d2 } else { T::zero() };
    Ok(Factorization { rank, scale })
}

/// Swap rows and columns `k` and `p` of the symmetric matrix `a` (the part not yet factored,
/// plus the rows of L computed so far).
fn swap_symmetric<T: Scalar>(a: &mut [T], n: usize, k: usize, p: usize) {
    for j in 0..n {
        a.swap(k * n + j, p * n + j);
    }
    for i in 0..n {
        a.swap(i * n + k, i * n + p);
    }
}

/// Solve G x = b with a full-rank factorization from [`factor_psd`]. `b` is overwritten by x;
/// `work` is scratch of length `n`.
pub fn solve_factored<T: Scalar>(a: &[T], n: usize, perm: &[usize], b: &mut [T], work: &mut [T]) {
    if n == 2 {
        // L D Lᵀ y = Π b written out: y₁ = b_p/d₁ − l·y₂, y₂ = (b_q − l·b_p)/d₂.
        let (p, q) = (perm[0], perm[1]);
        let (d1, l, d2) = (&a[0], &a[2], &a[3]);
        let y2 = (b[q].clone() - l.clone() * &b[p]) / d2;
        let y1 = b[p].clone() / d1 - l.clone() * &y2;
        b[p] = y1;
        b[q] = y2;
        return;
    }
    // Π G Πᵀ (Π x) = Π b  ⇒  L D Lᵀ y = Π b,  x = Πᵀ y.
    for k in 0..n {
        work[k] = b[perm[k]].clone();
    }
    for i in 0..n {
        for j in 0..i {
            let t = a[i * n + j].clone() * &work[j];
            work[i] -= t;
        }
    }
    for (i, w) in work.iter_mut().enumerate().take(n) {
        *w /= &a[i * n + i];
    }
    for i in (0..n).rev() {
        for j in i + 1..n {
            let t = a[j * n + i].clone() * &work[j];
            work[i] -= t;
        }
    }
    for k in 0..n {
        b[perm[k]] = work[k].clone();
    }
}

/// A solution of G x = b from a factorization of rank r ≤ n ([`factor_psd`]): with
/// Π G Πᵀ = [L11 0; L21 I] diag(D1, 0) [L11ᵀ L21ᵀ; 0 I], the last n − r pivoted entries of x
/// zero and the first r from L11 D1 L11ᵀ x1 = (Π b)_1 — the solution whenever b lies in the
/// range of G (a caller that does not know it checks the residual). `x` gets n entries;
/// `work` is scratch of length at least r.
pub fn solve_leading<T: Scalar>(
    a: &[T],
    n: usize,
    perm: &[usize],
    rank: usize,
    b: &[T],
    x: &mut Vec<T>,
    work: &mut [T],
) {
    let r = rank;
    for k in 0..r {
        work[k] = b[perm[k]].clone();
    }
    for i in 0..r {
        for j in 0..i {
            let t = a[i * n + j].clone() * &work[j];
            work[i] -= t;
        }
    }
    for (i, w) in work.iter_mut().enumerate().take(r) {
        *w /= &a[i * n + i];
    }
    for i in (0..r).rev() {
        for j in i + 1..r {
            let t = a[j * n + i].clone() * &work[j];
            work[i] -= t;
        }
    }
    x.clear();
    x.resize(n, T::zero());
    for k in 0..r {
        x[perm[k]] = work[k].clone();
    }
}

/// Δ = det G = Π d_k from a factorization (zero when rank-deficient).
pub fn determinant<T: Scalar>(a: &[T], n: usize) -> T {
    let mut det = T::one();
    for k in 0..n {
        det *= &a[k * n + k];
    }
    det
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::null_space;
    use crate::scalar::Exact;
    use num_traits::Zero;

    fn q(n: i64) -> Exact {
        Exact::from_integer(n.into())
    }

    fn gram(rows: &[[i64; 3]]) -> Vec<Exact> {
        let n = rows.len();
        let mut g = vec![Exact::zero(); n * n];
        for i in 0..n {
            for j in 0..n {
                g[i * n + j] = q((0..3).map(|c| rows[i][c] * rows[j][c]).sum());
            }
        }
        g
    }

    #[test]
    fn solves_and_reconstructs_exactly() {
        let g = gram(&[[1, 2, 0], [0, 1, 3], [2, 0, 1]]);
        let mut f = g.clone();
        let mut perm = [0; 3];
        let fac = factor_psd(&mut f, 3, &mut perm).unwrap();
        assert_eq!(fac.rank, 3);
        let x_true = [q(1), q(-2), q(5)];
        let mut b: Vec<Exact> = (0..3)
            .map(|i| (0..3).map(|j| g[i * 3 + j].clone() * &x_true[j]).sum())
            .collect();
        let mut work = vec![Exact::zero(); 3];
        solve_factored(&f, 3, &perm, &mut b, &mut work);
        assert_eq!(b, x_true.to_vec());
        // det of a Gram matrix = (det of the rows)² = (1·1·1 + 2·3·2 − 0)^2 = 13².
        assert_eq!(determinant(&f, 3), q(169));
    }

    #[test]
    fn rank_of_a_singular_gram_matrix_is_exact() {
        // Third row = first + second: rank 2, det 0.
        let mut f = gram(&[[1, 2, 0], [0, 1, 3], [1, 3, 3]]);
        let mut perm = [0; 3];
        let fac = factor_psd(&mut f, 3, &mut perm).unwrap();
        assert_eq!(fac.rank, 2);
        assert!(determinant(&f, 3).is_zero());
    }

    #[test]
    fn null_space_is_exact_and_complete() {
        // x + 2y − z = 0 and y + z = 0: rank 2, null space spanned by (3, −1, 1).
        let a = vec![q(1), q(2), q(-1), q(0), q(1), q(1)];
        let (rank, basis) = null_space(&a, 2, 3);
        assert_eq!(rank, 2);
        assert_eq!(basis, vec![vec![q(3), q(-1), q(1)]]);
        let (rank, basis) = null_space(&[q(0), q(0)], 1, 2);
        assert_eq!((rank, basis.len()), (0, 2));
    }

    /// The written-out 2×2 factorization reconstructs Π G Πᵀ = L D Lᵀ and solves exactly,
    /// also when singular.
    #[test]
    fn two_by_two_factorization_is_exact() {
        for rows in [
            [[1, 2, 0], [0, 1, 3]],
            [[3, 0, 1], [1, 1, 1]],
            [[0, 0, 1], [5, 1, 0]],
            [[1, 2, 3], [2, 4, 6]],
        ] {
            let g = gram(&rows);
            let mut f = g.clone();
            let mut perm = [0; 2];
            let fac = factor_psd(&mut f, 2, &mut perm).unwrap();
            let (d1, l, d2) = (f[0].clone(), f[2].clone(), f[3].clone());
            let pg = |i: usize, j: usize| g[perm[i] * 2 + perm[j]].clone();
            assert_eq!(pg(0, 0), d1.clone());
            assert_eq!(pg(1, 0), l.clone() * &d1);
            assert_eq!(pg(1, 1), l.clone() * &l * &d1 + &d2);
            assert_eq!(fac.rank, if d2.is_zero() { 1 } else { 2 });
            assert_eq!(
                determinant(&f, 2),
                g[0].clone() * &g[3] - g[1].clone() * &g[2]
            );
            if fac.rank == 2 {
                let x = [q(2), q(-7)];
                let mut b = vec![
                    g[0].clone() * &x[0] + g[1].clone() * &x[1],
                    g[2].clone() * &x[0] + g[3].clone() * &x[1],
                ];
                solve_factored(&f, 2, &perm, &mut b, &mut [q(0), q(0)]);
                assert_eq!(b, x.to_vec());
            }
        }
        let mut zero = vec![q(0); 4];
        assert_eq!(factor_psd(&mut zero, 2, &mut [0; 2]).unwrap().rank, 0);
    }

    #[test]
    fn indefinite_input_is_refused() {
        let mut f = vec![q(1), q(2), q(2), q(1)];
        let mut perm = [0; 2];
        assert_eq!(
            factor_psd(&mut f, 2, &mut perm),
            Err(NotSemidefinite { index: 1 })
        );
    }

    #[test]
    fn f64_matches_exact_on_a_well_conditioned_matrix() {
        let g = gram(&[[3, 1, 0], [1, 4, 1], [0, 1, 5]]);
        let gf: Vec<f64> = g.iter().map(|x| x.to_f64()).collect();
        let (mut fe, mut ff) = (g.clone(), gf.clone());
        let (mut pe, mut pf) = ([0; 3], [0; 3]);
        factor_psd(&mut fe, 3, &mut pe).unwrap();
        factor_psd(&mut ff, 3, &mut pf).unwrap();
        let mut be = vec![q(1), q(2), q(3)];
        let mut bf = vec![1.0, 2.0, 3.0];
        solve_factored(&fe, 3, &pe, &mut be, &mut vec![Exact::zero(); 3]);
        solve_factored(&ff, 3, &pf, &mut bf, &mut [0.0; 3]);
        for k in 0..3 {
            let e = be[k].to_f64();
            assert!((bf[k] - e).abs() <= 1e-14 * e.abs().max(1.0));
        }
    }
}
