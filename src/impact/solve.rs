//! The simultaneous collision at N points: assemble, factor, solve (§2–4, §6).
//!
//! For a body of mobility W (W = \[M\]⁻¹ for a free body) hit along the contact normals
//! {E_1x} … {E_Nx}, with hatted (unnormalised) axes as explained in [`crate::mechanics::contact`]:
//!
//! ```text
//! ĝ_ij = {Ê_ix}ᵀ η W {Ê_jx}                               inertances      (eq. 12, 126)
//! Newton:  Σ_j ĝ_ij P̂_j = (1 + k_i^N) v̂_ix⁰                               (eq. 15, 20)
//! Poisson: Σ_j ĝ_ij P̂_j^c = v̂_ix⁰,   P̂_i = (1 + k_i^P) P̂_i^c               (eq. 21–23)
//! {v} = {v⁰} − Σ_j P̂_j W {Ê_jx}                            after impact    (eq. 24)
//! v̂_ia = v̂_ia⁰ − Σ_j ĝ_ij,ax P̂_j,  a = x, y, z                             (eq. 13, 25, 26)
//! E_p  = ½ ({v} − {v⁰})ᵀ η M ({v} − {v⁰})                                  (eq. 28)
//! ΔE_c = ½ {v⁰}ᵀ η M {v⁰} − ½ {v}ᵀ η M {v} = ½ Σ_i P_i (v_ix⁰ + v_ix)             (eq. 32)
//! ```
//!
//! The last form follows from the momentum balance M({v} − {v⁰}) = −Σ P_i {E_ix} (+ U q for a
//! constrained body, whose term vanishes against {v⁰} + {v} ∈ span D since Dᵀ η U = 0):
//! T⁰ − T = ½ ({v⁰} + {v})ᵀ η M ({v⁰} − {v}) = ½ Σ P_i (v_ix⁰ + v_ix). It is how ΔE_c is
//! computed: T⁰ − T cancels catastrophically when the loss is small beside T⁰ (a heavy body
//! hit softly), this sum does not. E_p is computed from the velocity change (eq. 28, a
//! positive quadratic form). Eq. 32 as a difference of kinetic energies and the identity
//! ΔE_c = −E_p + Σ P_i v_ix⁰ (eq. 34) are then checks on the solve, not definitions — exact
//! equalities in exact types.
//!
//! **Near a singular G, floats solve from the wrenches, not from G.** G's rounding leaves the
//! split of the impulse between nearly dependent contacts uncertain to cond(G)·ε, and the sum
//! of eq. 24 would pass that to the twist. So where that could break the accuracy contract
//! ([`crate::analysis::accuracy`]) [`Impact::solve`] takes every output from the contact
//! wrenches orthogonalised in the metric ηW ([`crate::impact::gram_schmidt`]; the same laws,
//! rewritten there), which keeps the twist, the contact velocities and the energies to
//! √cond(G)·ε. Where G is well conditioned the normal equations above meet the same bounds
//! at less cost, and a float solve takes them: [`crate::impact::route`] derives the
//! threshold and decides per problem, once, at assembly ([`Impact::route`]). Exact types
//! always solve G x = b, and there both routes give the same numbers
//! ([`Impact::solve_orthogonal`], tested). The factorization of G decides the rank and Δ in
//! every type.
//!
//! [`Impact::assemble`] does the model-independent work once (frames, G, its factorization,
//! Δ); [`Impact::solve`] then runs one restitution model. Both reuse the buffers they own, so
//! repeated f64 solves allocate nothing. [`Impact::assemble_for`] does the same for the outputs
//! a caller asks for only ([`crate::impact::outputs`]): impulses and twist cost about 0.6 of
//! every output on Example 3.

use crate::impact::gram_schmidt::WrenchBasis;
use crate::impact::mechanism::Mechanism;
use crate::impact::outputs::Outputs;
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::route::Route;
use crate::impact::unilateral::UnilateralWork;
use crate::linalg::{self, NotSemidefinite};
use crate::mechanics::contact::{ContactFrame, TangentNotPerpendicular};
use crate::mechanics::screw::{Screw, Screws};
use crate::scalar::Scalar;

mod lane;

