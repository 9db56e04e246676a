//! Systems of bodies (`mechanics::system`, the scene reader, the CLI) against results the system
//! code did not compute, all derived in `derivations/systems.md`:
//!
//! * **Newton's cradle** of n = 3, 4, 5 equal balls under the simultaneous Newton and Poisson
//!   laws and both in inequality form (`--law unilateral`), against the hand closed form
//!   P_i = (1 + k) m v (n − i)/n, the striker leaving at (1 − (n − 1)k) v/n and every other ball
//!   at (1 + k) v/n, for k = 0, 1/3, 1/2, 9/10, 1;
//! * **two boxes meeting obliquely, both spinning**, a corner of one on a face of the other off
//!   the line of centres, against the textbook impulse
//!   P = (1 + k) v⁰ / (1/m₁ + 1/m₂ + (r₁×n)ᵀ J₁⁻¹ (r₁×n) + (r₂×n)ᵀ J₂⁻¹ (r₂×n)), with the
//!   boxes' inertias written by hand, through the scene reader and the CLI;
//! * **planar chains in joint coordinates** — a three-link leg (free hip) landing on heel and
//!   toe, a double pendulum striking a wall — against the impact map
//!   M(q)(q̇⁺ − q̇⁻) = −J_cᵀ P written here from the links' masses and inertias
//!   (M = Σ m J_vᵀJ_v + J J_ωᵀJ_ω, J_v of a point from the revolute Jacobian
//!   ∂p/∂θ_l = e_z × (p − o_l)), under every law;
//! * **free systems** of 2–4 bodies with random body–body contacts: momentum conserved and the
//!   energy identity ΔE_c = −E_p + Σ P_i v_ix⁰ (eq. 34) exactly, under every law (property test);
//! * **one body without joints** is the single-body `Problem`, bit for bit in f64 (property
//!   test, every output, both laws);
//! * the **example scenes** (`examples/cradle-3.toml`, `cradle-5.toml`, `box-on-box.toml`,
//!   `double-pendulum-wall.toml`, `leg-heel-toe.toml`) through `inertance solve --exact --json`
//!   against the same closed forms, and every example solving with status 0 in f64 and exactly.

mod common;

use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::constraint::Joint;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::mechanics::system::{Pair, System, SystemBody, SystemJoint, SystemScrew};
use inertance::scalar::{Exact, int, ratio};
use num_bigint::BigInt;
use num_traits::{One, Zero};
use proptest::prelude::*;
use serde_json::Value;

fn ex(n: i64) -> Exact {
    int(n)
}

fn q(p: i64, d: i64) -> Exact {
    ratio(p, d)
}

fn v3(x: Exact, y: Exact, z: Exact) -> Vec3<Exact> {
    Vec3::new(x, y, z)
}

/// The laws and models a system scene is solved under: (unilateral, model).
const LAWS: [(bool, Model); 4] = [
    (false, Model::Newton),
    (false, Model::Poisson),
    (true, Model::Newton),
    (true, Model::Poisson),
];

fn solve(
    system: &System<Exact>,
    unilateral: bool,
    model: Model,
) -> Outcome<Exact, SystemScrew<Exact>> {
    let mut impact = Impact::assemble(system).expect("assembles");
    let mut out = Outcome::default();
    if unilateral {
        impact
            .solve_unilateral(model, &mut out)
            .expect("the unilateral law answers");
    } else {
        impact.solve(model, &mut out).expect("G is regular");
    }
    out
}

// ------------------------------------------------------------------------------------------
// The CLI on the example scenes.

