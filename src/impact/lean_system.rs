//! The lean path of a system of bodies: the impulses and every body's twist after impact,
//! nothing else, with every buffer kept from one solve to the next — the system analogue of
//! [`crate::impact::lean`], for callers that solve the same system again and again (a
//! simulation's impacts, a sweep, a timing against Pinocchio's `impulseDynamics`).
//!
//! [`crate::impact::solve::Impact`] builds, for every solve, the contact frames, G, its
//! pivoted factorization (Δ, the rank and the singular families), the contact velocities,
//! the energies and the joints' impulses, in buffers it allocates. [`LeanSystem`] is built once
//! for a system's shape (its bodies, its joints' tree, its contacts) and then, for that system
//! in any configuration and state, recomputes only what the impulses and the twist need:
//!
//! ```text
//! W            the articulated-body factorization of the joints' forest, again
//!              (mechanics::system::articulated: Featherstone 2008, ch. 7, impulse form)
//! {Ê_i}        each contact's normal axis screw on its one or two bodies      (eq. 3–4)
//! q̂_k, W q̂_k   the axes orthogonalised in ⟨a, b⟩ = {a}ᵀ η W {b}: G = Uᵀ D U
//!              (impact::gram_schmidt — one response W q̂_k per contact)
//! w⁺           Newton's or Poisson's coordinates in that basis        (eq. 15, 21–23)
//! P̂ = U⁻¹ w⁺,  {v} = {v⁰} − Σ_k w⁺_k W q̂_k                                      (eq. 24)
//! ```
//!
//! These are the very operations the general solve performs on a system whose float route is
//! the orthogonalised wrenches ([`crate::impact::route`]; every system with joints): the same
//! factorization code, the same responses, the same basis code. The differences are
//! bookkeeping: the general solve forms G from a response W Ê_k of every axis before
//! orthogonalising (for Δ and the rank), which costs one response more per contact after the
//! first — here ĝ_kk for the second-pass test comes from Pythagoras after the first pass
//! ([`WrenchBasis::build_from`]); v̂⁰_ix is formed as n_i·(v_a(A_i) − v_b(A_i)) from the
//! contact's bodies rather than as {Ê_i}ᵀ η {v⁰} over every body; and {v} is {v⁰} less the
//! terms one by one rather than {v⁰} plus the twist change (different roundings of the same
//! sums). So the accuracy contract of
//! [`crate::analysis::accuracy`] applies to this path as it does to the general one (measured
//! in `tests/lean_system.rs` against exact solves, with the general path's bounds); in exact
//! types the two paths give the same numbers (tested for equality).
//!
//! **What it does not decide.** Δ and the rank come from the general path's pivoted LDLᵀ of G.
//! Here the basis's pivots d_k stand in for them: a solve is refused
//! ([`LeanSystemError::Singular`]) unless every d_k > τ ĝ_kk with τ = 2⁻²⁰ in floats (> 0 in
//! exact types) — d_k/ĝ_kk is the squared sine of the angle, in the metric ηW, between the
//! k-th axis and the span of the ones before it, so a refusal means two contacts whose
//! wrenches are within about 10⁻³ rad of dependence, where the impulses' split is
//! ill-determined and the general path's warnings and singular families are what the user
//! needs. Nor does it judge the answer: like the simultaneous law, it returns pulling
//! impulses as they are ([`crate::impact::unilateral`] is the law that refuses them).

use crate::impact::gram_schmidt::WrenchBasis;
use crate::impact::restitution::Model;
use crate::mechanics::body::Mobility;
use crate::mechanics::system::{Articulated, Pair, ResponseScratch, System, SystemScrew};
use crate::scalar::Scalar;
use std::cell::RefCell;

/// Why [`LeanSystem`] did not solve; [`crate::impact::solve::Impact`] answers every case.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LeanSystemError {
    /// The joints close a loop, or a joint's free screws are dependent, or (floats) an
    /// articulated pivot is negligible: the dense path of
    /// [`crate::mechanics::system::mobility`] is the one that answers.
    #[error(
        "the lean path factors joints along a tree; this system's joints close a loop or have \
         dependent free screws (Impact::solve factors them densely)"
    )]
    NotTree,
    /// The system solved is not of the shape the path was built for.
    #[error("the lean path was built for another system: {what} differ (build it for this one)")]
    Shape {
        /// What differs: `"bodies"`, `"joints"` or `"contacts"`.
        what: &'static str,
    },
    /// A pivot d_k of G = Uᵀ D U is not above τ ĝ_kk (module docs).
    #[error(
        "contact {pivot}'s wrench is too nearly dependent on the ones before it for the lean \
         path (d_k ≤ τ ĝ_kk): Impact::solve decides the rank and the singular families"
    )]
    Singular {
        /// The pivot's index.
        pivot: usize,
    },
}

/// The articulated mobility with its response scratch, as a [`Mobility`] for the basis.
struct Tree<'a, T: Scalar> {
    tree: &'a Articulated<T>,
    scratch: &'a RefCell<ResponseScratch<T>>,
}

impl<T: Scalar> Mobility<T, SystemScrew<T>> for Tree<'_, T> {
    fn response(&self, e: &SystemScrew<T>) -> SystemScrew<T> {
        let mut out = e.clone();
        self.tree
            .response_into(&mut out.0, &mut self.scratch.borrow_mut());
        out
    }

    fn response_into(&self, e: &SystemScrew<T>, out: &mut SystemScrew<T>) {
        out.clone_from(e);
        self.tree
            .response_into(&mut out.0, &mut self.scratch.borrow_mut());
    }
}