/// [`SolveError::Singular`]'s message.
fn singular_text(rank: usize, contacts: usize, rounded: bool) -> String {
    if rounded {
        format!(
            "the inertance matrix G is singular to working precision (rank {rank} of {contacts} \
             at the rounding tolerance; cond G beyond 1/ε, or Δ = 0 — `--exact` decides): the \
             impulses are not determined uniquely in this precision"
        )
    } else {
        format!(
            "the inertance matrix G is singular (Δ = 0; rank {rank} of {contacts}): the impulses \
             are not determined uniquely"
        )
    }
}

/// Why a collision could not be solved.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// Δ = det G = 0: the system for the impulses has no unique solution (§8) — exactly, or
    /// to working precision in a float type (`rounded`).
    #[error("{}", singular_text(*rank, *contacts, *rounded))]
    Singular {
        /// rank G.
        rank: usize,
        /// N.
        contacts: usize,
        /// Decided in floating point: a pivot within the rounding tolerance of zero, so G may
        /// be merely ill-conditioned beyond the type's precision (an exact run decides).
        rounded: bool,
    },
    /// A contact frame could not be built (not reached for a validated [`Problem`], whose
    /// tangents were checked by the same test).
    #[error(transparent)]
    Tangent(#[from] TangentNotPerpendicular),
    /// G was not positive semidefinite: cannot happen for a body with positive mass and
    /// moments; reported rather than trusted.
    #[error(transparent)]
    NotSemidefinite(#[from] NotSemidefinite),
}

/// The model-independent part of a collision, assembled for one [`Problem`] (of which it
/// keeps a copy, so every later call refers to that problem): frames, velocities before
/// impact, inertances, the factorization of G and Δ.
///
/// Everything here is in **hatted** form — the internal device of [`crate::mechanics::contact`]:
/// axes are the normals and tangents as given, unnormalised, so no square root is taken and
/// exact types run the same code. v_ix = v̂_ix / |n_i|, P_i = P̂_i |n_i|,
/// g_ij = ĝ_ij / (|n_i| |n_j|), Δ = Δ̂ / Π|n_i|². The values in the paper's units are
/// [`crate::impact::solution::Solution`]'s. Matrices are N×N, row-major.
#[derive(Clone, Debug)]
pub struct Impact<T: Scalar, M: Mechanism<T> = Problem<T>> {
    problem: M,
    /// The contact frames.
    frames: Vec<ContactFrame<T, M::Screw>>,
    /// (v̂_ix⁰, v̂_iy⁰, v̂_iz⁰) per contact (eq. 8).
    before_hat: Vec<[T; 3]>,
    /// W{Ê_jx}: the twist per unit hatted impulse at contact j.
    responses: Vec<M::Screw>,
    /// Ĝ = [ĝ_ij,xx].
    g_hat: Vec<T>,
    /// [ĝ_ij,yx] (eq. 127).
    g_yx_hat: Vec<T>,
    /// [ĝ_ij,zx] (eq. 128).
    g_zx_hat: Vec<T>,
    /// Δ̂ = det Ĝ = Δ · Π|x̂_i|².
    det_hat: T,
    /// rank G.
    rank: usize,
    /// ½ {v⁰}ᵀ η M {v⁰}.
    kinetic_before: T,
    factor: Vec<T>,
    perm: Vec<usize>,
    work: Vec<T>,
    /// The normals' axis screws orthogonalised in the metric ηW ([`crate::impact::gram_schmidt`]):
    /// float types solve from it where [`crate::impact::route`] says so.
    basis: WrenchBasis<T, M::Screw>,
    /// Whether `basis` holds the current problem's basis.
    basis_built: bool,
    /// The route [`Impact::solve`] takes for this problem.
    route: Route,
    /// The most contacts both routes' buffers have room for: a problem routed one way does
    /// not leave the other way's buffers unsized (repeated f64 solves allocate nothing).
    sized: usize,
    /// The outputs asked for ([`Impact::assemble_for`]).
    outputs: Outputs,
    /// The buffers of [`Impact::solve_unilateral`].
    pub(crate) unilateral: UnilateralWork<T>,
    /// N when the problem was built by the small-N float lane (module `lane`), 0 otherwise.
    pub(crate) lane: usize,
}

/// The result of one restitution model, in hatted form (see [`Impact`]); the paper's units
/// are [`crate::impact::solution::Solution`]'s.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome<T: Scalar, S: Screws<T> = Screw<T>> {
    /// P̂_i = P_i / |x̂_i|.
    pub impulses_hat: Vec<T>,
    /// P̂_i^c (Poisson only; empty for Newton).
    pub compression_hat: Vec<T>,
    /// {v} = [ω; v_C] after impact (a system: every body's).
    pub velocity: S,
    /// (v̂_ix, v̂_iy, v̂_iz) after impact, per contact (eq. 13, 25, 26).
    pub after_hat: Vec<[T; 3]>,
    /// E_p (eq. 28).
    pub lost_velocity_energy: T,
    /// ΔE_c (eq. 32).
    pub kinetic_energy_loss: T,
    /// The constraint impulses {q} (eq. 90–93; empty for a free body).
    pub constraint_impulses: Vec<T>,
    /// U q = [F; M_C], the constraint impulse as a wrench (zero for a free body;
    /// [`crate::mechanics::reaction`]).
    pub constraint_wrench: Screw<T>,
}

