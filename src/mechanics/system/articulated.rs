//! The mobility of a forest of joints by the articulated-body recursion, in time linear in the
//! bodies (Featherstone, *Rigid Body Dynamics Algorithms*, 2008, ch. 7, the impulse form).
//!
//! [`super::mobility`] writes the system's answer to an impulse {E} as W{E} = W₀{E} − W₀ H λ
//! with K λ = Hᵀ η W₀ {E}: forming and factoring K costs O(rows³). When the joints form a
//! forest the same answer follows from one pass up each tree and one down, eliminating every
//! joint through the screws it leaves **free** rather than through those it blocks.
//!
//! **Coordinates.** Body i's velocity is y_i = [v_i; ω_i] (v_i of its centre C_i, world
//! axes: the twist {V_i} = η y_i) and a wrench on it is z = [F; M] about C_i, so that the power
//! is zᵀ y and the mass matrix is M_i = diag(m_i I, J_i) (eq. 9 read in the order [v; ω]).
//! Root each tree at the body held to the ground (there is at most one: two joints to the
//! ground close a loop through it), or at any body for a tree free of the ground. Body i's
//! joint to its parent p leaves free the n_i = 6 − m_i independent twists S_i (6 × n_i, the
//! joint's free screws about C_i): y_i = X_i y_p + S_i q_i with q_i the joint's rates and
//! X_i y_p = [v_p + ω_p × r_i; ω_p], r_i = C_i − C_p, the parent's motion carried to C_i (a
//! joint to the ground has y_p = 0); X_iᵀ carries a wrench [F; M] at C_i to C_p as
//! [F; M + r_i × F].
//!
//! **Factor** (leaves first). The articulated inertia of body i is its own mass matrix plus
//! what its children transmit through their joints,
//!
//! ```text
//! I^A_i = M_i + Σ_{children c} X_cᵀ I^a_c X_c,
//! U_i = I^A_i S_i,   D_i = S_iᵀ U_i  (n_i × n_i),   K_i = U_i D_i⁻¹,
//! I^a_i = I^A_i − K_i U_iᵀ                               (eq. 7.33–7.38, without bias terms)
//! ```
//!
//! and a root free of the ground keeps (I^A_root)⁻¹. A fixed joint (n = 0) transmits I^A_i
//! whole; a revolute one costs a 1 × 1 inverse where a 6 × 6 block elimination of the joint's
//! five blocked rows (Baraff 1996) cost a 6 × 6 inversion and two 6 × 6 products.
//!
//! **Solve** for an impulse z (one wrench per body): up, w_i = S_iᵀ z_i and
//! z_p += X_iᵀ (z_i − K_i w_i); down, a'_i = X_i a_p (zero under the ground),
//! q_i = D_i⁻¹ w_i − K_iᵀ a'_i, a_i = a'_i + S_i q_i, and a_root = (I^A_root)⁻¹ z_root for a
//! free root. Then η a = W{E}: the twist the impulse gives every body, that of the Schur
//! complement of [`super::mobility`] (both solve the same KKT system, whose solution is
//! unique for a forest).
//!
//! **The pivots are nonzero exactly.** Each M_i is positive definite and each I^a_c positive
//! semidefinite (I^a_c = I^A_c − U D⁻¹ Uᵀ is the Schur complement that leaves a positive
//! definite I^A_c, restricted to the twists with S_cᵀ I^A_c y = 0, positive semidefinite; a
//! congruence X_cᵀ · X_c keeps it so), so every I^A_i is positive definite, and so is
//! D_i = S_iᵀ I^A_i S_i for independent free screws S_i. No pivot is zero in exact
//! arithmetic, so rationals and symbols take this path as they are; the path refuses (and the
//! dense pivoted path of [`super::mobility`] answers) only a joint whose free screws are
//! dependent, a loop, and in floats a pivot that rounding makes negligible or negative. Each
//! D_i and (I^A_root) is inverted through its unpivoted LDLᵀ, stable for a definite matrix
//! (Higham, *Accuracy and Stability of Numerical Algorithms*, §10.1).
//!
//! **The joints' impulses** need no third solve. Once Δ{V} and the contact impulses are
//! known, the wrench the joints exert on each body is r_i = M_i Δ{V_i} + Σ P̂ {Ê}_i = Σ_j
//! H_j(i) λ_j ([`super::mobility`]). Summed over the subtree of body i, carried to C_i, the
//! internal joints cancel in pairs (a joint's wrench on its first body is the opposite of that
//! on its second) and what is left is the wrench its own joint transmits:
//! f_i = r_i + Σ_{children c} X_cᵀ f_c = H_j(i) λ_j. Its joint's blocked screws, as
//! [`super::blocked_screws`] builds them, are the identity in the columns that are not pivots
//! of the free screws' echelon form, so λ_j is f_i about the world origin read in those
//! columns (signed for the joint's first body) — exact when Δ{V} is.

