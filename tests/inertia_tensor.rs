//! A full inertia tensor: a body written in axes that are not principal is the same body.
//!
//! Each scene is given in central principal axes (J diagonal) and then **posed** by a rational
//! rotation R — about z by (cos, sin) = (3/5, 4/5), and the general rotation of the rational
//! quaternion q = (1, 2, 3, 4), R = (quaternion matrix)/|q|² — as
//!
//! ```text
//! J' = R J Rᵀ (a full tensor),   r' = R r,   n' = R n,   y' = R y,   v' = R v,   ω' = R ω.
//! ```
//!
//! A rotation changes coordinates, not physics: in exact rationals the inertances G (and the
//! tangential blocks), Δ, the impulses of every law, the point velocities in the contact
//! frames and the energies E_p, ΔE_c are *equal*, and the twist after impact is exactly
//! R times the original. The scenes: the paper's Example 3 (the planar bar), a spatial scene
//! with three contacts, a body held by a spherical joint, and Example 3 with Coulomb friction
//! (which the posed scene keeps exact only because the planarity test finds the rotated plane).
//!
//! Then invariants with random symmetric positive definite tensors J = AᵀA + I (small integer
//! A): J (J⁻¹ μ) = μ exactly, G symmetric and equal to eq. (57), momentum balance and both
//! energies against formulas written out here; the refusal of tensors that are not positive
//! definite or not symmetric, naming the key; a scene file with a 3×3 `inertia` solved
//! through the CLI with the impulses of its principal-axes version, scaled, swept, and read
//! with symbols (eq. 57 in closed form); and the limit of the exact planar test (a plane
//! whose normal has an irrational length).
//!
//! **f64 against exact.** Every f64 output of the frictionless solve is a rational function of
//! the inputs evaluated in a fixed sequence of about 10² roundings (J' rounded once per entry,
//! J⁻¹ by the adjugate: ~40 operations; each ĝ_ij: ~30; the N×N elimination; the twist and the
//! energies), each of relative error ≤ ε = 2⁻⁵² (`f64::EPSILON`), and the impulses solve
//! G P = b, which amplifies relative errors by at most κ(G) = ‖G‖_∞ ‖G⁻¹‖_∞. So we allow
//! 2¹⁰ ε κ(G) (a factor 10 over 10² roundings) times the largest magnitude among the values
//! compared, with κ(G) computed exactly from the exact G.

mod common;

use common::{SceneFile, kinetic_energy};
use inertance::impact::friction::{Frictional, Restitution, solve_frictional};
use inertance::impact::problem::{Field, Problem, Reason};
use inertance::impact::restitution::Model;
use inertance::impact::solve::Impact;
use inertance::mechanics::body::{Inertia, Mobility, RigidBody, inertance, inertance_eq57};
use inertance::mechanics::constraint::Joint;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, Scalar, int, ratio};
use inertance::scene::Scene;
use inertance::{Solution, solve, solve_unilateral};
use num_traits::{One, Signed, Zero};
use proptest::prelude::*;

type Rotation = [[Exact; 3]; 3];

fn q(n: i64, d: i64) -> Exact {
    ratio(n, d)
}

fn v(x: Exact, y: Exact, z: Exact) -> Vec3<Exact> {
    Vec3::new(x, y, z)
}

fn vi(x: i64, y: i64, z: i64) -> Vec3<Exact> {
    Vec3::new(int(x), int(y), int(z))
}

/// The rotation about z by the angle with (cos, sin) = (3/5, 4/5).
fn about_z() -> Rotation {
    [
        [q(3, 5), q(-4, 5), int(0)],
        [q(4, 5), q(3, 5), int(0)],
        [int(0), int(0), int(1)],
    ]
}

/// The rotation of the quaternion (a, b, c, d): its matrix over |q|², rational and orthogonal.
fn quaternion(a: i64, b: i64, c: i64, d: i64) -> Rotation {
    let n = a * a + b * b + c * c + d * d;
    let r = |x: i64| q(x, n);
    [
        [
            r(a * a + b * b - c * c - d * d),
            r(2 * (b * c - a * d)),
            r(2 * (b * d + a * c)),
        ],
        [
            r(2 * (b * c + a * d)),
            r(a * a - b * b + c * c - d * d),
            r(2 * (c * d - a * b)),
        ],
        [
            r(2 * (b * d - a * c)),
            r(2 * (c * d + a * b)),
            r(a * a - b * b - c * c + d * d),
        ],
    ]
}

fn rotations() -> Vec<(&'static str, Rotation)> {
    vec![
        ("about z by (3/5, 4/5)", about_z()),
        ("quaternion (1, 2, 3, 4)", quaternion(1, 2, 3, 4)),
    ]
}

/// R x.
fn turn(r: &Rotation, x: &Vec3<Exact>) -> Vec3<Exact> {
    Vec3::from_fn(|i, _| (0..3).fold(Exact::zero(), |s, k| s + r[i][k].clone() * &x[k]))
}

/// R {v}: both halves of a twist (or an axis screw) turned.
fn turn_screw(r: &Rotation, s: &Screw<Exact>) -> Screw<Exact> {
    Screw::new(turn(r, &s.top()), turn(r, &s.bottom()))
}

/// R J Rᵀ.
fn turn_tensor(r: &Rotation, j: &Inertia<Exact>) -> [[Exact; 3]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|k| {
            let mut s = Exact::zero();
            for a in 0..3 {
                for b in 0..3 {
                    s += r[i][a].clone() * j.entry(a, b) * &r[k][b];
                }
            }
            s
        })
    })
}

