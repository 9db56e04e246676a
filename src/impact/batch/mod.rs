//! Many free-body scenes of the same N at once — sweeps, Monte Carlo — for the impulses and
//! the twist after impact.
//!
//! The scenes are held as structure of arrays ([`Scenes`]: one `Vec<f64>` per input
//! coordinate, scene s at index s of each), read [`width()`] scenes at a time into
//! [`lanes::Lanes`] and solved by the lean path's own arithmetic ([`crate::impact::lean`]),
//! every operation applied to the lanes together ([`sweep`]). Each lane computes what
//! [`crate::impact::lean::Lean`] computes for that scene alone, bit for bit (tested at every
//! width): IEEE 754 operations are correctly rounded lane by lane, and nothing is contracted
//! into a fused multiply-add (Rust never contracts, even where FMA is enabled). A scene the
//! lean route refuses — too nearly dependent contacts for the normal equations (the accuracy
//! contract), or invalid input — is solved by the generic path
//! ([`crate::impact::solve::Impact`]) instead, and [`Outcomes::routes`] says which route
//! answered, [`Outcomes::reasons`] why the others did not take the lean one.
//!
//! **Width and dispatch.** The lanes are as wide as the machine's vectors, chosen when the
//! program runs: eight f64 where the CPU has AVX-512 (x86-64-v4), four with AVX2 (x86-64-v3),
//! two (SSE2, the default target) otherwise. The `pulp` crate detects the instruction set and
//! runs the sweep inside a function compiled for it (`pulp::Simd::vectorize`); the sweep is
//! `#[inline(always)]` over `Lanes<L>`, so L f64 become one register there and the compiler
//! emits the vector instructions — no hand-written intrinsics, no `unsafe` here. `pulp` over
//! `wide`: `wide` picks its instructions when the crate is compiled (a default build would get
//! SSE2 only), `pulp` when the program runs.
//!
//! **What it costs** (2026-11-29, AMD EPYC Zen 4, eight AVX-512 lanes, both laws, criterion
//! medians of 256 scenes, batch and loop in one run at load ≈ 2; numbers and profile in
//! `guide/accuracy.md`). Two contacts take the written-out kernel of `pair.rs`: 2.8× the
//! one-by-one lean path on Example-3-class scenes (3.36 µs against 9.5 µs), 1.9–2.1× on the
//! random boxes the lean route accepts, about even (0.96–1.00×) on all random boxes with the
//! refused ones by the generic route — not the 4× of issue 29. The hot loop reads whole chunks
//! only, as plain vector loads (a lane-by-lane copy of the last, partial chunk in the same
//! load made LLVM build every input from pieces on the stack, 2.3× slower), decides a chunk by
//! sufficient tests (`sweep::surely_finite`) and leaves the lane-by-lane decisions to a
//! cold fallback. Refused scenes cost what the generic solve costs (≈ 900 ns each, assembled
//! once for both laws).

pub mod lanes;
mod pair;
mod sweep;
#[cfg(test)]
mod tests;

use std::array;

use crate::impact::lean::LeanError;
use crate::impact::problem::{InvalidProblem, Problem};
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::mechanics::body::{Inertia, RigidBody};
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Vec3};

/// Scenes per vector step on this machine (module docs): 8 with AVX-512, 4 with AVX2, else 2.
pub fn width() -> usize {
    match pulp::Arch::new() {
        #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
        pulp::Arch::V4(_) => 8,
        #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
        pulp::Arch::V3(_) => 4,
        _ => 2,
    }
}

/// Free bodies in central principal axes, each hit at N contacts, as structure of arrays:
/// scene s is index s of every vector (all of one length).
#[derive(Clone, Debug, PartialEq)]
pub struct Scenes<const N: usize> {
    /// m.
    pub mass: Vec<f64>,
    /// (J_x, J_y, J_z), principal moments.
    pub inertia: [Vec<f64>; 3],
    /// {v⁰} = [ω⁰; v_C⁰].
    pub velocity: [Vec<f64>; 6],
    /// r_j per contact j, coordinates x, y, z.
    pub points: [[Vec<f64>; 3]; N],
    /// n_j per contact j (need not be unit).
    pub normals: [[Vec<f64>; 3]; N],
    /// k_j^N.
    pub k_newton: [Vec<f64>; N],
    /// k_j^P.
    pub k_poisson: [Vec<f64>; N],
}

/// Why a batch could not be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BatchError {
    /// The vectors of [`Scenes`] differ in length.
    #[error("the scenes' arrays differ in length: {what} has {found} entries, mass has {expected}")]
    Lengths {
        /// The first array of another length.
        what: String,
        /// Its length.
        found: usize,
        /// The length of `mass`.
        expected: usize,
    },
    /// [`Scenes::push`] takes free bodies in principal axes with N contacts.
    #[error("a batch holds free bodies in principal axes with {0} contacts")]
    NotBatchable(usize),
}

/// Which route answered a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Route {
    /// The lean route, in lanes.
    Lean,
    /// The generic route, after the lean one refused the scene.
    Generic,
    /// No answer: the scene is invalid, or G singular (zeros in the outputs).
    Refused,
}