use crate::mechanics::body::Inertia;
use crate::mechanics::screw::Screw;
use crate::scalar::Scalar;

use super::{JointScrews, SystemBody, SystemJoint};

/// No parent (a root), or no joint (a root free of the ground).
const NONE: usize = usize::MAX;

/// A 6 × 6 block, row-major, in the coordinates [v; ω] and [F; M].
type Block<T> = [T; 36];

/// One body of the forest.
#[derive(Clone, Debug, PartialEq)]
struct Node<T: Scalar> {
    /// Its parent body, or [`NONE`] for a root.
    parent: usize,
    /// The joint to its parent or to the ground, or [`NONE`] for a root free of the ground.
    joint: usize,
    /// Whether it is its joint's first body.
    first: bool,
    /// n, its joint's free screws.
    free: usize,
    /// Where its columns of S and K start — for a free root, its index in `roots`.
    at: usize,
    /// Where its D⁻¹ starts (n × n, row-major).
    square: usize,
    /// r = C_i − C_parent (zero for a root).
    r: [T; 3],
}

/// The articulated-body factorization of a forest of joints (module docs).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Articulated<T: Scalar> {
    /// The bodies, leaves first: every body before its parent.
    order: Vec<usize>,
    /// Per body.
    nodes: Vec<Node<T>>,
    /// The columns of every S_i, as twists [ω; v] about C_i.
    s: Vec<[T; 6]>,
    /// The columns of every K_i = U_i D_i⁻¹, as wrenches [F; M] about C_i.
    k: Vec<[T; 6]>,
    /// D_i⁻¹ per body, n × n row-major.
    dinv: Vec<T>,
    /// (I^A)⁻¹ of each root free of the ground, on [F; M] to [v; ω].
    roots: Vec<Block<T>>,
    /// Scratch of the factorization: each body's articulated inertia until it is eliminated.
    inertia: Vec<Block<T>>,
}

/// Scratch of [`Articulated::response_into`], reused across responses.
#[derive(Clone, Debug)]
pub(crate) struct ResponseScratch<T: Scalar> {
    /// w_i = S_iᵀ z_i.
    w: Vec<T>,
    /// Whether a body's z can be nonzero.
    live: Vec<bool>,
}

impl<T: Scalar> Default for ResponseScratch<T> {
    fn default() -> Self {
        ResponseScratch {
            w: Vec::new(),
            live: Vec::new(),
        }
    }
}

impl<T: Scalar> Articulated<T> {
    /// The factorization for `bodies` held by `joints` (their free screws in `screws`), or
    /// `None` when the joints do not form a forest, a joint's free screws are dependent, or
    /// (floats) a pivot is negligible.
    pub(crate) fn new(
        bodies: &[SystemBody<T>],
        joints: &[SystemJoint<T>],
        screws: &JointScrews<T>,
    ) -> Option<Self> {
        if !screws.independent {
            return None;
        }
        let (order, nodes) = forest(bodies.len(), joints)?;
        let mut tree = Articulated {
            order,
            nodes,
            s: Vec::new(),
            k: Vec::new(),
            dinv: Vec::new(),
            roots: Vec::new(),
            inertia: Vec::new(),
        };
        tree.refactor(bodies, screws)?;
        Some(tree)
    }