/// The body, twist and contacts of `p` posed by `r` (constraints are posed by the caller).
fn pose_parts(
    p: &Problem<Exact>,
    r: &Rotation,
) -> (RigidBody<Exact>, Screw<Exact>, Vec<Contact<Exact>>) {
    let body = RigidBody::with_tensor(p.body().mass.clone(), turn_tensor(r, &p.body().inertia));
    let contacts = p
        .contacts()
        .iter()
        .map(|c| Contact {
            point: turn(r, &c.point),
            normal: turn(r, &c.normal),
            tangent: c.tangent.as_ref().map(|t| turn(r, t)),
            ..c.clone()
        })
        .collect();
    (body, turn_screw(r, p.velocity()), contacts)
}

fn pose(p: &Problem<Exact>, r: &Rotation) -> Problem<Exact> {
    let (body, twist, contacts) = pose_parts(p, r);
    Problem::new(body, twist, contacts).expect("a posed valid problem is valid")
}

/// The paper's Example 3 (§7): the planar bar, with A₂'s tangent given as in
/// `examples/planar-bar.toml`.
fn example_3(mu: Exact) -> Problem<Exact> {
    let c = |y: i64, k: Exact| Contact::new(vi(0, y, 0), vi(1, 0, 0), k).with_friction(mu.clone());
    Problem::new(
        RigidBody::principal(int(1), v(int(12), q(8, 5), int(12))),
        Screw::new(v(int(0), int(0), q(2, 5)), vi(3, 2, 0)),
        vec![c(-2, q(3, 10)), c(4, q(1, 5)).with_tangent(vi(0, 1, 0))],
    )
    .unwrap()
}

/// A spatial scene: three contacts on a body with three distinct moments, normals in three
/// directions (one of irrational length), tangents from the velocities (§12).
fn spatial() -> Problem<Exact> {
    let c = |p: Vec3<Exact>, n: Vec3<Exact>, kn: Exact, kp: Exact| Contact {
        k_newton: kn,
        k_poisson: kp.clone(),
        k_energetic: kp,
        ..Contact::new(p, n, int(0))
    };
    Problem::new(
        RigidBody::principal(int(2), v(int(1), int(2), int(3))),
        Screw::new(v(q(1, 2), q(-1, 3), q(1, 5)), vi(1, -2, -3)),
        vec![
            c(vi(1, 1, -1), vi(0, 0, -1), q(1, 2), q(1, 3)),
            c(vi(-1, 1, 0), vi(-1, 1, 0), q(1, 4), q(1, 4)),
            c(v(int(0), int(-1), q(1, 2)), vi(0, -1, 0), q(3, 5), q(2, 5)),
        ],
    )
    .unwrap()
}

/// The centre of a spherical joint, and the spin about it before impact.
fn pivot() -> (Vec3<Exact>, Vec3<Exact>) {
    (vi(0, 0, 2), v(int(1), q(1, 2), int(0)))
}

/// A body held by a spherical joint at the pivot, spinning about it, hitting two supports.
fn constrained(r: Option<&Rotation>) -> Problem<Exact> {
    let (point, w) = pivot();
    let free = Problem::new(
        RigidBody::principal(int(3), v(int(2), int(3), int(4))),
        Screw::new(w.clone(), point.cross(&w)),
        vec![
            Contact::new(vi(1, 0, -1), vi(1, 0, 0), q(1, 2)),
            Contact::new(vi(0, 1, -1), v(int(0), int(1), q(1, 3)), q(1, 5)),
        ],
    )
    .unwrap();
    let (free, point) = match r {
        None => (free, point),
        Some(r) => (pose(&free, r), turn(r, &point)),
    };
    free.with_joints(&[Joint::Spherical { point }]).unwrap()
}

/// Every solution of `p`: the simultaneous law under both models, then the unilateral law
/// under both.
fn solutions(p: &Problem<Exact>) -> Vec<Solution<Exact>> {
    let mut out = Vec::new();
    for model in [Model::Newton, Model::Poisson] {
        out.push(solve(p, model).expect("Δ ≠ 0"));
        out.push(solve_unilateral(p, model).expect("not jammed"));
    }
    out
}

/// `posed` is `p` turned by `r`: equal inertances, Δ, impulses, frame velocities and
/// energies; the twist after impact turned.
fn assert_same_impact(name: &str, p: &Problem<Exact>, posed: &Problem<Exact>, r: &Rotation) {
    let (a, b) = (
        Impact::assemble(p).unwrap(),
        Impact::assemble(posed).unwrap(),
    );
    assert_eq!(a.g_hat(), b.g_hat(), "{name}: G");
    assert_eq!(a.g_yx_hat(), b.g_yx_hat(), "{name}: G_yx");
    assert_eq!(a.g_zx_hat(), b.g_zx_hat(), "{name}: G_zx");
    assert_eq!(a.det_hat(), b.det_hat(), "{name}: Δ");
    assert_eq!(a.kinetic_before(), b.kinetic_before(), "{name}: T⁰");
    for (s, t) in solutions(p).into_iter().zip(solutions(posed)) {
        let what = format!("{name}, {:?}", s.model);
        assert_eq!(s.det, t.det, "{what}: Δ");
        assert_eq!(s.inertances, t.inertances, "{what}: G");
        assert_eq!(s.impulses, t.impulses, "{what}: P");
        assert_eq!(
            s.compression_impulses, t.compression_impulses,
            "{what}: P^c"
        );
        assert_eq!(
            s.contact_velocities_before, t.contact_velocities_before,
            "{what}: v⁰"
        );
        assert_eq!(s.contact_velocities, t.contact_velocities, "{what}: v");
        assert_eq!(
            s.lost_velocity_energy, t.lost_velocity_energy,
            "{what}: E_p"
        );
        assert_eq!(s.kinetic_energy_loss, t.kinetic_energy_loss, "{what}: ΔE_c");
        assert_eq!(turn_screw(r, &s.twist), t.twist, "{what}: twist");
    }
}

