//! The contact wrenches orthogonalised in the metric of the mobility: the twist after impact
//! without the impulses' split.
//!
//! G is a Gram matrix: ĝ_ij = ⟨Ê_i, Ê_j⟩ with the inner product ⟨a, b⟩ = {a}ᵀ η W {b} of the
//! body's mobility W (eq. 12, 86; positive definite for a free body, semidefinite for a
//! constrained one). Modified Gram–Schmidt in that inner product, without normalising (so no
//! square root is taken and the code is field-generic), writes the contact axes as
//!
//! ```text
//! Ê = Q U,   ⟨q̂_k, q̂_l⟩ = d_k δ_kl,   U unit upper triangular,   G = Uᵀ D U
//! ```
//!
//! (the square-root-free Cholesky factor of G, obtained from the wrenches themselves rather
//! than from G). Every simultaneous outcome is a wrench y = Σ_j P̂_j Ê_j = Σ_k w_k q̂_k. With
//! c⁰_k = {q̂_k}ᵀ η {v⁰} (the velocity before impact along the k-th orthogonal wrench;
//! c⁰ = U⁻ᵀ v̂⁰_x), a_k = c⁰_k / d_k (the wrench that stops every contact: G⁻¹ v̂⁰_x = U⁻¹ a)
//! and a mean k̄ of the model's coefficients k_i:
//!
//! ```text
//! Newton:   w± = (1 ± k̄) a ± D⁻¹ U⁻ᵀ (K − k̄) v̂⁰_x        (P̂ = G⁻¹ (1 + K) v̂⁰_x,  eq. 15)
//! Poisson:  w± = (1 ± k̄) a ± U (K − k̄) U⁻¹ a             (P̂ = (1 + K) G⁻¹ v̂⁰_x,  eq. 21–23)
//! P̂ = U⁻¹ w⁺,   P̂^c = U⁻¹ a                                     impulses (eq. 15, 21)
//! {v} − {v⁰} = −Σ_k w⁺_k W q̂_k                                              (eq. 24)
//! v̂_ix = v̂⁰_ix − Σ_{k ≤ i} u_ki d_k w⁺_k                                    (eq. 13)
//! E_p  = ½ Σ_k d_k (w⁺_k)²                                                   (eq. 28)
//! ΔE_c = ½ Σ_k d_k w⁺_k w⁻_k                                                 (eq. 32)
//! ```
//!
//! with K = diag(k_i): w⁺ = U P̂ are the coordinates of the impulses' wrench, w⁻ those of
//! G⁻¹(v̂⁰_x + v̂_x), the impulses that would give each contact its mean velocity; ΔE_c = ½ Σ P_i
//! (v_ix⁰ + v_ix) = ½ ⟨y⁺, y⁻⟩ and E_p = ½ ⟨y⁺, y⁺⟩ because W is the mobility (eq. 28, 32). The
//! identities hold for any k̄; k̄ = (min k_i + max k_i)/2 makes the correction vanish when the
//! k_i are equal.
//!
//! **Why.** The impulses are ill-determined when G is nearly singular (cond₂ G ≈ 10¹³ for two
//! contacts 10⁻⁸ apart): their split between nearby contacts is, the motion is not. Σ P̂_j W Ê_j
//! sums impulses of size 1/λ_min(G) into a twist of size 1/√λ_min(G), so it loses a factor
//! √cond G beyond what the problem allows. Here the small wrench q̂_2 = Ê_2 − u_12 Ê_1 is formed
//! as the difference of the axes themselves (to ε‖Ê‖ absolutely), d_2 from it, and the twist
//! from W q̂_k: its error follows cond(Ê) = √cond G, not cond G (Björck, *Numerical Methods for
//! Least Squares Problems*, §2.4: orthogonalising the columns rather than forming the normal
//! equations). A vector whose first pass removed more than half its squared norm is
//! orthogonalised a second time ("twice is enough": Giraud, Langou and Rozložník 2005), so Q
//! is orthogonal to working precision and the sums of squares above hold in floats too. The error bounds this gives are derived in [`crate::analysis::accuracy`].
//!
//! Float solves that take this route ([`crate::impact::route`]: a G too ill conditioned for
//! the normal equations to meet the accuracy contract, a constrained body, a full inertia
//! tensor) take the impulses from here too: formed from the wrenches, they are never less
//! accurate than the normal equations' and far more so near a singular G, where the split
//! between two contacts comes from the difference of their wrenches. The pivoted LDLᵀ of G
//! ([`crate::linalg::ldlt`]) still decides the rank and Δ; well-conditioned problems and
//! exact types solve G x = b, and in exact types every route gives the same numbers.

