//! The analysis in the space of the contact wrenches: cost linear in the number of contacts.
//!
//! G is a Gram matrix (eq. 12, 86): ĝ_ij = ⟨Ê_i, Ê_j⟩ with ⟨a, b⟩ = {a}ᵀ η W {b}, W the body's
//! mobility (\[M\]⁻¹ for a free body, the constrained mobility of eq. 85 otherwise). Writing
//! E = [Ê_1 … Ê_N] (6×N), Ĝ = Eᵀ η W E has rank r ≤ 6 (≤ the degrees of freedom): beyond six
//! contacts G is singular, and every question [`crate::analysis`] asks of it is one about r
//! wrenches. Pivoted Gram–Schmidt in ⟨·,·⟩ (as [`crate::impact::gram_schmidt`], without
//! normalising: no square root, so exact types run it) picks r independent contacts P — at each
//! step the contact whose residual has the largest d_j = ⟨res_j, res_j⟩, stopping when none
//! exceeds N·ε·max ĝ_ii (floats) or is nonzero (exact types) — and writes
//!
//! ```text
//! Ê_{p_k} = q̂_k + Σ_{l<k} u_lk q̂_l,   ⟨q̂_k, q̂_l⟩ = d_k δ_kl,   G_PP = Uᵀ D U        (r×r)
//! Ê_j ≡ Σ_k c_jk Ê_{p_k}   (equal in the metric: ⟨Ê_j − Σ c_jk Ê_{p_k}, ·⟩ = 0),   U c_j = μ_j
//! Ĝ = Cᵀ G_PP C,   C = [c_1 … c_N]   (r×N, the identity on the columns of P)
//! ```
//!
//! with μ_jl = ⟨q̂_l, Ê_j⟩ / d_l. So, in O(N·r²) work and O(N·r) memory, for G x = b (eq. 15,
//! 21):
//!
//! * **rank G = r**; Δ = Π d_k when r = N, else 0; the null space is ker C, of dimension N − r,
//!   spanned by e_j − Σ_k c_jk e_{p_k} for the contacts j ∉ P;
//! * **compatibility** (eq. 61–68): range Ĝ = range Cᵀ, so b is compatible iff b_j = c_jᵀ b_P
//!   for every j ∉ P, and then G x = b ⟺ C x = α := G_PP⁻¹ b_P (Cᵀ is injective);
//! * **the least-norm impulses**: with P̂ = s∘x (s_i = 1 for Newton, 1 + k_i^P for Poisson,
//!   eq. 23) and the physical norm Σ |x̂_i|² P̂_i², the minimiser over C S⁻¹ P̂ = α is
//!   P̂_i = a_iᵀλ / |x̂_i|², a_i = c_i / s_i, with (Σ_i a_i a_iᵀ / |x̂_i|²) λ = α (r×r) — the
//!   same member [`crate::analysis`]'s N×N route finds (a strictly convex minimum on an affine
//!   set is unique);
//! * **what the impulses fix** (eq. 24–28, 32): the twist {v} = {v⁰} − Σ P̂_j W Ê_j, the contact
//!   velocities v̂_ia = v̂_ia⁰ + {Ê_ia}ᵀ η ({v} − {v⁰}) and both energies, all in O(N);
//! * **whether the twist is fixed along the family**: the direction of contact j ∉ P moves the
//!   twist by s_j W Ê_j − Σ_k c_jk s_{p_k} W Ê_{p_k} (zero for Newton, eq. 57–58);
//! * **which impulses vary**: every j ∉ P, and p_k iff some c_jk ≠ 0.
//!
//! The nonzero eigenvalues of G are those of the r×r matrix G_PP·C S⁻²Cᵀ (S = diag|x̂_i|: the
//! physical G is S⁻¹ĜS⁻¹), so the condition number is ∞ whenever N > r. Nothing N×N is formed.

use crate::analysis::{Admissibility, Classification, ModelAnalysis};
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Outcome, SolveError};
use crate::mechanics::body::Mobility;
use crate::mechanics::contact::ContactFrame;
use crate::mechanics::screw::Screw;
use crate::scalar::Scalar;