impl<T: Scalar, S: Screws<T>> Default for Outcome<T, S> {
    fn default() -> Self {
        Outcome {
            impulses_hat: Vec::new(),
            compression_hat: Vec::new(),
            velocity: S::default(),
            after_hat: Vec::new(),
            lost_velocity_energy: T::zero(),
            kinetic_energy_loss: T::zero(),
            constraint_impulses: Vec::new(),
            constraint_wrench: Screw::zero(),
        }
    }
}

impl<T: Scalar, S: Screws<T>> Outcome<T, S> {
    /// No constraint impulse: q empty and U q zero (a free body, or not asked for).
    pub(crate) fn clear_constraint_impulses(&mut self) {
        self.constraint_impulses.clear();
        self.constraint_wrench = Screw::zero();
    }
}

impl<T: Scalar, M: Mechanism<T>> Impact<T, M> {
    /// Build frames, inertances and the factorization of G for `problem`, the mechanism
    /// answering impulses through its mobility (a free or constrained body, a system). A
    /// singular G is not an error here: `rank` and `det_hat` say so, and [`Impact::solve`]
    /// refuses.
    ///
    /// # Errors
    /// [`SolveError::NotSemidefinite`] if rounding made G indefinite (floats only).
    pub fn assemble(problem: &M) -> Result<Self, SolveError> {
        Impact::assemble_for(problem, Outputs::ALL)
    }

    /// [`Impact::assemble`] for the `outputs` asked for ([`crate::impact::outputs`]): the
    /// tangent axes and the tangential inertances are built only for
    /// [`Outputs::TANGENTIAL`], T⁰ only for [`Outputs::ENERGIES`], and [`Impact::solve`] then
    /// computes only those outputs and what they are formed from. G, its factorization, Δ
    /// and the velocities along the normals before impact are built whatever is asked.
    ///
    /// # Errors
    /// As [`Impact::assemble`].
    pub fn assemble_for(problem: &M, outputs: Outputs) -> Result<Self, SolveError> {
        Impact::assemble_owned(problem.clone(), outputs)
    }

    /// [`Impact::assemble_for`] taking the problem by value: the same impact, without the
    /// copy of the problem that [`Impact::assemble`] keeps (for a system, a copy of each of
    /// its vectors).
    ///
    /// # Errors
    /// As [`Impact::assemble`].
    pub fn assemble_owned(problem: M, outputs: Outputs) -> Result<Self, SolveError> {
        let mut impact = Impact {
            problem,
            frames: Vec::new(),
            before_hat: Vec::new(),
            responses: Vec::new(),
            g_hat: Vec::new(),
            g_yx_hat: Vec::new(),
            g_zx_hat: Vec::new(),
            det_hat: T::one(),
            rank: 0,
            kinetic_before: T::zero(),
            factor: Vec::new(),
            perm: Vec::new(),
            work: Vec::new(),
            basis: WrenchBasis::default(),
            basis_built: false,
            route: Route::NormalEquations,
            sized: 0,
            outputs,
            unilateral: UnilateralWork::default(),
            lane: 0,
        };
        impact.build()?;
        Ok(impact)
    }

