//! The joints' KKT system factored along a tree, in time linear in the bodies (Baraff 1996).
//!
//! [`super::mobility`] writes the system's answer to an impulse {E} as W{E} = W₀{E} − W₀ H λ
//! with K λ = Hᵀ η W₀ {E}, K = Hᵀ η W₀ H. Forming and factoring K costs O(rows³) and couples
//! every joint to every other. Written instead as one symmetric system in the bodies' velocities
//! and the joints' impulses together (Gauss's principle, the KKT system of
//! [`super::mobility`]), with y = η W{E} (each body's [v_C; ω]) and A = η W₀ = diag(m⁻¹ I, J⁻¹)
//! per body (eq. 56),
//!
//! ```text
//! [ A⁻¹  H ] [ y ]   [ E ]          A⁻¹ y + H λ = E   ⇒   y = A (E − H λ),
//! [ Hᵀ   0 ] [ λ ] = [ c ],          Hᵀ y = c          ⇒   K λ = Hᵀ A E − c,
//! ```
//!
//! so c = 0 gives W{E} = η y and the multipliers of `constrain`, and E = 0, c = −Hᵀ η t gives
//! K λ = Hᵀ η t (the joints' impulses). A⁻¹ = diag(m I, J) on [v_C; ω] is each body's mass
//! matrix \[η\]\[M\] read in the order [v; ω], and H's block at body b and joint j is the
//! joint's blocked screws about C_b (6 × m_j, signed as in [`super::mobility`]).
//!
//! **The graph.** Take one node per body (a 6 × 6 diagonal block A_b⁻¹) and one per joint (an
//! m_j × m_j zero block), and an edge between a joint and each body it holds (the block
//! H_j(b)). When the joints, as edges between bodies and the ground, form a forest, this graph
//! is a forest too; root each tree at its joint to the ground (there is at most one: two
//! would close a loop through the ground) or, for a tree free of the ground, at a body. A
//! block LDLᵀ that eliminates every node before its parent then creates **no fill-in**: the
//! only entry a node's elimination changes is its parent's diagonal block (Baraff, "Linear-time
//! dynamics using Lagrange multipliers", SIGGRAPH 1996, §4–5). With Q_i = D_i⁻¹ S_{i,p} for the
//! parent p of node i,
//!
//! ```text
//! D_i = S_ii − Σ_{children c} S_{i,c} Q_c,       S = L D Lᵀ,  L_{p,i} = Q_iᵀ,
//! ```
//!
//! and a solve is one pass up the trees (z_p −= Q_iᵀ z_i, then z_i ← D_i⁻¹ z_i) and one pass
//! down (x_i = z_i − Q_i x_p): O(Σ sizes²) work, linear in the bodies for bounded joint sizes
//! (≤ 6 rows each), whatever the degree of a body.
//!
//! **The pivots.** A body's block stays positive definite: A_b⁻¹ plus, for each child joint,
//! −H D_j⁻¹ Hᵀ with D_j negative definite. A joint's block is D_j = −H_j(c)ᵀ D_c⁻¹ H_j(c) for
//! its child body c — negative definite because a joint's blocked screws are independent. So
//! for a forest every pivot is nonzero **exactly** (an elimination of the leaves shows H has
//! full column rank: a leaf body's only joint has λ_j = 0 in any H λ = 0), K is nonsingular and
//! λ is unique; the pivots are taken without reordering, each block's LDLᵀ unpivoted (it is
//! definite, which makes that stable in floats). A pivot that rounding makes negligible or of
//! the wrong sign (floats only) refuses the tree, and the dense pivoted path of
//! [`super::mobility`] answers instead, as it does for closed loops and redundant joints.

use crate::mechanics::body::RigidBody;
use crate::scalar::Scalar;

use super::mobility::Row;

/// No parent: a root.
const ROOT: usize = usize::MAX;