/// The contact wrenches of a problem, reduced to r independent ones (module docs).
#[derive(Clone, Debug)]
pub struct WrenchSpace<T: Scalar> {
    problem: Problem<T>,
    frames: Vec<ContactFrame<T>>,
    /// (v̂_ix⁰, v̂_iy⁰, v̂_iz⁰) per contact (eq. 8).
    before_hat: Vec<[T; 3]>,
    /// W{Ê_jx}.
    responses: Vec<Screw<T>>,
    /// ĝ_ii = ⟨Ê_i, Ê_i⟩.
    diagonal: Vec<T>,
    /// The pivot contacts p_0 … p_{r−1}.
    pivots: Vec<usize>,
    /// d_k = ⟨q̂_k, q̂_k⟩.
    d: Vec<T>,
    /// U, r×r row-major, u_lk (l < k) above the unit diagonal.
    u: Vec<T>,
    /// c_j, N×r row-major (e_k for the pivot p_k).
    c: Vec<T>,
    /// Whether each contact is a pivot.
    is_pivot: Vec<bool>,
    /// N·ε·max ĝ_ii (floats).
    tolerance: Option<f64>,
    kinetic_before: T,
}

impl<T: Scalar> WrenchSpace<T> {
    /// Frames, velocities, responses and the pivoted Gram–Schmidt of the normals' wrenches:
    /// O(N) memory, O(N·r) work.
    ///
    /// # Errors
    /// A contact frame that cannot be built (as [`crate::impact::solve::Impact::assemble`]).
    pub fn build(problem: &Problem<T>) -> Result<Self, SolveError> {
        let n = problem.contacts().len();
        let mut frames = Vec::with_capacity(n);
        let mut before_hat = Vec::with_capacity(n);
        let mut responses = Vec::with_capacity(n);
        let mut diagonal = Vec::with_capacity(n);
        for (i, c) in problem.contacts().iter().enumerate() {
            let f = ContactFrame::new(i, c, problem.velocity())?;
            before_hat.push(f.velocity(problem.velocity()));
            let r = problem.response(&f.axes[0]);
            diagonal.push(f.axes[0].reciprocal(&r));
            responses.push(r);
            frames.push(f);
        }
        let gmax = diagonal.iter().map(T::to_f64).fold(0.0, f64::max);
        let tolerance = (!T::IS_EXACT).then(|| n as f64 * T::epsilon_f64() * gmax);
        // Residuals and their responses, updated in place; μ_jl per contact.
        let mut res: Vec<Screw<T>> = frames.iter().map(|f| f.axes[0].clone()).collect();
        let mut wres = responses.clone();
        let mut norms = diagonal.clone();
        let mut mu = vec![T::zero(); n * 6];
        let mut is_pivot = vec![false; n];
        let (mut pivots, mut d, mut q, mut wq) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for k in 0..6.min(n) {
            let mut best: Option<usize> = None;
            for j in (0..n).filter(|&j| !is_pivot[j]) {
                if best.is_none_or(|b| norms[j].abs_gt(&norms[b])) {
                    best = Some(j);
                }
            }
            let Some(p) = best else { break };
            let dk = norms[p].clone();
            let zero = match tolerance {
                Some(t) => dk.to_f64() <= t,
                None => dk.signum_i8() <= 0,
            };
            if zero {
                break;
            }
            is_pivot[p] = true;
            let (qk, wqk) = (res[p].clone(), wres[p].clone());
            for j in (0..n).filter(|&j| !is_pivot[j]) {
                let m = qk.reciprocal(&wres[j]) / &dk;
                res[j].add_scaled(&-m.clone(), &qk);
                wres[j].add_scaled(&-m.clone(), &wqk);
                norms[j] = res[j].reciprocal(&wres[j]);
                mu[j * 6 + k] = m;
            }
            pivots.push(p);
            d.push(dk);
            q.push(qk);
            wq.push(wqk);
        }
        let r = pivots.len();
        let mut u = vec![T::zero(); r * r];
        for k in 0..r {
            u[k * r + k] = T::one();
            for l in 0..k {
                u[l * r + k] = mu[pivots[k] * 6 + l].clone();
            }
        }
        let mut c = vec![T::zero(); n * r];
        for j in 0..n {
            if is_pivot[j] {
                continue;
            }
            // U c_j = μ_j, back substitution.
            for k in (0..r).rev() {
                let mut s = mu[j * 6 + k].clone();
                for m in k + 1..r {
                    s -= u[k * r + m].clone() * &c[j * r + m];
                }
                c[j * r + k] = s;
            }
        }
        for (k, &p) in pivots.iter().enumerate() {
            c[p * r + k] = T::one();
        }
        Ok(WrenchSpace {
            kinetic_before: problem.body().kinetic_energy(problem.velocity()),
            problem: problem.clone(),
            frames,
            before_hat,
            responses,
            diagonal,
            pivots,
            d,
            u,
            c,
            is_pivot,
            tolerance,
        })
    }

