//! Lemke's complementary pivoting method (Lemke 1965), with the lexicographic ratio test that
//! makes it terminate on degenerate problems (Cottle, Pang and Stone 1992, §4.4; as in Siconos'
//! `lcp_lexicolemke`).
//!
//! The tableau holds, for the basic variables x_B, the system x_B + T_N x_N = b over the
//! variables (w₁ … w_n, z₁ … z_n, z₀), starting from w − M z − e z₀ = q with w basic. The
//! artificial z₀ enters first, so that every b stays ≥ 0; then the complement of the variable
//! that left enters, until z₀ leaves (a solution) or no row bounds the entering variable (a
//! ray). Ties in the ratio b_i / T_ic are broken lexicographically on the rows of B⁻¹ (the
//! columns of w), which are independent, so the choice is unique and no basis repeats.
//!
//! Exact types decide every sign exactly. In floats an entry of the entering column counts as
//! positive when it exceeds 4n·ε times the column's largest entry — the rounding error of the
//! O(n) operations that produced it — and ratios within 4n·ε of each other are ties.
//!
//! **A bounded budget.** Each pivot costs O(n²), and the path is at most
//! [`PIVOTS_PER_ROW`]·(n + 1) pivots long: the work is O(n³) whatever the data. Exact paths on
//! the inertance matrices of random bodies take at most about 2.5 n pivots (n = 10–40, rank 6);
//! in floats, rounding can make a lexicographic path on a singular G cycle, and the budget is
//! then what ends it — quadratic in n before, it let one 200-contact `analyze` run for minutes.

use super::{Lcp, LcpError, LcpSolution};
use crate::scalar::Scalar;

/// The pivot budget of an n-dimensional problem is this many pivots per row, plus one row:
/// four times the longest exact path measured (module docs).
pub const PIVOTS_PER_ROW: usize = 10;

/// Solve LCP(M, q) (see [`super`]).
///
/// # Errors
/// [`LcpError::Ray`] when the LCP has no solution (for a positive semidefinite M);
/// [`LcpError::IterationLimit`] when the pivot budget (a safeguard) runs out.
pub fn lemke<T: Scalar>(lcp: Lcp<'_, T>) -> Result<LcpSolution<T>, LcpError> {
    let mut work = LcpWork::default();
    let pivots = lemke_in(&mut work, lcp)?;
    Ok(LcpSolution {
        z: work.z,
        w: work.w,
        pivots,
    })
}

/// The buffers of [`lemke_in`]: the tableau, the basis and the solution. Reused across solves,
/// so repeated f64 solves of the same size allocate nothing.
#[derive(Clone, Debug)]
pub struct LcpWork<T> {
    t: Vec<T>,
    basis: Vec<usize>,
    /// z of the last solution.
    pub z: Vec<T>,
    /// w = M z + q of the last solution.
    pub w: Vec<T>,
}

impl<T> Default for LcpWork<T> {
    fn default() -> Self {
        LcpWork {
            t: Vec::new(),
            basis: Vec::new(),
            z: Vec::new(),
            w: Vec::new(),
        }
    }
}

/// [`lemke`] in caller-owned buffers: the solution is left in `work.z`, `work.w`; the pivots
/// made are returned.
///
/// # Errors
/// As [`lemke`].
pub fn lemke_in<T: Scalar>(work: &mut LcpWork<T>, lcp: Lcp<'_, T>) -> Result<usize, LcpError> {
    let n = lcp.q.len();
    debug_assert_eq!(lcp.m.len(), n * n);
    if lcp.q.iter().all(|x| x.signum_i8() >= 0) {
        work.z.clear();
        work.z.resize(n, T::zero());
        work.w.clear();
        work.w.extend_from_slice(lcp.q);
        return Ok(0);
    }
    let mut t = Tableau::new(work, lcp);
    // z₀ enters at the level that makes the most negative q_i zero (lowest index on ties:
    // the lexicographic rule for the column −e).
    let mut r = 0;
    for i in 1..n {
        if (lcp.q[i].clone() - &lcp.q[r]).signum_i8() < 0 {
            r = i;
        }
    }
    let mut entering = t.z0;
    let budget = PIVOTS_PER_ROW * (n + 1);
    for pivots in 0..budget {
        let leaving = t.pivot(r, entering);
        if leaving == t.z0 {
            t.solution();
            return Ok(pivots + 1);
        }
        entering = if leaving < n {
            leaving + n
        } else {
            leaving - n
        };
        r = match t.ratio_test(entering) {
            Some(r) => r,
            None => return Err(LcpError::Ray { pivots: pivots + 1 }),
        };
    }
    Err(LcpError::IterationLimit { pivots: budget })
}

/// The dense tableau [I | −M | −e | q] as it is pivoted, and which variable is basic in each
/// row, in the buffers of an [`LcpWork`].
struct Tableau<'w, T> {
    n: usize,
    /// Columns: w (0..n), z (n..2n), z₀ (2n), right-hand side b (2n + 1).
    cols: usize,
    z0: usize,
    work: &'w mut LcpWork<T>,
}

impl<'w, T: Scalar> Tableau<'w, T> {
    fn new(work: &'w mut LcpWork<T>, lcp: Lcp<'_, T>) -> Self {
        let n = lcp.q.len();
        let cols = 2 * n + 2;
        work.t.clear();
        work.t.resize(n * cols, T::zero());
        for i in 0..n {
            let row = &mut work.t[i * cols..(i + 1) * cols];
            row[i] = T::one();
            for j in 0..n {
                row[n + j] = -lcp.m[i * n + j].clone();
            }
            row[2 * n] = -T::one();
            row[2 * n + 1] = lcp.q[i].clone();
        }
        work.basis.clear();
        work.basis.extend(0..n);
        Tableau {
            n,
            cols,
            z0: 2 * n,
            work,
        }
    }