    /// Factor again for `bodies` and the joints' `screws` of a system of the same shape (the
    /// same bodies, joined by the same joints: the tree is kept) in a new configuration —
    /// centres, inertias, anchors and axes — reusing every buffer, so that repeated solves
    /// allocate nothing (the lean path, [`crate::impact::lean_system`]). `None` as
    /// [`Articulated::new`] for a pivot.
    pub(crate) fn refactor(
        &mut self,
        bodies: &[SystemBody<T>],
        screws: &JointScrews<T>,
    ) -> Option<()> {
        let Articulated {
            order,
            nodes,
            s,
            k,
            dinv,
            roots,
            inertia,
        } = self;
        // S about each body's centre, from the joint's free screws about the origin:
        // [ω; v_O] ↦ [ω; v_O + ω × C].
        s.clear();
        let mut square = 0;
        for (i, node) in nodes.iter_mut().enumerate() {
            if node.parent != NONE {
                let (ci, cp) = (&bodies[i].centre, &bodies[node.parent].centre);
                node.r = std::array::from_fn(|k| ci[k].clone() - &cp[k]);
            }
            if node.joint == NONE {
                continue;
            }
            let free = screws.free(node.joint);
            node.at = s.len();
            node.free = free.len();
            node.square = square;
            square += free.len() * free.len();
            let c = &bodies[i].centre;
            for f in free {
                let (w, v) = (f.top(), f.bottom());
                let vc = v + w.cross(c);
                s.push([
                    w[0].clone(),
                    w[1].clone(),
                    w[2].clone(),
                    vc[0].clone(),
                    vc[1].clone(),
                    vc[2].clone(),
                ]);
            }
        }
        // Filled at each body's place as the bodies are eliminated, leaves first.
        k.clear();
        k.resize(s.len(), std::array::from_fn(|_| T::zero()));
        dinv.clear();
        dinv.resize(square, T::zero());
        roots.clear();
        if inertia.len() != bodies.len() {
            inertia.clear();
            inertia.resize(bodies.len(), zero_block());
        }
        for (block, body) in inertia.iter_mut().zip(bodies) {
            write_mass_block(body, block);
        }
        let mut d: Block<T> = zero_block();
        let mut u: [[T; 6]; 6] = std::array::from_fn(|_| std::array::from_fn(|_| T::zero()));
        for &i in order.iter() {
            let node = &mut nodes[i];
            // Body i's articulated inertia, and its parent's (the ground's: none) to add to.
            let (a, to) = match node.parent {
                NONE => (&mut inertia[i], None),
                p => {
                    let (x, y) = pair_mut(inertia, i, p);
                    (x, Some(y))
                }
            };
            if node.joint == NONE {
                invert_definite(a, 6)?;
                node.at = roots.len();
                roots.push(a.clone());
                continue;
            }
            let n = node.free;
            let si = &s[node.at..node.at + n];
            if n == 1 {
                // One free screw (revolute, prismatic): the same operations, without the
                // loops over columns and the n × n buffers.
                let col = &si[0];
                let y: [&T; 6] = [&col[3], &col[4], &col[5], &col[0], &col[1], &col[2]];
                let u0: [T; 6] = std::array::from_fn(|r| {
                    let row = &a[6 * r..6 * r + 6];
                    let mut t = T::zero();
                    for q in 0..6 {
                        if T::IS_EXACT && y[q].is_zero() {
                            continue;
                        }
                        t += row[q].clone() * y[q];
                    }
                    t
                });
                let mut d1 = [power(&u0, col)];
                invert_definite(&mut d1, 1)?;
                let [d1] = d1;
                let kc: [T; 6] = std::array::from_fn(|r| u0[r].clone() * &d1);
                dinv[node.square] = d1;
                if let Some(to) = to {
                    eliminate(a, [(&kc, &u0)], &node.r, to);
                }
                k[node.at] = kc;
                continue;
            }
            // U = I^A S column by column (I^A on [v; ω], S's columns [ω; v]: a wrench).
            for (c, col) in si.iter().enumerate() {
                let y: [&T; 6] = [&col[3], &col[4], &col[5], &col[0], &col[1], &col[2]];
                for r in 0..6 {
                    let row = &a[6 * r..6 * r + 6];
                    let mut t = T::zero();
                    for q in 0..6 {
                        if T::IS_EXACT && y[q].is_zero() {
                            continue;
                        }
                        t += row[q].clone() * y[q];
                    }
                    u[c][r] = t;
                }
            }
            // D = Sᵀ U (the power of U's wrenches on S's twists), then D⁻¹.
            for x in 0..n {
                for y in 0..=x {
                    let t = power(&u[y], &si[x]);
                    d[n * x + y] = t.clone();
                    d[n * y + x] = t;
                }
            }
            invert_definite(&mut d[..n * n], n)?;
            dinv[node.square..node.square + n * n].clone_from_slice(&d[..n * n]);
            // K = U D⁻¹.
            for c in 0..n {
                let mut kc = u[0].clone();
                let d0 = &d[c];
                for x in kc.iter_mut() {
                    *x *= d0;
                }
                for (b, ub) in u.iter().enumerate().take(n).skip(1) {
                    let db = &d[n * b + c];
                    for (x, y) in kc.iter_mut().zip(ub) {
                        *x += y.clone() * db;
                    }
                }
                k[node.at + c] = kc;
            }
            if let Some(to) = to {
                eliminate(a, k[node.at..node.at + n].iter().zip(&u), &node.r, to);
            }
        }
        Some(())
    }