    /// [`Impact::assemble`] for another problem, reusing this impact's buffers (repeated f64
    /// solves of free bodies allocate nothing), for the same outputs.
    ///
    /// # Errors
    /// As [`Impact::assemble`].
    pub fn reassemble(&mut self, problem: &M) -> Result<(), SolveError> {
        self.problem.clone_from(problem);
        self.build()
    }

    /// The problem assembled.
    pub fn problem(&self) -> &M {
        &self.problem
    }

    /// Number of contacts.
    pub fn contacts(&self) -> usize {
        self.problem.contacts().len()
    }

    /// Whether G is singular (rank G < N).
    pub fn singular(&self) -> bool {
        self.rank < self.contacts()
    }

    /// The outputs asked for ([`Impact::assemble_for`]; [`Outputs::ALL`] by default).
    pub fn outputs(&self) -> Outputs {
        self.outputs
    }

    /// Whether the tangent axes and tangential inertances were built
    /// ([`Outputs::TANGENTIAL`] asked for).
    fn tangential(&self) -> bool {
        self.outputs.needs().contains(Outputs::TANGENTIAL)
    }

    /// The contact frames; without [`Outputs::TANGENTIAL`] only their normals x̂ (the
    /// tangent axes and their norms are zero, [`ContactFrame::normal`]).
    pub fn frames(&self) -> &[ContactFrame<T, M::Screw>] {
        &self.frames
    }

    /// (v̂_ix⁰, v̂_iy⁰, v̂_iz⁰) per contact, hatted (eq. 8); v̂_iy⁰ = v̂_iz⁰ = 0 unless
    /// [`Outputs::TANGENTIAL`] was asked for.
    pub fn before_hat(&self) -> &[[T; 3]] {
        &self.before_hat
    }

    /// W{Ê_jx}: the twist per unit hatted impulse at contact j.
    pub fn responses(&self) -> &[M::Screw] {
        &self.responses
    }

    /// Ĝ = \[ĝ_ij,xx\], N×N row-major, hatted.
    pub fn g_hat(&self) -> &[T] {
        &self.g_hat
    }

    /// \[ĝ_ij,yx\] (eq. 127), hatted; empty unless [`Outputs::TANGENTIAL`] was asked for.
    pub fn g_yx_hat(&self) -> &[T] {
        &self.g_yx_hat
    }

    /// \[ĝ_ij,zx\] (eq. 128), hatted; empty unless [`Outputs::TANGENTIAL`] was asked for.
    pub fn g_zx_hat(&self) -> &[T] {
        &self.g_zx_hat
    }

    /// Δ̂ = det Ĝ = Δ · Π|x̂_i|².
    pub fn det_hat(&self) -> &T {
        &self.det_hat
    }

    /// The pivot order of G's factorization: `pivots()[k]` is the contact pivoted k-th, so
    /// the first `rank()` are a set of contacts whose inertances are independent.
    pub fn pivots(&self) -> &[usize] {
        &self.perm
    }

    /// rank G.
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// The route [`Impact::solve`] takes for this problem ([`crate::impact::route`]): the
    /// normal equations in exact types, and in float types unless G is too ill conditioned for
    /// them to meet the accuracy contract (or the body is constrained or has a full inertia
    /// tensor), where the orthogonalised wrenches are taken — when they can be built.
    pub fn route(&self) -> Route {
        self.route
    }

    /// T⁰ = ½ {v⁰}ᵀ η M {v⁰}, the kinetic energy before impact (zero unless
    /// [`Outputs::ENERGIES`] was asked for).
    pub fn kinetic_before(&self) -> &T {
        &self.kinetic_before
    }