/// The factored KKT system of a forest of joints (module docs).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Tree<T: Scalar> {
    /// Bodies (nodes 0..B; the joints are nodes B..B+J).
    bodies: usize,
    /// The nodes, leaves first: every node before its parent.
    order: Vec<usize>,
    /// Per node: its parent node, or [`ROOT`].
    parent: Vec<usize>,
    /// Per node: where its entries start in a stacked vector [y_1 … y_B, λ] (bodies: 6 each;
    /// joint j: its rows, in the order of the rows of H).
    offset: Vec<usize>,
    /// Per node: its size (6 for a body, m_j for a joint).
    size: Vec<usize>,
    /// Per node: where its factored D_i (size², row-major, L below the diagonal, D on it)
    /// starts in `diag`.
    diag_at: Vec<usize>,
    diag: Vec<T>,
    /// Per node: where Q_i = D_i⁻¹ S_{i,p} (size_i × size_p, row-major) starts in `coupling`.
    coupling_at: Vec<usize>,
    coupling: Vec<T>,
}

impl<T: Scalar> Tree<T> {
    /// The factorization of the KKT system of `bodies` held by joints whose rows are `rows`
    /// (each joint's rows consecutive, joints in order, `pairs[j]` the bodies of joint j), or
    /// `None` when the joints do not form a forest or (floats) a pivot is negligible.
    pub(crate) fn new(
        bodies: &[RigidBody<T>],
        rows: &[Row<T>],
        pairs: &[(usize, Option<usize>)],
    ) -> Option<Self> {
        let b = bodies.len();
        let joints = pairs.len();
        let (order, parent) = eliminate_leaves_first(b, pairs)?;
        let nodes = b + joints;
        let mut size = vec![6; nodes];
        let mut offset: Vec<usize> = (0..nodes).map(|i| 6 * i.min(b)).collect();
        // Each joint's rows are consecutive: its offset is 6B + its first row.
        let mut first_row = vec![usize::MAX; joints];
        for (k, r) in rows.iter().enumerate() {
            if first_row[r.joint] == usize::MAX {
                first_row[r.joint] = k;
            }
            size[b + r.joint] = k + 1 - first_row[r.joint];
        }
        for j in 0..joints {
            if first_row[j] == usize::MAX {
                size[b + j] = 0;
                first_row[j] = rows.len();
            }
            offset[b + j] = 6 * b + first_row[j];
        }
        let mut diag_at = Vec::with_capacity(nodes);
        let mut coupling_at = Vec::with_capacity(nodes);
        let (mut d_len, mut q_len) = (0, 0);
        for i in 0..nodes {
            diag_at.push(d_len);
            coupling_at.push(q_len);
            d_len += size[i] * size[i];
            if parent[i] != ROOT {
                q_len += size[i] * size[parent[i]];
            }
        }
        let mut tree = Tree {
            bodies: b,
            order,
            parent,
            offset,
            size,
            diag_at,
            diag: vec![T::zero(); d_len],
            coupling_at,
            coupling: vec![T::zero(); q_len],
        };
        // S_ii: A_b⁻¹ = diag(m I, J) on [v_C; ω] for a body; zero for a joint.
        for (i, body) in bodies.iter().enumerate() {
            let d = &mut tree.diag[tree.diag_at[i]..tree.diag_at[i] + 36];
            for k in 0..3 {
                d[7 * k] = body.mass.clone();
            }
            let j = body.inertia.matrix();
            for r in 0..3 {
                for c in 0..3 {
                    d[6 * (3 + r) + 3 + c] = j[(r, c)].clone();
                }
            }
        }
        tree.factor(rows, &first_row)?;
        Some(tree)
    }