/// Why a scene did not take the lean route.
#[derive(Clone, Debug, PartialEq)]
pub enum Reason {
    /// The lean route refused it (then the generic route answered).
    Lean(LeanError),
    /// The scene is not a valid problem.
    Invalid(InvalidProblem),
    /// G is singular: no simultaneous answer (see [`crate::analysis`]).
    Unsolvable(SolveError),
}

/// The impulses and twists of a batch for one model, as structure of arrays like [`Scenes`].
/// A scene without an answer ([`Route::Refused`]) has zeros there.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcomes<const N: usize> {
    /// P̂_j = P_j / |n_j| per contact.
    pub impulses_hat: [Vec<f64>; N],
    /// {v} = [ω; v_C] after impact.
    pub velocity: [Vec<f64>; 6],
    /// Which route answered each scene.
    pub routes: Vec<Route>,
    /// For each scene off the lean route (in order), its index and why.
    pub reasons: Vec<(usize, Reason)>,
}

/// N empty vectors.
fn empty<T, const N: usize>(f: impl Fn() -> T) -> [T; N] {
    array::from_fn(|_| f())
}

impl<const N: usize> Default for Scenes<N> {
    fn default() -> Self {
        Scenes {
            mass: Vec::new(),
            inertia: empty(Vec::new),
            velocity: empty(Vec::new),
            points: empty(|| empty(Vec::new)),
            normals: empty(|| empty(Vec::new)),
            k_newton: empty(Vec::new),
            k_poisson: empty(Vec::new),
        }
    }
}

impl<const N: usize> Default for Outcomes<N> {
    fn default() -> Self {
        Outcomes {
            impulses_hat: empty(Vec::new),
            velocity: empty(Vec::new),
            routes: Vec::new(),
            reasons: Vec::new(),
        }
    }
}

impl<const N: usize> Outcomes<N> {
    /// Size the vectors for `n` scenes, keeping their capacity. The numbers are not cleared:
    /// the sweep writes every entry (a lane's answer, or zeros where no route answers).
    fn reset(&mut self, n: usize) {
        for v in self.impulses_hat.iter_mut().chain(&mut self.velocity) {
            v.resize(n, 0.0);
        }
        self.routes.clear();
        self.routes.resize(n, Route::Lean);
        self.reasons.clear();
    }
}

impl<const N: usize> Scenes<N> {
    /// Number of scenes.
    pub fn len(&self) -> usize {
        self.mass.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.mass.is_empty()
    }

    /// Append the scene of `problem`.
    ///
    /// # Errors
    /// [`BatchError::NotBatchable`] unless it is a free body in principal axes with N contacts.
    pub fn push(&mut self, problem: &Problem<f64>) -> Result<(), BatchError> {
        let (body, c) = (problem.body(), problem.contacts());
        let Inertia::Principal(j) = &body.inertia else {
            return Err(BatchError::NotBatchable(N));
        };
        if c.len() != N || problem.constraints().is_some() {
            return Err(BatchError::NotBatchable(N));
        }
        self.mass.push(body.mass);
        for k in 0..3 {
            self.inertia[k].push(j[k]);
        }
        for (k, v) in problem.velocity().as_slice().iter().enumerate() {
            self.velocity[k].push(*v);
        }
        for (i, c) in c.iter().enumerate() {
            for k in 0..3 {
                self.points[i][k].push(c.point[k]);
                self.normals[i][k].push(c.normal[k]);
            }
            self.k_newton[i].push(c.k_newton);
            self.k_poisson[i].push(c.k_poisson);
        }
        Ok(())
    }

    /// The first array whose length differs from `mass`'s, named.
    fn mismatch(&self) -> Option<(String, usize)> {
        let n = self.len();
        let bad = |v: &Vec<f64>| v.len() != n;
        let xyz = ["x", "y", "z"];
        if let Some(k) = self.inertia.iter().position(bad) {
            return Some((format!("inertia[{k}]"), self.inertia[k].len()));
        }
        if let Some(k) = self.velocity.iter().position(bad) {
            return Some((format!("velocity[{k}]"), self.velocity[k].len()));
        }
        for i in 0..N {
            for (name, a) in [("points", &self.points[i]), ("normals", &self.normals[i])] {
                if let Some(k) = a.iter().position(bad) {
                    return Some((format!("{name}[{i}].{}", xyz[k]), a[k].len()));
                }
            }
            for (name, v) in [
                ("k_newton", &self.k_newton[i]),
                ("k_poisson", &self.k_poisson[i]),
            ] {
                if bad(v) {
                    return Some((format!("{name}[{i}]"), v.len()));
                }
            }
        }
        None
    }