    /// Frames, velocities before impact, the inertances (eq. 12, 126–128), the
    /// factorization of G and Δ̂, for `self.problem`.
    fn build(&mut self) -> Result<(), SolveError> {
        let n = self.problem.contacts().len();
        if n > self.sized {
            self.work.reserve(n.saturating_sub(self.work.len()));
            self.basis.reserve(n);
            self.sized = n;
        }
        self.lane = 0;
        if M::assemble_fast(self)? {
            return Ok(());
        }
        let tangential = self.tangential();
        let problem = &self.problem;
        self.before_hat.clear();
        self.responses.clear();
        self.frames.clear();
        let v0 = problem.velocity();
        for i in 0..problem.contacts().len() {
            self.frames.push(problem.frame(i, tangential)?);
            if tangential {
                self.before_hat.push(self.frames[i].velocity(v0));
            } else {
                let x = self.frames[i].axes[0].reciprocal(v0);
                self.before_hat.push([x, T::zero(), T::zero()]);
            }
            self.responses
                .push(problem.response(&self.frames[i].axes[0]));
        }
        self.g_hat.clear();
        self.g_yx_hat.clear();
        self.g_zx_hat.clear();
        for f in &self.frames {
            for r in &self.responses {
                self.g_hat.push(f.axes[0].reciprocal(r));
                if tangential {
                    self.g_yx_hat.push(f.axes[1].reciprocal(r));
                    self.g_zx_hat.push(f.axes[2].reciprocal(r));
                }
            }
        }
        self.factor.clone_from(&self.g_hat);
        self.perm.resize(n, 0);
        let fac = linalg::factor_psd(&mut self.factor, n, &mut self.perm)?;
        self.rank = fac.rank;
        self.det_hat = linalg::determinant(&self.factor, n);
        self.kinetic_before = if self.outputs.contains(Outputs::ENERGIES) {
            problem.kinetic_energy(problem.velocity())
        } else {
            T::zero()
        };
        // Exact types solve G x = b (every route gives the same numbers, that one the fastest),
        // and so do floats whose G is well conditioned. A singular G is refused whatever the
        // route; should the basis fail to build for a regular one (rounding made some
        // d_k ≤ 0), the normal equations answer.
        let orthogonal = self.problem.route(&self.g_hat, n) == Route::OrthogonalWrenches;
        self.basis_built = orthogonal && self.rank == n && self.build_basis();
        self.route = if orthogonal && (self.basis_built || self.rank < n) {
            Route::OrthogonalWrenches
        } else {
            Route::NormalEquations
        };
        Ok(())
    }

    /// Solve the restitution `model` for the assembled problem into `out` (its buffers are
    /// reused), with the constraint impulses q for a constrained body: the outputs asked for
    /// ([`Impact::outputs`]), each bit for bit what [`Outputs::ALL`] gives; the vectors of
    /// the others are left empty and their numbers as they were.
    ///
    /// # Errors
    /// [`SolveError::Singular`] when G is singular (Δ = 0): see [`crate::analysis`].
    pub fn solve(
        &mut self,
        model: Model,
        out: &mut Outcome<T, M::Screw>,
    ) -> Result<(), SolveError> {
        let n = self.contacts();
        if self.rank < n {
            return Err(SolveError::Singular {
                rank: self.rank,
                contacts: n,
                rounded: !T::IS_EXACT,
            });
        }
        if M::solve_fast(self, model, out) {
        } else if self.route == Route::OrthogonalWrenches {
            self.solve_in_basis(model, out);
        } else {
            self.solve_normal_equations(model, out);
        }
        if !self.outputs.contains(Outputs::IMPULSES) {
            out.impulses_hat.clear();
            out.compression_hat.clear();
        }
        if !self
            .outputs
            .intersects(Outputs::NORMAL_VELOCITIES | Outputs::TANGENTIAL)
        {
            out.after_hat.clear();
        }
        Ok(())
    }

    /// The impulses from G x = b, every other output asked for from them.
    fn solve_normal_equations(&mut self, model: Model, out: &mut Outcome<T, M::Screw>) {
        let n = self.contacts();
        // Scratch for the general solve; it writes every entry before reading it.
        self.work.resize(n, T::zero());
        self.rhs(model, &mut out.impulses_hat);
        linalg::solve_factored(
            &self.factor,
            n,
            &self.perm,
            &mut out.impulses_hat,
            &mut self.work,
        );
        out.compression_hat.clear();
        if model == Model::Poisson {
            if self.outputs.contains(Outputs::IMPULSES) {
                out.compression_hat.extend(out.impulses_hat.iter().cloned());
            }
            for (p, c) in out.impulses_hat.iter_mut().zip(self.problem.contacts()) {
                *p *= T::one() + &c.k_poisson; // eq. 23
            }
        }
        self.complete(out);
    }