use crate::impact::outputs::Outputs;
use crate::impact::restitution::Model;
use crate::mechanics::body::Mobility;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Screws};
use crate::scalar::Scalar;

/// The contact normals' axis screws orthogonalised in ⟨a, b⟩ = {a}ᵀ η W {b} (module docs),
/// with the buffers of the solve (reused: repeated f64 solves allocate nothing).
#[derive(Clone, Debug)]
pub struct WrenchBasis<T: Scalar, S: Screws<T> = Screw<T>> {
    /// q̂_k.
    wrenches: Vec<S>,
    /// W q̂_k.
    responses: Vec<S>,
    /// d_k = ⟨q̂_k, q̂_k⟩ > 0.
    norms2: Vec<T>,
    /// U, N×N row-major: u_ik for i < k above the diagonal (1 on it, 0 below, not stored).
    u: Vec<T>,
    /// a_k = c⁰_k / d_k.
    stop: Vec<T>,
    /// w⁺_k.
    plus: Vec<T>,
    /// w⁻_k.
    minus: Vec<T>,
    /// Scratch of length N.
    work: Vec<T>,
}

impl<T: Scalar, S: Screws<T>> Default for WrenchBasis<T, S> {
    fn default() -> Self {
        WrenchBasis {
            wrenches: Vec::new(),
            responses: Vec::new(),
            norms2: Vec::new(),
            u: Vec::new(),
            stop: Vec::new(),
            plus: Vec::new(),
            minus: Vec::new(),
            work: Vec::new(),
        }
    }
}

/// What one model gives in the orthogonal basis (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct BasisOutcome<T: Scalar, S: Screws<T> = Screw<T>> {
    /// {v} − {v⁰}.
    pub twist_change: S,
    /// E_p.
    pub lost_velocity_energy: T,
    /// ΔE_c.
    pub kinetic_energy_loss: T,
}