/// `inertance solve examples/NAME.toml ARGS…` from the crate root: (status, stdout, stderr).
fn solve_example(name: &str, args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .arg("solve")
        .arg(format!("examples/{name}.toml"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The exact JSON report of an example under `law`.
fn exact_report(name: &str, law: &str) -> Value {
    let (status, stdout, stderr) = solve_example(name, &["--exact", "--json", "--law", law]);
    assert_eq!(status, 0, "{name} --law {law}: {stderr}");
    serde_json::from_str(&stdout).expect("JSON")
}

/// An exact number as the report prints it: `p/q` or `p`.
fn parse(v: &Value) -> Exact {
    let s = v
        .as_str()
        .unwrap_or_else(|| panic!("not an exact number: {v}"));
    let (p, d) = s.split_once('/').unwrap_or((s, "1"));
    Exact::new(p.parse::<BigInt>().unwrap(), d.parse::<BigInt>().unwrap())
}

fn parse_all(v: &Value) -> Vec<Exact> {
    v.as_array().expect("an array").iter().map(parse).collect()
}

fn parse3(v: &Value) -> Vec3<Exact> {
    let a = parse_all(v);
    assert_eq!(a.len(), 3);
    v3(a[0].clone(), a[1].clone(), a[2].clone())
}

/// Body `b`'s (ω, v_C) after impact under `model` in a report.
fn twist_in(report: &Value, model: &str, b: usize) -> (Vec3<Exact>, Vec3<Exact>) {
    let body = &report["models"][model]["bodies"][b];
    (parse3(&body["angular_velocity"]), parse3(&body["velocity"]))
}

// ------------------------------------------------------------------------------------------
// Newton's cradle.

/// The closed form of derivations/systems.md for n equal balls of mass m, the striker at v,
/// one k at every contact — the same under every law: (P_i, P_i^c, each ball's speed after,
/// E_p, ΔE_c).
struct Cradle {
    impulses: Vec<Exact>,
    compression: Vec<Exact>,
    speeds: Vec<Exact>,
    lost_velocity_energy: Exact,
    kinetic_energy_loss: Exact,
}

fn cradle_closed_form(n: i64, m: &Exact, v: &Exact, k: &Exact) -> Cradle {
    let nn = ex(n);
    let one_k = Exact::one() + k;
    let compression: Vec<Exact> = (1..n).map(|i| m.clone() * v * &ex(n - i) / &nn).collect();
    let impulses = compression.iter().map(|p| one_k.clone() * p).collect();
    let mut speeds = vec![(Exact::one() - ex(n - 1) * k) * v / &nn];
    speeds.extend((1..n).map(|_| one_k.clone() * v / &nn));
    let half = q(1, 2);
    let frac = ex(n - 1) / &nn;
    Cradle {
        impulses,
        compression,
        speeds,
        lost_velocity_energy: half.clone() * m * &one_k * &one_k * v * v * &frac,
        kinetic_energy_loss: half * m * v * v * &(Exact::one() - k.clone() * k) * &frac,
    }
}

/// n balls of mass m and radius r touching along x, the striker at v: (system, ball inertia).
fn cradle(n: i64, m: &Exact, r: &Exact, v: &Exact, k: &Exact) -> System<Exact> {
    let j = q(2, 5) * m * r * r;
    let bodies = (0..n)
        .map(|i| SystemBody {
            body: RigidBody::principal(m.clone(), v3(j.clone(), j.clone(), j.clone())),
            centre: v3(ex(2 * i) * r, ex(0), ex(0)),
        })
        .collect();
    let twists = (0..n)
        .map(|i| {
            let speed = if i == 0 { v.clone() } else { ex(0) };
            Screw::new(Vec3::zeros(), v3(speed, ex(0), ex(0)))
        })
        .collect();
    let contacts = (0..n - 1)
        .map(|i| {
            Contact::new(
                v3(ex(2 * i + 1) * r, ex(0), ex(0)),
                v3(ex(1), ex(0), ex(0)),
                k.clone(),
            )
        })
        .collect();
    let pairs = (0..n - 1)
        .map(|i| Pair {
            first: i as usize,
            second: Some(i as usize + 1),
        })
        .collect();
    System::new(bodies, SystemScrew(twists), contacts, pairs, Vec::new()).expect("valid")
}

/// The cradle of n = 3, 4, 5 balls under the simultaneous Newton and Poisson laws and both in
/// inequality form, against the hand closed form (derivations/systems.md): impulses, Poisson's
/// compression impulses, every ball's velocity, the contacts' normal velocities after
/// (−k v at the first, 0 at the others), E_p and ΔE_c.
#[test]
fn newtons_cradle_of_three_to_five_balls_under_every_law_is_the_hand_closed_form() {
    let (m, r, v) = (q(3, 2), q(1, 4), q(5, 2));
    for n in 3..=5 {
        for k in [ex(0), q(1, 3), q(1, 2), q(9, 10), ex(1)] {
            let system = cradle(n, &m, &r, &v, &k);
            let want = cradle_closed_form(n, &m, &v, &k);
            for (unilateral, model) in LAWS {
                let out = solve(&system, unilateral, model);
                let at = format!("n = {n}, k = {k}, {model:?}, unilateral {unilateral}");
                assert_eq!(out.impulses_hat, want.impulses, "{at}");
                if model == Model::Poisson {
                    assert_eq!(out.compression_hat, want.compression, "{at}");
                }
                for (b, s) in out.velocity.0.iter().enumerate() {
                    assert_eq!(s.top(), Vec3::zeros(), "{at}");
                    assert_eq!(s.bottom(), v3(want.speeds[b].clone(), ex(0), ex(0)), "{at}");
                }
                for (i, a) in out.after_hat.iter().enumerate() {
                    let normal = if i == 0 { -(k.clone() * &v) } else { ex(0) };
                    assert_eq!(a[0], normal, "{at}");
                }
                assert_eq!(out.lost_velocity_energy, want.lost_velocity_energy, "{at}");
                assert_eq!(out.kinetic_energy_loss, want.kinetic_energy_loss, "{at}");
            }
        }
    }
}

/// The closed form's striker stops (and the last ball takes v) for no k ∈ [0, 1] when n ≥ 3:
/// (1 − (n − 1)k) v/n = 0 needs k = 1/(n − 1), and then the last ball leaves at
/// (1 + k) v/n = v/(n − 1) ≠ v. The experiment is out of reach of every simultaneous law.
#[test]
fn no_coefficient_makes_the_simultaneous_cradle_the_experiment() {
    let (m, r, v) = (ex(1), q(1, 2), ex(1));
    for n in 3..=5 {
        let k = q(1, n - 1);
        for (unilateral, model) in LAWS {
            let out = solve(&cradle(n, &m, &r, &v, &k), unilateral, model);
            let speeds: Vec<Exact> = out
                .velocity
                .0
                .iter()
                .map(|s| s.bottom()[0].clone())
                .collect();
            assert_eq!(speeds[0], ex(0));
            assert_eq!(speeds[n as usize - 1], q(1, n - 1));
            assert_ne!(speeds[n as usize - 1], v);
        }
    }
}

#[test]
fn the_cradle_examples_give_the_hand_closed_form() {
    for (name, n, k) in [("cradle-3", 3, ex(1)), ("cradle-5", 5, q(9, 10))] {
        let want = cradle_closed_form(n, &q(1, 2), &ex(1), &k);
        for law in ["simultaneous", "unilateral"] {
            let report = exact_report(name, law);
            for model in ["newton", "poisson"] {
                let r = &report["models"][model];
                assert_eq!(
                    parse_all(&r["impulses"]),
                    want.impulses,
                    "{name} {law} {model}"
                );
                for b in 0..n as usize {
                    let (w, vc) = twist_in(&report, model, b);
                    assert_eq!(w, Vec3::zeros());
                    assert_eq!(
                        vc,
                        v3(want.speeds[b].clone(), ex(0), ex(0)),
                        "{name} {law} {model}"
                    );
                }
                assert_eq!(parse(&r["lost_velocity_energy"]), want.lost_velocity_energy);
                assert_eq!(parse(&r["kinetic_energy_loss"]), want.kinetic_energy_loss);
                assert_eq!(r["admissible"], Value::Bool(true));
            }
        }
    }
}

// ------------------------------------------------------------------------------------------
// Two boxes meeting obliquely, both spinning.

/// Box A (0.4 × 0.2 × 0.2 m, 3 kg) at the origin, and box B (a 0.4 m cube, 2 kg) turned by
/// the rational rotation of the quaternion (5, 1, 1, 1) — R = [[6, −2, 3], [3, 6, −2],
/// [−2, 3, 6]]/7 — so that its face −x of its own axes, normal n = R e_x = (6, 3, −2)/7, meets
/// A's one corner farthest along n, (1/5, 1/10, −1/10) (A's corner [1, 1, −1]). B's centre is
/// that corner + (1/5) n + (1/10) R e_y − (1/20) R e_z = (9/28, 2/7, −11/70): the point lies on
/// B's face, off the line of centres, so both rotational terms are nonzero. Both boxes spin:
/// ω_A = (1, 2, −1), ω_B = (0, −1, 3). The box inertias by hand: J = m(b² + c²)/3 with
/// half-sides b, c (the cube's is isotropic, so B's rotation leaves it diagonal).
const OBLIQUE: &str = r#"
name = "two boxes, oblique, spinning"
[[body]]
name = "A"
shape = { box = [0.4, 0.2, 0.2] }
mass = 3
velocity = [1, 0.5, 0]
angular_velocity = [1, 2, -1]
[[body]]
name = "B"
shape = { box = [0.4, 0.4, 0.4] }
mass = 2
pose = { quaternion = [5, 1, 1, 1] }
position = ["9/28", "2/7", "-11/70"]
velocity = [-0.5, 0, 1]
angular_velocity = [0, -1, 3]
[[contact]]
bodies = ["A", "B"]
corner = [1, 1, -1]
normal = ["6/7", "3/7", "-2/7"]
k = KVALUE
"#;

#[test]
fn two_boxes_meeting_obliquely_while_spinning_take_the_textbook_impulse() {
    let box_inertia = |m: Exact, a: Exact, b: Exact, c: Exact| {
        let third = q(1, 3);
        v3(
            third.clone() * &m * &(b.clone() * &b + c.clone() * &c),
            third.clone() * &m * &(a.clone() * &a + c.clone() * &c),
            third * &m * &(a.clone() * &a + b.clone() * &b),
        )
    };
    let (ma, mb) = (ex(3), ex(2));
    let ja = box_inertia(ma.clone(), q(1, 5), q(1, 10), q(1, 10));
    let jb = box_inertia(mb.clone(), q(1, 5), q(1, 5), q(1, 5));
    let (ca, cb) = (Vec3::<Exact>::zeros(), v3(q(9, 28), q(2, 7), q(-11, 70)));
    let point = v3(q(1, 5), q(1, 10), q(-1, 10));
    let n = v3(q(6, 7), q(3, 7), q(-2, 7));
    let (wa, va) = (v3(ex(1), ex(2), ex(-1)), v3(ex(1), q(1, 2), ex(0)));
    let (wb, vb) = (v3(ex(0), ex(-1), ex(3)), v3(q(-1, 2), ex(0), ex(1)));
    let (r1, r2) = (point.clone() - ca.clone(), point.clone() - cb.clone());
    let (t1, t2) = (r1.cross(&n), r2.cross(&n));
    // The rotational terms are not zero: the point is off the line of centres.
    assert_ne!(t1, Vec3::zeros());
    assert_ne!(t2, Vec3::zeros());
    let quad = |t: &Vec3<Exact>, j: &Vec3<Exact>| {
        (0..3).fold(Exact::zero(), |s, i| s + t[i].clone() * &t[i] / &j[i])
    };
    let g = Exact::one() / &ma + Exact::one() / &mb + quad(&t1, &ja) + quad(&t2, &jb);
    let approach = n.dot(&((va.clone() + wa.cross(&r1)) - (vb.clone() + wb.cross(&r2))));
    assert!(approach.is_positive(), "approaching: {approach}");
    for (k_text, k) in [("0", ex(0)), ("0.5", q(1, 2)), ("1", ex(1))] {
        let scene = common::SceneFile::new(
            &format!("oblique-boxes-{k_text}"),
            &OBLIQUE.replace("KVALUE", k_text),
        );
        let p = (Exact::one() + &k) * &approach / &g;
        for law in ["simultaneous", "unilateral"] {
            let out = scene.run(&["solve", "--exact", "--json", "--law", law]);
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            let report: Value = serde_json::from_slice(&out.stdout).unwrap();
            for model in ["newton", "poisson"] {
                assert_eq!(
                    parse_all(&report["models"][model]["impulses"]),
                    vec![p.clone()]
                );
                // A takes −P n at the point, B takes +P n: Δv = ∓P n/m, Δω = ∓P J⁻¹ (r × n).
                let turn = |t: &Vec3<Exact>, j: &Vec3<Exact>| {
                    v3(
                        t[0].clone() / &j[0],
                        t[1].clone() / &j[1],
                        t[2].clone() / &j[2],
                    ) * p.clone()
                };
                assert_eq!(
                    twist_in(&report, model, 0),
                    (
                        wa.clone() - turn(&t1, &ja),
                        va.clone() - n.clone() * (p.clone() / &ma)
                    )
                );
                assert_eq!(
                    twist_in(&report, model, 1),
                    (
                        wb.clone() + turn(&t2, &jb),
                        vb.clone() + n.clone() * (p.clone() / &mb)
                    )
                );
                // The points leave at −k times their approach.
                let after = &report["models"][model]["contacts"][0]["velocity"][0];
                assert_eq!(parse(after), -(k.clone() * &approach));
            }
        }
    }
}

// ------------------------------------------------------------------------------------------
// Planar chains in joint coordinates.

/// A planar 2D vector as (x, y).
type P2 = [Exact; 2];

fn sub2(a: &P2, b: &P2) -> P2 {
    [a[0].clone() - &b[0], a[1].clone() - &b[1]]
}

fn dot2(a: &P2, b: &P2) -> Exact {
    a[0].clone() * &b[0] + a[1].clone() * &b[1]
}

fn p2(x: Exact, y: Exact) -> P2 {
    [x, y]
}

/// One link of a planar chain: its mass, its moment of inertia about its centre (J_z), its
/// proximal hinge o_l and its centre, in the plane.
struct Link {
    mass: Exact,
    inertia: Exact,
    hinge: P2,
    centre: P2,
}

/// A contact of a chain: the link, the world point, the normal out of the chain, k.
struct ChainContact {
    link: usize,
    point: P2,
    normal: P2,
    k: Exact,
}

/// A planar chain of links hinged in turn, its first hinge pinned to the ground or free (a
/// floating base at the first hinge), its generalised coordinates q = ([x, y,] θ₁, …, θ_L) —
/// θ₁ the first link's angle, θ_l (l > 1) the hinge angles — and rates q̇.
struct Chain {
    free_base: bool,
    links: Vec<Link>,
    rates: Vec<Exact>,
    contacts: Vec<ChainContact>,
}

impl Chain {
    fn dofs(&self) -> usize {
        self.links.len() + if self.free_base { 2 } else { 0 }
    }

    /// Column index of θ_l.
    fn angle(&self, l: usize) -> usize {
        l + if self.free_base { 2 } else { 0 }
    }

    /// J_v of point p carried by link j: ∂p/∂x = e_x, ∂p/∂y = e_y, ∂p/∂θ_l = e_z × (p − o_l)
    /// for every hinge l ≤ j (turning hinge l turns everything beyond it about o_l).
    fn point_jacobian(&self, j: usize, p: &P2) -> Vec<P2> {
        let mut cols = vec![p2(ex(0), ex(0)); self.dofs()];
        if self.free_base {
            cols[0] = p2(ex(1), ex(0));
            cols[1] = p2(ex(0), ex(1));
        }
        for l in 0..=j {
            let d = sub2(p, &self.links[l].hinge);
            cols[self.angle(l)] = p2(-d[1].clone(), d[0].clone());
        }
        cols
    }

    /// J_ω of link j: 1 for every hinge l ≤ j.
    fn angular_jacobian(&self, j: usize) -> Vec<Exact> {
        (0..self.dofs())
            .map(|c| {
                let hinge = (0..=j).any(|l| self.angle(l) == c);
                if hinge { ex(1) } else { ex(0) }
            })
            .collect()
    }

    /// M(q) = Σ_links m J_vᵀ J_v + J J_ωᵀ J_ω, d × d row-major.
    fn mass_matrix(&self) -> Vec<Exact> {
        let d = self.dofs();
        let mut m = vec![ex(0); d * d];
        for (j, link) in self.links.iter().enumerate() {
            let jv = self.point_jacobian(j, &link.centre);
            let jw = self.angular_jacobian(j);
            for a in 0..d {
                for b in 0..d {
                    m[a * d + b] += link.mass.clone() * &dot2(&jv[a], &jv[b])
                        + link.inertia.clone() * &jw[a] * &jw[b];
                }
            }
        }
        m
    }

    /// J_c: row i is n_i · J_v(A_i).
    fn contact_rows(&self) -> Vec<Vec<Exact>> {
        self.contacts
            .iter()
            .map(|c| {
                self.point_jacobian(c.link, &c.point)
                    .iter()
                    .map(|col| dot2(&c.normal, col))
                    .collect()
            })
            .collect()
    }

    fn velocity_of(&self, j: usize, p: &P2, rates: &[Exact]) -> P2 {
        let jv = self.point_jacobian(j, p);
        let mut v = p2(ex(0), ex(0));
        for (col, r) in jv.iter().zip(rates) {
            v[0] += col[0].clone() * r;
            v[1] += col[1].clone() * r;
        }
        v
    }

    fn omega_of(&self, j: usize, rates: &[Exact]) -> Exact {
        self.angular_jacobian(j)
            .iter()
            .zip(rates)
            .fold(ex(0), |s, (a, r)| s + a.clone() * r)
    }

    /// The system of this chain: each link a body (J_z about every axis), its twist from q̇,
    /// hinges about z between consecutive links (and to the ground when pinned), the contacts
    /// against obstacles.
    fn system(&self) -> System<Exact> {
        let z = |p: &P2| v3(p[0].clone(), p[1].clone(), ex(0));
        let bodies = self
            .links
            .iter()
            .map(|l| SystemBody {
                body: RigidBody::principal(
                    l.mass.clone(),
                    v3(l.inertia.clone(), l.inertia.clone(), l.inertia.clone()),
                ),
                centre: z(&l.centre),
            })
            .collect();
        let twists = (0..self.links.len())
            .map(|j| {
                Screw::new(
                    v3(ex(0), ex(0), self.omega_of(j, &self.rates)),
                    z(&self.velocity_of(j, &self.links[j].centre, &self.rates)),
                )
            })
            .collect();
        let hinge = |l: usize, pair: Pair| SystemJoint {
            joint: Joint::Revolute {
                point: z(&self.links[l].hinge),
                axis: v3(ex(0), ex(0), ex(1)),
            },
            pair,
        };
        let mut joints: Vec<SystemJoint<Exact>> = (1..self.links.len())
            .map(|l| {
                hinge(
                    l,
                    Pair {
                        first: l - 1,
                        second: Some(l),
                    },
                )
            })
            .collect();
        if !self.free_base {
            joints.insert(
                0,
                hinge(
                    0,
                    Pair {
                        first: 0,
                        second: None,
                    },
                ),
            );
        }
        System::new(
            bodies,
            SystemScrew(twists),
            self.contacts
                .iter()
                .map(|c| Contact::new(z(&c.point), z(&c.normal), c.k.clone()))
                .collect(),
            self.contacts
                .iter()
                .map(|c| Pair {
                    first: c.link,
                    second: None,
                })
                .collect(),
            joints,
        )
        .expect("the chain's twists satisfy its hinges")
    }

    /// The impact in joint coordinates under a law: P (and P^c under Poisson), q̇⁺.
    fn impact(&self, unilateral: bool, model: Model) -> JointImpact {
        let d = self.dofs();
        let m = self.mass_matrix();
        let jc = self.contact_rows();
        let n = jc.len();
        // X = M⁻¹ J_cᵀ, column by column; G = J_c X; v⁰ = J_c q̇⁻.
        let x: Vec<Vec<Exact>> = jc
            .iter()
            .map(|row| common::gauss(m.clone(), row.clone(), d).expect("M(q) is regular"))
            .collect();
        let mut g = vec![ex(0); n * n];
        for i in 0..n {
            for j in 0..n {
                g[i * n + j] = jc[i]
                    .iter()
                    .zip(&x[j])
                    .fold(ex(0), |s, (a, b)| s + a.clone() * b);
            }
        }
        let v0: Vec<Exact> = jc
            .iter()
            .map(|row| {
                row.iter()
                    .zip(&self.rates)
                    .fold(ex(0), |s, (a, b)| s + a.clone() * b)
            })
            .collect();
        let k: Vec<Exact> = self.contacts.iter().map(|c| c.k.clone()).collect();
        let scale = |p: &[Exact]| -> Vec<Exact> {
            p.iter()
                .zip(&k)
                .map(|(p, k)| (Exact::one() + k) * p)
                .collect()
        };
        let neg = |v: &[Exact]| -> Vec<Exact> { v.iter().map(|x| -x.clone()).collect() };
        let times_g = |p: &[Exact]| -> Vec<Exact> {
            (0..n)
                .map(|i| (0..n).fold(ex(0), |s, j| s + g[i * n + j].clone() * &p[j]))
                .collect()
        };
        let (impulses, compression) = match (unilateral, model) {
            // G P = (1 + k)∘v⁰ (eq. 15).
            (false, Model::Newton) => (
                common::gauss(g.clone(), scale(&v0), n).expect("G regular"),
                Vec::new(),
            ),
            // G Pᶜ = v⁰, P = (1 + k)∘Pᶜ (eq. 21–23).
            (false, _) => {
                let pc = common::gauss(g.clone(), v0.clone(), n).expect("G regular");
                (scale(&pc), pc)
            }
            // P ≥ 0 ⊥ G P − (v⁰ + k∘max(v⁰, 0)) ≥ 0.
            (true, Model::Newton) => {
                let rhs: Vec<Exact> = v0
                    .iter()
                    .zip(&k)
                    .map(|(v, k)| {
                        v.clone() + k.clone() * &(if v.is_positive() { v.clone() } else { ex(0) })
                    })
                    .collect();
                (
                    common::enumerate(&g, &neg(&rhs)).expect("solvable").0,
                    Vec::new(),
                )
            }
            // Compression Pᶜ ≥ 0 ⊥ G Pᶜ − v⁰ ≥ 0; expansion X ≥ 0 ⊥ G((1 + k)∘Pᶜ + X) − v⁰ ≥ 0.
            (true, _) => {
                let pc = common::enumerate(&g, &neg(&v0)).expect("solvable").0;
                let start = scale(&pc);
                let gs = times_g(&start);
                let rhs: Vec<Exact> = gs.iter().zip(&v0).map(|(a, b)| a.clone() - b).collect();
                let extra = common::enumerate(&g, &rhs).expect("solvable").0;
                (
                    start
                        .iter()
                        .zip(&extra)
                        .map(|(a, b)| a.clone() + b)
                        .collect(),
                    pc,
                )
            }
        };
        // q̇⁺ = q̇⁻ − M⁻¹ J_cᵀ P.
        let mut after = self.rates.clone();
        for (p, col) in impulses.iter().zip(&x) {
            for (a, c) in after.iter_mut().zip(col) {
                *a -= p.clone() * c;
            }
        }
        JointImpact {
            impulses,
            compression,
            after,
            mass: m,
            rows: jc,
        }
    }
}

struct JointImpact {
    impulses: Vec<Exact>,
    compression: Vec<Exact>,
    after: Vec<Exact>,
    mass: Vec<Exact>,
    rows: Vec<Vec<Exact>>,
}

impl JointImpact {
    /// ½ q̇ᵀ M q̇.
    fn energy(&self, rates: &[Exact]) -> Exact {
        let d = rates.len();
        let mut t = ex(0);
        for a in 0..d {
            for b in 0..d {
                t += self.mass[a * d + b].clone() * &rates[a] * &rates[b];
            }
        }
        t * q(1, 2)
    }
}

/// The chain's q̇ read back from a system's twists: the base velocity at the first hinge
/// (v_C1 + ω₁ × (o₁ − C₁)), θ̇₁ = ω₁, θ̇_l = ω_l − ω_{l−1}.
fn rates_of(chain: &Chain, twist: &SystemScrew<Exact>) -> Vec<Exact> {
    let mut q = Vec::new();
    if chain.free_base {
        let s = &twist.0[0];
        let r = sub2(&chain.links[0].hinge, &chain.links[0].centre);
        let w = s.top()[2].clone();
        q.push(s.bottom()[0].clone() - w.clone() * &r[1]);
        q.push(s.bottom()[1].clone() + w * &r[0]);
    }
    for l in 0..chain.links.len() {
        let w = twist.0[l].top()[2].clone();
        q.push(if l == 0 {
            w
        } else {
            w - twist.0[l - 1].top()[2].clone()
        });
    }
    q
}

/// Compare a system's outcome with the joint-coordinate impact, and check the impact map
/// M(q)(q̇⁺ − q̇⁻) = −J_cᵀ P with the system's own impulses and rates.
fn assert_matches_joint_coordinates(
    chain: &Chain,
    reference: &JointImpact,
    impulses: &[Exact],
    twist: &SystemScrew<Exact>,
    energies: (&Exact, &Exact),
    at: &str,
) {
    assert_eq!(impulses, reference.impulses.as_slice(), "{at}");
    for (j, link) in chain.links.iter().enumerate() {
        let s = &twist.0[j];
        let v = chain.velocity_of(j, &link.centre, &reference.after);
        assert_eq!(
            s.top(),
            v3(ex(0), ex(0), chain.omega_of(j, &reference.after)),
            "{at}: link {j}"
        );
        assert_eq!(
            s.bottom(),
            v3(v[0].clone(), v[1].clone(), ex(0)),
            "{at}: link {j}"
        );
    }
    let after = rates_of(chain, twist);
    assert_eq!(after, reference.after, "{at}");
    let d = chain.dofs();
    for a in 0..d {
        let lhs = (0..d).fold(ex(0), |s, b| {
            s + reference.mass[a * d + b].clone() * &(after[b].clone() - &chain.rates[b])
        });
        let rhs = reference
            .rows
            .iter()
            .zip(impulses)
            .fold(ex(0), |s, (row, p)| s - row[a].clone() * p);
        assert_eq!(lhs, rhs, "{at}: M(q̇⁺ − q̇⁻) = −J_cᵀ P, row {a}");
    }
    // E_p = ½ Δq̇ᵀ M Δq̇, ΔE_c = T(q̇⁻) − T(q̇⁺), both in joint coordinates.
    let delta: Vec<Exact> = after
        .iter()
        .zip(&chain.rates)
        .map(|(a, b)| a.clone() - b)
        .collect();
    assert_eq!(energies.0, &reference.energy(&delta), "{at}: E_p");
    assert_eq!(
        energies.1,
        &(reference.energy(&chain.rates) - reference.energy(&after)),
        "{at}: ΔE_c"
    );
}

/// The leg of derivations/systems.md and examples/leg-heel-toe.toml: thigh, shank and foot,
/// hip free, foot flat with heel (−1/10, 0) and toe (1/5, 0) on the ground y = 0.
fn leg(k_heel: Exact, k_toe: Exact) -> Chain {
    let down = p2(ex(0), ex(-1));
    Chain {
        free_base: true,
        links: vec![
            Link {
                mass: ex(7),
                inertia: q(7, 48),
                hinge: p2(ex(0), q(9, 10)),
                centre: p2(q(3, 20), q(7, 10)),
            },
            Link {
                mass: ex(3),
                inertia: q(1, 16),
                hinge: p2(q(3, 10), q(1, 2)),
                centre: p2(q(3, 20), q(3, 10)),
            },
            Link {
                mass: ex(1),
                inertia: q(1, 120),
                hinge: p2(ex(0), q(1, 10)),
                centre: p2(q(1, 20), q(1, 20)),
            },
        ],
        // v_H = (1, −1); absolute link rates (1/2, −1, 1/2).
        rates: vec![ex(1), ex(-1), q(1, 2), q(-3, 2), q(3, 2)],
        contacts: vec![
            ChainContact {
                link: 2,
                point: p2(q(-1, 10), ex(0)),
                normal: down.clone(),
                k: k_heel,
            },
            ChainContact {
                link: 2,
                point: p2(q(1, 5), ex(0)),
                normal: down,
                k: k_toe,
            },
        ],
    }
}

/// The double pendulum of examples/double-pendulum-wall.toml: rods of length 2 and mass 1
/// along u₁ = (3/5, −4/5) and u₂ = (4/5, −3/5) from O, the tip against the wall x = 14/5.
fn double_pendulum() -> Chain {
    Chain {
        free_base: false,
        links: vec![
            Link {
                mass: ex(1),
                inertia: q(1, 3),
                hinge: p2(ex(0), ex(0)),
                centre: p2(q(3, 5), q(-4, 5)),
            },
            Link {
                mass: ex(1),
                inertia: q(1, 3),
                hinge: p2(q(6, 5), q(-8, 5)),
                centre: p2(ex(2), q(-11, 5)),
            },
        ],
        // Absolute rates (1, 2).
        rates: vec![ex(1), ex(1)],
        contacts: vec![ChainContact {
            link: 1,
            point: p2(q(14, 5), q(-14, 5)),
            normal: p2(ex(1), ex(0)),
            k: q(1, 2),
        }],
    }
}

/// The leg landing on heel and toe under every law, for coefficients that make the
/// simultaneous answer admissible and ones that do not (Poisson leaving the toe approaching,
/// which the unilateral Poisson law corrects with an expansion impulse X at the toe).
#[test]
fn a_three_link_leg_landing_on_heel_and_toe_is_its_impact_map_in_joint_coordinates() {
    for (kh, kt) in [
        (ex(0), ex(0)),
        (q(1, 5), ex(0)),
        (q(1, 2), q(1, 4)),
        (ex(1), ex(1)),
        (ex(0), ex(1)),
    ] {
        let chain = leg(kh.clone(), kt.clone());
        let system = chain.system();
        for (unilateral, model) in LAWS {
            let at = format!("k = ({kh}, {kt}), {model:?}, unilateral {unilateral}");
            let reference = chain.impact(unilateral, model);
            let out = solve(&system, unilateral, model);
            assert_matches_joint_coordinates(
                &chain,
                &reference,
                &out.impulses_hat,
                &out.velocity,
                (&out.lost_velocity_energy, &out.kinetic_energy_loss),
                &at,
            );
            if model == Model::Poisson {
                assert_eq!(out.compression_hat, reference.compression, "{at}");
            }
        }
    }
}

#[test]
fn a_double_pendulum_striking_a_wall_is_its_impact_map_in_joint_coordinates() {
    let chain = double_pendulum();
    let system = chain.system();
    for (unilateral, model) in LAWS {
        let reference = chain.impact(unilateral, model);
        let out = solve(&system, unilateral, model);
        assert_matches_joint_coordinates(
            &chain,
            &reference,
            &out.impulses_hat,
            &out.velocity,
            (&out.lost_velocity_energy, &out.kinetic_energy_loss),
            &format!("{model:?}, unilateral {unilateral}"),
        );
    }
}

/// An example scene of a chain through the CLI: every model under both laws against the
/// joint-coordinate impact map.
fn check_chain_example(name: &str, chain: &Chain) {
    for law in ["simultaneous", "unilateral"] {
        let report = exact_report(name, law);
        for (model, m) in [("newton", Model::Newton), ("poisson", Model::Poisson)] {
            let reference = chain.impact(law == "unilateral", m);
            let r = &report["models"][model];
            let twist = SystemScrew(
                (0..chain.links.len())
                    .map(|b| {
                        let (w, v) = twist_in(&report, model, b);
                        Screw::new(w, v)
                    })
                    .collect(),
            );
            assert_matches_joint_coordinates(
                chain,
                &reference,
                &parse_all(&r["impulses"]),
                &twist,
                (
                    &parse(&r["lost_velocity_energy"]),
                    &parse(&r["kinetic_energy_loss"]),
                ),
                &format!("{name} {law} {model}"),
            );
        }
    }
}

#[test]
fn the_leg_example_is_its_impact_map_in_joint_coordinates() {
    let chain = leg(q(1, 5), ex(0));
    check_chain_example("leg-heel-toe", &chain);
    // The simultaneous Poisson answer leaves the toe approaching: the CLI says so, and the
    // unilateral one does not.
    let (status, _, stderr) = solve_example("leg-heel-toe", &["--exact"]);
    assert_eq!(status, 0);
    assert!(
        stderr.contains("poisson: contact 2 is still approaching after impact"),
        "{stderr}"
    );
    let report = exact_report("leg-heel-toe", "unilateral");
    assert_eq!(report["models"]["poisson"]["admissible"], Value::Bool(true));
    assert_eq!(
        parse(&report["models"]["poisson"]["contacts"][1]["velocity"][0]),
        ex(0)
    );
}

#[test]
fn the_double_pendulum_example_is_its_impact_map_and_its_hinge_takes_the_momentum_change() {
    let chain = double_pendulum();
    check_chain_example("double-pendulum-wall", &chain);
    // The ground hinge's force on the upper rod is the system's momentum change minus the
    // wall's impulse on the lower rod (−λ n): Σ m Δv_C + λ n.
    let report = exact_report("double-pendulum-wall", "simultaneous");
    let r = &report["models"]["newton"];
    let lambda = parse(&r["impulses"][0]);
    let mut force = v3(lambda, ex(0), ex(0));
    for (b, link) in chain.links.iter().enumerate() {
        let before = chain.velocity_of(b, &link.centre, &chain.rates);
        let (_, after) = twist_in(&report, "newton", b);
        force += (after - v3(before[0].clone(), before[1].clone(), ex(0))) * link.mass.clone();
    }
    assert_eq!(parse3(&r["joint_reactions"][0]["force"]), force);
}

// ------------------------------------------------------------------------------------------
// A box landing on a box on the floor.

/// examples/box-on-box.toml by hand (derivations/systems.md): the base stays at rest and the
/// top box rebounds off its lowest edge as off a fixed table, P = (1 + k) v / (2/m + 2d²/J_y)
/// at each corner; the floor's least-norm impulses (Newton) are (P/2)(1 ± X/A).
#[test]
fn the_box_on_box_example_is_the_hand_closed_form() {
    let (m, k, v) = (ex(2), q(1, 2), ex(1));
    let (a, h) = (q(1, 5), q(1, 20));
    let (c, s) = (q(24, 25), q(7, 25));
    let d = c.clone() * &a - s.clone() * &h;
    assert_eq!(d, q(89, 500));
    let jy = m.clone() * &(a.clone() * &a + h.clone() * &h) / &ex(3);
    let p = (Exact::one() + &k) * &v / &(ex(2) / &m + ex(2) * &d * &d / &jy);
    let (x, big_a) = (q(-1, 10) + &d, q(3, 10));
    let half = p.clone() / &ex(2);
    let report = exact_report("box-on-box", "unilateral");
    for model in ["newton", "poisson"] {
        let r = &report["models"][model];
        let impulses = parse_all(&r["impulses"]);
        assert_eq!(impulses[..2], [p.clone(), p.clone()], "{model}");
        assert_eq!(
            twist_in(&report, model, 0),
            (
                v3(ex(0), -(ex(2) * &p * &d / &jy), ex(0)),
                v3(q(1, 2), ex(0), -v.clone() + ex(2) * &p / &m)
            ),
            "{model}"
        );
        assert_eq!(
            twist_in(&report, model, 1),
            (Vec3::zeros(), Vec3::zeros()),
            "{model}"
        );
        // The floor's impulses (corners at x = +A, +A, −A, −A) hold the base: they sum to 2P
        // and balance the top box's push at x = X.
        let floor = &impulses[2..];
        let total = floor.iter().fold(ex(0), |s, f| s + f.clone());
        let moment = (floor[0].clone() + &floor[1] - &floor[2] - &floor[3]) * &big_a;
        assert_eq!(total, ex(2) * &p, "{model}");
        assert_eq!(moment, ex(2) * &p * &x, "{model}");
        if model == "newton" {
            let plus = half.clone() * &(Exact::one() + x.clone() / &big_a);
            let minus = half.clone() * &(Exact::one() - x.clone() / &big_a);
            assert_eq!(floor, [plus.clone(), plus, minus.clone(), minus]);
        }
    }
    // The simultaneous law: G is singular (4 floor contacts, 3 motions of the base): status 3.
    let (status, _, stderr) = solve_example("box-on-box", &["--exact", "--law", "simultaneous"]);
    assert_eq!(status, 3, "{stderr}");
    assert!(stderr.contains("singular"), "{stderr}");
}

/// The same in f64: Newton's floor impulses are the least-norm member of their set, as exact
/// (before the negligible contact velocities were judged against the impact's speed, every
/// w_i being rounding noise made the rounding look like separation: a vertex of the set was
/// reported and called unique). Both models say the impulses may be one of a set. Tolerance:
/// the regular part of G has cond ≈ 30 and its entries carry (3ℓ + 16N)ε ≈ 10⁻¹⁴ relative
/// error (the accuracy contract), so 10⁻¹² of P bounds the least-norm member's error with a
/// margin; measured: ~10⁻¹⁶.
#[test]
fn the_box_on_box_example_in_f64_reports_the_least_norm_impulses_and_says_they_may_be_one_of_a_set()
{
    let exact = exact_report("box-on-box", "unilateral");
    let (status, stdout, stderr) = solve_example("box-on-box", &["--json"]);
    assert_eq!(status, 0, "{stderr}");
    let float: Value = serde_json::from_str(&stdout).expect("JSON");
    for model in ["newton", "poisson"] {
        assert_eq!(float["models"][model]["impulses_unique"], false, "{model}");
        assert_eq!(exact["models"][model]["impulses_unique"], false, "{model}");
    }
    let want = parse_all(&exact["models"]["newton"]["impulses"]);
    let got: Vec<f64> = float["models"]["newton"]["impulses"]
        .as_array()
        .expect("impulses")
        .iter()
        .map(|v| v.as_f64().expect("a number"))
        .collect();
    let scale = inertance::scalar::Scalar::to_f64(&want[0]);
    for (i, (w, g)) in want.iter().zip(&got).enumerate() {
        assert!(
            (inertance::scalar::Scalar::to_f64(w) - g).abs() <= 1e-12 * scale,
            "P{}: {g} against {w}",
            i + 1
        );
    }
}

/// Every example scene of a system solves with status 0, in f64 and exactly, under its own law
/// and the unilateral one (box-on-box's own law is the unilateral one).
#[test]
fn every_system_example_solves() {
    for name in [
        "cradle-3",
        "cradle-5",
        "box-on-box",
        "double-pendulum-wall",
        "leg-heel-toe",
    ] {
        for args in [
            &[][..],
            &["--exact"],
            &["--law", "unilateral"],
            &["--exact", "--law", "unilateral"],
            &["--json"],
        ] {
            let (status, stdout, stderr) = solve_example(name, args);
            assert_eq!(status, 0, "{name} {args:?}: {stderr}");
            assert!(!stdout.is_empty());
            assert!(
                !stderr.contains("checks failed"),
                "{name} {args:?}: {stderr}"
            );
        }
    }
}

// ------------------------------------------------------------------------------------------
// Property tests.

/// A free system of 2–4 bodies with 1–4 contacts, each between two different bodies.
fn free_system() -> impl Strategy<Value = System<Exact>> {
    (2usize..=4)
        .prop_flat_map(|b| {
            (
                prop::collection::vec(common::body(), b),
                prop::collection::vec(common::vec3(4, 2), b),
                prop::collection::vec((common::vec3(3, 2), common::vec3(3, 2)), b),
                prop::collection::vec(
                    (
                        0..b,
                        1..b,
                        common::vec3(4, 2),
                        common::direction(),
                        common::coefficient(),
                    ),
                    1..=4,
                ),
            )
        })
        .prop_map(|(bodies, centres, twists, contacts)| {
            let count = bodies.len();
            System::new(
                bodies
                    .into_iter()
                    .zip(centres)
                    .map(|(body, centre)| SystemBody { body, centre })
                    .collect(),
                SystemScrew(twists.into_iter().map(|(w, v)| Screw::new(w, v)).collect()),
                contacts
                    .iter()
                    .map(|(_, _, p, n, k)| Contact::new(p.clone(), n.clone(), k.clone()))
                    .collect(),
                contacts
                    .iter()
                    .map(|(a, o, ..)| Pair {
                        first: *a,
                        second: Some((a + o) % count),
                    })
                    .collect(),
                Vec::new(),
            )
            .expect("valid by construction")
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    /// A free system's linear and angular momentum are conserved and the energy identity
    /// ΔE_c = −E_p + Σ P_i v_ix⁰ (eq. 34) holds, exactly, under every law — with ΔE_c also
    /// T⁰ − T written out body by body.
    #[test]
    fn free_systems_conserve_momentum_and_keep_the_energy_identity_under_every_law(system in free_system()) {
        let mut impact = Impact::assemble(&system).expect("assembles");
        let energy = |s: &SystemScrew<Exact>| {
            system.bodies().iter().zip(&s.0).fold(ex(0), |t, (b, s)| t + common::kinetic_energy(&b.body, s))
        };
        let mut solved = 0;
        for (unilateral, model) in LAWS {
            let mut out = Outcome::default();
            let ok = if unilateral {
                impact.solve_unilateral(model, &mut out).is_ok()
            } else {
                !impact.singular() && impact.solve(model, &mut out).is_ok()
            };
            if !ok {
                continue;
            }
            solved += 1;
            prop_assert_eq!(system.momentum(&out.velocity), system.momentum(system.velocity()));
            let work = impact.impulse_work(&out);
            prop_assert_eq!(&out.kinetic_energy_loss, &(work - out.lost_velocity_energy.clone()));
            prop_assert_eq!(&out.kinetic_energy_loss, &(energy(system.velocity()) - energy(&out.velocity)));
        }
        // Poisson's unilateral law is never jammed (src/impact/unilateral.rs).
        prop_assert!(solved >= 1);
    }

    /// One body without joints, in f64, is the single-body problem bit for bit: every output
    /// of both models under both laws (the body at the origin, so its contact points are the
    /// same numbers in both).
    ///
    /// Both take the same small-N float lane (`Mechanism::lane_body`): before they did, the
    /// system took the general code and differed in the last bits for 2 and 3 contacts (on
    /// 400 random problems: N = 2, the impulses in 53 of 78; N = 3, in 6 of 70).
    #[test]
    fn one_body_without_joints_is_the_single_body_problem_bit_for_bit_in_f64(p in common::problem(4)) {
        let p: Problem<f64> = common::convert(&p);
        let system = System::new(
            vec![SystemBody { body: p.body().clone(), centre: Vec3::zeros() }],
            SystemScrew(vec![p.velocity().clone()]),
            p.contacts().to_vec(),
            vec![Pair { first: 0, second: None }; p.contacts().len()],
            Vec::new(),
        )
        .expect("valid");
        let mut single = Impact::assemble(&p).expect("assembles");
        let mut many = Impact::assemble(&system).expect("assembles");
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
        let bits3 = |v: &[[f64; 3]]| v.iter().flatten().map(|x| x.to_bits()).collect::<Vec<u64>>();
        let twist = |s: &Screw<f64>| s.0.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
        prop_assert_eq!(bits(single.g_hat()), bits(many.g_hat()));
        prop_assert_eq!(single.det_hat().to_bits(), many.det_hat().to_bits());
        prop_assert_eq!(bits3(single.before_hat()), bits3(many.before_hat()));
        prop_assert_eq!(single.rank(), many.rank());
        for (unilateral, model) in LAWS {
            let mut a: Outcome<f64> = Outcome::default();
            let mut b: Outcome<f64, SystemScrew<f64>> = Outcome::default();
            let (ra, rb) = if unilateral {
                (
                    single.solve_unilateral(model, &mut a).map(|x| format!("{x:?}")).map_err(|e| e.to_string()),
                    many.solve_unilateral(model, &mut b).map(|x| format!("{x:?}")).map_err(|e| e.to_string()),
                )
            } else {
                (
                    single.solve(model, &mut a).map(|_| String::new()).map_err(|e| e.to_string()),
                    many.solve(model, &mut b).map(|_| String::new()).map_err(|e| e.to_string()),
                )
            };
            prop_assert_eq!(&ra, &rb, "{:?} unilateral {}", model, unilateral);
            if ra.is_err() {
                continue;
            }
            prop_assert_eq!(bits(&a.impulses_hat), bits(&b.impulses_hat));
            prop_assert_eq!(bits(&a.compression_hat), bits(&b.compression_hat));
            prop_assert_eq!(twist(&a.velocity), twist(&b.velocity.0[0]));
            prop_assert_eq!(bits3(&a.after_hat), bits3(&b.after_hat));
            prop_assert_eq!(a.lost_velocity_energy.to_bits(), b.lost_velocity_energy.to_bits());
            prop_assert_eq!(a.kinetic_energy_loss.to_bits(), b.kinetic_energy_loss.to_bits());
            prop_assert_eq!(bits(&a.constraint_impulses), bits(&b.constraint_impulses));
            prop_assert_eq!(single.impulse_work(&a).to_bits(), many.impulse_work(&b).to_bits());
        }
    }
}