    /// The orthogonalised wrenches' route, whatever [`Impact::route`] says, in any type: in
    /// exact types it gives the very outcome [`Impact::solve`] gives (tested), so it is the
    /// check of that route; in float types, where both routes apply, the two agree within
    /// the accuracy contract (tested).
    ///
    /// # Errors
    /// [`SolveError::Singular`] when G is singular, or (floats) when rounding makes an
    /// orthogonalised wrench's d_k ≤ 0.
    pub fn solve_orthogonal(
        &mut self,
        model: Model,
        out: &mut Outcome<T, M::Screw>,
    ) -> Result<(), SolveError> {
        let n = self.contacts();
        if self.rank < n || !(self.basis_built || self.build_basis()) {
            return Err(SolveError::Singular {
                rank: self.rank.min(self.basis.len()),
                contacts: n,
                rounded: !T::IS_EXACT,
            });
        }
        self.basis_built = true;
        self.solve_in_basis(model, out);
        Ok(())
    }

    /// Orthogonalise the normals' axis screws in the metric of the mobility; `false` when
    /// some d_k ≤ 0.
    fn build_basis(&mut self) -> bool {
        let axes = self.frames.iter().map(|f| &f.axes[0]);
        self.basis.build(axes.zip(&self.responses), &self.problem)
    }

    /// The solve from the orthogonalised wrenches
    /// ([`crate::impact::gram_schmidt`]) instead of the normal equations G x = b: impulses,
    /// twist, velocities along the normals and both energies, so that they keep the accuracy
    /// the wrenches determine when G is nearly singular. The tangential velocities follow
    /// from the twist change (eq. 25–26: v̂_ia = v̂_ia⁰ + {Ê_ia}ᵀ η ({v} − {v⁰})).
    fn solve_in_basis(&mut self, model: Model, out: &mut Outcome<T, M::Screw>) {
        let (asked, needs) = (self.outputs, self.outputs.needs());
        let problem = &self.problem;
        let b = self.basis.solve(
            model,
            problem.velocity(),
            problem.contacts(),
            &self.before_hat,
            needs,
        );
        if needs.contains(Outputs::TWIST) {
            out.velocity = problem.velocity().clone();
            out.velocity.add_scaled(&T::one(), &b.twist_change);
        }
        out.after_hat.clear();
        let (normal, tangential) = (
            needs.contains(Outputs::NORMAL_VELOCITIES),
            needs.contains(Outputs::TANGENTIAL),
        );
        if normal || tangential {
            for (i, (f, v0)) in self.frames.iter().zip(&self.before_hat).enumerate() {
                let along = |a: usize| match tangential {
                    true => v0[a].clone() + f.axes[a].reciprocal(&b.twist_change),
                    false => T::zero(),
                };
                out.after_hat.push([
                    match normal {
                        true => self.basis.normal_velocity(i, &v0[0]),
                        false => T::zero(),
                    },
                    along(1),
                    along(2),
                ]);
            }
        }
        if needs.contains(Outputs::ENERGIES) {
            out.lost_velocity_energy = b.lost_velocity_energy;
            out.kinetic_energy_loss = b.kinetic_energy_loss;
        }
        out.compression_hat.clear();
        if asked.contains(Outputs::IMPULSES) || needs.contains(Outputs::CONSTRAINT_IMPULSES) {
            self.basis.impulses(&mut out.impulses_hat);
            if model == Model::Poisson {
                self.basis.compression_impulses(&mut out.compression_hat);
            }
        } else {
            out.impulses_hat.clear();
        }
        if needs.contains(Outputs::CONSTRAINT_IMPULSES) {
            self.constraint_impulses(&b.twist_change, out);
        } else {
            out.clear_constraint_impulses();
        }
    }

    /// The right-hand side of the model's system G x = b: b_i = (1 + k_i^N) v̂_ix⁰ (Newton,
    /// eq. 15) or v̂_ix⁰ (Poisson, eq. 21, for the compression impulses).
    pub(crate) fn rhs(&self, model: Model, b: &mut Vec<T>) {
        b.clear();
        for (i, c) in self.problem.contacts().iter().enumerate() {
            let v0 = self.before_hat[i][0].clone();
            b.push(match model {
                Model::Newton => (T::one() + &c.k_newton) * &v0,
                Model::Poisson => v0,
            });
        }
    }

