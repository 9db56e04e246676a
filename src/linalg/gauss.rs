//! Gauss–Jordan elimination of a general (non-symmetric, possibly singular) system, over the
//! field: the reduced row echelon form with partial pivoting, the solution set of A x = b as a
//! particular solution plus a null-space basis, and the null space alone.
//!
//! Exact types decide every pivot exactly; floats treat |pivot| ≤ cols·ε·max|a_ij| as zero.
//! Field-only, so rational input gives rational output.

use crate::scalar::Scalar;

/// The reduced row echelon form of a `rows × cols` matrix (row-major), computed in place, with
/// the same row operations applied to the `extra` columns of `rhs` (`rows × extra`, row-major).
/// Returns the pivot columns, in order.
pub fn rref<T: Scalar>(
    m: &mut [T],
    rows: usize,
    cols: usize,
    rhs: &mut [T],
    extra: usize,
) -> Vec<usize> {
    let mut pivots = Vec::new();
    rref_in(m, rows, cols, rhs, extra, &mut pivots);
    pivots
}

/// [`rref`], the pivot columns written into `pivots` (cleared first): no allocation once
/// `pivots` has grown.
pub fn rref_in<T: Scalar>(
    m: &mut [T],
    rows: usize,
    cols: usize,
    rhs: &mut [T],
    extra: usize,
    pivots: &mut Vec<usize>,
) {
    let scale = largest_entry(m);
    rref_scaled(m, rows, cols, rhs, extra, pivots, &scale);
}

/// The entry of largest magnitude (the first of them; zero for an empty matrix), signed.
fn largest_entry<T: Scalar>(m: &[T]) -> T {
    let mut scale = T::zero();
    for x in m {
        if x.abs_gt(&scale) {
            scale = x.clone();
        }
    }
    scale
}

/// [`rref_in`] with the entry of largest magnitude of `m` given ([`largest_entry`]), the
/// scale of its negligible pivots.
fn rref_scaled<T: Scalar>(
    m: &mut [T],
    rows: usize,
    cols: usize,
    rhs: &mut [T],
    extra: usize,
    pivots: &mut Vec<usize>,
    scale: &T,
) {
    pivots.clear();
    pivots.reserve(rows.min(cols));
    let mut r = 0;
    for c in 0..cols {
        if r == rows {
            break;
        }
        let mut p = r;
        for i in r + 1..rows {
            if m[i * cols + c].abs_gt(&m[p * cols + c]) {
                p = i;
            }
        }
        if m[p * cols + c].is_negligible(scale, cols) {
            continue;
        }
        // The row operations act column by column, and a pivot column, once eliminated, is
        // read again by nobody: they run on the live columns only — the free ones left of c
        // (c − r of them) and those right of it — and column c is set to its unit column.
        // Every live entry sees the same operations in the same order as a sweep over all
        // the columns would give it.
        let live = |j: usize| j > c || (j < c && !pivots.contains(&j));
        let first = if c == r { c + 1 } else { 0 };
        if p != r {
            m.swap(r * cols + c, p * cols + c);
            for j in (first..cols).filter(|&j| live(j)) {
                m.swap(r * cols + j, p * cols + j);
            }
            for j in 0..extra {
                rhs.swap(r * extra + j, p * extra + j);
            }
        }
        let piv = m[r * cols + c].clone();
        m[r * cols + c] = T::one();
        for j in (first..cols).filter(|&j| live(j)) {
            m[r * cols + j] /= &piv;
        }
        for j in 0..extra {
            rhs[r * extra + j] /= &piv;
        }
        for i in 0..rows {
            if i != r && !m[i * cols + c].is_zero() {
                let f = std::mem::replace(&mut m[i * cols + c], T::zero());
                for j in (first..cols).filter(|&j| live(j)) {
                    let t = f.clone() * &m[r * cols + j];
                    m[i * cols + j] -= t;
                }
                for j in 0..extra {
                    let t = f.clone() * &rhs[r * extra + j];
                    rhs[i * extra + j] -= t;
                }
            }
        }
        pivots.push(c);
        r += 1;
    }
}

/// The null-space basis of a matrix in reduced row echelon form with these pivot columns: one
/// vector per free column, with a 1 in that column.
pub fn basis<T: Scalar>(m: &[T], cols: usize, pivots: &[usize]) -> Vec<Vec<T>> {
    let mut basis = Vec::new();
    for free in (0..cols).filter(|c| !pivots.contains(c)) {
        let mut x = vec![T::zero(); cols];
        x[free] = T::one();
        for (k, &pc) in pivots.iter().enumerate() {
            x[pc] = -m[k * cols + free].clone();
        }
        basis.push(x);
    }
    basis
}