#[test]
fn example_3_posed_by_rotations_is_the_same_impact_exactly() {
    let p = example_3(int(0));
    // The paper's values, so the comparison is not between two wrong answers.
    let newton = solve(&p, Model::Newton).unwrap();
    assert_eq!(newton.impulses[1].exact_text().unwrap(), "89/450");
    for (name, r) in rotations() {
        let posed = pose(&p, &r);
        assert!(matches!(posed.body().inertia, Inertia::Tensor(_)));
        assert_eq!(posed.body().inertia.entry(0, 1), {
            // J'_xy = Σ_k R_xk R_yk J_k: not zero, so the tensor is full.
            let j = [int::<Exact>(12), q(8, 5), int(12)];
            (0..3).fold(Exact::zero(), |s, k| s + r[0][k].clone() * &r[1][k] * &j[k])
        });
        assert!(!posed.body().inertia.entry(0, 1).is_zero(), "{name}");
        assert_same_impact(&format!("example 3, {name}"), &p, &posed, &r);
    }
}

#[test]
fn a_spatial_scene_posed_by_rotations_is_the_same_impact_exactly() {
    let p = spatial();
    assert!(!Impact::assemble(&p).unwrap().det_hat().is_zero());
    for (name, r) in rotations() {
        assert_same_impact(&format!("spatial, {name}"), &p, &pose(&p, &r), &r);
    }
}

#[test]
fn a_constrained_body_posed_by_rotations_is_the_same_impact_exactly() {
    let p = constrained(None);
    for (name, r) in rotations() {
        let posed = constrained(Some(&r));
        assert_same_impact(&format!("spherical joint, {name}"), &p, &posed, &r);
        // The constraint impulses are coordinates in a derived basis of U; their number, and
        // the kinetic energy they leave, are frame-independent.
        let (s, t) = (
            solve(&p, Model::Newton).unwrap(),
            solve(&posed, Model::Newton).unwrap(),
        );
        assert_eq!(s.constraint_impulses.len(), t.constraint_impulses.len());
    }
}

/// The frame-independent part of a frictional outcome: per contact the impulse vectors
/// (normal, tangential) in body axes, then the twist, the velocities along the axes, and the
/// energies.
fn friction_summary(
    f: &Frictional<Exact>,
    r: Option<&Rotation>,
) -> (Vec<Vec3<Exact>>, Screw<Exact>, Vec<Exact>, [Exact; 3]) {
    let id = |x: &Vec3<Exact>| r.map_or_else(|| x.clone(), |r| turn(r, x));
    let mut impulses = Vec::new();
    for i in 0..f.blocks.contacts() {
        let (n, t) = f.impulse_vectors(i);
        impulses.push(id(&n));
        impulses.push(id(&t));
    }
    let twist = r.map_or_else(|| f.velocity.clone(), |r| turn_screw(r, &f.velocity));
    // The normal velocities (hatted, |n'| = |n|) are frame-independent; tangential ones
    // change sign with the orientation of the plane's normal, so compare their squares.
    let after = f.after.iter().map(|x| x.clone() * x).collect();
    let energies = [
        f.kinetic_energy_loss.clone(),
        f.friction_dissipation.clone(),
        f.lost_velocity_energy.clone(),
    ];
    (impulses, twist, after, energies)
}

#[test]
fn example_3_with_friction_posed_by_rotations_stays_planar_and_exact() {
    let mut compared = 0;
    for mu in [q(1, 10), q(1, 2)] {
        let p = example_3(mu.clone());
        for (name, r) in rotations() {
            let posed = pose(&p, &r);
            for law in Restitution::ALL {
                let what = format!("μ = {mu}, {name}, {law}");
                let (a, b) = match (
                    solve_frictional(&p, law, 0.0),
                    solve_frictional(&posed, law, 0.0),
                ) {
                    (Ok(a), Ok(b)) => (a, b),
                    (Err(a), Err(b)) => {
                        assert_eq!(a, b, "{what}");
                        continue;
                    }
                    (a, b) => panic!("{what}: {:?} / {:?}", a.err(), b.err()),
                };
                // The plane is R e_z (up to its orientation), found exactly.
                let e = b.blocks.plane.clone().expect("planar");
                let ez = turn(&r, &vi(0, 0, 1));
                assert!(e == ez || e == -ez.clone(), "{what}: plane {e:?}");
                assert!(a.energy_residual.is_zero() && b.energy_residual.is_zero());
                assert_eq!(
                    friction_summary(&a, Some(&r)),
                    friction_summary(&b, None),
                    "{what}"
                );
                assert_eq!(a.verdicts, b.verdicts, "{what}");
                compared += 1;
            }
        }
    }
    assert!(compared >= 8, "{compared} outcomes compared");
}