    /// Everything that follows from the impulses `out.impulses_hat` (one per contact): the
    /// twist after impact, the contact velocities, both energies (eq. 24–26, 28, 32) and, for
    /// a constrained body, the constraint impulses (eq. 90–93).
    ///
    /// Only the outputs asked for ([`Impact::outputs`]) and what they are formed from.
    pub(crate) fn complete(&self, out: &mut Outcome<T, M::Screw>) {
        let n = self.contacts();
        debug_assert_eq!(out.impulses_hat.len(), n, "one impulse per contact");
        let needs = self.outputs.needs();
        let problem = &self.problem;
        if needs.contains(Outputs::TWIST) {
            // eq. 24: {v} = {v⁰} − Σ P̂_j W{Ê_jx}.
            out.velocity = problem.velocity().clone();
            for (p, r) in out.impulses_hat.iter().zip(&self.responses) {
                out.velocity.add_scaled(&-p.clone(), r);
            }
        }
        // eq. 13, 25, 26 through the inertances.
        out.after_hat.clear();
        let (normal, tangential) = (
            needs.contains(Outputs::NORMAL_VELOCITIES),
            needs.contains(Outputs::TANGENTIAL),
        );
        if normal || tangential {
            // Each component's sum in the same order whichever are formed; one loop per case,
            // so that asking for every output costs no test per term.
            for i in 0..n {
                let mut v = self.before_hat[i].clone();
                let terms = out
                    .impulses_hat
                    .iter()
                    .enumerate()
                    .map(|(j, p)| (i * n + j, p));
                match (normal, tangential) {
                    (true, true) => {
                        for (k, p) in terms {
                            v[0] -= self.g_hat[k].clone() * p;
                            v[1] -= self.g_yx_hat[k].clone() * p;
                            v[2] -= self.g_zx_hat[k].clone() * p;
                        }
                    }
                    (true, false) => {
                        for (k, p) in terms {
                            v[0] -= self.g_hat[k].clone() * p;
                        }
                    }
                    _ => {
                        v[0] = T::zero();
                        for (k, p) in terms {
                            v[1] -= self.g_yx_hat[k].clone() * p;
                            v[2] -= self.g_zx_hat[k].clone() * p;
                        }
                    }
                }
                out.after_hat.push(v);
            }
        }
        if !needs.intersects(Outputs::ENERGIES | Outputs::CONSTRAINT_IMPULSES) {
            out.clear_constraint_impulses();
            return;
        }
        // eq. 28 from the velocity change; ΔE_c from the momentum balance, ½ Σ P̂_i (v̂_ix⁰ + v̂_ix)
        // (module docs), free of the cancellation in T⁰ − T.
        let dv = out.velocity.minus(problem.velocity());
        if !needs.contains(Outputs::ENERGIES) {
            self.constraint_impulses(&dv, out);
            return;
        }
        out.lost_velocity_energy = problem.kinetic_energy(&dv);
        out.kinetic_energy_loss = energy_loss(&out.impulses_hat, &self.before_hat, &out.after_hat);
        if needs.contains(Outputs::CONSTRAINT_IMPULSES) {
            self.constraint_impulses(&dv, out);
        } else {
            out.clear_constraint_impulses();
        }
    }

    /// The constraint impulses q for the twist change `dv` and the impulses of `out` (eq.
    /// 90–93; none for a free body).
    fn constraint_impulses(&self, dv: &M::Screw, out: &mut Outcome<T, M::Screw>) {
        self.problem.constraint_impulses(dv, &self.frames, out);
    }

    /// Solve G x = b in place for a nonsingular G (b becomes x); `false` when G is singular.
    pub(crate) fn solve_system(&mut self, b: &mut [T]) -> bool {
        let n = self.contacts();
        debug_assert_eq!(b.len(), n, "one entry per contact");
        if self.rank < n {
            return false;
        }
        resize(&mut self.work, n);
        linalg::solve_factored(&self.factor, n, &self.perm, b, &mut self.work);
        true
    }