    /// W{E}: the twist of every body for the impulse `e` (one wrench [F; M] about each
    /// body's centre), by one pass up and one down (module docs).
    pub(crate) fn response(&self, e: &[Screw<T>]) -> Vec<Screw<T>> {
        let mut z: Vec<Screw<T>> = e.to_vec();
        self.response_into(&mut z, &mut ResponseScratch::default());
        z
    }

    /// [`Articulated::response`] in place: `z` holds the impulse on entry and its twists on
    /// return; `scratch` is reused (nothing is allocated once it has grown to the system).
    pub(crate) fn response_into(&self, z: &mut [Screw<T>], scratch: &mut ResponseScratch<T>) {
        let ResponseScratch { w, live } = scratch;
        // Whether a body's z can be nonzero: an impulse on a few bodies reaches their
        // ancestors only.
        live.clear();
        live.extend(z.iter().map(|s| s.0.iter().any(|x| !x.is_zero())));
        // w_i = S_iᵀ z_i, n_i numbers per body, at the body's columns.
        w.clear();
        w.resize(self.s.len(), T::zero());
        for &i in &self.order {
            let node = &self.nodes[i];
            if node.joint == NONE || !live[i] {
                continue;
            }
            let cols = node.at..node.at + node.free;
            let zi = &mut z[i].0;
            if node.free == 1 {
                // One free screw (revolute, prismatic): the same, without the loops.
                let (sc, kc) = (&self.s[node.at], &self.k[node.at]);
                let wc = power(zi.as_slice(), sc);
                if !(T::IS_EXACT && wc.is_zero()) {
                    for r in 0..6 {
                        zi[r] -= kc[r].clone() * &wc;
                    }
                }
                w[node.at] = wc;
            } else {
                for ((sc, kc), wc) in self.s[cols.clone()]
                    .iter()
                    .zip(&self.k[cols.clone()])
                    .zip(&mut w[cols])
                {
                    *wc = power(zi.as_slice(), sc);
                    if T::IS_EXACT && wc.is_zero() {
                        continue;
                    }
                    for r in 0..6 {
                        zi[r] -= kc[r].clone() * &*wc;
                    }
                }
            }
            if node.parent != NONE {
                let za = z[i].clone();
                carry_wrench(&za, &node.r, &mut z[node.parent]);
                live[node.parent] = true;
            }
        }
        // Down: z_i becomes a_i, a twist [ω; v] (read by the children after).
        for &i in self.order.iter().rev() {
            let node = &self.nodes[i];
            if node.joint == NONE {
                let inv = &self.roots[node.at];
                let zi = &z[i].0;
                // (I^A)⁻¹ maps [F; M] to [v; ω].
                let y: [T; 6] = std::array::from_fn(|r| {
                    let mut t = T::zero();
                    for c in 0..6 {
                        t += inv[6 * r + c].clone() * &zi[c];
                    }
                    t
                });
                z[i] = Screw(nalgebra::SVector::<T, 6>::from_fn(|k, _| {
                    y[(k + 3) % 6].clone()
                }));
                continue;
            }
            let mut ai = match node.parent {
                NONE => Screw::zero(),
                p => carry_twist(&z[p], &node.r),
            };
            let n = node.free;
            if n == 1 {
                let q = self.dinv[node.square].clone() * &w[node.at]
                    - power(&self.k[node.at], ai.0.as_slice());
                if !(T::IS_EXACT && q.is_zero()) {
                    for (x, y) in ai.0.iter_mut().zip(&self.s[node.at]) {
                        *x += y.clone() * &q;
                    }
                }
                z[i] = ai;
                continue;
            }
            let cols = node.at..node.at + n;
            let di = &self.dinv[node.square..node.square + n * n];
            let wi = &w[cols.clone()];
            let mut q: [T; 6] = std::array::from_fn(|_| T::zero());
            for (c, kc) in self.k[cols.clone()].iter().enumerate() {
                let mut t = -power(kc, ai.0.as_slice());
                for (x, y) in di[n * c..n * c + n].iter().zip(wi) {
                    t += x.clone() * y;
                }
                q[c] = t;
            }
            for (sc, qc) in self.s[cols].iter().zip(&q) {
                if T::IS_EXACT && qc.is_zero() {
                    continue;
                }
                for r in 0..6 {
                    ai.0[r] += sc[r].clone() * qc;
                }
            }
            z[i] = ai;
        }
    }

