//! The small-N float lane of [`Impact`]: the same assembly and normal-equations solve as the
//! general code, for the common case — a free body in principal axes hit at 2 ≤ N ≤ 4
//! contacts, in a float type, whose G the route test sends to the normal equations — with N
//! a constant, so that every loop is unrolled and every buffer is a fixed array.
//!
//! What changes against the general code is bookkeeping, not mathematics:
//!
//! * the response of a principal-axes body to the axis screw {Ê_ix} = [x̂_i; A_i × x̂_i] is
//!   W{Ê_ix} = [J⁻¹ (A_i × x̂_i); x̂_i / m], formed with 1/m and 1/J_k computed once
//!   (products instead of 6N divisions);
//! * Ĝ = L D Lᵀ is factored without pivoting, and the route test is the lean path's
//!   sufficient form of [`crate::impact::route`]'s, from the pivots
//!   ([`crate::impact::lean::route_test`]);
//! * Ĝ is formed from its lower triangle, ĝ_ij = {Ê_ix}ᵀ η W{Ê_jx} for j ≤ i, and mirrored,
//!   so it is symmetric in floats too (eq. 12: ĝ_ij = ĝ_ji);
//! * the solve (eq. 15, 21–24) and what follows from it (eq. 13, 25–26, 28, 32) are written
//!   for N fixed.
//!
//! The rounding differs from the general code's by the order of a few operations (within the
//! accuracy contract of [`crate::analysis::accuracy`], tested in `tests/lane.rs` against
//! exact and against the general code); the outputs asked for are, as in the general code,
//! bit for bit those of [`Outputs::ALL`], since each is formed by the same expression whatever
//! else is asked. A problem outside the lane — or whose G the route test sends to the
//! orthogonalised wrenches ([`crate::impact::route`]) — is built by the general code.
//!
//! The lane serves any [`Mechanism`] that is one free body ([`Mechanism::lane_body`]): a
//! [`crate::impact::problem::Problem`] without constraints, and a system of one body with no
//! joints whose contacts all touch obstacles — so that such a system gives the single body's
//! results bit for bit (issue 24), its screws a stack of one ([`Screws::from_single`]).

use std::array;

use super::{Impact, Outcome, SolveError, energy_loss};
use crate::impact::lean::{ldl, route_test};
use crate::impact::mechanism::Mechanism;
use crate::impact::outputs::Outputs;
use crate::impact::restitution::Model;
use crate::impact::route::Route;
use crate::linalg;
use crate::mechanics::body::Inertia;
use crate::mechanics::screw::{Screw, Screws, Vec3};
use crate::scalar::Scalar;

impl<T: Scalar, M: Mechanism<T>> Impact<T, M> {
    /// Build `self.problem` through the lane when it applies; `Ok(false)` leaves it to the
    /// general build (exact types, constraints, a full inertia tensor, N outside 2..=4, or a
    /// G the route test does not give to the normal equations).
    pub(crate) fn build_lane(&mut self) -> Result<bool, SolveError> {
        if T::IS_EXACT {
            return Ok(false);
        }
        self.build_lane_any()
    }

    /// [`Impact::build_lane`] in any type, exact ones included (there the pivots are only
    /// required to be positive): how the tests check the lane's formulas for exact equality
    /// with the general code ([`Impact::assemble_in_lane`]).
    pub(super) fn build_lane_any(&mut self) -> Result<bool, SolveError> {
        let Some(body) = self.problem.lane_body() else {
            return Ok(false);
        };
        if !matches!(body.inertia, Inertia::Principal(_)) {
            return Ok(false);
        }
        match self.problem.contacts().len() {
            2 => self.build_n::<2>(),
            3 => self.build_n::<3>(),
            4 => self.build_n::<4>(),
            _ => Ok(false),
        }
    }