impl<T: Scalar, S: Screws<T>> WrenchBasis<T, S> {
    /// Orthogonalise the axis screws in the metric of `mobility`: `axes` yields, in order,
    /// each axis screw Ê_k with its response W Ê_k (already computed for G). `false` when some
    /// d_k is not positive (G singular, or so nearly that rounding decided it): the basis is
    /// then unusable.
    ///
    /// A vector is orthogonalised a second time only when the first pass removed more than
    /// half its squared norm (Σ_i r_i² d_i > ĝ_kk/2, Pythagoras; Kahan and Parlett's test,
    /// Parlett, *The Symmetric Eigenvalue Problem*, §6.9): otherwise rounding cannot have left
    /// it measurably off orthogonal, and a well-conditioned G costs one pass. In exact types
    /// the second pass would change nothing.
    pub fn build<'a>(
        &mut self,
        axes: impl ExactSizeIterator<Item = (&'a S, &'a S)>,
        mobility: &impl Mobility<T, S>,
    ) -> bool
    where
        S: 'a,
    {
        self.build_from(axes.map(|(e, r)| (e, Some(r))), mobility)
    }

    /// [`WrenchBasis::build`] from the axis screws alone (`None` for a response not already
    /// computed): the first's response is then computed here, and a later vector's ĝ_kk for
    /// the test is taken after its first pass as Σ r_i² d_i + d_k (Pythagoras), from the
    /// response its wrench needs anyway — the lean path of a system
    /// ([`crate::impact::lean_system`]), which so takes one response per contact (two for a
    /// contact orthogonalised twice).
    pub fn build_from<'a>(
        &mut self,
        axes: impl ExactSizeIterator<Item = (&'a S, Option<&'a S>)>,
        mobility: &impl Mobility<T, S>,
    ) -> bool
    where
        S: 'a,
    {
        let n = axes.len();
        // The wrenches and responses are written over the previous solve's (a system's stack
        // of screws keeps its storage), and the extra ones dropped at the end.
        self.norms2.clear();
        self.u.clear();
        self.u.resize(n * n, T::zero());
        let two = T::one() + T::one();
        for (k, (e, response)) in axes.enumerate() {
            if k == self.responses.len() {
                self.responses.push(e.clone());
            }
            // ĝ_kk, when the response of the axis is known (always for the first).
            let own = match (k, response) {
                (_, Some(r)) => Some(e.reciprocal(r)),
                (0, None) => {
                    mobility.response_into(e, &mut self.responses[0]);
                    Some(e.reciprocal(&self.responses[0]))
                }
                _ => None,
            };
            if k < self.wrenches.len() {
                self.wrenches[k].clone_from(e);
            } else {
                self.wrenches.push(e.clone());
            }
            let (done, rest) = self.wrenches.split_at_mut(k);
            let q = &mut rest[0];
            let mut removed = T::zero();
            let mut d = None;
            for pass in 0..2 {
                for i in 0..k {
                    let r = q.reciprocal(&self.responses[i]) / &self.norms2[i];
                    q.add_scaled(&-r.clone(), &done[i]);
                    if pass == 0 {
                        removed += r.clone() * &r * &self.norms2[i];
                    }
                    self.u[i * n + k] += r;
                }
                if k == 0 || pass == 1 {
                    break;
                }
                let again = match &own {
                    Some(own) => (removed.clone() * &two).abs_gt(own),
                    None => {
                        // ĝ_kk = Σ r_i² d_i + d_k after one pass (Pythagoras): the test
                        // from the response the wrench needs anyway, taken again only when
                        // a second pass changes the wrench.
                        mobility.response_into(q, &mut self.responses[k]);
                        let dk = q.reciprocal(&self.responses[k]);
                        let again = (removed.clone() * &two).abs_gt(&(removed.clone() + &dk));
                        d = (!again).then_some(dk);
                        again
                    }
                };
                if !again {
                    break;
                }
            }
            // The first wrench is its axis: its response and norm are those of G.
            let d = if k == 0 {
                if let Some(r) = response {
                    self.responses[0].clone_from(r);
                }
                own.expect("the first axis's ĝ_11")
            } else if let Some(d) = d {
                d
            } else {
                mobility.response_into(q, &mut self.responses[k]);
                q.reciprocal(&self.responses[k])
            };
            if d.signum_i8() <= 0 {
                self.wrenches.truncate(k);
                self.responses.truncate(k);
                return false;
            }
            self.u[k * n + k] = T::one();
            self.norms2.push(d);
        }
        self.wrenches.truncate(n);
        self.responses.truncate(n);
        true
    }

    /// Room for `n` wrenches in every buffer, so that building and solving for at most `n`
    /// contacts allocates nothing.
    pub fn reserve(&mut self, n: usize) {
        fn room<T>(v: &mut Vec<T>, n: usize) {
            v.reserve(n.saturating_sub(v.len()));
        }
        room(&mut self.wrenches, n);
        room(&mut self.responses, n);
        room(&mut self.norms2, n);
        room(&mut self.u, n * n);
        room(&mut self.stop, n);
        room(&mut self.plus, n);
        room(&mut self.minus, n);
        room(&mut self.work, n);
    }

    /// Number of wrenches.
    pub fn len(&self) -> usize {
        self.norms2.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.norms2.is_empty()
    }

    /// u_ik (i < k): Ê_k = q̂_k + Σ_{i<k} u_ik q̂_i, so ĝ_kk = d_k + Σ_{i<k} u_ik² d_i.
    pub fn coefficient(&self, i: usize, k: usize) -> &T {
        &self.u[i * self.len() + k]
    }

    /// d_k = ⟨q̂_k, q̂_k⟩: the pivots of G = Uᵀ D U, so Δ̂ = Π d_k.
    pub fn norms2(&self) -> &[T] {
        &self.norms2
    }

    /// The outcome of `model` for the twist before impact `velocity`, the `contacts` (for
    /// their k_i) and the velocities before impact `before` (v̂⁰_ia, eq. 8); the velocities
    /// along the normals after impact are then [`WrenchBasis::normal_velocity`]. The twist
    /// change and the energies are formed only when `needs` holds [`Outputs::TWIST`] and
    /// [`Outputs::ENERGIES`] (zero otherwise), each by the same operations either way.
    pub fn solve(
        &mut self,
        model: Model,
        velocity: &S,
        contacts: &[Contact<T>],
        before: &[[T; 3]],
        needs: Outputs,
    ) -> BasisOutcome<T, S> {
        self.coordinates(model, velocity, contacts, before);
        let n = self.len();
        let two = T::one() + T::one();
        let mut twist_change = velocity.zero_like();
        let (mut lost, mut loss) = (T::zero(), T::zero());
        let (twist, energies) = (
            needs.contains(Outputs::TWIST),
            needs.contains(Outputs::ENERGIES),
        );
        for j in 0..n {
            let (wp, d) = (&self.plus[j], &self.norms2[j]);
            if twist {
                twist_change.add_scaled(&-wp.clone(), &self.responses[j]);
            }
            if energies {
                let dw = d.clone() * wp;
                lost += dw.clone() * wp;
                loss += dw * &self.minus[j];
            }
        }
        BasisOutcome {
            twist_change,
            lost_velocity_energy: lost / two.clone(),
            kinetic_energy_loss: loss / two,
        }
    }

    /// {v} = {v⁰} − Σ_k w⁺_k W q̂_k (eq. 24) of `model` into `after` (its storage reused), for
    /// the twist before impact `velocity`, the `contacts` and the velocities before impact
    /// `before`, as [`WrenchBasis::solve`] — the velocity itself rather than its change, and
    /// no energies: what the lean path of a system returns ([`crate::impact::lean_system`]).
    pub fn solve_velocity(
        &mut self,
        model: Model,
        velocity: &S,
        contacts: &[Contact<T>],
        before: &[[T; 3]],
        after: &mut S,
    ) {
        self.coordinates(model, velocity, contacts, before);
        after.clone_from(velocity);
        for (wp, response) in self.plus.iter().zip(&self.responses) {
            after.add_scaled(&-wp.clone(), response);
        }
    }

    /// a, the correction δ and w± of `model` (module docs) into `stop`, `work`, `plus` and
    /// `minus`.
    fn coordinates(
        &mut self,
        model: Model,
        velocity: &S,
        contacts: &[Contact<T>],
        before: &[[T; 3]],
    ) {
        let n = self.len();
        debug_assert_eq!(contacts.len(), n, "one contact per wrench");
        let k = |i: usize| match model {
            Model::Newton => &contacts[i].k_newton,
            Model::Poisson => &contacts[i].k_poisson,
        };
        let two = T::one() + T::one();
        // k̄ = (min k + max k)/2.
        let (mut lo, mut hi) = (k(0).clone(), k(0).clone());
        for i in 1..n {
            if (k(i).clone() - &lo).signum_i8() < 0 {
                lo = k(i).clone();
            }
            if (k(i).clone() - &hi).signum_i8() > 0 {
                hi = k(i).clone();
            }
        }
        let mean = (lo + hi) / two.clone();
        self.stop.clear();
        for (q, d) in self.wrenches.iter().zip(&self.norms2) {
            self.stop.push(q.reciprocal(velocity) / d);
        }
        // The correction δ (module docs), into `work`.
        self.work.clear();
        if model == Model::Newton {
            // U⁻ᵀ (K − k̄) v̂⁰_x by forward substitution (Uᵀ is unit lower triangular), / d.
            for (i, v) in before.iter().enumerate() {
                let mut t = (k(i).clone() - &mean) * &v[0];
                for j in 0..i {
                    t -= self.u[j * n + i].clone() * &self.work[j];
                }
                self.work.push(t);
            }
            for (t, d) in self.work.iter_mut().zip(&self.norms2) {
                *t /= d;
            }
        } else {
            // p = U⁻¹ a = P̂^c, then U (K − k̄) p.
            let mut work = std::mem::take(&mut self.work);
            self.back_substitute(&self.stop, &mut work);
            self.work = work;
            for (i, p) in self.work.iter_mut().enumerate() {
                *p *= k(i).clone() - &mean;
            }
            for i in 0..n {
                for j in i + 1..n {
                    let t = self.u[i * n + j].clone() * &self.work[j];
                    self.work[i] += t;
                }
            }
        }
        self.plus.clear();
        self.minus.clear();
        let (one_plus, one_minus) = (T::one() + &mean, T::one() - &mean);
        for (a, delta) in self.stop.iter().zip(&self.work) {
            self.plus.push(one_plus.clone() * a + delta);
            self.minus.push(one_minus.clone() * a - delta);
        }
    }

    /// The impulses P̂ = U⁻¹ w⁺ of the model last solved, into `p`.
    pub fn impulses(&self, p: &mut Vec<T>) {
        self.back_substitute(&self.plus, p);
    }

    /// The compression impulses P̂^c = G⁻¹ v̂⁰_x = U⁻¹ a (Poisson, eq. 21), into `p`.
    pub fn compression_impulses(&self, p: &mut Vec<T>) {
        self.back_substitute(&self.stop, p);
    }

    /// x = U⁻¹ y into `x` (U is unit upper triangular).
    fn back_substitute(&self, y: &[T], x: &mut Vec<T>) {
        let n = self.len();
        x.clear();
        x.extend(y.iter().cloned());
        for i in (0..n).rev() {
            for j in i + 1..n {
                let t = self.u[i * n + j].clone() * &x[j];
                x[i] -= t;
            }
        }
    }

    /// v̂_ix = v̂⁰_ix − (Uᵀ D w⁺)_i (eq. 13) for the model last solved, from `before_x` = v̂⁰_ix.
    pub fn normal_velocity(&self, i: usize, before_x: &T) -> T {
        let n = self.len();
        let mut v = before_x.clone();
        for k in 0..=i {
            v -= self.u[k * n + i].clone() * &self.norms2[k] * &self.plus[k];
        }
        v
    }
}
