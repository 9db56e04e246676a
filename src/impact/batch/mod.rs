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
//! path ([`crate::impact::solve::Impact`]) instead, and [`Outcomes::answers`] says which
//! route answered, or why none did.

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

/// Scenes per vector step: four f64 lanes (two SSE2 or one AVX register per operation);
/// measured no slower than two or eight on the default target.
pub const LANES: usize = 4;

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

/// Which route answered a scene, or why none could.
#[derive(Clone, Debug, PartialEq)]
pub enum Answer {
    /// The lean route, in lanes.
    Lean,
    /// The generic route, after the lean one refused the scene (its reason).
    Generic(LeanError),
    /// The scene is not a valid problem.
    Invalid(InvalidProblem),
    /// G is singular: no simultaneous answer (see [`crate::analysis`]).
    Unsolvable(SolveError),
}

/// The impulses and twists of a batch, as structure of arrays like [`Scenes`]. A scene
/// without an answer ([`Answer::Invalid`], [`Answer::Unsolvable`]) has zeros there.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcomes<const N: usize> {
    /// P̂_j = P_j / |n_j| per contact.
    pub impulses_hat: [Vec<f64>; N],
    /// {v} = [ω; v_C] after impact.
    pub velocity: [Vec<f64>; 6],
    /// Which route answered each scene.
    pub answers: Vec<Answer>,
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
            answers: Vec::new(),
        }
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

    /// Every array with its name, for the length check.
    fn arrays(&self) -> impl Iterator<Item = (String, &Vec<f64>)> {
        let xyz = ["x", "y", "z"];
        let mut all: Vec<(String, &Vec<f64>)> = Vec::new();
        for k in 0..3 {
            all.push((format!("inertia[{k}]"), &self.inertia[k]));
        }
        for k in 0..6 {
            all.push((format!("velocity[{k}]"), &self.velocity[k]));
        }
        for i in 0..N {
            for (k, c) in xyz.iter().enumerate() {
                all.push((format!("points[{i}].{c}"), &self.points[i][k]));
                all.push((format!("normals[{i}].{c}"), &self.normals[i][k]));
            }
            all.push((format!("k_newton[{i}]"), &self.k_newton[i]));
            all.push((format!("k_poisson[{i}]"), &self.k_poisson[i]));
        }
        all.into_iter()
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
                Contact::new(v3(&self.points[i]), v3(&self.normals[i]), self.k_newton[i][s])
                    .with_coefficients(self.k_newton[i][s], self.k_poisson[i][s])
            })
            .collect();
        Problem::new(body, velocity, contacts)
    }

    /// Whether scene `s` passes [`Problem::new`]'s checks, decided without building it: m,
    /// J_k > 0, every number finite, normals nonzero, k ∈ [0, 1].
    #[inline]
    fn valid(&self, s: usize) -> bool {
        let positive = |x: f64| x > 0.0 && x.is_finite();
        let k = |x: f64| (0.0..=1.0).contains(&x);
        positive(self.mass[s])
            && self.inertia.iter().all(|j| positive(j[s]))
            && self.velocity.iter().all(|v| v[s].is_finite())
            && (0..N).all(|i| {
                let n = &self.normals[i];
                self.points[i].iter().all(|p| p[s].is_finite())
                    && n.iter().all(|x| x[s].is_finite())
                    && n.iter().any(|x| x[s] != 0.0)
                    && k(self.k_newton[i][s])
                    && k(self.k_poisson[i][s])
            })
    }

    /// Scenes `start ..` `start + LANES` as lanes; past the end, lanes repeat the last scene.
    #[inline(always)]
    fn lanes(&self, start: usize) -> Data<Lanes<LANES>, N> {
        let last = self.len() - 1;
        let at = |v: &Vec<f64>| Lanes(array::from_fn(|i| v[(start + i).min(last)]));
        let three = |a: &[Vec<f64>; 3]| [at(&a[0]), at(&a[1]), at(&a[2])];
        Data {
            mass: at(&self.mass),
            inertia: InverseInertia::Principal(three(&self.inertia)),
            velocity: array::from_fn(|k| at(&self.velocity[k])),
            points: array::from_fn(|i| three(&self.points[i])),
            normals: array::from_fn(|i| three(&self.normals[i])),
            k_newton: array::from_fn(|i| at(&self.k_newton[i])),
            k_poisson: array::from_fn(|i| at(&self.k_poisson[i])),
        }
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
    let n = scenes.len();
    if let Some((what, v)) = scenes.arrays().find(|(_, v)| v.len() != n) {
        return Err(BatchError::Lengths {
            what,
            found: v.len(),
            expected: n,
        });
    }
    for v in out.impulses_hat.iter_mut().chain(&mut out.velocity) {
        v.clear();
        v.resize(n, 0.0);
    }
    out.answers.clear();
    let mut generic = None;
    for start in (0..n).step_by(LANES) {
        let factored = scenes.lanes(start).factor();
        let (p, v) = factored.solve(model);
        let (g, d) = (factored.inertances(), factored.pivots());
        for lane in 0..LANES.min(n - start) {
            let s = start + lane;
            let lean = if scenes.valid(s) {
                route_test::<N>(|i, j| g[i][j].0[lane], |j| d[j].0[lane]).and_then(|()| {
                    let finite = p.iter().chain(&v).all(|x| x.0[lane].is_finite());
                    finite.then_some(()).ok_or(LeanError::NotFinite)
                })
            } else {
                Err(LeanError::NotFinite)
            };
            match lean {
                Ok(()) => {
                    for (o, x) in out.impulses_hat.iter_mut().zip(&p) {
                        o[s] = x.0[lane];
                    }
                    for (o, x) in out.velocity.iter_mut().zip(&v) {
                        o[s] = x.0[lane];
                    }
                    out.answers.push(Answer::Lean);
                }
                Err(why) => {
                    let answer = solve_generic(scenes, s, model, why, out, &mut generic);
                    out.answers.push(answer);
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
) -> Answer {
    let problem = match scenes.problem(s) {
        Ok(p) => p,
        Err(e) => return Answer::Invalid(e),
    };
    let assembled = match work.take() {
        Some((mut impact, o)) => impact.reassemble(&problem).map(|()| (impact, o)),
        None => Impact::assemble(&problem).map(|i| (i, Outcome::default())),
    };
    let (mut impact, mut o) = match assembled {
        Ok(x) => x,
        Err(e) => return Answer::Unsolvable(e),
    };
    let answer = match impact.solve(model, &mut o) {
        Ok(()) => {
            for (j, p) in o.impulses_hat.iter().enumerate() {
                out.impulses_hat[j][s] = *p;
            }
            for (k, x) in o.velocity.as_slice().iter().enumerate() {
                out.velocity[k][s] = *x;
            }
            Answer::Generic(why)
        }
        Err(e) => Answer::Unsolvable(e),
    };
    *work = Some((impact, o));
    answer
}