    /// The block LDLᵀ, leaves first (module docs); `None` at a negligible or wrongly signed
    /// pivot.
    fn factor(&mut self, rows: &[Row<T>], first_row: &[usize]) -> Option<()> {
        let b = self.bodies;
        let mut s = [(); 36].map(|_| T::zero());
        let mut column = [(); 6].map(|_| T::zero());
        for at in 0..self.order.len() {
            let i = self.order[at];
            let n = self.size[i];
            let sign = if i < b { 1 } else { -1 };
            let d = &mut self.diag[self.diag_at[i]..self.diag_at[i] + n * n];
            factor_definite(d, n, sign)?;
            let p = self.parent[i];
            if p == ROOT {
                continue;
            }
            // S_{i,p}, size_i × size_p: a body under its joint p holds H_p(i) (6 × m_p); a
            // joint under its body p holds H_i(p)ᵀ (m_i × 6).
            let np = self.size[p];
            let (body, joint) = if i < b { (i, p - b) } else { (p, i - b) };
            for r in 0..self.size[b + joint] {
                let h = rows[first_row[joint] + r].on(body);
                for k in 0..6 {
                    let (row, col) = if i < b { (k, r) } else { (r, k) };
                    s[row * np + col] = h.0[k].clone();
                }
            }
            // Q_i = D_i⁻¹ S_{i,p}, column by column.
            let q_at = self.coupling_at[i];
            let d = &self.diag[self.diag_at[i]..self.diag_at[i] + n * n];
            for c in 0..np {
                for r in 0..n {
                    column[r] = s[r * np + c].clone();
                }
                solve_definite(d, n, &mut column[..n]);
                for r in 0..n {
                    self.coupling[q_at + r * np + c] = column[r].clone();
                }
            }
            // D_p −= S_{p,i} Q_i = S_{i,p}ᵀ Q_i (the lower triangle, which the factor reads).
            let q = &self.coupling[q_at..q_at + n * np];
            let dp = &mut self.diag[self.diag_at[p]..self.diag_at[p] + np * np];
            for r in 0..np {
                for c in 0..=r {
                    let mut t = T::zero();
                    for k in 0..n {
                        if !s[k * np + r].is_zero() {
                            t += s[k * np + r].clone() * &q[k * np + c];
                        }
                    }
                    dp[r * np + c] -= t;
                }
            }
        }
        Some(())
    }

    /// Solve the KKT system in place: `x` holds [E_1 … E_B, c] (each E_b a wrench [F; M]
    /// about C_b, c one entry per row) and receives [y_1 … y_B, λ] (y_b = [v_C; ω]).
    pub(crate) fn solve(&self, x: &mut [T]) {
        let mut z = [(); 6].map(|_| T::zero());
        // Up: z_p −= Q_iᵀ z_i, then z_i ← D_i⁻¹ z_i.
        for &i in &self.order {
            let (o, n) = (self.offset[i], self.size[i]);
            let p = self.parent[i];
            if p != ROOT {
                let (op, np) = (self.offset[p], self.size[p]);
                let q = &self.coupling[self.coupling_at[i]..self.coupling_at[i] + n * np];
                for c in 0..np {
                    let mut t = T::zero();
                    for r in 0..n {
                        t += q[r * np + c].clone() * &x[o + r];
                    }
                    x[op + c] -= t;
                }
            }
            let d = &self.diag[self.diag_at[i]..self.diag_at[i] + n * n];
            solve_definite(d, n, &mut x[o..o + n]);
        }
        // Down: x_i = z_i − Q_i x_p.
        for &i in self.order.iter().rev() {
            let p = self.parent[i];
            if p == ROOT {
                continue;
            }
            let (o, n) = (self.offset[i], self.size[i]);
            let (op, np) = (self.offset[p], self.size[p]);
            for (zc, xc) in z.iter_mut().zip(&x[op..op + np]) {
                zc.clone_from(xc);
            }
            let q = &self.coupling[self.coupling_at[i]..self.coupling_at[i] + n * np];
            for r in 0..n {
                let mut t = T::zero();
                for c in 0..np {
                    t += q[r * np + c].clone() * &z[c];
                }
                x[o + r] -= t;
            }
        }
    }
}