    /// The joints' impulses λ (one per blocked screw, joint by joint, as `screws` orders
    /// them) from `wrench`, the wrench Σ_j H_j(i) λ_j the joints exert on each body
    /// (M_i Δ{V_i} + Σ P̂ {Ê}_i), consumed (module docs).
    pub(crate) fn impulses(
        &self,
        bodies: &[SystemBody<T>],
        screws: &JointScrews<T>,
        mut wrench: Vec<Screw<T>>,
    ) -> Vec<T> {
        let mut lambda = vec![T::zero(); screws.rows()];
        for &i in &self.order {
            let node = &self.nodes[i];
            if node.joint == NONE {
                continue;
            }
            let f = wrench[i].0.clone();
            // About the origin: M_O = M_C + C × F.
            let c = &bodies[i].centre;
            let fo = [
                f[0].clone(),
                f[1].clone(),
                f[2].clone(),
                f[3].clone() + c[1].clone() * &f[2] - c[2].clone() * &f[1],
                f[4].clone() + c[2].clone() * &f[0] - c[0].clone() * &f[2],
                f[5].clone() + c[0].clone() * &f[1] - c[1].clone() * &f[0],
            ];
            let (start, columns) = screws.columns(node.joint);
            for (k, &col) in columns.iter().enumerate() {
                let x = fo[col as usize].clone();
                lambda[start + k] = if node.first { x } else { -x };
            }
            if node.parent != NONE {
                carry_wrench(&Screw(f), &node.r, &mut wrench[node.parent]);
            }
        }
        lambda
    }
}

