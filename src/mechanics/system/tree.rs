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
//! so c = 0 gives the response W{E} = η y, and E = 0, c = −Hᵀ η t gives
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
//! down (x_i = z_i − Q_i x_p): three 6 × 6 products per node, linear in the bodies whatever
//! the degree of a body. The factorization keeps D_i⁻¹ itself (from an LDLᵀ of the block) and
//! Q_i, so that a solve — one per contact axis — is products only.
//!
//! **The pivots.** A body's block stays positive definite: A_b⁻¹ plus, for each child joint,
//! −H D_j⁻¹ Hᵀ with D_j negative definite. A joint's block is D_j = −H_j(c)ᵀ D_c⁻¹ H_j(c) for
//! its child body c — negative definite because a joint's blocked screws are independent. So
//! for a forest every pivot is nonzero **exactly** (an elimination of the leaves shows H has
//! full column rank: a leaf body's only joint has λ_j = 0 in any H λ = 0), K is nonsingular and
//! λ is unique; the pivots are taken without reordering, each block's LDLᵀ unpivoted (it is
//! definite, which makes that stable in floats; Higham, *Accuracy and Stability of Numerical
//! Algorithms*, §10.1). A pivot that rounding makes negligible or of
//! the wrong sign (floats only) refuses the tree, and the dense pivoted path of
//! [`super::mobility`] answers instead, as it does for closed loops and redundant joints.

use crate::mechanics::body::RigidBody;
use crate::scalar::Scalar;

use super::mobility::Row;

/// No parent: a root.
const ROOT: usize = usize::MAX;

/// A 6 × 6 block, row-major. Every node's block is 6 × 6: a joint of m < 6 rows is padded
/// with 6 − m rows of its own, −1 on the diagonal and zero elsewhere, whose multipliers are
/// zero — so every kernel has one fixed size, which the compiler unrolls.
type Block<T> = [T; 36];

/// The factored KKT system of a forest of joints (module docs).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Tree<T: Scalar> {
    /// Bodies (nodes 0..B; the joints are nodes B..B+J). Node i's entries in a stacked
    /// vector are 6i..6i + 6: [y_1 … y_B, λ of joint 1 (padded to 6), …].
    bodies: usize,
    /// The nodes, leaves first: every node before its parent.
    order: Vec<usize>,
    /// Per node: its parent node, or [`ROOT`].
    parent: Vec<usize>,
    /// Per joint: its first row of H and its number of rows.
    rows: Vec<(usize, usize)>,
    /// Per node: D_i⁻¹.
    inverse: Vec<Block<T>>,
    /// Per node: Q_i = D_i⁻¹ S_{i,p} (zero for a root).
    coupling: Vec<Block<T>>,
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
        let mut joint_rows = vec![(rows.len(), 0); joints];
        for (k, r) in rows.iter().enumerate() {
            let (first, count) = &mut joint_rows[r.joint];
            *first = (*first).min(k);
            *count += 1;
        }
        if joint_rows.iter().any(|&(_, m)| m > 6) {
            return None;
        }
        // S_ii: A_b⁻¹ = diag(m I, J) on [v_C; ω] for a body; zero (and the padding) for a
        // joint.
        let mut inverse = Vec::with_capacity(b + joints);
        for body in bodies {
            let mut d = zero_block();
            for k in 0..3 {
                d[7 * k] = body.mass.clone();
            }
            let j = body.inertia.matrix();
            for r in 0..3 {
                for c in 0..3 {
                    d[6 * (3 + r) + 3 + c] = j[(r, c)].clone();
                }
            }
            inverse.push(d);
        }
        for &(_, m) in &joint_rows {
            let mut d = zero_block();
            for k in m..6 {
                d[7 * k] = -T::one();
            }
            inverse.push(d);
        }
        let mut tree = Tree {
            bodies: b,
            order,
            parent,
            rows: joint_rows,
            inverse,
            coupling: vec![zero_block(); b + joints],
        };
        tree.factor(rows)?;
        Some(tree)
    }

    /// The block LDLᵀ, leaves first (module docs), keeping D_i⁻¹ and Q_i; `None` at a
    /// negligible or wrongly signed pivot.
    fn factor(&mut self, rows: &[Row<T>]) -> Option<()> {
        let b = self.bodies;
        let mut s: Block<T> = zero_block();
        for at in 0..self.order.len() {
            let i = self.order[at];
            let (sign, real) = if i < b {
                (1, 6)
            } else {
                (-1, self.rows[i - b].1)
            };
            invert_definite(&mut self.inverse[i], sign, real)?;
            let p = self.parent[i];
            if p == ROOT {
                continue;
            }
            // S_{i,p}: a body under its joint p holds H_p(i) (columns: the joint's rows); a
            // joint under its body p holds H_i(p)ᵀ (rows: the joint's rows).
            let (body, joint) = if i < b { (i, p - b) } else { (p, i - b) };
            let (first, m) = self.rows[joint];
            s.iter_mut().for_each(|x| x.set_zero());
            for r in 0..m {
                let h = rows[first + r].on(body).as_slice();
                for k in 0..6 {
                    let at = if i < b { 6 * k + r } else { 6 * r + k };
                    s[at] = h[k].clone();
                }
            }
            // Q_i = D_i⁻¹ S_{i,p}; D_p −= S_{i,p}ᵀ Q_i.
            let q = multiply(&self.inverse[i], &s);
            let update = multiply_transposed(&s, &q);
            for (d, u) in self.inverse[p].iter_mut().zip(update) {
                *d -= u;
            }
            self.coupling[i] = q;
        }
        Some(())
    }

    /// Where joint `j`'s multipliers start in a stacked vector, and how many it has.
    pub(crate) fn joint_span(&self, j: usize) -> (usize, usize) {
        (6 * (self.bodies + j), self.rows[j].1)
    }

    /// The length of a stacked vector: six entries per node.
    pub(crate) fn len(&self) -> usize {
        6 * self.inverse.len()
    }

    /// Solve the KKT system in place: `x` ([`Tree::len`] entries) holds [E_1 … E_B, c] (each
    /// E_b a wrench [F; M] about C_b; joint j's entries of c at [`Tree::joint_span`], zero
    /// past them) and receives [y_1 … y_B, λ] (y_b = [v_C; ω]).
    pub(crate) fn solve(&self, x: &mut [T]) {
        let take = |x: &[T], i: usize| -> [T; 6] { std::array::from_fn(|k| x[6 * i + k].clone()) };
        // Up: z_p −= Q_iᵀ z_i, then z_i ← D_i⁻¹ z_i.
        for &i in &self.order {
            let z = take(x, i);
            let p = self.parent[i];
            if p != ROOT {
                let q = &self.coupling[i];
                let zp = &mut x[6 * p..6 * p + 6];
                for c in 0..6 {
                    let mut t = T::zero();
                    for r in 0..6 {
                        t += q[6 * r + c].clone() * &z[r];
                    }
                    zp[c] -= t;
                }
            }
            let d = &self.inverse[i];
            let zi = &mut x[6 * i..6 * i + 6];
            for r in 0..6 {
                let mut t = T::zero();
                for c in 0..6 {
                    t += d[6 * r + c].clone() * &z[c];
                }
                zi[r] = t;
            }
        }
        // Down: x_i = z_i − Q_i x_p.
        for &i in self.order.iter().rev() {
            let p = self.parent[i];
            if p == ROOT {
                continue;
            }
            let xp = take(x, p);
            let q = &self.coupling[i];
            let xi = &mut x[6 * i..6 * i + 6];
            for r in 0..6 {
                let mut t = T::zero();
                for c in 0..6 {
                    t += q[6 * r + c].clone() * &xp[c];
                }
                xi[r] -= t;
            }
        }
    }
}