/// A basis of the null space {x : A x = 0} of the `rows × cols` matrix `a` (row-major), by
/// reduced row echelon form with partial pivoting. Returns the rank and the basis (one
/// vector per free column, with a 1 in that column).
pub fn null_space<T: Scalar>(a: &[T], rows: usize, cols: usize) -> (usize, Vec<Vec<T>>) {
    let mut m: Vec<T> = a.to_vec();
    let pivots = rref(&mut m, rows, cols, &mut [], 0);
    (pivots.len(), basis(&m, cols, &pivots))
}

/// The solution set of A x = b.
#[derive(Clone, Debug, PartialEq)]
pub struct Solutions<T: Scalar> {
    /// A particular solution: the free variables set to zero.
    pub particular: Vec<T>,
    /// A basis of the null space of A (empty when A has full column rank: x is unique).
    pub null: Vec<Vec<T>>,
}

/// |x|.
fn magnitude<T: Scalar>(x: T) -> T {
    if x.signum_i8() < 0 { -x } else { x }
}

/// Solve the `rows × cols` system A x = b (row-major). `None` when it is inconsistent (some
/// zero row of the echelon form meets a nonzero right-hand side; in floats, one above
/// cols·ε (max|b| + max|a| Σ|x_j|), the rounding of elimination).
pub fn solve_general<T: Scalar>(
    a: &[T],
    rows: usize,
    cols: usize,
    b: &[T],
) -> Option<Solutions<T>> {
    let mut m: Vec<T> = a.to_vec();
    let mut rhs: Vec<T> = b.to_vec();
    let (mut pivots, mut particular) = (Vec::new(), Vec::new());
    if !solve_general_in(&mut m, rows, cols, &mut rhs, &mut pivots, &mut particular) {
        return None;
    }
    Some(Solutions {
        particular,
        null: basis(&m, cols, &pivots),
    })
}

/// [`solve_general`] in place, for callers that solve many small systems on buffers they keep:
/// `a` and `b` are overwritten by the reduced row echelon form, the pivot columns are left in
/// `pivots` and the particular solution in `particular` (no allocation once these have grown).
/// Returns `false` when the system is inconsistent. The null space is then
/// [`basis`]`(a, cols, pivots)`, empty when `pivots.len() == cols`. The same operations in the
/// same order as [`solve_general`]: the same result, bit for bit.
pub fn solve_general_in<T: Scalar>(
    a: &mut [T],
    rows: usize,
    cols: usize,
    b: &mut [T],
    pivots: &mut Vec<usize>,
    particular: &mut Vec<T>,
) -> bool {
    let floats = T::epsilon_f64() > 0.0;
    // the largest entry of A scales both the elimination's negligible pivots and the residual
    let largest_a = largest_entry(a);
    let (scale_b, scale_a) = match floats {
        true => (magnitude(largest_entry(b)), magnitude(largest_a.clone())),
        false => (T::zero(), T::zero()),
    };
    rref_scaled(a, rows, cols, b, 1, pivots, &largest_a);
    // The residual of a consistent system is rounding of the size of the terms it cancels:
    // the backward error of elimination bounds it by a multiple of ε (max|b| + max|a| Σ|x_j|)
    // (Higham, Accuracy and Stability of Numerical Algorithms, §9.3). Exact types: zero.
    let scale = match floats {
        true => {
            let mut sum = T::zero();
            for x in &b[..pivots.len()] {
                sum += magnitude(x.clone());
            }
            scale_b + scale_a * sum
        }
        false => T::zero(),
    };
    if b[pivots.len()..]
        .iter()
        .any(|r| !r.is_negligible(&scale, cols.max(1)))
    {
        return false;
    }
    fill_particular(cols, b, pivots, particular);
    true
}