/// The posed scene in f64 is not planar to the last bit (3/5 is not a binary fraction), so it
/// is integrated as a spatial scene; it agrees with the exact planar answer within the
/// integrator's estimate plus the effect of rounding the posed inputs (2⁻⁴⁰ of the scale,
/// far above 10² roundings of ε κ for these well-conditioned scenes).
#[test]
fn example_3_with_friction_posed_in_f64_agrees_with_exact_within_the_estimate() {
    let r = quaternion(1, 2, 3, 4);
    let posed = pose(&example_3(q(1, 2)), &r);
    let float = common::convert::<f64>(&posed);
    let mut compared = 0;
    for law in Restitution::ALL {
        let (Ok(exact), Ok(f)) = (
            solve_frictional(&posed, law, 0.0),
            solve_frictional(&float, law, 1e-10),
        ) else {
            continue;
        };
        let est = f.error_estimate.expect("spatial: an estimate");
        let (pe, we, ..) = friction_summary(&exact, None);
        let mut pf = Vec::new();
        for i in 0..f.blocks.contacts() {
            let (n, t) = f.impulse_vectors(i);
            pf.push(n);
            pf.push(t);
        }
        let mut scale = 1.0f64;
        let mut diff = 0.0f64;
        for (x, y) in pe.iter().zip(&pf) {
            for k in 0..3 {
                scale = scale.max(x[k].to_f64().abs());
                diff = diff.max((x[k].to_f64() - y[k]).abs());
            }
        }
        for (x, y) in we.as_slice().iter().zip(f.velocity.as_slice()) {
            scale = scale.max(x.to_f64().abs());
            diff = diff.max((x.to_f64() - y).abs());
        }
        let bound = est + scale * 2f64.powi(-40);
        assert!(diff <= bound, "{law}: |Δ| = {diff:e} > {bound:e}");
        println!("{law}: |Δ| = {diff:.1e}, estimate {est:.1e}");
        compared += 1;
    }
    assert!(compared >= 2, "{compared} laws compared");
}

/// κ(G) = ‖G‖_∞ ‖G⁻¹‖_∞ of the exact hatted G, as f64.
fn condition(g: &[Exact], n: usize) -> f64 {
    let norm = |m: &[Exact]| {
        (0..n)
            .map(|i| (0..n).fold(Exact::zero(), |s, j| s + m[i * n + j].abs()))
            .fold(Exact::zero(), |a, b| if b > a { b } else { a })
            .to_f64()
    };
    let mut inverse = Vec::with_capacity(n * n);
    for col in 0..n {
        let e: Vec<Exact> = (0..n)
            .map(|i| {
                if i == col {
                    Exact::one()
                } else {
                    Exact::zero()
                }
            })
            .collect();
        inverse.push(common::gauss(g.to_vec(), e, n).expect("G nonsingular"));
    }
    let inverse: Vec<Exact> = (0..n * n).map(|k| inverse[k % n][k / n].clone()).collect();
    norm(g) * norm(&inverse)
}

#[test]
fn posed_scenes_in_f64_agree_with_exact_within_the_derived_bound() {
    for (name, p) in [("example 3", example_3(int(0))), ("spatial", spatial())] {
        for (rname, r) in rotations() {
            let posed = pose(&p, &r);
            let n = posed.contacts().len();
            let kappa = condition(Impact::assemble(&posed).unwrap().g_hat(), n);
            let tol = 2f64.powi(10) * f64::EPSILON * kappa;
            let float = common::convert::<f64>(&posed);
            for model in [Model::Newton, Model::Poisson] {
                let (e, f) = (solve(&posed, model).unwrap(), solve(&float, model).unwrap());
                let groups: [(&str, Vec<f64>, Vec<f64>); 4] = [
                    (
                        "impulses",
                        e.impulses.iter().map(|x| x.to_f64()).collect(),
                        f.impulses.iter().map(|x| x.to_f64()).collect(),
                    ),
                    (
                        "G",
                        e.inertances.iter().map(|x| x.to_f64()).collect(),
                        f.inertances.iter().map(|x| x.to_f64()).collect(),
                    ),
                    (
                        "twist",
                        e.twist.as_slice().iter().map(|x| x.to_f64()).collect(),
                        f.twist.as_slice().to_vec(),
                    ),
                    (
                        "energies",
                        vec![
                            e.lost_velocity_energy.to_f64(),
                            e.kinetic_energy_loss.to_f64(),
                        ],
                        vec![f.lost_velocity_energy, f.kinetic_energy_loss],
                    ),
                ];
                for (what, x, y) in groups {
                    let scale = x.iter().fold(0.0f64, |m, a| m.max(a.abs()));
                    let worst = x
                        .iter()
                        .zip(&y)
                        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                    assert!(
                        worst <= tol * scale,
                        "{name}, {rname}, {model:?}, {what}: |Δ| = {worst:e} (κ = {kappa:.1})"
                    );
                    println!(
                        "{name}, {rname}, {model:?}, {what}: |Δ|/scale = {:.1e} ≤ {tol:.1e}",
                        worst / scale
                    );
                }
            }
        }
    }
}

// ---- Invariants with random symmetric positive definite tensors ----

/// J = AᵀA + I with A a small integer matrix: symmetric positive definite by construction.
fn spd() -> impl Strategy<Value = [[Exact; 3]; 3]> {
    prop::array::uniform3(prop::array::uniform3(-2i64..=2)).prop_map(|a| {
        std::array::from_fn(|i| {
            std::array::from_fn(|k| {
                let s: i64 = (0..3).map(|r| a[r][i] * a[r][k]).sum();
                int(s + i64::from(i == k))
            })
        })
    })
}

fn tensor_body() -> impl Strategy<Value = RigidBody<Exact>> {
    (common::positive(20, 4), spd()).prop_map(|(m, j)| RigidBody::with_tensor(m, j))
}