    /// Scene `s` as a [`Problem`] (validated), for the generic route.
    fn problem(&self, s: usize) -> Result<Problem<f64>, InvalidProblem> {
        let v3 = |a: &[Vec<f64>; 3]| Vec3::new(a[0][s], a[1][s], a[2][s]);
        let body = RigidBody::principal(self.mass[s], v3(&self.inertia));
        let v = &self.velocity;
        let velocity = Screw::new(
            Vec3::new(v[0][s], v[1][s], v[2][s]),
            Vec3::new(v[3][s], v[4][s], v[5][s]),
        );
        let contacts = (0..N)
            .map(|i| {
                Contact::new(
                    v3(&self.points[i]),
                    v3(&self.normals[i]),
                    self.k_newton[i][s],
                )
                .with_coefficients(self.k_newton[i][s], self.k_poisson[i][s])
            })
            .collect();
        Problem::new(body, velocity, contacts)
    }
}

/// Solve every scene of `scenes` under `model` into `out` (its vectors are reused).
///
/// # Errors
/// [`BatchError::Lengths`] when the arrays of `scenes` differ in length.
pub fn solve<const N: usize>(
    scenes: &Scenes<N>,
    model: Model,
    out: &mut Outcomes<N>,
) -> Result<(), BatchError> {
    solve_models(scenes, &mut [(model, out)])
}

/// Both models at once, sharing each scene's factorization: Newton into `newton`, Poisson
/// into `poisson`.
///
/// # Errors
/// [`BatchError::Lengths`] when the arrays of `scenes` differ in length.
pub fn solve_both<const N: usize>(
    scenes: &Scenes<N>,
    newton: &mut Outcomes<N>,
    poisson: &mut Outcomes<N>,
) -> Result<(), BatchError> {
    solve_models(
        scenes,
        &mut [(Model::Newton, newton), (Model::Poisson, poisson)],
    )
}

/// Every model of `outs` into its outcomes, at the machine's width (module docs).
fn solve_models<const N: usize>(
    scenes: &Scenes<N>,
    outs: &mut [(Model, &mut Outcomes<N>)],
) -> Result<(), BatchError> {
    let n = scenes.len();
    if let Some((what, found)) = scenes.mismatch() {
        return Err(BatchError::Lengths {
            what,
            found,
            expected: n,
        });
    }
    for (_, out) in outs.iter_mut() {
        out.reset(n);
    }
    match pulp::Arch::new() {
        #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
        pulp::Arch::V4(simd) => pulp::Simd::vectorize(simd, Sweep::<8, N>(scenes, outs)),
        #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
        pulp::Arch::V3(simd) => pulp::Simd::vectorize(simd, Sweep::<4, N>(scenes, outs)),
        _ => sweep::sweep::<2, N>(scenes, outs),
    }
    Ok(())
}

/// [`sweep::sweep`] at L lanes, as the operation `pulp` runs compiled for an instruction set.
struct Sweep<'a, 'o, const L: usize, const N: usize>(
    &'a Scenes<N>,
    &'a mut [(Model, &'o mut Outcomes<N>)],
);

impl<const L: usize, const N: usize> pulp::WithSimd for Sweep<'_, '_, L, N> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        sweep::sweep::<L, N>(self.0, self.1)
    }
}

/// The generic solve's buffers, kept from one refused scene to the next.
type Work = Option<(Impact<f64>, Outcome<f64>)>;

/// Scene `s` by the generic route under the models `outs[m]` of `refused` (m, and why the
/// lean route did not answer that model): assembled once, solved per model, written into
/// `outs[m]`.
fn solve_generic<const N: usize>(
    scenes: &Scenes<N>,
    s: usize,
    refused: &[(usize, LeanError)],
    outs: &mut [(Model, &mut Outcomes<N>)],
    work: &mut Work,
) {
    let mut assembled = assemble(scenes, s, work);
    for (m, why) in refused {
        let (model, out) = &mut outs[*m];
        let solved = match &mut assembled {
            Ok(w) => {
                let (impact, o) = &mut **w;
                match impact.solve(*model, o) {
                    Ok(_) => Ok(&*o),
                    Err(e) => Err(Reason::Unsolvable(e)),
                }
            }
            Err(reason) => Err(reason.clone()),
        };
        let (route, reason) = match solved {
            Ok(o) => {
                for (j, p) in o.impulses_hat.iter().enumerate() {
                    out.impulses_hat[j][s] = *p;
                }
                for (k, x) in o.velocity.as_slice().iter().enumerate() {
                    out.velocity[k][s] = *x;
                }
                (Route::Generic, Reason::Lean(why.clone()))
            }
            Err(reason) => (Route::Refused, reason),
        };
        out.routes[s] = route;
        out.reasons.push((s, reason));
    }
}

/// Scene `s` built, validated and assembled for the generic solve, reusing `work`.
fn assemble<'w, const N: usize>(
    scenes: &Scenes<N>,
    s: usize,
    work: &'w mut Work,
) -> Result<&'w mut (Impact<f64>, Outcome<f64>), Reason> {
    let problem = scenes.problem(s).map_err(Reason::Invalid)?;
    match work {
        Some(w) => {
            w.0.reassemble(&problem).map_err(Reason::Unsolvable)?;
            Ok(w)
        }
        None => {
            let impact = Impact::assemble(&problem).map_err(Reason::Unsolvable)?;
            Ok(work.insert((impact, Outcome::default())))
        }
    }
}