    /// N.
    pub fn contacts(&self) -> usize {
        self.frames.len()
    }

    /// rank G.
    pub fn rank(&self) -> usize {
        self.pivots.len()
    }

    /// The problem.
    pub fn problem(&self) -> &Problem<T> {
        &self.problem
    }

    /// The contact frames.
    pub fn frames(&self) -> &[ContactFrame<T>] {
        &self.frames
    }

    /// (v̂_ix⁰, v̂_iy⁰, v̂_iz⁰) per contact (eq. 8).
    pub fn before_hat(&self) -> &[[T; 3]] {
        &self.before_hat
    }

    /// ĝ_ii per contact.
    pub fn diagonal(&self) -> &[T] {
        &self.diagonal
    }

    /// T⁰ = ½ {v⁰}ᵀ η M {v⁰}.
    pub fn kinetic_before(&self) -> &T {
        &self.kinetic_before
    }

    /// The zero-pivot tolerance (floats).
    pub fn tolerance(&self) -> Option<f64> {
        self.tolerance
    }

    /// Δ̂ = det Ĝ: Π d_k when r = N, else zero.
    pub fn det_hat(&self) -> T {
        if self.rank() < self.contacts() {
            return T::zero();
        }
        self.d.iter().fold(T::one(), |p, d| p * d)
    }

    /// The f64 eigenvalues of the physical G's r×r reduction G_PP·C S⁻² Cᵀ (module docs):
    /// the nonzero eigenvalues of G.
    pub fn nonzero_eigenvalues(&self) -> Vec<f64> {
        let (n, r) = (self.contacts(), self.rank());
        if r == 0 {
            return Vec::new();
        }
        // G_PP = Uᵀ D U in f64, and K = Σ_j c_j c_jᵀ / |x̂_j|².
        let u = |l: usize, k: usize| self.u[l * r + k].to_f64();
        let mut gpp = nalgebra::DMatrix::<f64>::zeros(r, r);
        for a in 0..r {
            for b in 0..r {
                gpp[(a, b)] = (0..=a.min(b))
                    .map(|l| u(l, a) * self.d[l].to_f64() * u(l, b))
                    .sum();
            }
        }
        let mut k = nalgebra::DMatrix::<f64>::zeros(r, r);
        for j in 0..n {
            let w = self.frames[j].norm2[0].to_f64();
            for a in 0..r {
                for b in 0..r {
                    k[(a, b)] += self.c[j * r + a].to_f64() * self.c[j * r + b].to_f64() / w;
                }
            }
        }
        // Symmetric form Lᵀ K L with G_PP = L Lᵀ (same eigenvalues as G_PP K).
        match gpp.cholesky() {
            Some(ch) => {
                let l = ch.l();
                (l.transpose() * k * l)
                    .symmetric_eigenvalues()
                    .iter()
                    .copied()
                    .collect()
            }
            None => vec![0.0; r],
        }
    }

    /// cond₂ G: ∞ when N > r (or the reduction is singular to working precision).
    pub fn condition_number(&self) -> f64 {
        let n = self.contacts();
        if n == 0 {
            return 1.0;
        }
        if self.rank() < n {
            return f64::INFINITY;
        }
        let eig = self.nonzero_eigenvalues();
        let max = eig.iter().copied().fold(f64::MIN, f64::max);
        let min = eig.iter().copied().fold(f64::MAX, f64::min);
        if min <= max * n as f64 * f64::EPSILON || min <= 0.0 {
            f64::INFINITY
        } else {
            max / min
        }
    }