    fn at(&self, i: usize, j: usize) -> &T {
        &self.work.t[i * self.cols + j]
    }

    /// Make column `c` basic in row `r`; the variable that leaves.
    fn pivot(&mut self, r: usize, c: usize) -> usize {
        let cols = self.cols;
        let p = self.at(r, c).clone();
        for j in 0..cols {
            self.work.t[r * cols + j] /= &p;
        }
        for i in 0..self.n {
            if i == r {
                continue;
            }
            let f = self.at(i, c).clone();
            if f.is_zero() {
                continue;
            }
            for j in 0..cols {
                let d = f.clone() * self.at(r, j);
                self.work.t[i * cols + j] -= d;
            }
        }
        std::mem::replace(&mut self.work.basis[r], c)
    }

    /// The row that leaves when column `c` enters: among rows with a positive entry, the
    /// lexicographic minimum of (b_i, B⁻¹_i) / T_ic; `None` when no entry is positive (a ray).
    fn ratio_test(&self, c: usize) -> Option<usize> {
        let n = self.n;
        let mut colmax = T::zero();
        for i in 0..n {
            if self.at(i, c).abs_gt(&colmax) {
                colmax = self.at(i, c).clone();
            }
        }
        let rhs = 2 * n + 1;
        let mut best: Option<usize> = None;
        for i in 0..n {
            let a = self.at(i, c);
            if a.signum_i8() <= 0 || a.is_negligible(&colmax, 4 * n) {
                continue;
            }
            best = Some(match best {
                None => i,
                Some(b) => {
                    // Compare (b_i, B⁻¹_i)/a_i against (b_b, B⁻¹_b)/a_b component by component.
                    let order = std::iter::once(rhs).chain(0..n).find_map(|j| {
                        let (x, y) = (
                            self.at(i, j).clone() / a,
                            self.at(b, j).clone() / self.at(b, c),
                        );
                        let d = x.clone() - &y;
                        let reference = if x.abs_gt(&y) { x } else { y };
                        (!d.is_negligible(&reference, 4 * n)).then(|| d.signum_i8())
                    });
                    if order == Some(-1) { i } else { b }
                }
            });
        }
        best
    }

    /// Read z and w off the final basis into the work's buffers.
    fn solution(&mut self) {
        let n = self.n;
        let work = &mut *self.work;
        work.z.clear();
        work.z.resize(n, T::zero());
        work.w.clear();
        work.w.resize(n, T::zero());
        for i in 0..n {
            let v = work.basis[i];
            let b = work.t[i * self.cols + 2 * n + 1].clone();
            if v < n {
                work.w[v] = b;
            } else if v < 2 * n {
                work.z[v - n] = b;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int, ratio};

    fn solve(m: &[i64], q: &[i64]) -> Result<LcpSolution<Exact>, LcpError> {
        let m: Vec<Exact> = m.iter().map(|&x| int(x)).collect();
        let q: Vec<Exact> = q.iter().map(|&x| int(x)).collect();
        lemke(Lcp { m: &m, q: &q })
    }

    #[test]
    fn a_nonnegative_q_needs_no_pivot() {
        let s = solve(&[2, 1, 1, 2], &[1, 0]).unwrap();
        assert_eq!(s.z, vec![int(0), int(0)]);
        assert_eq!(s.pivots, 0);
    }

    #[test]
    fn a_positive_definite_problem_is_solved_exactly() {
        // w = [[2, 1], [1, 2]] z + (−5, −6): both active, z = (4/3, 7/3).
        let s = solve(&[2, 1, 1, 2], &[-5, -6]).unwrap();
        assert_eq!(s.z, vec![ratio(4, 3), ratio(7, 3)]);
        assert_eq!(s.w, vec![int(0), int(0)]);
        // One active: w = (2z₁ − 5, z₁ + 2) → z₁ = 5/2, w₂ = 9/2.
        let s = solve(&[2, 1, 1, 2], &[-5, 2]).unwrap();
        assert_eq!(s.z, vec![ratio(5, 2), int(0)]);
        assert_eq!(s.w, vec![int(0), ratio(9, 2)]);
    }

    #[test]
    fn an_infeasible_problem_ends_on_a_ray() {
        // M = 0 with q < 0: w = q < 0 for every z.
        assert!(matches!(
            solve(&[0, 0, 0, 0], &[-1, 2]),
            Err(LcpError::Ray { .. })
        ));
        // Singular M: z₁ and z₂ push against each other, w₁ + w₂ = q₁ + q₂ < 0 always.
        assert!(matches!(
            solve(&[1, -1, -1, 1], &[-1, -1]),
            Err(LcpError::Ray { .. })
        ));
    }

    #[test]
    fn a_degenerate_problem_terminates() {
        // Equal q's and a singular M: ties in every ratio test.
        let s = solve(&[1, 1, 1, 1, 1, 1, 1, 1, 1], &[-1, -1, -1]).unwrap();
        let sum: Exact = s.z.iter().cloned().sum();
        assert_eq!(sum, int(1));
        assert!(s.w.iter().all(|x| *x == int(0)));
    }
}