    /// [`Impact::build_lane`] for N contacts.
    fn build_n<const N: usize>(&mut self) -> Result<bool, SolveError> {
        let tangential = self.tangential();
        let problem = &self.problem;
        let Some(body) = problem.lane_body() else {
            return Ok(false);
        };
        let Inertia::Principal(j) = &body.inertia else {
            return Ok(false);
        };
        let inv_m = T::one() / &body.mass;
        let inv_j: [T; 3] = array::from_fn(|k| T::one() / &j[k]);
        let v0 = problem.velocity();
        self.frames.clear();
        self.before_hat.clear();
        self.responses.clear();
        for i in 0..N {
            let frame = problem.frame(i, tangential)?;
            let Some(axis) = frame.axes[0].single() else {
                return Ok(false);
            };
            let e = axis.as_slice();
            let response = Screw::new(
                Vec3::new(
                    e[3].clone() * &inv_j[0],
                    e[4].clone() * &inv_j[1],
                    e[5].clone() * &inv_j[2],
                ),
                Vec3::new(
                    e[0].clone() * &inv_m,
                    e[1].clone() * &inv_m,
                    e[2].clone() * &inv_m,
                ),
            );
            self.before_hat.push(if tangential {
                frame.velocity(v0)
            } else {
                [frame.axes[0].reciprocal(v0), T::zero(), T::zero()]
            });
            self.responses.push(M::Screw::from_single(response));
            self.frames.push(frame);
        }
        let mut g: [[T; N]; N] = array::from_fn(|_| array::from_fn(|_| T::zero()));
        for i in 0..N {
            for k in 0..=i {
                g[i][k] = self.frames[i].axes[0].reciprocal(&self.responses[k]);
            }
        }
        // Ĝ = L D Lᵀ without pivoting (the route test below needs its pivots, and proves G
        // well conditioned, where pivoting is not needed for stability).
        let (l, d, _) = ldl(&g);
        if T::IS_EXACT && d.iter().any(|dk| dk.signum_i8() <= 0) {
            return Ok(false); // singular (exactly): the general code says so
        }
        // The normal equations' route, by the lean path's sufficient test of
        // [`crate::impact::route`]'s bound ((N − 1) Σ_j c_ij² ≤ s*² implies Σ_j |c_ij| ≤ s*;
        // for N = 2 the two are the same test): what it refuses, the general build decides.
        if !T::IS_EXACT && route_test::<N>(|i, k| g[i][k].to_f64(), |k| d[k].to_f64()).is_err() {
            return Ok(false);
        }
        self.g_hat.clear();
        for i in 0..N {
            for k in 0..N {
                self.g_hat
                    .push(if k <= i { &g[i][k] } else { &g[k][i] }.clone());
            }
        }
        // The factored form [`linalg::factor_psd`] leaves (L below the diagonal, D on it,
        // the identity permutation), for [`linalg::solve_factored`] and the unilateral solve.
        self.factor.clone_from(&self.g_hat);
        self.perm.clear();
        self.perm.extend(0..N);
        for k in 0..N {
            self.factor[k * N + k] = d[k].clone();
            for i in k + 1..N {
                self.factor[i * N + k] = l[i][k].clone();
            }
        }
        self.g_yx_hat.clear();
        self.g_zx_hat.clear();
        if tangential {
            for f in &self.frames {
                for r in &self.responses {
                    self.g_yx_hat.push(f.axes[1].reciprocal(r));
                    self.g_zx_hat.push(f.axes[2].reciprocal(r));
                }
            }
        }
        self.rank = N;
        self.det_hat = linalg::determinant(&self.factor, N);
        self.kinetic_before = if self.outputs.contains(Outputs::ENERGIES) {
            self.problem.kinetic_energy(self.problem.velocity())
        } else {
            T::zero()
        };
        self.basis_built = false;
        self.route = Route::NormalEquations;
        self.lane = N;
        Ok(true)
    }

    /// Solve `model` through the lane built by [`Impact::build_lane`] (`self.lane` contacts).
    /// `false` (nothing done) when the lane was not built for one free body.
    pub(crate) fn solve_lane(&mut self, model: Model, out: &mut Outcome<T, M::Screw>) -> bool {
        match self.lane {
            2 => self.solve_n::<2>(model, out),
            3 => self.solve_n::<3>(model, out),
            _ => self.solve_n::<4>(model, out),
        }
    }