    /// The right-hand side b of the model (as [`crate::impact::solve::Impact`]'s).
    fn rhs(&self, model: Model, i: usize) -> T {
        let v0 = self.before_hat[i][0].clone();
        match model {
            Model::Newton => (T::one() + &self.problem.contacts()[i].k_newton) * &v0,
            Model::Poisson => v0,
        }
    }

    fn scale(&self, model: Model, i: usize) -> T {
        match model {
            Model::Newton => T::one(),
            Model::Poisson => T::one() + &self.problem.contacts()[i].k_poisson,
        }
    }

    /// α = G_PP⁻¹ b_P with G_PP = Uᵀ D U; `None` when b ∉ range G.
    fn alpha(&self, model: Model) -> Option<Vec<T>> {
        let (n, r) = (self.contacts(), self.rank());
        let bp: Vec<T> = self.pivots.iter().map(|&p| self.rhs(model, p)).collect();
        for j in (0..n).filter(|&j| !self.is_pivot[j]) {
            let bj = self.rhs(model, j);
            let mut s = -bj.clone();
            let mut scale = bj;
            for k in 0..r {
                let t = self.c[j * r + k].clone() * &bp[k];
                if t.abs_gt(&scale) {
                    scale = t.clone();
                }
                s += t;
            }
            if !s.is_negligible(&scale, 64 * n) {
                return None;
            }
        }
        // Uᵀ y = b_P (unit lower), z = D⁻¹ y, U α = z (unit upper).
        let mut y = bp;
        for k in 0..r {
            for l in 0..k {
                let t = self.u[l * r + k].clone() * &y[l];
                y[k] -= t;
            }
        }
        for k in 0..r {
            y[k] = y[k].clone() / &self.d[k];
        }
        for k in (0..r).rev() {
            for m in k + 1..r {
                let t = self.u[k * r + m].clone() * &y[m];
                y[k] -= t;
            }
        }
        Some(y)
    }

    /// The analysis of `model` (the same contract as the N×N route of [`crate::analysis`]),
    /// without the family's basis: `family` is empty and `nullity` = N − r.
    pub fn analyze_model(&self, model: Model) -> ModelAnalysis<T> {
        let (n, r) = (self.contacts(), self.rank());
        let approaching: Vec<bool> = self
            .before_hat
            .iter()
            .map(|v| v[0].signum_i8() > 0)
            .collect();
        let Some(alpha) = self.alpha(model) else {
            return ModelAnalysis::incompatible(model, r + 1, &approaching);
        };
        // (Σ a_i a_iᵀ / |x̂_i|²) λ = α, a_i = c_i / s_i.
        let s: Vec<T> = (0..n).map(|i| self.scale(model, i)).collect();
        let mut m = vec![T::zero(); r * r];
        let mut a = vec![T::zero(); r];
        for i in 0..n {
            let w = self.frames[i].norm2[0].clone() * &s[i] * &s[i];
            for k in 0..r {
                a[k] = self.c[i * r + k].clone() / &w;
            }
            for k in 0..r {
                for l in 0..r {
                    m[k * r + l] += a[k].clone() * &self.c[i * r + l];
                }
            }
        }
        let mut perm = vec![0; r];
        let mut lambda = alpha;
        if r > 0 {
            // Σ a_i a_iᵀ/|x̂_i|² ⪰ C_P C_Pᵀ / max = positive definite: the factorization holds.
            let _ = crate::linalg::factor_psd(&mut m, r, &mut perm);
            let mut work = vec![T::zero(); r];
            crate::linalg::solve_factored(&m, r, &perm, &mut lambda, &mut work);
        }
        let mut out = Outcome::default();
        for i in 0..n {
            let mut x = T::zero();
            for k in 0..r {
                x += self.c[i * r + k].clone() * &lambda[k];
            }
            // P̂_i = a_iᵀλ / |x̂_i|² = (c_iᵀλ) / (s_i |x̂_i|²).
            let p = x / &(self.frames[i].norm2[0].clone() * &s[i]);
            if model == Model::Poisson {
                out.compression_hat.push(p.clone() / &s[i]);
            }
            out.impulses_hat.push(p);
        }
        self.complete(&mut out);
        let reference = self.kinetic_before.clone() + &self.kinetic_before;
        let mut twist_fixed = true;
        let mut varies: Vec<bool> = self.is_pivot.iter().map(|p| !p).collect();
        for j in (0..n).filter(|&j| !self.is_pivot[j]) {
            let mut dv = Screw::zero();
            dv.add_scaled(&s[j], &self.responses[j]);
            for (k, &p) in self.pivots.iter().enumerate() {
                let c = &self.c[j * r + k];
                if !c.is_negligible(&T::one(), n) {
                    varies[p] = true;
                }
                dv.add_scaled(&-(c.clone() * &s[p]), &self.responses[p]);
            }
            if twist_fixed
                && !self
                    .problem
                    .body()
                    .kinetic_energy(&dv)
                    .is_negligible(&reference, 16 * n)
            {
                twist_fixed = false;
            }
        }
        let admissible = (0..n)
            .map(|i| Admissibility {
                approaching: approaching[i],
                compressive: Some(out.impulses_hat[i].signum_i8() > 0),
                varies: varies[i],
            })
            .collect();
        let gain = Some(out.kinetic_energy_loss.signum_i8() < 0);
        ModelAnalysis {
            model,
            augmented_rank: r,
            classification: if r == n {
                Classification::Unique
            } else {
                Classification::SingularCompatible
            },
            outcome: Some(out),
            family: Vec::new(),
            nullity: n - r,
            twist_fixed,
            admissible,
            energy_gain: gain,
        }
    }