/// A system's impulses and twist after impact, solved again and again without allocating
/// (module docs).
#[derive(Clone, Debug)]
pub struct LeanSystem<T: Scalar> {
    /// The joints' pairs of the system it was built for (its shape).
    joints: Vec<Pair>,
    /// Its bodies and contacts.
    bodies: usize,
    contacts: usize,
    tree: Articulated<T>,
    scratch: RefCell<ResponseScratch<T>>,
    /// {Ê_i}.
    axes: Vec<SystemScrew<T>>,
    basis: WrenchBasis<T, SystemScrew<T>>,
    /// v̂⁰_ix per contact, as the basis reads it ([v̂⁰_ix, 0, 0]).
    before: Vec<[T; 3]>,
    impulses: Vec<T>,
    velocity: SystemScrew<T>,
}

impl<T: Scalar> LeanSystem<T> {
    /// The lean path for `system`'s shape (its buffers sized for it).
    ///
    /// # Errors
    /// [`LeanSystemError::NotTree`] for joints not factored along a tree.
    pub fn new(system: &System<T>) -> Result<Self, LeanSystemError> {
        let tree = system.articulated().ok_or(LeanSystemError::NotTree)?;
        let (b, n) = (system.bodies().len(), system.contacts().len());
        let mut basis = WrenchBasis::default();
        basis.reserve(n);
        Ok(LeanSystem {
            joints: system.joints().iter().map(|j| j.pair).collect(),
            bodies: b,
            contacts: n,
            tree,
            scratch: RefCell::new(ResponseScratch::default()),
            axes: vec![SystemScrew::zeros(b); n],
            basis,
            before: Vec::with_capacity(n),
            impulses: Vec::with_capacity(n),
            velocity: SystemScrew::zeros(b),
        })
    }

    /// Solve `system` — of the shape this path was built for, in any configuration and
    /// state — under `model`: [`LeanSystem::impulses_hat`] and [`LeanSystem::velocity`].
    ///
    /// # Errors
    /// [`LeanSystemError::Shape`] for another system, [`LeanSystemError::NotTree`] for a
    /// negligible articulated pivot, [`LeanSystemError::Singular`] (module docs).
    pub fn solve(&mut self, system: &System<T>, model: Model) -> Result<(), LeanSystemError> {
        self.check_shape(system)?;
        system
            .refactor(&mut self.tree)
            .ok_or(LeanSystemError::NotTree)?;
        let v0 = system.velocity();
        for (i, (axis, c)) in self.axes.iter_mut().zip(system.contacts()).enumerate() {
            system.contact_axis_into(i, &c.normal, axis);
        }
        let tree = Tree {
            tree: &self.tree,
            scratch: &self.scratch,
        };
        // One response per contact: the first axis's, then each orthogonalised wrench's.
        if !self
            .basis
            .build_from(self.axes.iter().map(|a| (a, None)), &tree)
        {
            return Err(LeanSystemError::Singular {
                pivot: self.basis.len(),
            });
        }
        self.accept()?;
        // v̂⁰_ix = n_i · (v_a(A_i) − v_b(A_i)) (eq. 8), from the contact's one or two bodies
        // rather than the dense stacks of screws.
        self.before.clear();
        self.before
            .extend(system.contacts().iter().enumerate().map(|(i, c)| {
                let v = system.relative_velocity(i);
                [c.normal.dot(&v), T::zero(), T::zero()]
            }));
        self.basis.solve_velocity(
            model,
            v0,
            system.contacts(),
            &self.before,
            &mut self.velocity,
        );
        self.basis.impulses(&mut self.impulses);
        Ok(())
    }

    /// P̂_i = P_i / |n_i| of the last solve (P_i for unit normals).
    pub fn impulses_hat(&self) -> &[T] {
        &self.impulses
    }

    /// Every body's twist after impact of the last solve (world axes, about its centre).
    pub fn velocity(&self) -> &SystemScrew<T> {
        &self.velocity
    }

    fn check_shape(&self, system: &System<T>) -> Result<(), LeanSystemError> {
        let what = if system.bodies().len() != self.bodies {
            "bodies"
        } else if system.contacts().len() != self.contacts {
            "contacts"
        } else if !system
            .joints()
            .iter()
            .map(|j| j.pair)
            .eq(self.joints.iter().copied())
        {
            "joints"
        } else {
            return Ok(());
        };
        Err(LeanSystemError::Shape { what })
    }

    /// Every d_k > τ ĝ_kk, ĝ_kk = d_k + Σ_{i<k} u_ik² d_i (module docs).
    fn accept(&self) -> Result<(), LeanSystemError> {
        let d = self.basis.norms2();
        let tau = if T::IS_EXACT {
            T::zero()
        } else {
            T::from_f64(2f64.powi(-20)).expect("2⁻²⁰ in every float type")
        };
        for k in 0..d.len() {
            let mut own = d[k].clone();
            for (i, di) in d.iter().enumerate().take(k) {
                let u = self.basis.coefficient(i, k);
                own += u.clone() * u * di;
            }
            if (d[k].clone() - tau.clone() * &own).signum_i8() <= 0 {
                return Err(LeanSystemError::Singular { pivot: k });
            }
        }
        Ok(())
    }
}