    /// For a singular G (rank r < N): a solution of G x = b with its last N − r pivoted
    /// entries zero, written into `x` — `None` when b is not in the range of G (the system is
    /// incompatible). Compatibility is decided on the residual G x − b: exactly zero in exact
    /// types, negligible against ‖G‖·|x| + |b| in floats.
    pub(crate) fn solve_singular(&mut self, b: &[T], x: &mut Vec<T>) -> Option<()> {
        let (n, r) = (self.contacts(), self.rank);
        debug_assert_eq!(b.len(), n, "one entry per contact");
        resize(&mut self.work, n);
        linalg::solve_leading(&self.factor, n, &self.perm, r, b, x, &mut self.work);
        let mut scale = T::zero();
        for bi in b {
            if bi.abs_gt(&scale) {
                scale = bi.clone();
            }
        }
        for i in 0..n {
            let mut ri = -b[i].clone();
            let mut row_scale = scale.clone();
            for j in 0..n {
                let t = self.g_hat[i * n + j].clone() * &x[j];
                if t.abs_gt(&row_scale) {
                    row_scale = t.clone();
                }
                ri += t;
            }
            if !ri.is_negligible(&row_scale, 4 * n * n) {
                return None;
            }
        }
        Some(())
    }

    /// A basis of the null space of G from its factorization: for each pivot k ≥ rank,
    /// x = Πᵀ [−L11⁻ᵀ L21ᵀ e_k; e_k].
    pub(crate) fn null_space(&self) -> Vec<Vec<T>> {
        let (n, r) = (self.contacts(), self.rank);
        let mut basis = Vec::with_capacity(n - r);
        for k in r..n {
            let mut y = vec![T::zero(); n];
            y[k] = T::one();
            // L11ᵀ y1 = −L21ᵀ e_k: unit upper triangular, back substitution.
            for i in (0..r).rev() {
                let mut s = -self.factor[k * n + i].clone();
                for j in i + 1..r {
                    s -= self.factor[j * n + i].clone() * &y[j];
                }
                y[i] = s;
            }
            let mut x = vec![T::zero(); n];
            for (pk, yk) in self.perm.iter().zip(y) {
                x[*pk] = yk;
            }
            basis.push(x);
        }
        basis
    }

    /// Σ_i P̂_i v̂_ix⁰ = Σ_i P_i v_ix⁰: the right-hand side of the energy identity (eq. 34).
    pub fn impulse_work(&self, out: &Outcome<T, M::Screw>) -> T {
        let mut s = T::zero();
        for (p, v) in out.impulses_hat.iter().zip(&self.before_hat) {
            s += p.clone() * &v[0];
        }
        s
    }
}

/// ΔE_c = ½ Σ_i P̂_i (v̂_ix⁰ + v̂_ix), from the momentum balance (module docs): free of the
/// cancellation in T⁰ − T.
fn energy_loss<T: Scalar>(impulses: &[T], before: &[[T; 3]], after: &[[T; 3]]) -> T {
    let mut loss = T::zero();
    for ((p, b), a) in impulses.iter().zip(before).zip(after) {
        loss += p.clone() * &(b[0].clone() + &a[0]);
    }
    loss / (T::one() + T::one())
}

/// Resize to `n` zeros without reallocating when the capacity suffices.
fn resize<T: Scalar>(v: &mut Vec<T>, n: usize) {
    v.clear();
    v.resize(n, T::zero());
}

impl<T: Scalar> Impact<T> {
    /// [`Impact::assemble`] through the small-N lane (module `lane`) in any scalar type — exact
    /// ones included, which otherwise take the general code — or `None` when the problem is
    /// outside the lane (constrained, a full inertia tensor, N outside 2..=4, a singular or,
    /// in floats, ill-conditioned G). For tests: in exact types the lane must give every
    /// output of the general code exactly.
    #[doc(hidden)]
    pub fn assemble_in_lane(problem: &Problem<T>) -> Option<Self> {
        let mut impact = Impact::assemble(problem).ok()?;
        impact.lane = 0;
        (impact.build_lane_any().ok()? && impact.lane != 0).then_some(impact)
    }

    /// N when this problem was built by the small-N float lane (module `lane`: a free body in
    /// principal axes hit at 2 to 4 contacts whose G the route test gives to the normal
    /// equations), `None` when by the general code.
    pub fn lane(&self) -> Option<usize> {
        (self.lane != 0).then_some(self.lane)
    }
}