/// M_i = diag(m I, J) on [v; ω], written over `d`.
fn write_mass_block<T: Scalar>(body: &SystemBody<T>, d: &mut Block<T>) {
    for x in d.iter_mut() {
        x.set_zero();
    }
    for k in 0..3 {
        d[7 * k] = body.body.mass.clone();
    }
    match &body.body.inertia {
        Inertia::Principal(j) => {
            for k in 0..3 {
                d[21 + 7 * k] = j[k].clone();
            }
        }
        inertia => {
            let j = inertia.matrix();
            for r in 0..3 {
                for c in 0..3 {
                    d[6 * (3 + r) + 3 + c] = j[(r, c)].clone();
                }
            }
        }
    }
}

/// `&mut v[i]` and `&mut v[j]`, i ≠ j.
fn pair_mut<X>(v: &mut [X], i: usize, j: usize) -> (&mut X, &mut X) {
    debug_assert_ne!(i, j);
    if i < j {
        let (lo, hi) = v.split_at_mut(j);
        (&mut lo[i], &mut hi[0])
    } else {
        let (lo, hi) = v.split_at_mut(i);
        (&mut hi[0], &mut lo[j])
    }
}

fn zero_block<T: Scalar>() -> Block<T> {
    [(); 36].map(|_| T::zero())
}

/// The power of the wrench `f` = [F; M] on the twist `t` = [ω; v]: F·v + M·ω (the mixed
/// product of eq. 6).
fn power<T: Scalar>(f: &[T], t: &[T]) -> T {
    let mut s = T::zero();
    for k in 0..3 {
        if !(T::IS_EXACT && f[k].is_zero()) {
            s += f[k].clone() * &t[k + 3];
        }
        if !(T::IS_EXACT && f[k + 3].is_zero()) {
            s += f[k + 3].clone() * &t[k];
        }
    }
    s
}

/// `to` += the wrench `z` = [F; M] at the child carried to its parent: [F; M + r × F].
fn carry_wrench<T: Scalar>(z: &Screw<T>, r: &[T; 3], to: &mut Screw<T>) {
    let (z, to) = (&z.0, &mut to.0);
    for k in 0..6 {
        to[k] += &z[k];
    }
    to[3] += r[1].clone() * &z[2] - r[2].clone() * &z[1];
    to[4] += r[2].clone() * &z[0] - r[0].clone() * &z[2];
    to[5] += r[0].clone() * &z[1] - r[1].clone() * &z[0];
}

/// The parent's twist [ω; v] carried to the child: [ω; v + ω × r].
fn carry_twist<T: Scalar>(y: &Screw<T>, r: &[T; 3]) -> Screw<T> {
    let y = &y.0;
    Screw(nalgebra::SVector::<T, 6>::new(
        y[0].clone(),
        y[1].clone(),
        y[2].clone(),
        y[3].clone() + y[1].clone() * &r[2] - y[2].clone() * &r[1],
        y[4].clone() + y[2].clone() * &r[0] - y[0].clone() * &r[2],
        y[5].clone() + y[0].clone() * &r[1] - y[1].clone() * &r[0],
    ))
}

/// r × v.
fn cross<T: Scalar>(r: &[T; 3], v: [&T; 3]) -> [T; 3] {
    [
        r[1].clone() * v[2] - r[2].clone() * v[1],
        r[2].clone() * v[0] - r[0].clone() * v[2],
        r[0].clone() * v[1] - r[1].clone() * v[0],
    ]
}

/// I^a = I^A − Σ_c K_c U_cᵀ (eq. 7.38) in `a` (its lower triangle, then mirrored), carried to
/// the parent's `to`.
fn eliminate<'a, T: Scalar + 'a>(
    a: &mut Block<T>,
    ku: impl IntoIterator<Item = (&'a [T; 6], &'a [T; 6])>,
    r: &[T; 3],
    to: &mut Block<T>,
) {
    for (kb, ub) in ku {
        for i in 0..6 {
            for j in 0..=i {
                a[6 * i + j] -= kb[i].clone() * &ub[j];
            }
        }
    }
    for i in 0..6 {
        for j in 0..i {
            a[6 * j + i] = a[6 * i + j].clone();
        }
    }
    transport(a, r, to);
}

