//! Many free-body scenes of the same N at once — sweeps, Monte Carlo — for the impulses and
//! the twist after impact.
//!
//! The scenes are held as structure of arrays ([`Scenes`]: one `Vec<f64>` per input
//! coordinate, scene s at index s of each), read [`LANES`] scenes at a time into
//! [`lanes::Lanes`] and solved by the lean path's own arithmetic ([`crate::impact::lean`]),
//! every operation applied to the lanes together: the compiler emits vector instructions for
//! it. Each lane computes what [`crate::impact::lean::Lean`] computes for that scene alone,
//! bit for bit (tested). A scene the lean route refuses — too nearly dependent contacts for
//! the normal equations (the accuracy contract), or invalid input — is solved by the generic
//! path ([`crate::impact::solve::Impact`]) instead, and [`Outcomes::routes`] says which
//! route answered, [`Outcomes::reasons`] why the others did not take the lean one.

pub mod lanes;

use std::array;

use crate::impact::lean::{Data, InverseInertia, LeanError, route_test};
use crate::impact::problem::{InvalidProblem, Problem};
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::mechanics::body::{Inertia, RigidBody};
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Vec3};

use lanes::Lanes;

/// Scenes per vector step: two f64 lanes, one SSE2 register per operation. Measured on the
/// default x86-64 target (criterion, `batch-256/soa-lanes-f64`): 24.6 µs per 256 scenes with
/// two lanes, 36.5 µs with four, 36.7 µs with eight — wider lanes made the inliner give up on
/// the field-generic code.
pub const LANES: usize = 2;
const _: () = assert!(LANES == 2, "`at` reads two lanes");

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
    /// Empty the vectors and size them for `n` scenes, keeping their capacity.
    fn reset(&mut self, n: usize) {
        for v in self.impulses_hat.iter_mut().chain(&mut self.velocity) {
            v.clear();
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

    /// Scenes `start ..` `start + LANES` as lanes; past the end, lanes repeat the last scene.
    #[inline(always)]
    fn lanes(&self, start: usize) -> Data<Lanes<LANES>, N> {
        let three = |a: &[Vec<f64>; 3]| [at(&a[0], start), at(&a[1], start), at(&a[2], start)];
        Data {
            mass: at(&self.mass, start),
            inertia: InverseInertia::Principal(three(&self.inertia)),
            velocity: array::from_fn(|k| at(&self.velocity[k], start)),
            points: array::from_fn(|i| three(&self.points[i])),
            normals: array::from_fn(|i| three(&self.normals[i])),
            k_newton: array::from_fn(|i| at(&self.k_newton[i], start)),
            k_poisson: array::from_fn(|i| at(&self.k_poisson[i], start)),
        }
    }
}

/// `v[start .. start + LANES]` as lanes; past the end, the last entry repeated.
#[inline(always)]
fn at(v: &[f64], start: usize) -> Lanes<LANES> {
    match v.get(start..start + LANES) {
        Some(&[a, b]) => Lanes([a, b]),
        _ => {
            let last = v.len() - 1;
            Lanes([v[start.min(last)], v[(start + 1).min(last)]])
        }
    }
}

/// Lane by lane, whether `x` lies in `lo ..= hi` (`false` for NaN).
#[inline(always)]
fn within(ok: &mut [bool; LANES], x: &Lanes<LANES>, lo: f64, hi: f64) {
    for (o, x) in ok.iter_mut().zip(x.0) {
        *o &= x >= lo && x <= hi;
    }
}

/// Lane by lane, whether every value of `xs` is finite: Σ 0·x is 0 then, NaN otherwise.
#[inline(always)]
fn finite(ok: &mut [bool; LANES], xs: &[Lanes<LANES>]) {
    let zero = Lanes::<LANES>::splat(0.0);
    let mut sum = zero;
    for x in xs {
        sum += zero * x;
    }
    for (o, s) in ok.iter_mut().zip(sum.0) {
        *o &= s == 0.0;
    }
}

/// Which lanes of `data` pass [`Problem::new`]'s checks: m, J_k > 0, every number finite,
/// normals nonzero, k ∈ [0, 1] (decided lane by lane, without building a problem).
#[inline(always)]
fn valid<const N: usize>(data: &Data<Lanes<LANES>, N>) -> [bool; LANES] {
    let mut ok = [true; LANES];
    let InverseInertia::Principal(j) = &data.inertia else {
        return [false; LANES];
    };
    let tiny = f64::MIN_POSITIVE * f64::EPSILON; // the least positive f64
    within(&mut ok, &data.mass, tiny, f64::MAX);
    for j in j {
        within(&mut ok, j, tiny, f64::MAX);
    }
    finite(&mut ok, &data.velocity);
    for i in 0..N {
        finite(&mut ok, &data.points[i]);
        finite(&mut ok, &data.normals[i]);
        within(&mut ok, &data.k_newton[i], 0.0, 1.0);
        within(&mut ok, &data.k_poisson[i], 0.0, 1.0);
        let n = &data.normals[i];
        for (l, o) in ok.iter_mut().enumerate() {
            *o &= n[0].0[l] != 0.0 || n[1].0[l] != 0.0 || n[2].0[l] != 0.0;
        }
    }
    ok
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

/// Every model of `outs` into its outcomes.
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
    let mut generic = None;
    for start in (0..n).step_by(LANES) {
        let data = scenes.lanes(start);
        let valid = valid(&data);
        let (factored, g) = data.factor();
        let d = factored.pivots();
        let count = LANES.min(n - start);
        for (model, out) in outs.iter_mut() {
            let (p, v) = factored.solve(*model);
            let mut ok = valid;
            finite(&mut ok, &p);
            finite(&mut ok, &v);
            // The common case, every lane valid and accepted: whole lanes out at once.
            if count == LANES
                && ok.iter().all(|o| *o)
                && (0..LANES).all(|l| route_test::<N>(|i, j| g[i][j].0[l], |j| d[j].0[l]).is_ok())
            {
                let range = start..start + LANES;
                for (o, x) in out.impulses_hat.iter_mut().zip(&p) {
                    o[range.clone()].copy_from_slice(&x.0);
                }
                for (o, x) in out.velocity.iter_mut().zip(&v) {
                    o[range.clone()].copy_from_slice(&x.0);
                }
                continue;
            }
            for (l, ok) in ok.into_iter().enumerate().take(count) {
                let s = start + l;
                let route = match ok {
                    true => route_test::<N>(|i, j| g[i][j].0[l], |j| d[j].0[l]),
                    false => Err(LeanError::NotFinite),
                };
                match route {
                    Ok(()) => {
                        for (o, x) in out.impulses_hat.iter_mut().zip(&p) {
                            o[s] = x.0[l];
                        }
                        for (o, x) in out.velocity.iter_mut().zip(&v) {
                            o[s] = x.0[l];
                        }
                    }
                    Err(why) => solve_generic(scenes, s, *model, why, out, &mut generic),
                }
            }
        }
    }
    Ok(())
}

/// Scene `s` by the generic route, into `out`; `work` keeps the generic solve's buffers for
/// the next refused scene.
fn solve_generic<const N: usize>(
    scenes: &Scenes<N>,
    s: usize,
    model: Model,
    why: LeanError,
    out: &mut Outcomes<N>,
    work: &mut Option<(Impact<f64>, Outcome<f64>)>,
) {
    let (route, reason) = match generic(scenes, s, model, work) {
        Ok(o) => {
            for (j, p) in o.impulses_hat.iter().enumerate() {
                out.impulses_hat[j][s] = *p;
            }
            for (k, x) in o.velocity.as_slice().iter().enumerate() {
                out.velocity[k][s] = *x;
            }
            (Route::Generic, Reason::Lean(why))
        }
        Err(reason) => (Route::Refused, reason),
    };
    out.routes[s] = route;
    out.reasons.push((s, reason));
}

/// The generic solve of scene `s`, reusing `work`.
fn generic<'w, const N: usize>(
    scenes: &Scenes<N>,
    s: usize,
    model: Model,
    work: &'w mut Option<(Impact<f64>, Outcome<f64>)>,
) -> Result<&'w Outcome<f64>, Reason> {
    let problem = scenes.problem(s).map_err(Reason::Invalid)?;
    let (impact, o) = match work {
        Some((impact, o)) => {
            impact.reassemble(&problem).map_err(Reason::Unsolvable)?;
            (impact, o)
        }
        None => {
            let impact = Impact::assemble(&problem).map_err(Reason::Unsolvable)?;
            let w = work.insert((impact, Outcome::default()));
            (&mut w.0, &mut w.1)
        }
    };
    impact.solve(model, o).map_err(Reason::Unsolvable)?;
    Ok(o)
}