    /// Everything that follows from `out.impulses_hat` in O(N) (eq. 24–26, 28, 32, 90–93).
    pub fn complete(&self, out: &mut Outcome<T>) {
        let problem = &self.problem;
        let mut dv = Screw::zero();
        for (p, r) in out.impulses_hat.iter().zip(&self.responses) {
            dv.add_scaled(&-p.clone(), r);
        }
        out.velocity = problem.velocity().clone();
        out.velocity.add_scaled(&T::one(), &dv);
        out.after_hat.clear();
        for (f, v0) in self.frames.iter().zip(&self.before_hat) {
            out.after_hat.push([
                v0[0].clone() + f.axes[0].reciprocal(&dv),
                v0[1].clone() + f.axes[1].reciprocal(&dv),
                v0[2].clone() + f.axes[2].reciprocal(&dv),
            ]);
        }
        out.lost_velocity_energy = problem.body().kinetic_energy(&dv);
        let mut loss = T::zero();
        for ((p, b), a) in out
            .impulses_hat
            .iter()
            .zip(&self.before_hat)
            .zip(&out.after_hat)
        {
            loss += p.clone() * &(b[0].clone() + &a[0]);
        }
        out.kinetic_energy_loss = loss / (T::one() + T::one());
        match problem.constraints() {
            Some(c) => {
                let axes = self.frames.iter().map(|f| &f.axes[0]);
                out.constraint_wrench = c.impulses_into(
                    &dv,
                    out.impulses_hat.iter().zip(axes),
                    &mut out.constraint_impulses,
                );
            }
            None => out.clear_constraint_impulses(),
        }
    }

    /// Whether G is diagonal (g_ij = 0 for i ≠ j, eq. 59–60) in O(N): the contacts with
    /// ĝ_ii ≠ 0 must be pairwise orthogonal, hence independent, hence at most r of them; a
    /// contact with ĝ_ii = 0 is orthogonal to every other (Cauchy–Schwarz in a semidefinite
    /// metric).
    pub fn g_diagonal(&self) -> bool {
        let n = self.contacts();
        let gmax = self
            .diagonal
            .iter()
            .fold(T::zero(), |m, x| if x.abs_gt(&m) { x.clone() } else { m });
        let live: Vec<usize> = (0..n)
            .filter(|&i| !self.diagonal[i].is_negligible(&gmax, 16 * n))
            .collect();
        if live.len() > self.rank() {
            return false;
        }
        live.iter().enumerate().all(|(a, &i)| {
            live[a + 1..].iter().all(|&j| {
                self.frames[i].axes[0]
                    .reciprocal(&self.responses[j])
                    .is_negligible(&self.diagonal[i], 16 * n)
            })
        })
    }
}
