//! # inertance
//!
//! The simultaneous frictionless collision of a rigid body at N points, after Dragna, Pandrea
//! and Stănescu, *Simultaneous Collision of the Rigid Body at Two Points*, Symmetry 13 (2021)
//! 1924 — "the paper"; equation numbers in the docs are the paper's.
//!
//! ## Quick start
//!
//! The paper's Example 3 — a planar bar striking two supports — built in code, validated, and
//! solved in floating point and in exact rationals:
//!
//! ```
//! use inertance::{Contact, Exact, Model, Problem, RigidBody, Scalar, Screw, Vec3, solve};
//!
//! fn example_3<T: Scalar>() -> Result<Problem<T>, inertance::InvalidProblem> {
//!     let q = inertance::scalar::ratio::<T>;
//!     let v = |x, y, z| Vec3::new(q(x, 1), q(y, 1), q(z, 1));
//!     let body = RigidBody::principal(q(1, 1), Vec3::new(q(12, 1), q(8, 5), q(12, 1)));
//!     // {v⁰} = [ω⁰; v_C⁰]: ω⁰ = 0.4 rad/s about z, v_C⁰ = (3, 2, 0) m/s.
//!     let twist = Screw::new(Vec3::new(q(0, 1), q(0, 1), q(2, 5)), v(3, 2, 0));
//!     let contacts = vec![
//!         Contact::new(v(0, -2, 0), v(1, 0, 0), q(3, 10)),
//!         // A normal need not be a unit vector: impulses still come out in N s.
//!         Contact::new(v(0, 4, 0), v(2, 0, 0), q(1, 5)),
//!     ];
//!     Problem::new(body, twist, contacts)
//! }
//!
//! let newton = solve(&example_3::<f64>()?, Model::Newton)?;
//! assert!((newton.impulses[0].to_f64() - 3.655556).abs() < 1e-6); // P_1, N s
//!
//! let exact = solve(&example_3::<Exact>()?, Model::Newton)?;
//! assert_eq!(exact.det, inertance::scalar::ratio::<Exact>(3, 1)); // Δ = det G, exactly
//! assert_eq!(exact.impulses[1].exact_text().unwrap(), "89/450"); // P_2 = 89/450 N s
//! assert_eq!(exact.lost_velocity_energy.to_f64(), 413791.0 / 45000.0); // E_p, J
//!
//! // Bad input is refused with the field named, as in scene files.
//! let body = RigidBody::principal(-1.0, Vec3::new(1.0, 1.0, 1.0));
//! let err = Problem::new(body, Screw::zero(), vec![]).unwrap_err();
//! assert_eq!(err.to_string(), "body.mass must be positive");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! [`Problem::new`] validates (m > 0, J_k > 0 or a symmetric positive definite tensor, finite
//! numbers, nonzero normals, tangents perpendicular to their normals, k ∈ [0, 1], at least one
//! contact) and names the offending field; [`solve`] returns a [`Solution`] in the paper's
//! units. Scenes written as TOML files go through [`scene::Scene`] and [`scene::pipeline`]; the
//! lower-level [`impact::solve::Impact`] reuses its buffers across solves (no allocation in
//! f64).
//!
//! ## Notation (used everywhere)
//!
//! * Cxyz: the body axes through the centre of mass C — central principal axes, with
//!   m, J = diag(J_x, J_y, J_z) as in the paper, or any axes, with J the full symmetric central
//!   inertia tensor ([`RigidBody::with_tensor`]; J⁻¹ exact, by the adjugate).
//! * Twist {v} = [ω; v_C]; axis screw {E} = [u; r × u] (eq. 3–4); η = [[0, I], [I, 0]] (eq. 5)
//!   and the mixed product {a}ᵀ η {b} (eq. 6).
//! * \[M\] = [[0, m I], [J, 0]] and \[M\]⁻¹ = [[0, J⁻¹], [m⁻¹ I, 0]] (eq. 9).
//! * Inertances g_ij,ab = {E_ia}ᵀ η \[M\]⁻¹ {E_jb} (eq. 12); G = \[g_ij,xx\]; Δ = det G.
//! * P_i: the impulse at A_i, acting along −x_i (x_i is the outward normal, eq. 10).
//!
//! ## Layers, bottom up
//!
//! | module | what lives there |
//! |---|---|
//! | [`number`] | numbers as written: the one expression grammar, exact reading, rational text |
//! | [`scalar`] | the fields a solve runs in: f32, f64, double-double, exact rationals, symbolic; dual numbers over them (sensitivities) |
//! | [`linalg`] | field-only linear algebra: pivoted LDLᵀ, rank, null space |
//! | [`mechanics`] | screws, the body and its mobility, contact frames, constraints, surfaces |
//! | [`impact`] | the validated problem, the restitution laws, the solve, the solution in physical units |
//! | [`analysis`] | degenerate cases (§8): ranks, compatibility, families, admissibility |
//! | [`report`] | what a solve reports, as a table or JSON |
//! | [`scene`] | TOML scenes and the pipeline from a scene to a report |
//! | [`tools`] | the commands: `analyze`, `check`, `derive`, `bench`, `sweep` |
//!
//! Each layer uses only those above it in this table; the `inertance` binary is a thin CLI
//! over [`tools`] and [`scene`].

#![deny(missing_docs)]
// Index loops over i, j read like the paper's sums (g_ij, Σ_j P_j g_ij); keep them.
#![allow(clippy::needless_range_loop)]

pub mod analysis;
pub mod impact;
pub mod linalg;
pub mod mechanics;
pub mod number;
pub mod report;
pub mod scalar;
pub mod scene;
pub mod simulate;
pub mod tools;

/// The guide's Rust examples, compiled and run by `cargo test --doc` so that they cannot go stale.
#[cfg(doctest)]
#[doc = include_str!("../guide/library.md")]
mod guide_library {}

/// The crate's version (the workspace's, in Cargo.toml): `inertance --version` and Python's
/// `inertance.__version__` print it.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

pub use impact::outputs::Outputs;
pub use impact::problem::{Field, InvalidProblem, Problem, Reason};
pub use impact::restitution::Model;
pub use impact::solution::{Solution, solve, solve_for, solve_unilateral};
pub use impact::solve::SolveError;
pub use impact::unilateral::{Law, UnilateralError};
pub use mechanics::body::RigidBody;
pub use mechanics::constraint::Joint;
pub use mechanics::contact::{Contact, Surd};
pub use mechanics::screw::{Screw, Vec3};
pub use scalar::{Exact, Scalar};