/// [`solve_general_in`] for a system consistent by construction (a principal submatrix of a
/// positive semidefinite matrix against a right-hand side in its range): the rows the
/// elimination leaves below its pivots hold rounding, not a contradiction, and are not
/// tested — in floats a nearly singular system leaves them above the backward-error bound
/// that [`solve_general_in`] tests, by its conditioning. The particular solution is the same.
///
/// **Its rank, in floats.** A pivot below √ε_T of the matrix's largest entry is taken as zero
/// (exact types: exactly zero), not below n ε_T: such a matrix is a singular one — two points
/// of one line whose tangential impulses along it only their sum determines — whose geometry
/// carries rounding (a body posed by an integration, its contacts projected, holds its
/// corners collinear to 10⁻¹⁰ or so, not to ε). Below √ε the unique solution's component
/// along the nearly null direction is the right-hand side's rounding divided by the pivot —
/// a member of the family chosen by noise, which jumps from one evaluation to the next; taken
/// as a family, the caller chooses its member (the rates of [`crate::impact::friction`]:
/// in proportion to the cones). By Weyl's inequality a perturbation of relative size δ moves
/// the smallest singular value by at most δ, so a pivot above √ε ≫ δ is a genuine rank.
pub fn solve_consistent_in<T: Scalar>(
    a: &mut [T],
    rows: usize,
    cols: usize,
    b: &mut [T],
    pivots: &mut Vec<usize>,
    particular: &mut Vec<T>,
) {
    let eps = T::epsilon_f64();
    let mut scale = largest_entry(a);
    if eps > 0.0
        && let Some(widen) = T::from_f64(eps.sqrt() / (cols.max(1) as f64 * eps))
    {
        scale *= widen;
    }
    rref_scaled(a, rows, cols, b, 1, pivots, &scale);
    fill_particular(cols, b, pivots, particular);
}

/// The particular solution of a reduced system: each pivot column's right-hand side, the free
/// columns zero.
fn fill_particular<T: Scalar>(cols: usize, b: &[T], pivots: &[usize], particular: &mut Vec<T>) {
    particular.clear();
    particular.resize(cols, T::zero());
    for (k, &pc) in pivots.iter().enumerate() {
        particular[pc] = b[k].clone();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int, ratio};

    fn m(v: &[i64]) -> Vec<Exact> {
        v.iter().map(|&x| int(x)).collect()
    }

    /// A consistent PSD system singular but for a relative 10⁻¹² (two points of one line whose
    /// geometry carries rounding): in f64 one pivot (a family; the nearly null component is
    /// not the rounding of the right-hand side divided by 10⁻¹²), exactly two.
    #[test]
    fn a_nearly_singular_consistent_system_is_a_family_in_floats_only() {
        let d = 1e-12;
        let (mut a, mut b) = (vec![1.0, 1.0, 1.0, 1.0 + d], vec![2.0, 2.0 + 1e-16]);
        let (mut pivots, mut x) = (Vec::new(), Vec::new());
        solve_consistent_in(&mut a, 2, 2, &mut b, &mut pivots, &mut x);
        assert_eq!(pivots.len(), 1);
        assert_eq!(x, vec![2.0, 0.0]);
        let mut a: Vec<Exact> = vec![
            int(1),
            int(1),
            int(1),
            int::<Exact>(1) + ratio::<Exact>(1, 1_000_000_000_000),
        ];
        let mut b: Vec<Exact> = vec![int(2), int(2)];
        let (mut pivots, mut x) = (Vec::new(), Vec::new());
        solve_consistent_in(&mut a, 2, 2, &mut b, &mut pivots, &mut x);
        assert_eq!(pivots.len(), 2);
        assert_eq!(x, vec![int(2), int(0)]);
    }

    #[test]
    fn unique_solution_is_exact() {
        // [2 1; 1 3] x = [3; 5] → x = (4/5, 7/5).
        let s = solve_general(&m(&[2, 1, 1, 3]), 2, 2, &m(&[3, 5])).unwrap();
        assert_eq!(s.particular, vec![ratio(4, 5), ratio(7, 5)]);
        assert!(s.null.is_empty());
    }

    #[test]
    fn singular_consistent_system_has_a_family() {
        // x + y = 2 twice: particular (2, 0), null (−1, 1).
        let s = solve_general(&m(&[1, 1, 1, 1]), 2, 2, &m(&[2, 2])).unwrap();
        assert_eq!(s.particular, m(&[2, 0]));
        assert_eq!(s.null, vec![m(&[-1, 1])]);
    }

    #[test]
    fn inconsistent_system_is_refused() {
        assert!(solve_general(&m(&[1, 1, 1, 1]), 2, 2, &m(&[2, 3])).is_none());
    }

    #[test]
    fn floats_agree_with_exact_on_a_regular_system() {
        let a = [4.0, -2.0, 1.0, -2.0, 4.0, -2.0, 1.0, -2.0, 4.0];
        let b = [11.0, -16.0, 17.0];
        let s = solve_general(&a, 3, 3, &b).unwrap();
        let e = solve_general(
            &m(&[4, -2, 1, -2, 4, -2, 1, -2, 4]),
            3,
            3,
            &m(&[11, -16, 17]),
        )
        .unwrap();
        for (x, q) in s.particular.iter().zip(&e.particular) {
            assert!((x - q.to_f64()).abs() <= 1e-14 * q.to_f64().abs().max(1.0));
        }
    }
}