/// `to` += Xᵀ a X for the symmetric `a` = [[A, B], [Bᵀ, C]] (3 × 3 blocks, on [v; ω]) and
/// X = [[I, R], [0, I]], R ω = ω × r: [[A, T], [Tᵀ, Rᵀ T + Bᵀ R + C]] with T = A R + B. Row i
/// of M R is r × (row i of M) and column j of Rᵀ M is r × (column j of M).
fn transport<T: Scalar>(a: &Block<T>, r: &[T; 3], to: &mut Block<T>) {
    let at = |i: usize, j: usize| &a[6 * i + j];
    // T = A R + B, row by row (A is symmetric: its rows are its columns).
    let t: [[T; 3]; 3] = std::array::from_fn(|i| {
        let x = cross(r, [at(i, 0), at(i, 1), at(i, 2)]);
        std::array::from_fn(|j| x[j].clone() + at(i, 3 + j))
    });
    // Column j of Rᵀ T and of Rᵀ B.
    let rtt: [[T; 3]; 3] = std::array::from_fn(|j| cross(r, [&t[0][j], &t[1][j], &t[2][j]]));
    let rtb: [[T; 3]; 3] =
        std::array::from_fn(|j| cross(r, [at(0, 3 + j), at(1, 3 + j), at(2, 3 + j)]));
    for i in 0..3 {
        for j in 0..3 {
            to[6 * i + j] += at(i, j);
            to[6 * i + 3 + j] += &t[i][j];
            to[6 * (3 + j) + i] += &t[i][j];
            // (Rᵀ T)_ij + (Bᵀ R)_ij + C_ij, (Bᵀ R)_ij = (Rᵀ B)_ji.
            let x = rtt[j][i].clone() + &rtb[i][j] + at(3 + i, 3 + j);
            to[6 * (3 + i) + 3 + j] += x;
        }
    }
}

/// The bodies leaves first and their nodes (parent, joint, side), when the joints — edges
/// between bodies, or between a body and the ground — form a forest; `None` when they close
/// a loop (through the ground too). Each tree is rooted at its body held to the ground, or
/// at its first body.
fn forest<T: Scalar>(b: usize, joints: &[SystemJoint<T>]) -> Option<(Vec<usize>, Vec<Node<T>>)> {
    // Union–find over the bodies and the ground (node b): a joint whose ends are already
    // connected closes a loop.
    let mut set: Vec<usize> = (0..=b).collect();
    fn find(set: &mut [usize], mut i: usize) -> usize {
        while set[i] != i {
            set[i] = set[set[i]];
            i = set[i];
        }
        i
    }
    for j in joints {
        let (x, y) = (
            find(&mut set, j.pair.first),
            find(&mut set, j.pair.second.unwrap_or(b)),
        );
        if x == y {
            return None;
        }
        set[x] = y;
    }
    // The joints at each body (compressed rows).
    let mut start = vec![0; b + 1];
    for j in joints {
        start[j.pair.first + 1] += 1;
        if let Some(s) = j.pair.second {
            start[s + 1] += 1;
        }
    }
    for i in 0..b {
        start[i + 1] += start[i];
    }
    let mut incident = vec![0; start[b]];
    let mut fill = start.clone();
    for (k, j) in joints.iter().enumerate() {
        for body in std::iter::once(j.pair.first).chain(j.pair.second) {
            incident[fill[body]] = k;
            fill[body] += 1;
        }
    }
    let mut nodes: Vec<Node<T>> = (0..b)
        .map(|_| Node {
            parent: NONE,
            joint: NONE,
            first: true,
            free: 0,
            at: 0,
            square: 0,
            r: std::array::from_fn(|_| T::zero()),
        })
        .collect();
    let mut seen = vec![false; b];
    let mut order = Vec::with_capacity(b);
    // Breadth first from the roots: the bodies held to the ground, then any body not reached.
    let grounded = joints
        .iter()
        .enumerate()
        .filter(|(_, j)| j.pair.second.is_none())
        .map(|(k, j)| (j.pair.first, k));
    let free = (0..b).map(|i| (i, NONE));
    for (root, joint) in grounded.chain(free) {
        if seen[root] {
            continue;
        }
        seen[root] = true;
        nodes[root].joint = joint;
        let from = order.len();
        order.push(root);
        let mut at = from;
        while at < order.len() {
            let i = order[at];
            at += 1;
            for &k in &incident[start[i]..start[i + 1]] {
                let pair = joints[k].pair;
                let Some(second) = pair.second else { continue };
                let other = if pair.first == i { second } else { pair.first };
                if !seen[other] {
                    seen[other] = true;
                    nodes[other].parent = i;
                    nodes[other].joint = k;
                    nodes[other].first = pair.first == other;
                    order.push(other);
                }
            }
        }
    }
    order.reverse();
    Some((order, nodes))
}