fn tensor_problem(max: usize) -> impl Strategy<Value = Problem<Exact>> {
    (
        tensor_body(),
        common::vec3(5, 2),
        common::vec3(5, 2),
        prop::collection::vec(common::contact(), 1..=max),
    )
        .prop_map(|(body, w, v, contacts)| {
            Problem::new(body, Screw::new(w, v), contacts).expect("valid by construction")
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// J (J⁻¹ μ) = μ and m (u/m) = u: the momentum of the response to {E} is {E} itself.
    #[test]
    fn the_momentum_of_the_response_is_the_impulse_screw(
        body in tensor_body(), p in common::vec3(6, 3), n in common::direction()
    ) {
        let e = Screw::axis(&p, &n);
        prop_assert_eq!(body.momentum(&body.response(&e)), e);
    }

    /// G is symmetric, each entry is eq. (57) with J⁻¹ (adjugate over determinant, formed
    /// apart from the body's stored J⁻¹), and the impact balances momentum,
    /// M (v − v⁰) = −Σ P̂_i {E_i}, with both energies as written out in `common`.
    #[test]
    fn a_tensor_body_keeps_the_invariants(p in tensor_problem(3)) {
        let body = p.body();
        let axes: Vec<Screw<Exact>> =
            p.contacts().iter().map(|c| Screw::axis(&c.point, &c.normal)).collect();
        let n = axes.len();
        let impact = Impact::assemble(&p).unwrap();
        for i in 0..n {
            for j in 0..n {
                let eq57 = inertance_eq57(body, &axes[i], &axes[j]);
                prop_assert_eq!(&impact.g_hat()[i * n + j], &impact.g_hat()[j * n + i]);
                prop_assert_eq!(&impact.g_hat()[i * n + j], &eq57);
                prop_assert_eq!(inertance(body, &axes[i], &axes[j]), eq57);
            }
        }
        let v0 = p.velocity();
        let Ok((_, outcomes)) = common::solve_models(&p, &[Model::Newton, Model::Poisson]) else {
            return Ok(());
        };
        for (_, out) in outcomes {
            let mut balance = body.momentum(&out.velocity);
            balance.add_scaled(&-Exact::one(), &body.momentum(v0));
            let mut impulse = Screw::zero();
            for (e, p_hat) in axes.iter().zip(&out.impulses_hat) {
                impulse.add_scaled(&-p_hat.clone(), e);
            }
            prop_assert_eq!(&balance, &impulse);
            let mut dv = out.velocity.clone();
            dv.add_scaled(&-Exact::one(), v0);
            prop_assert_eq!(&out.lost_velocity_energy, &kinetic_energy(body, &dv));
            prop_assert_eq!(
                &out.kinetic_energy_loss,
                &(kinetic_energy(body, v0) - kinetic_energy(body, &out.velocity))
            );
        }
    }

    /// A rational rotation of a random principal-axes problem: G, Δ, the impulses, the
    /// energies equal, the twist turned.
    #[test]
    fn random_problems_posed_by_random_rotations_are_the_same_impact(
        p in common::problem(3),
        (a, b, c, d) in (-3i64..=3, -3i64..=3, -3i64..=3, -3i64..=3)
            .prop_filter("a quaternion", |&(a, b, c, d)| (a, b, c, d) != (0, 0, 0, 0)),
    ) {
        let r = quaternion(a, b, c, d);
        let posed = pose(&p, &r);
        let (x, y) = (Impact::assemble(&p).unwrap(), Impact::assemble(&posed).unwrap());
        prop_assert_eq!(x.g_hat(), y.g_hat());
        prop_assert_eq!(x.det_hat(), y.det_hat());
        for model in [Model::Newton, Model::Poisson] {
            if let (Ok(s), Ok(t)) = (solve(&p, model), solve(&posed, model)) {
                prop_assert_eq!(&s.impulses, &t.impulses);
                prop_assert_eq!(&s.lost_velocity_energy, &t.lost_velocity_energy);
                prop_assert_eq!(&s.kinetic_energy_loss, &t.kinetic_energy_loss);
                prop_assert_eq!(turn_screw(&r, &s.twist), t.twist);
            }
        }
    }
}

// ---- Refusals ----

fn with_tensor<T: Scalar>(rows: [[i64; 3]; 3]) -> Result<Problem<T>, inertance::InvalidProblem> {
    let c = |x: i64| int::<T>(x);
    Problem::new(
        RigidBody::with_tensor(c(1), rows.map(|r| r.map(c))),
        Screw::new(Vec3::zeros(), Vec3::new(c(3), c(0), c(0))),
        vec![Contact::new(
            Vec3::new(c(0), c(-2), c(0)),
            Vec3::new(c(1), c(0), c(0)),
            c(0),
        )],
    )
}

fn refusal<T: Scalar>(rows: [[i64; 3]; 3]) -> (Field, Reason, String) {
    let e = with_tensor::<T>(rows).expect_err("refused");
    (e.field, e.reason.clone(), e.to_string())
}

#[test]
fn a_tensor_that_is_not_positive_definite_is_refused_naming_the_minor() {
    for (field, reason, message) in [
        refusal::<Exact>([[1, 2, 0], [2, 1, 0], [0, 0, 1]]),
        refusal::<f64>([[1, 2, 0], [2, 1, 0], [0, 0, 1]]),
    ] {
        assert_eq!(field, Field::InertiaTensor);
        assert_eq!(
            reason,
            Reason::NotPositiveDefinite {
                minor: 2,
                value: -3.0
            }
        );
        assert_eq!(
            message,
            "body.inertia is not positive definite: its leading principal minor Δ₂ = J_xx J_yy − \
             J_xy² = -3 is not positive (Sylvester's criterion); a physical inertia tensor must \
             be positive definite"
        );
    }
    // Positive diagonal, Δ₂ > 0, det J = −1: only the last minor fails.
    let (field, reason, _) = refusal::<Exact>([[1, 0, 1], [0, 1, 1], [1, 1, 1]]);
    assert_eq!(
        (field, reason),
        (
            Field::InertiaTensor,
            Reason::NotPositiveDefinite {
                minor: 3,
                value: -1.0
            }
        )
    );
    // Singular: det J = 0 is not positive either (and no inverse is ever formed).
    let (_, reason, _) = refusal::<Exact>([[1, 1, 0], [1, 2, 1], [0, 1, 1]]);
    assert_eq!(
        reason,
        Reason::NotPositiveDefinite {
            minor: 3,
            value: 0.0
        }
    );
    // A diagonal entry ≤ 0 is named like a principal moment; an asymmetric pair by the entry.
    let (field, reason, message) = refusal::<Exact>([[1, 0, 0], [0, -1, 0], [0, 0, 1]]);
    assert_eq!((field, reason), (Field::Inertia(1), Reason::NotPositive));
    assert_eq!(message, "body.inertia[1] must be positive");
    let (field, reason, message) = refusal::<f64>([[2, 1, 0], [1, 2, 0], [0, 1, 2]]);
    assert_eq!(field, Field::InertiaProduct(2, 1));
    assert_eq!(
        reason,
        Reason::NotSymmetric {
            value: 1.0,
            mirror: 0.0
        }
    );
    assert!(message.starts_with("body.inertia[2][1] is 1 but its mirror across the diagonal is 0"));
    assert!(with_tensor::<Exact>([[2, 1, 0], [1, 2, 1], [0, 1, 2]]).is_ok());
}

// ---- Scene files ----

fn text(x: &Exact) -> String {
    format!("\"{}\"", x.exact_text().unwrap())
}

fn triple(x: &Vec3<Exact>) -> String {
    format!("[{}, {}, {}]", text(&x[0]), text(&x[1]), text(&x[2]))
}

/// `p` as a scene file: `inertia` as the principal moments or as the 3×3 tensor.
fn scene_text(p: &Problem<Exact>) -> String {
    let body = p.body();
    let inertia = match &body.inertia {
        Inertia::Principal(j) => triple(j),
        Inertia::Tensor(t) => {
            let m = t.matrix();
            let rows: Vec<String> = (0..3)
                .map(|i| {
                    format!(
                        "[{}, {}, {}]",
                        text(&m[(i, 0)]),
                        text(&m[(i, 1)]),
                        text(&m[(i, 2)])
                    )
                })
                .collect();
            format!("[{}]", rows.join(", "))
        }
    };
    let mut s = format!(
        "[body]\nmass = {}\ninertia = {inertia}\nvelocity = {}\nangular_velocity = {}\n",
        text(&body.mass),
        triple(&p.velocity().bottom()),
        triple(&p.velocity().top())
    );
    for c in p.contacts() {
        s += &format!(
            "[[contact]]\npoint = {}\nnormal = {}\nk_newton = {}\nk_poisson = {}\n",
            triple(&c.point),
            triple(&c.normal),
            text(&c.k_newton),
            text(&c.k_poisson)
        );
        if let Some(t) = &c.tangent {
            s += &format!("tangent = {}\n", triple(t));
        }
    }
    s
}

#[test]
fn a_scene_with_a_3x3_inertia_reads_into_the_tensor_body() {
    let r = quaternion(1, 2, 3, 4);
    let posed = pose(&example_3(int(0)), &r);
    let scene = Scene::parse(&scene_text(&posed), "posed.toml").unwrap();
    assert!(scene.inertia_products.is_some());
    let keys: Vec<String> = scene.numbers().map(|(k, _)| k).collect();
    for key in [
        "body.inertia[0]",
        "body.inertia[2]",
        "body.inertia[0][1]",
        "body.inertia[0][2]",
        "body.inertia[1][2]",
    ] {
        assert!(keys.iter().any(|k| k == key), "{key} in {keys:?}");
    }
    assert_eq!(scene.problem::<Exact>().unwrap().body(), posed.body());
    // A 3×3 with zeros off the diagonal is the principal body.
    let diagonal = scene_text(&example_3(int(0))).replace(
        "inertia = [\"12\", \"8/5\", \"12\"]",
        "inertia = [[12, 0, 0], [0, \"8/5\", 0], [0, 0, 12]]",
    );
    let scene = Scene::parse(&diagonal, "diagonal.toml").unwrap();
    assert_eq!(scene.inertia_products, None);
    assert_eq!(
        scene.problem::<Exact>().unwrap().body(),
        example_3(int(0)).body()
    );
}

#[test]
fn scene_refusals_name_the_entry_and_both_values() {
    let bar = scene_text(&example_3(int(0)));
    let with = |inertia: &str| {
        bar.replace(
            "inertia = [\"12\", \"8/5\", \"12\"]",
            &format!("inertia = {inertia}"),
        )
    };
    let e = Scene::parse(&with("[[12, 1, 0], [2, 2, 0], [0, 0, 12]]"), "s.toml").unwrap_err();
    assert_eq!(e.key, "body.inertia[1][0]");
    assert_eq!(e.value.as_deref(), Some("2"));
    assert!(e.message.contains("`body.inertia[0][1]` = 1"), "{e}");
    // Irrational entries are compared in f64, to a few ulps.
    let ok = with("[[12, \"sqrt(2)\", 0], [\"2^(1/2)\", 2, 0], [0, 0, 12]]");
    assert!(Scene::parse(&ok, "s.toml").is_ok());
    let e = Scene::parse(
        &with("[[12, \"sqrt(2)\", 0], [1.414, 2, 0], [0, 0, 12]]"),
        "s.toml",
    )
    .unwrap_err();
    assert_eq!(e.key, "body.inertia[1][0]");
    let e = Scene::parse(&with("[[12, 0, 0], [0, -2, 0], [0, 0, 12]]"), "s.toml").unwrap_err();
    assert_eq!(e.key, "body.inertia[1][1]");
    let e = Scene::parse(&with("[[12, 0, 0], [0, 2], [0, 0, 12]]"), "s.toml").unwrap_err();
    assert_eq!(e.key, "body.inertia[1]");
    let e = Scene::parse(&with("[12, [0, 2, 0], 12]"), "s.toml").unwrap_err();
    assert_eq!(e.key, "body.inertia");
    // Not positive definite: read, then refused by the problem, naming `body.inertia` and
    // showing the tensor as written.
    let scene = Scene::parse(&with("[[1, 2, 0], [2, 1, 0], [0, 0, 1]]"), "s.toml").unwrap();
    let e = scene.problem::<Exact>().unwrap_err();
    assert_eq!(e.key, "body.inertia");
    assert_eq!(
        e.value.as_deref(),
        Some("[[1, 2, 0], [2, 1, 0], [0, 0, 1]]")
    );
    assert!(e.message.contains("must be positive definite"), "{e}");
}

fn json(out: &std::process::Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn the_cli_solves_a_3x3_inertia_with_the_impulses_of_its_principal_axes() {
    let p = example_3(int(0));
    let r = quaternion(1, 2, 3, 4);
    let principal = SceneFile::new("tensor-principal", &scene_text(&p));
    let posed = SceneFile::new("tensor-posed", &scene_text(&pose(&p, &r)));
    let a = json(&principal.run(&["solve", "--exact", "--json"]));
    let b = json(&posed.run(&["solve", "--exact", "--json"]));
    assert_eq!(a["models"]["newton"]["impulses"][1], "89/450");
    for key in ["inertance", "inertance_yx", "inertance_zx", "det"] {
        assert_eq!(a[key], b[key], "{key}");
    }
    for model in ["newton", "poisson"] {
        for key in [
            "impulses",
            "lost_velocity_energy",
            "kinetic_energy_loss",
            "admissible",
        ] {
            assert_eq!(
                a["models"][model][key], b["models"][model][key],
                "{model}: {key}"
            );
        }
        let s = solve(
            &p,
            if model == "newton" {
                Model::Newton
            } else {
                Model::Poisson
            },
        )
        .unwrap();
        let w = turn(&r, &s.twist.top());
        let shown: Vec<String> = (0..3).map(|k| w[k].exact_text().unwrap()).collect();
        assert_eq!(
            b["models"][model]["angular_velocity"],
            serde_json::json!(shown),
            "{model}: ω"
        );
    }
    // Not positive definite: exit 2, the key and the minor named.
    let bad = scene_text(&p).replace(
        "inertia = [\"12\", \"8/5\", \"12\"]",
        "inertia = [[1, 2, 0], [2, 1, 0], [0, 0, 1]]",
    );
    let out = SceneFile::new("tensor-indefinite", &bad).run(&["solve"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("key `body.inertia`") && err.contains("Δ₂"),
        "{err}"
    );
}

#[test]
fn a_tensor_scene_is_scaled_like_its_moments() {
    // Lengths of 2⁻⁶⁰⁰ m: the f64 solve runs in scaled units, the products scaled with the
    // moments (M·L²), and agrees with the exact answer.
    let p = pose(&example_3(int(0)), &quaternion(1, 2, 3, 4));
    let tiny = |x: &Exact| x.clone() / num_traits::pow(Exact::from_integer(2.into()), 600);
    let (body, twist, contacts) = (
        p.body().clone(),
        p.velocity().clone(),
        p.contacts().to_vec(),
    );
    let tensor: [[Exact; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|k| tiny(&tiny(&body.inertia.entry(i, k)))));
    let small = Problem::new(
        RigidBody::with_tensor(body.mass.clone(), tensor),
        Screw::new(
            twist.top() * num_traits::pow(Exact::from_integer(2.into()), 600),
            twist.bottom(),
        ),
        contacts
            .iter()
            .map(|c| Contact {
                point: c.point.map(|x| tiny(&x)),
                ..c.clone()
            })
            .collect(),
    )
    .unwrap();
    let scene = Scene::parse(&scene_text(&small), "small.toml").unwrap();
    let (scaled, units) = inertance::scene::scale::scale(&scene).expect("scaled");
    let two = |k: i64| num_traits::pow(Exact::from_integer(2.into()), k.unsigned_abs() as usize);
    let unit = units.mass + 2 * units.length;
    assert!(unit < -1000, "J in units of 2^{unit}");
    let products = scaled.inertia_products.as_ref().unwrap();
    for (k, (i, j)) in [(0, 1), (0, 2), (1, 2)].into_iter().enumerate() {
        assert_eq!(
            products[k].exact.as_ref().unwrap(),
            &(small.body().inertia.entry(i, j) * two(unit)).to_big_rational(),
            "J'_{i}{j}"
        );
    }
    // Impulses do not depend on the unit of length (P = m Δv): Example 3's P₂ = 89/450 N s.
    let out = SceneFile::new("tensor-small", &scene_text(&small)).run(&["solve", "--json"]);
    let got = json(&out)["models"]["newton"]["impulses"][1]
        .as_f64()
        .unwrap();
    assert!((got - 89.0 / 450.0).abs() <= 1e-12, "{got:e}");
}

#[test]
fn a_tensor_scene_is_varied_by_the_keys_it_lists() {
    use inertance::scene::{parse_document, set_value};
    use inertance::tools::sweep::{SweepOptions, Vary, sweep};
    let text = scene_text(&pose(&example_3(int(0)), &quaternion(1, 2, 3, 4)));
    // `body.inertia[1]` is the diagonal entry J_yy; `body.inertia[1][2]` sets J_yz and its
    // mirror J_zy, so the tensor stays symmetric.
    let mut doc = parse_document(&text, "posed.toml").unwrap();
    set_value(&mut doc, "body.inertia[1]", "20").unwrap();
    set_value(&mut doc, "body.inertia[1][2]", "\"1/2\"").unwrap();
    let scene = Scene::from_document(&doc, "posed.toml").unwrap();
    let body = scene.problem::<Exact>().unwrap().body().clone();
    assert_eq!(body.inertia.entry(1, 1), int(20));
    assert_eq!(body.inertia.entry(1, 2), q(1, 2));
    assert_eq!(body.inertia.entry(2, 1), q(1, 2));
    assert!(set_value(&mut doc, "body.inertia[3][0]", "1").is_err());
    // Sweeps over a diagonal entry (set in the scene directly) and over a product (through
    // the document) both run.
    let file = SceneFile::new("tensor-sweep", &text);
    for vary in ["body.inertia[1]=10:20:3", "body.inertia[1][2]=0:1/4:3"] {
        let opts = SweepOptions {
            scene: file.path.clone(),
            vary: vec![Vary::parse(vary).unwrap()],
            exact: true,
            out: file.dir().join("out.csv"),
            ..SweepOptions::default()
        };
        let summary = sweep(&opts).unwrap_or_else(|e| panic!("{vary}: {e}"));
        assert_eq!((summary.points, summary.singular), (3, 0), "{vary}");
    }
}

#[test]
fn a_symbolic_tensor_gives_the_closed_form_of_eq_57() {
    use inertance::scalar::symbolic::{RatFun, symbolic};
    // A body with J_xy = p hit at (0, 0, 1) along x: μ = r × n = (0, 1, 0), so eq. (57) reads
    // g = 1/m + (J⁻¹)_yy = 1/m + J/(J² − p²).
    let text = r#"
        [body]
        mass = "m"
        inertia = [["J", "p", 0], ["p", "J", 0], [0, 0, "K"]]
        velocity = [-1, 0, 0]
        angular_velocity = [0, 0, 0]
        [[contact]]
        point = [0, 0, 1]
        normal = [1, 0, 0]
        tangent = [0, 1, 0]
        k = "k"
    "#;
    let symbols: Vec<String> = ["m", "J", "p", "K", "k"].map(String::from).to_vec();
    let scene = Scene::parse_with(text, "symbolic.toml", &symbols).unwrap();
    let p = scene.problem::<RatFun>().unwrap();
    let impact = Impact::assemble(&p).unwrap();
    assert_eq!(
        impact.g_hat()[0],
        symbolic("1/m + J/(J^2 - p^2)", &symbols).unwrap()
    );
    // An asymmetric symbolic pair is refused: the entries are compared as expressions.
    let e = Scene::parse_with(
        &text.replace("[\"p\", \"J\", 0]", "[\"2*p\", \"J\", 0]"),
        "s.toml",
        &symbols,
    )
    .unwrap_err();
    assert_eq!(e.key, "body.inertia[1][0]");
}

/// The limit of the exact planar test: a bar moving in the plane of normal (1, 1, 0)/√2 is
/// planar, but the unit normal, hence the cone, would carry √2 — and no rational rotation
/// changes that (it keeps |R d| = |d|, and a rational vector along R (1, 1, 0) has a length in
/// ℚ√2). Exact types refuse it; floats integrate it as a spatial scene.
#[test]
fn a_plane_whose_normal_has_an_irrational_length_is_left_to_the_spatial_integrator() {
    use inertance::impact::friction::{Blocks, FrictionError};
    // J = diag(12, 12, 8/5): (1, 1, 0) is a principal direction, the bar lies along z.
    let n = vi(1, -1, 0);
    let c = |z: i64, k: Exact| Contact::new(vi(0, 0, z), n.clone(), k).with_friction(q(1, 2));
    let p = Problem::new(
        RigidBody::principal(int(1), v(int(12), int(12), q(8, 5))),
        Screw::new(v(q(2, 5), q(2, 5), int(0)), vi(3, -3, 2)),
        vec![c(-2, q(3, 10)), c(4, q(1, 5))],
    )
    .unwrap();
    assert!(Blocks::planar(&p).is_none());
    assert_eq!(
        solve_frictional(&p, Restitution::Poisson, 0.0).unwrap_err(),
        FrictionError::NotPlanar
    );
    let f = solve_frictional(&common::convert::<f64>(&p), Restitution::Poisson, 1e-10).unwrap();
    assert!(f.error_estimate.is_some(), "spatial");
    assert!(Blocks::planar(&pose(&p, &quaternion(1, 2, 3, 4))).is_none());
}