/// The nodes (bodies 0..B, joints B..B+J) ordered leaves first, and each node's parent, when
/// the joints — edges between bodies, or between a body and the ground — form a forest;
/// `None` when they close a loop (through the ground too).
fn eliminate_leaves_first(
    b: usize,
    pairs: &[(usize, Option<usize>)],
) -> Option<(Vec<usize>, Vec<usize>)> {
    // Union–find over the bodies and the ground (node B): a joint whose ends are already
    // connected closes a loop.
    let mut set: Vec<usize> = (0..=b).collect();
    fn find(set: &mut [usize], mut i: usize) -> usize {
        while set[i] != i {
            set[i] = set[set[i]];
            i = set[i];
        }
        i
    }
    for &(first, second) in pairs {
        let (x, y) = (find(&mut set, first), find(&mut set, second.unwrap_or(b)));
        if x == y {
            return None;
        }
        set[x] = y;
    }
    // The joints at each body (compressed rows).
    let mut start = vec![0; b + 1];
    for &(first, second) in pairs {
        start[first + 1] += 1;
        if let Some(s) = second {
            start[s + 1] += 1;
        }
    }
    for i in 0..b {
        start[i + 1] += start[i];
    }
    let mut incident = vec![0; start[b]];
    let mut fill = start.clone();
    for (j, &(first, second)) in pairs.iter().enumerate() {
        for body in std::iter::once(first).chain(second) {
            incident[fill[body]] = j;
            fill[body] += 1;
        }
    }
    // Breadth first from the roots: the joints to the ground, then any body not yet reached.
    let nodes = b + pairs.len();
    let mut parent = vec![ROOT; nodes];
    let mut seen = vec![false; nodes];
    let mut order = Vec::with_capacity(nodes);
    let roots = pairs
        .iter()
        .enumerate()
        .filter(|(_, p)| p.1.is_none())
        .map(|(j, _)| b + j)
        .chain(0..b);
    for root in roots {
        if seen[root] {
            continue;
        }
        seen[root] = true;
        let from = order.len();
        order.push(root);
        let mut at = from;
        while at < order.len() {
            let i = order[at];
            at += 1;
            let mut visit = |k: usize| {
                if !seen[k] {
                    seen[k] = true;
                    parent[k] = i;
                    order.push(k);
                }
            };
            if i < b {
                for &j in &incident[start[i]..start[i + 1]] {
                    visit(b + j);
                }
            } else {
                let (first, second) = pairs[i - b];
                std::iter::once(first).chain(second).for_each(visit);
            }
        }
    }
    order.reverse();
    Some((order, parent))
}

/// A symmetric definite `n × n` block (row-major, the lower triangle read) factored in place
/// as L D Lᵀ without pivoting; every pivot must have the sign `sign` and not be negligible
/// against the block's largest diagonal entry.
fn factor_definite<T: Scalar>(a: &mut [T], n: usize, sign: i8) -> Option<()> {
    let mut scale = T::zero();
    for k in 0..n {
        if a[k * n + k].abs_gt(&scale) {
            scale = a[k * n + k].clone();
        }
    }
    for k in 0..n {
        let d = a[k * n + k].clone();
        if d.signum_i8() != sign || d.is_negligible(&scale, n) {
            return None;
        }
        // a_ij −= a_ik a_jk / d below the pivot (rows from the bottom up, so that a_jk, j ≤ i,
        // is still unscaled), then column k becomes L.
        for i in (k + 1..n).rev() {
            if a[i * n + k].is_zero() {
                continue;
            }
            let l = a[i * n + k].clone() / &d;
            for j in k + 1..=i {
                let t = l.clone() * &a[j * n + k];
                a[i * n + j] -= t;
            }
            a[i * n + k] = l;
        }
    }
    Some(())
}

/// x ← (L D Lᵀ)⁻¹ x for a block factored by [`factor_definite`].
fn solve_definite<T: Scalar>(a: &[T], n: usize, x: &mut [T]) {
    for i in 0..n {
        for j in 0..i {
            if !a[i * n + j].is_zero() {
                let t = a[i * n + j].clone() * &x[j];
                x[i] -= t;
            }
        }
    }
    for i in 0..n {
        x[i] /= &a[i * n + i];
    }
    for i in (0..n).rev() {
        for j in i + 1..n {
            if !a[j * n + i].is_zero() {
                let t = a[j * n + i].clone() * &x[j];
                x[i] -= t;
            }
        }
    }
}