    /// [`Impact::solve_lane`] for N contacts: the impulses from the factored G (eq. 15, 21–23),
    /// then the twist (eq. 24), the contact velocities (eq. 13, 25–26) and the energies
    /// (eq. 28; ΔE_c = ½ Σ P̂_i (v̂_ix⁰ + v̂_ix)) asked for.
    fn solve_n<const N: usize>(&mut self, model: Model, out: &mut Outcome<T, M::Screw>) -> bool {
        let (asked, needs) = (self.outputs, self.outputs.needs());
        let problem = &self.problem;
        let (Some(body), Some(v0)) = (problem.lane_body(), problem.velocity().single()) else {
            return false; // not one free body: the lane was not built (build_lane_any)
        };
        let contacts = problem.contacts();
        let mut x: [T; N] = array::from_fn(|i| {
            let v = self.before_hat[i][0].clone();
            match model {
                Model::Newton => (T::one() + &contacts[i].k_newton) * &v,
                Model::Poisson => v,
            }
        });
        // L D Lᵀ x = b with the lane's factors (identity permutation): forward, scale, back.
        let f = &self.factor[..N * N];
        for i in 1..N {
            for m in 0..i {
                let t = f[i * N + m].clone() * &x[m];
                x[i] -= t;
            }
        }
        for (i, xi) in x.iter_mut().enumerate() {
            *xi /= &f[i * N + i];
        }
        for i in (0..N - 1).rev() {
            for m in i + 1..N {
                let t = f[m * N + i].clone() * &x[m];
                x[i] -= t;
            }
        }
        out.compression_hat.clear();
        if model == Model::Poisson {
            if asked.contains(Outputs::IMPULSES) {
                out.compression_hat.extend(x.iter().cloned());
            }
            for (p, c) in x.iter_mut().zip(contacts) {
                *p *= T::one() + &c.k_poisson; // eq. 23
            }
        }
        out.impulses_hat.clear();
        if asked.contains(Outputs::IMPULSES) {
            out.impulses_hat.extend(x.iter().cloned());
        }
        let mut after = None;
        if needs.contains(Outputs::TWIST) {
            // eq. 24: {v} = {v⁰} − Σ P̂_j W{Ê_jx}.
            let mut v: [T; 6] = array::from_fn(|k| v0.0[k].clone());
            for (p, r) in x.iter().zip(&self.responses) {
                let Some(r) = r.single() else {
                    return false; // the lane's responses are one body's (build_n)
                };
                for (vk, rk) in v.iter_mut().zip(r.as_slice()) {
                    *vk -= p.clone() * rk;
                }
            }
            let v = Screw::new(
                Vec3::new(v[0].clone(), v[1].clone(), v[2].clone()),
                Vec3::new(v[3].clone(), v[4].clone(), v[5].clone()),
            );
            out.velocity = M::Screw::from_single(v.clone());
            after = Some(v);
        }
        out.after_hat.clear();
        let (normal, tangential) = (
            needs.contains(Outputs::NORMAL_VELOCITIES),
            needs.contains(Outputs::TANGENTIAL),
        );
        if normal || tangential {
            let gx = &self.g_hat[..N * N];
            let (gy, gz) = match tangential {
                true => (&self.g_yx_hat[..N * N], &self.g_zx_hat[..N * N]),
                false => (gx, gx),
            };
            for i in 0..N {
                let mut v = self.before_hat[i].clone();
                for (k, p) in x.iter().enumerate() {
                    if normal {
                        v[0] -= gx[i * N + k].clone() * p;
                    }
                    if tangential {
                        v[1] -= gy[i * N + k].clone() * p;
                        v[2] -= gz[i * N + k].clone() * p;
                    }
                }
                if !normal {
                    v[0] = T::zero();
                }
                out.after_hat.push(v);
            }
        }
        // ENERGIES needs TWIST (`Outputs::needs`), so `after` is set when asked.
        if let (true, Some(after)) = (needs.contains(Outputs::ENERGIES), &after) {
            // eq. 28 from the velocity change; ΔE_c from the momentum balance (module docs of
            // `solve`), free of the cancellation in T⁰ − T.
            let dv = Screw(after.0.clone() - v0.0.clone());
            out.lost_velocity_energy = body.kinetic_energy(&dv);
            out.kinetic_energy_loss = energy_loss(&x, &self.before_hat, &out.after_hat);
        }
        out.clear_constraint_impulses();
        if !asked.intersects(Outputs::NORMAL_VELOCITIES | Outputs::TANGENTIAL) {
            out.after_hat.clear();
        }
        true
    }
}