/// a b. Exact types skip the zeros of `a` (most of S's entries); floats keep the loops
/// branch-free.
fn multiply<T: Scalar>(a: &Block<T>, b: &Block<T>) -> Block<T> {
    let mut out = zero_block();
    for r in 0..6 {
        for k in 0..6 {
            let x = &a[6 * r + k];
            if T::IS_EXACT && x.is_zero() {
                continue;
            }
            for c in 0..6 {
                out[6 * r + c] += x.clone() * &b[6 * k + c];
            }
        }
    }
    out
}

/// aᵀ b, as [`multiply`].
fn multiply_transposed<T: Scalar>(a: &Block<T>, b: &Block<T>) -> Block<T> {
    let mut out = zero_block();
    for k in 0..6 {
        for r in 0..6 {
            let x = &a[6 * k + r];
            if T::IS_EXACT && x.is_zero() {
                continue;
            }
            for c in 0..6 {
                out[6 * r + c] += x.clone() * &b[6 * k + c];
            }
        }
    }
    out
}

fn zero_block<T: Scalar>() -> Block<T> {
    [(); 36].map(|_| T::zero())
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

/// The symmetric definite block `a` replaced by its inverse: a = L D Lᵀ without pivoting,
/// then a⁻¹ = L⁻ᵀ D⁻¹ L⁻¹. Each of the first `real` pivots must have the sign `sign` and not
/// be negligible against the largest of the first `real` diagonal entries (else `None`); the
/// others are a joint's padding, −1 and uncoupled, in no unit of the block's.
fn invert_definite<T: Scalar>(a: &mut Block<T>, sign: i8, real: usize) -> Option<()> {
    let mut scale = T::zero();
    for k in 0..real {
        if a[7 * k].abs_gt(&scale) {
            scale = a[7 * k].clone();
        }
    }
    // L (strictly below the diagonal) and D (on it), in place; the lower triangle is read.
    for k in 0..6 {
        let d = a[7 * k].clone();
        if k < real && (d.signum_i8() != sign || d.is_negligible(&scale, 6)) {
            return None;
        }
        // a_ij −= a_ik a_jk / d below the pivot (rows from the bottom up, so that a_jk, j ≤ i,
        // is still unscaled), then column k becomes L.
        for i in (k + 1..6).rev() {
            if T::IS_EXACT && a[6 * i + k].is_zero() {
                continue;
            }
            let l = a[6 * i + k].clone() / &d;
            for j in k + 1..=i {
                let t = l.clone() * &a[6 * j + k];
                a[6 * i + j] -= t;
            }
            a[6 * i + k] = l;
        }
    }
    // M = L⁻¹ (unit lower triangular): m_ij = −Σ_{j≤k<i} l_ik m_kj.
    let mut m = zero_block::<T>();
    for i in 0..6 {
        m[7 * i] = T::one();
        for j in 0..i {
            let mut t = a[6 * i + j].clone();
            for k in j + 1..i {
                t += a[6 * i + k].clone() * &m[6 * k + j];
            }
            m[6 * i + j] = -t;
        }
    }
    // a⁻¹ = Mᵀ D⁻¹ M: (a⁻¹)_rc = Σ_{k ≥ max(r, c)} m_kr m_kc / d_k.
    let inv_d: [T; 6] = std::array::from_fn(|k| T::one() / &a[7 * k]);
    for r in 0..6 {
        for c in 0..=r {
            let mut t = T::zero();
            for k in r..6 {
                t += m[6 * k + r].clone() * &m[6 * k + c] * &inv_d[k];
            }
            a[6 * r + c] = t.clone();
            a[6 * c + r] = t;
        }
    }
    Some(())
}