/// The symmetric definite n × n matrix `a` (row-major, n ≤ 6) replaced by its inverse:
/// a = L D Lᵀ without pivoting, then a⁻¹ = L⁻ᵀ D⁻¹ L⁻¹. Every pivot must be positive and not
/// negligible against the largest diagonal entry (else `None`: floats only).
fn invert_definite<T: Scalar>(a: &mut [T], n: usize) -> Option<()> {
    if n == 1 {
        if a[0].signum_i8() <= 0 {
            return None;
        }
        a[0] = T::one() / &a[0];
        return Some(());
    }
    let mut scale = T::zero();
    for k in 0..n {
        if a[(n + 1) * k].abs_gt(&scale) {
            scale = a[(n + 1) * k].clone();
        }
    }
    // L (strictly below the diagonal) and D (on it), in place; the lower triangle is read.
    for k in 0..n {
        let d = a[(n + 1) * k].clone();
        if d.signum_i8() <= 0 || d.is_negligible(&scale, 6) {
            return None;
        }
        // a_ij −= a_ik a_jk / d below the pivot (rows from the bottom up, so that a_jk, j ≤ i,
        // is still unscaled), then column k becomes L.
        for i in (k + 1..n).rev() {
            if T::IS_EXACT && a[n * i + k].is_zero() {
                continue;
            }
            let l = a[n * i + k].clone() / &d;
            for j in k + 1..=i {
                let t = l.clone() * &a[n * j + k];
                a[n * i + j] -= t;
            }
            a[n * i + k] = l;
        }
    }
    // M = L⁻¹ (unit lower triangular): m_ij = −Σ_{j≤k<i} l_ik m_kj.
    let mut m: [T; 36] = zero_block();
    for i in 0..n {
        m[7 * i] = T::one();
        for j in 0..i {
            let mut t = a[n * i + j].clone();
            for k in j + 1..i {
                t += a[n * i + k].clone() * &m[6 * k + j];
            }
            m[6 * i + j] = -t;
        }
    }
    // a⁻¹ = Mᵀ D⁻¹ M: (a⁻¹)_rc = Σ_{k ≥ max(r, c)} m_kr m_kc / d_k.
    let inv_d: [T; 6] = std::array::from_fn(|k| match k < n {
        true => T::one() / &a[(n + 1) * k],
        false => T::zero(),
    });
    for r in 0..n {
        for c in 0..=r {
            let mut t = T::zero();
            for k in r..n {
                t += m[6 * k + r].clone() * &m[6 * k + c] * &inv_d[k];
            }
            a[n * r + c] = t.clone();
            a[n * c + r] = t;
        }
    }
    Some(())
}
