//! Regression: a constrained body's reaction was reported only as q, the multipliers of the
//! constraint screws U_a (eq. 90–93). For joints U is derived by elimination, so q is in a
//! basis nobody wrote: a hinge's q₅ = −1996/875 had to be combined with U₅ by hand into a
//! force of 5.703 N s. Each model now also reports the wrench U q = [F; M_C] — the impulsive
//! force the constraints exert on the body and its moment about C — and each joint's reaction,
//! that wrench reduced to the joint's anchor (`mechanics::reaction`); q stays, in the basis of
//! U, for the paper's form.
//!
//! Checked against what the code did not write: a rod pinned at one end and struck at the
//! other, solved by hand; the momentum balance and each joint's reciprocity written out in
//! components; the same constraints with U in other bases and in the paper's form; a posed
//! scene in world axes against its body-axes solve turned by the rotation; and float solves
//! against the exact one within a bound built from the accuracy contract's.

mod common;

use common::*;
use inertance::analysis::accuracy::{Bounds, Conditioning};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::{Inertia, Mobility, RigidBody};
use inertance::mechanics::constraint::{Joint, complement};
use inertance::mechanics::contact::Contact;
use inertance::mechanics::reaction::Wrench;
use inertance::mechanics::screw::{Screw, Vec3, dot};
use inertance::scalar::dd::DoubleDouble;
use inertance::scalar::symbolic::symbolic;
use inertance::scalar::{Exact, Scalar, int};
use inertance::scene::pipeline::{prepare, run};
use inertance::scene::scale::scale;
use inertance::scene::{Scene, parse_document};
use inertance::solve;
use inertance::tools::check::lookup;
use inertance::tools::derive::derive;
use num_traits::{One, Zero};
use proptest::prelude::*;

fn v(x: Exact, y: Exact, z: Exact) -> Vec3<Exact> {
    Vec3::new(x, y, z)
}

/// A rod of mass m and length l along y, centre of mass C at the origin, moments (j, j_y, j)
/// about C, pinned at O = (0, −l/2, 0) about z and turning about O at ω⁰ = −w k (so
/// v_C⁰ = ω⁰ × (C − O) = (wl/2, 0, 0)); struck at its free end A = (0, l/2, 0), whose outward
/// normal is x and whose velocity wl approaches the obstacle.
fn pinned_rod(m: &Exact, l: &Exact, j: &Exact, jy: &Exact, w: &Exact, k: &Exact) -> Problem<Exact> {
    let (zero, two) = (Exact::zero, || int::<Exact>(2));
    let half = l.clone() / two();
    let body = RigidBody::principal(m.clone(), v(j.clone(), jy.clone(), j.clone()));
    let twist = Screw::new(
        v(zero(), zero(), -w.clone()),
        v(w.clone() * &half, zero(), zero()),
    );
    let strike = Contact::new(
        v(zero(), half.clone(), zero()),
        v(Exact::one(), zero(), zero()),
        k.clone(),
    );
    let hinge = Joint::Revolute {
        point: v(zero(), -half, zero()),
        axis: v(zero(), zero(), Exact::one()),
    };
    valid(body, twist, vec![strike])
        .with_joints(&[hinge])
        .expect("the twist turns the rod about the hinge")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// The pinned rod, by hand. About O the hinge exerts no moment along z, so the angular
    /// momentum about O changes by the blow's moment alone: J_O Δω = l P, with
    /// J_O = j + m l²/4 (Steiner) and P the impulse along −x at A. A's velocity along x is
    /// −ω l, so Δv_Ax = −l² P/J_O, and Newton's law Δv_Ax = −(1 + k) w l gives
    /// P = (1 + k) w J_O / l (Poisson's too: one contact, P = (1 + k) P_c with v_Ax = 0 after
    /// compression). C moves with v_Cx = −ω l/2, so m Δv_Cx = −m l² P/(2 J_O) = −P + F_x:
    ///
    /// ```text
    /// F = (P (1 − m l²/(2 J_O)), 0, 0),   M_O = 0,   M_C = M_O + p × F = (0, 0, l F_x / 2)
    /// ```
    ///
    /// with p = O = (0, −l/2, 0) (the rod turns about z only, so the hinge needs no moment
    /// about x or y either). For a thin rod, J_O = m l²/3 and F_x = −P/2: the hinge pulls back
    /// with half the blow. Exact, for every rational m, l, j, w, k.
    #[test]
    fn a_rod_pinned_at_one_end_and_struck_at_the_other_has_the_hand_solved_hinge_reaction(
        m in positive(20, 3), l in positive(9, 2), j in positive(20, 3), jy in positive(20, 3),
        w in positive(5, 2), k in coefficient(),
    ) {
        let rod = pinned_rod(&m, &l, &j, &jy, &w, &k);
        let (zero, two) = (Exact::zero, || int::<Exact>(2));
        let j_o = j.clone() + m.clone() * &l * &l / int::<Exact>(4);
        let p = (Exact::one() + &k) * &w * &j_o / &l;
        let f = p.clone() * (Exact::one() - m.clone() * &l * &l / (two() * &j_o));
        for model in Model::ALL {
            let s = solve(&rod, model).unwrap();
            prop_assert_eq!(&s.impulses[0].coeff, &p);
            prop_assert_eq!(
                &s.joint_reactions,
                &vec![Wrench {
                    point: v(zero(), -l.clone() / two(), zero()),
                    force: v(f.clone(), zero(), zero()),
                    moment: Vec3::zeros(),
                }]
            );
            prop_assert_eq!(
                &s.constraint_wrench,
                &Screw::new(v(f.clone(), zero(), zero()), v(zero(), zero(), l.clone() * &f / two()))
            );
        }
    }
}

/// A body held by 1–2 joints (possibly dependent: then skipped), with an allowed twist
/// v⁰ = D ξ⁰ and 1–3 contacts.
fn held() -> impl Strategy<Value = (Problem<Exact>, Vec<Joint<Exact>>)> {
    (
        problem(3),
        prop::collection::vec(joint(), 1..=2),
        prop::collection::vec(rational(4, 3), 6),
    )
        .prop_map(|(p, joints, xi)| {
            let mut v0 = Screw::zero();
            for (s, x) in joints.iter().flat_map(Joint::free_screws).zip(&xi) {
                v0.add_scaled(x, &s);
            }
            let (body, _, contacts) = p.into_parts();
            (valid(body, v0, contacts), joints)
        })
}

/// An invertible k×k matrix A = L R, row-major: L unit lower triangular (entries of `low`), R
/// upper triangular with the nonzero diagonal `diagonal` (entries of `up` above it).
fn invertible(k: usize, low: &[Exact], up: &[Exact], diagonal: &[Exact]) -> Vec<Exact> {
    let l = |i: usize, j: usize| match i.cmp(&j) {
        std::cmp::Ordering::Greater => low[i * 6 + j].clone(),
        std::cmp::Ordering::Equal => Exact::one(),
        std::cmp::Ordering::Less => Exact::zero(),
    };
    let r = |i: usize, j: usize| match i.cmp(&j) {
        std::cmp::Ordering::Less => up[i * 6 + j].clone(),
        std::cmp::Ordering::Equal => diagonal[i].clone(),
        std::cmp::Ordering::Greater => Exact::zero(),
    };
    (0..k * k)
        .map(|ij| (0..k).fold(Exact::zero(), |s, t| s + l(ij / k, t) * r(t, ij % k)))
        .collect()
}

/// Each joint does no work on the motions it allows: its reaction about its anchor p is
/// reciprocal to its own free screws, written out by kind from the joint's definition.
fn reciprocal_to_its_joint(joint: &Joint<Exact>, w: &Wrench<Exact>) -> bool {
    let zero = |x: Exact| x.is_zero();
    match joint {
        Joint::Revolute { point, axis } => *point == w.point && zero(dot(&w.moment, axis)),
        Joint::Prismatic { axis } => w.point == Vec3::zeros() && zero(dot(&w.force, axis)),
        Joint::Cylindrical { point, axis } => {
            *point == w.point && zero(dot(&w.moment, axis)) && zero(dot(&w.force, axis))
        }
        Joint::Spherical { point } => *point == w.point && w.moment == Vec3::zeros(),
        Joint::Planar { normal } => {
            w.point == Vec3::zeros()
                && w.force.cross(normal) == Vec3::zeros()
                && zero(dot(&w.moment, normal))
        }
        // A weld allows no motion: any wrench is reciprocal to its (empty) set of screws.
        Joint::Fixed { point } => *point == w.point,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// eq. 76 written out in components, with the reported force and moment about C:
    ///
    /// ```text
    /// m (v_C − v_C⁰) = −Σ P̂_i n_i + F,     J (ω − ω⁰) = −Σ P̂_i r_i × n_i + M_C
    /// ```
    ///
    /// (P̂_i n_i the impulse vector, n_i as written), exactly, for both models; and each
    /// joint's reaction is reciprocal to that joint's motions.
    #[test]
    fn the_momentum_balance_holds_with_the_reported_force_and_moment((p, joints) in held()) {
        let Ok(held) = p.clone().with_joints(&joints) else { return Ok(()) };
        let Ok((_, outcomes)) = solve_models(&held, &Model::ALL) else { return Ok(()) };
        let body = p.body();
        for (model, out) in &outcomes {
            let (force, moment) = (out.constraint_wrench.top(), out.constraint_wrench.bottom());
            let (w, vc) = (out.velocity.top(), out.velocity.bottom());
            let (w0, vc0) = (p.velocity().top(), p.velocity().bottom());
            let mut linear = force.clone();
            let mut angular = moment.clone();
            for (c, ph) in p.contacts().iter().zip(&out.impulses_hat) {
                linear -= c.normal.clone() * ph.clone();
                angular -= c.point.cross(&c.normal) * ph.clone();
            }
            prop_assert_eq!((vc - vc0) * body.mass.clone(), linear);
            let dw = w - w0;
            let jdw = Vec3::from_fn(|i, _| {
                (0..3).fold(Exact::zero(), |s, k| s + body.inertia.entry(i, k) * &dw[k])
            });
            prop_assert_eq!(jdw, angular);
            let s = solve(&held, *model).unwrap();
            prop_assert_eq!(&s.constraint_wrench, &out.constraint_wrench);
            prop_assert_eq!(s.joint_reactions.len(), joints.len());
            for (joint, r) in joints.iter().zip(&s.joint_reactions) {
                prop_assert!(reciprocal_to_its_joint(joint, r), "{joint:?}: {r:?}");
                prop_assert_eq!(r.screw(), out.constraint_wrench.clone());
            }
        }
    }

    /// The same joints three ways — as joints (U derived), as the paper's `free` alone (U
    /// derived), and as `free` with `blocked` = U A for an invertible A (U in another basis)
    /// — give exactly the same force and moment, and each joint's reaction is that wrench
    /// about its anchor; q changes with the basis (q′ = A⁻¹ q), and Σ q′_a U′_a is the wrench.
    #[test]
    fn the_reaction_does_not_depend_on_the_basis_of_u(
        (p, joints) in held(),
        low in prop::collection::vec(rational(3, 2), 36),
        up in prop::collection::vec(rational(3, 2), 36),
        diagonal in prop::collection::vec(positive(4, 3), 6),
        signs in prop::collection::vec(any::<bool>(), 6),
    ) {
        let Ok(as_joints) = p.clone().with_joints(&joints) else { return Ok(()) };
        let free: Vec<Screw<Exact>> = joints.iter().flat_map(Joint::free_screws).collect();
        let u = complement(&free);
        let k = u.len();
        let diagonal: Vec<Exact> = diagonal.iter().zip(&signs).map(|(d, s)| if *s { -d.clone() } else { d.clone() }).collect();
        let a = invertible(k, &low, &up, &diagonal);
        let mixed: Vec<Screw<Exact>> = (0..k)
            .map(|b| {
                let mut s = Screw::zero();
                for (t, ut) in u.iter().enumerate() {
                    s.add_scaled(&a[t * k + b], ut);
                }
                s
            })
            .collect();
        let derived = p.clone().with_constraints(free.clone(), None).unwrap();
        let given = p.clone().with_constraints(free, Some(mixed.clone())).unwrap();
        for model in Model::ALL {
            let Ok(s) = solve(&as_joints, model) else { return Ok(()) };
            let (d, g) = (solve(&derived, model).unwrap(), solve(&given, model).unwrap());
            prop_assert_eq!(&d.constraint_wrench, &s.constraint_wrench);
            prop_assert_eq!(&g.constraint_wrench, &s.constraint_wrench);
            prop_assert!(d.joint_reactions.is_empty() && g.joint_reactions.is_empty());
            for (joint, r) in joints.iter().zip(&s.joint_reactions) {
                let anchor = joint.anchor().cloned().unwrap_or_else(Vec3::zeros);
                prop_assert_eq!(r, &Wrench::about(&g.constraint_wrench, anchor));
            }
            let mut uq = Screw::zero();
            for (q, ua) in g.constraint_impulses.iter().zip(&mixed) {
                uq.add_scaled(q, ua);
            }
            prop_assert_eq!(uq, s.constraint_wrench.clone());
        }
    }
}

/// The pinned rod with every datum a symbol: `derive` gives the hinge's reaction as a closed
/// form (named `newton.J1.F`, `newton.J1.M` as `check` reads them), equal as a rational
/// function to the hand-solved one above, F_x = P (1 − m l²/(2 J_O)) with
/// P = (1 + k) w J_O / l and J_O = j + m l²/4, and M_C = (0, 0, l F_x/2).
#[test]
fn derive_gives_the_hinge_reaction_as_a_closed_form() {
    let text = r#"
[params]
m = 3
l = 2
j = 1
w = 1
k = 0.5
[body]
mass = "m"
inertia = ["j", "1/100", "j"]
velocity = ["w*l/2", 0, 0]
angular_velocity = [0, 0, "-w"]
[[contact]]
point = [0, "l/2", 0]
normal = [1, 0, 0]
k = "k"
[[constraints.joint]]
kind = "revolute"
point = [0, "-l/2", 0]
axis = [0, 0, 1]
"#;
    let symbols: Vec<String> = ["m", "l", "j", "w", "k"].map(String::from).to_vec();
    let scene =
        Scene::from_document_with(&parse_document(text, "rod").unwrap(), "rod", &symbols).unwrap();
    let d = derive(&scene, &symbols, None).unwrap();
    let expr = |t: &str| symbolic(t, &symbols).unwrap_or_else(|e| panic!("{t}: {e}"));
    let derived = |q: &str| {
        let v = lookup(d.report.body().expect("one body"), q).unwrap();
        expr(v[0].exact.as_deref().expect("an exact text"))
    };
    let f = "(1 + k)*w*(j + m*l^2/4)/l * (1 - m*l^2/(2*(j + m*l^2/4)))";
    for model in ["newton", "poisson"] {
        assert_eq!(derived(&format!("{model}.J1.F[0]")), expr(f));
        assert_eq!(
            derived(&format!("{model}.MC[2]")),
            expr(&format!("l*({f})/2"))
        );
        for k in 0..3 {
            assert_eq!(derived(&format!("{model}.J1.M[{k}]")), expr("0"));
        }
        for k in 1..3 {
            assert_eq!(derived(&format!("{model}.J1.F[{k}]")), expr("0"));
        }
    }
    assert!(d.to_text(false).contains("newton.J1.F[0] = "));
    assert!(d.to_text(true).contains("F_{J1,x}^{N}"));
}

/// The pinned rod of the hand-solved test at m = 3, l = 2, j = 1, w = 1, k = 1/2: P = 3 N s,
/// F = (−3/2, 0, 0) N s, M_O = 0, M_C = (0, 0, −3/2) N m s.
const ROD: &str = r#"
name = "rod pinned at one end, struck at the other"
[body]
mass = 3
inertia = [1, "1/100", 1]
velocity = [1, 0, 0]
angular_velocity = [0, 0, -1]
[[contact]]
point = [0, 1, 0]
normal = [1, 0, 0]
k = 0.5
[[constraints.joint]]
kind = "revolute"
point = [0, -1, 0]
axis = [0, 0, 1]
"#;

/// The report's JSON and table carry the reaction: per joint `kind`, `about`, `point`,
/// `force`, `moment`, and `constraint_wrench` about C (guide/solving.md, "JSON report"); a prismatic
/// joint, which has no point, is reduced to C and says so.
#[test]
fn the_report_gives_each_joints_force_and_moment() {
    let scene = Scene::parse(ROD, "rod.toml").unwrap();
    let json = run::<Exact>(&scene, None).unwrap().report.to_json();
    for model in ["newton", "poisson"] {
        let m = &json["models"][model];
        assert_eq!(
            m["joint_reactions"],
            serde_json::json!([{
                "kind": "revolute", "about": "point", "point": ["0", "-1", "0"],
                "force": ["-3/2", "0", "0"], "moment": ["0", "0", "0"],
            }])
        );
        assert_eq!(
            m["constraint_wrench"],
            serde_json::json!({ "force": ["-3/2", "0", "0"], "moment": ["0", "0", "-3/2"] })
        );
        assert_eq!(m["impulses"], serde_json::json!(["3"]));
    }
    let table = run::<f64>(&scene, None).unwrap().report.to_table();
    assert!(table.contains("J1 revolute at [0, -1, 0] m"), "{table}");
    let row = |label: &str| {
        table
            .lines()
            .find_map(|l| l.trim_start().strip_prefix(label))
            .unwrap_or_else(|| panic!("no row {label}: {table}"))
            .split_whitespace()
            .collect::<Vec<_>>()
    };
    assert_eq!(row("J1 Fx [N s]"), ["-1.5", "-1.5"]);
    assert_eq!(row("J1 Mz [N m s]"), ["0", "0"]);

    // A slider along x struck along (1, 1, 0): the rail takes F_y, and the moment about C.
    let slider = r#"
[body]
mass = 2
inertia = [1, 2, 3]
velocity = [1, 0, 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = [1, 1, 0]
normal = [1, 1, 0]
k = 0
[[constraints.joint]]
kind = "prismatic"
axis = [1, 0, 0]
[solve]
models = ["newton"]
"#;
    let scene = Scene::parse(slider, "slider.toml").unwrap();
    let report = run::<Exact>(&scene, None).unwrap().report;
    let r = &report.to_json()["models"]["newton"]["joint_reactions"][0];
    assert_eq!(
        (&r["kind"], &r["about"]),
        (&"prismatic".into(), &"centre-of-mass".into())
    );
    assert_eq!(r["point"], serde_json::json!(["0", "0", "0"]));
    // Newton, k = 0: the slider stops, m Δv_x = −P̂ ⇒ P̂ = 2 (impulse −2(1, 1, 0)); the
    // rail gives F = (0, 2, 0) and cancels the blow's moment (1, 1, 0) × (−2, −2, 0) = 0.
    assert_eq!(r["force"], serde_json::json!(["0", "2", "0"]));
    assert_eq!(r["moment"], serde_json::json!(["0", "0", "0"]));
    let table = report.to_table();
    assert!(
        table.contains("J1 prismatic at C (it has no point)"),
        "{table}"
    );
}

/// Float solves run in units chosen from the scene (`scene::scale`) and scale the report back:
/// the reaction's point is a length, its force an impulse, its moment an impulse times a
/// length. The pinned rod with mass 3·10^a kg and lengths 10^b times the hand-solved one's
/// (J = 10^(a+2b), v_C⁰ = 10^b m/s, ω⁰ = −1 rad/s) has F = (−3/2, 0, 0)·10^(a+b) N s,
/// M_O = 0 and the anchor (0, −10^b, 0) m. Each value is a handful of roundings of inputs
/// rounded once (ε/2 each): within 64ε of its own scale — |F| for the force, |F|·10^b for
/// the moment (M_O = M_C − p × F cancels two such terms), 10^b for the point.
#[test]
fn the_reaction_is_scaled_back_with_the_scenes_units() {
    for (a, b) in [(-300, 0), (300, -100), (-200, 100), (0, 0)] {
        let text = ROD
            .replace("mass = 3", &format!("mass = 3e{a}"))
            .replace(
                "inertia = [1, \"1/100\", 1]",
                &format!("inertia = [1e{0}, 1e{0}, 1e{0}]", a + 2 * b),
            )
            .replace("velocity = [1, 0, 0]", &format!("velocity = [1e{b}, 0, 0]"))
            .replace("point = [0, 1, 0]", &format!("point = [0, 1e{b}, 0]"))
            .replace("point = [0, -1, 0]", &format!("point = [0, -1e{b}, 0]"));
        let scene = Scene::parse(&text, "scaled-rod.toml").unwrap();
        let report = run::<f64>(&scene, None).unwrap().report;
        let (force, length) = (1.5 * 10f64.powi(a + b), 10f64.powi(b));
        let near = |x: &inertance::report::Value, want: f64, scale: f64, what: &str| {
            assert!(
                (x.f64 - want).abs() <= 64.0 * f64::EPSILON * scale,
                "10^{a} kg, 10^{b} m, {what}: {} against {want:e}",
                x.f64
            );
        };
        for m in &report.models {
            let r = &m.joint_reactions[0];
            near(&r.point[1], -length, length, "anchor");
            near(&r.force[0], -force, force, "F_x");
            for k in 0..3 {
                near(&r.moment[k], 0.0, force * length, "M_O");
                near(&r.point[k], [0.0, -length, 0.0][k], length, "anchor");
            }
            for k in 1..3 {
                near(&r.force[k], 0.0, force, "F");
            }
            let c = m.constraint_wrench.as_ref().unwrap();
            near(&c.moment[2], -force * length, force * length, "M_C");
        }
    }
}

/// R of the unit quaternion (1, 2, 3, 4)/√30, body → world: rational.
fn rotation() -> [[Exact; 3]; 3] {
    let (w, x, y, z) = (1, 2, 3, 4);
    let r = [
        [
            w * w + x * x - y * y - z * z,
            2 * (x * y - w * z),
            2 * (x * z + w * y),
        ],
        [
            2 * (x * y + w * z),
            w * w - x * x + y * y - z * z,
            2 * (y * z - w * x),
        ],
        [
            2 * (x * z - w * y),
            2 * (y * z + w * x),
            w * w - x * x - y * y + z * z,
        ],
    ];
    r.map(|row| row.map(|e| Exact::new(e.into(), 30.into())))
}

fn turn(r: &[[Exact; 3]; 3], u: [Exact; 3]) -> [Exact; 3] {
    std::array::from_fn(|i| (0..3).fold(Exact::zero(), |s, k| s + r[i][k].clone() * &u[k]))
}

/// The pinned rod posed by a rational rotation R, its inputs written in the world frame: the
/// reactions come back in world axes (positions from C) as R times the rod's hand-solved
/// body-axes ones, and with `axes = "body"` as those themselves — exactly.
#[test]
fn a_posed_body_reports_its_reactions_in_world_axes_or_body_axes() {
    let r = rotation();
    let q = |n: i64, d: i64| Exact::new(n.into(), d.into());
    let text = |u: [Exact; 3]| {
        let t: Vec<String> = u
            .iter()
            .map(|x| format!("\"{}\"", x.exact_text().unwrap()))
            .collect();
        format!("[{}]", t.join(", "))
    };
    let world = |u: [i64; 3]| text(turn(&r, u.map(|x| q(x, 1))));
    let matrix = r
        .iter()
        .map(|row| text(row.clone()))
        .collect::<Vec<_>>()
        .join(", ");
    let scene = |axes: &str| {
        let toml = format!(
            r#"
[body]
mass = 3
inertia = [1, "1/100", 1]
pose = {{ matrix = [{matrix}] }}
velocity = {}
angular_velocity = {}
[[contact]]
body_point = [0, 1, 0]
normal = {}
k = 0.5
[[constraints.joint]]
kind = "revolute"
point = {}
axis = {}
[solve]
axes = "{axes}"
"#,
            world([1, 0, 0]),
            world([0, 0, -1]),
            world([1, 0, 0]),
            world([0, -1, 0]),
            world([0, 0, 1]),
        );
        let scene = Scene::parse(&toml, "posed-rod.toml").unwrap();
        run::<Exact>(&scene, None).unwrap().report.to_json()
    };
    let strings = |u: [Exact; 3]| serde_json::json!(u.map(|x| x.exact_text().unwrap()));
    for (axes, map) in [
        (
            "world",
            Box::new(|u| turn(&r, u)) as Box<dyn Fn([Exact; 3]) -> [Exact; 3]>,
        ),
        ("body", Box::new(|u| u)),
    ] {
        let json = scene(axes);
        assert_eq!(json["axes"], axes);
        for model in ["newton", "poisson"] {
            let m = &json["models"][model];
            let reaction = &m["joint_reactions"][0];
            assert_eq!(
                reaction["point"],
                strings(map([q(0, 1), q(-1, 1), q(0, 1)])),
                "{axes}"
            );
            assert_eq!(
                reaction["force"],
                strings(map([q(-3, 2), q(0, 1), q(0, 1)])),
                "{axes}"
            );
            assert_eq!(
                reaction["moment"],
                strings([q(0, 1), q(0, 1), q(0, 1)]),
                "{axes}"
            );
            assert_eq!(
                m["constraint_wrench"]["moment"],
                strings(map([q(0, 1), q(0, 1), q(-3, 2)])),
                "{axes}"
            );
        }
    }
}

/// ‖w‖_* = (wᵀ η M⁻¹ w)^½ = (|F|²/m + Σ_a M_a²/J_a)^½ of a wrench on a body in principal
/// axes: the dual of the kinetic-energy norm of twists, |wᵀ η v| ≤ ‖w‖_* ‖v‖_M.
fn wrench_norm(body: &RigidBody<Exact>, w: &Screw<Exact>) -> f64 {
    let Inertia::Principal(j) = &body.inertia else {
        panic!("the float corpus is in principal axes")
    };
    let mut s = Exact::zero();
    for a in 0..3 {
        s += &w.0[a] * &w.0[a] / &body.mass + &w.0[a + 3] * &w.0[a + 3] / &j[a];
    }
    s.to_f64().sqrt()
}

/// The float corpus: the pinned rod, the constrained hard cases, and written scenes for the
/// other joints (coordinates such as 0.3 and 0.7 round in every float type), with mass
/// ratios m l²/J from 10⁻⁸ to 10⁸.
fn float_corpus() -> Vec<Scene> {
    let mut scenes = vec![Scene::parse(ROD, "rod").unwrap()];
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/hard_cases");
    for name in [
        "constrained-near-singular-1e-4",
        "constrained-near-singular-1e-7",
    ] {
        scenes.push(Scene::load(&dir.join(format!("{name}.toml"))).unwrap());
    }
    let joints = [
        "kind = \"spherical\"\npoint = [0.3, -0.7, 0.1]",
        "kind = \"cylindrical\"\npoint = [0, -0.7, 0.3]\naxis = [0.2, 0.1, 1]",
        "kind = \"planar\"\nnormal = [0.1, 0.3, 1]",
        "kind = \"revolute\"\npoint = [-0.3, 0.7, 0]\naxis = [0, 0, 1]\n[[constraints.joint]]\nkind = \"prismatic\"\naxis = [0.7, 0.3, 0]",
    ];
    for (i, joint) in joints.iter().enumerate() {
        for mass in ["1e-8", "1", "1e8"] {
            let text = format!(
                r#"
name = "joint {i}, mass {mass}"
[body]
mass = {mass}
inertia = [0.3, 0.7, 1.1]
velocity = [0, 0, 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = [0.3, 0.9, -0.2]
normal = [1, 0.2, 0.1]
k = 0.3
[[contact]]
point = [-0.6, 0.1, 0.4]
normal = [0.1, -1, 0.3]
k = 0.7
[[constraints.joint]]
{joint}
"#
            );
            scenes.push(Scene::parse(&text, "corpus").unwrap());
        }
    }
    scenes
}

/// The twist before impact of a scene written at rest: a motion the joints allow, Σ ±D_a
/// over the free screws, with the first signs that make every contact approach (else all +).
fn moving(problem: Problem<Exact>) -> Problem<Exact> {
    let c = problem.constraints().expect("constrained").clone();
    if problem.velocity().0.iter().any(|x| !x.is_zero()) {
        return problem;
    }
    let (body, _, contacts) = problem.into_parts();
    let twists = (0..1u32 << c.free.len()).map(|signs| {
        let mut t = Screw::zero();
        for (a, d) in c.free.iter().enumerate() {
            let sign = if signs >> a & 1 == 0 { 1 } else { -1 };
            t.add_scaled(&int(sign), d);
        }
        t
    });
    let approaching = |t: &Screw<Exact>| {
        contacts
            .iter()
            .all(|k| dot(&k.normal, &(t.bottom() + t.top().cross(&k.point))) > Exact::zero())
    };
    let all: Vec<Screw<Exact>> = twists.collect();
    let twist = all
        .iter()
        .find(|t| approaching(t))
        .unwrap_or(&all[0])
        .clone();
    valid(body, twist, contacts)
        .with_constrained(c)
        .expect("a combination of the free screws is allowed")
}

/// One float type over the corpus: each scene and model solved exactly and in `T`, the
/// float wrench's error in ‖·‖_* asserted within the bound of
/// [`float_reactions_meet_their_bound_against_the_exact_solve`]; the largest ratio
/// error/bound and the number of solves measured.
fn worst_ratio<T: Scalar>(scenes: &[Scene]) -> (f64, usize) {
    let eps = T::epsilon_f64();
    let (mut worst, mut solved) = (0.0f64, 0);
    for scene in scenes {
        let scene = scale(scene).map_or_else(|| scene.clone(), |(s, _)| s);
        let exact_problem = moving(prepare::<Exact>(&scene).unwrap());
        let mut exact = Impact::assemble(&exact_problem).unwrap();
        let Some(cond) = Conditioning::of(&mut exact) else {
            continue;
        };
        let float_problem = convert_held::<T>(&exact_problem);
        let mut float = Impact::assemble(&float_problem).unwrap();
        let body = exact_problem.body();
        let Inertia::Principal(j) = &body.inertia else {
            unreachable!("principal axes")
        };
        for model in Model::ALL {
            let mut x = Outcome::default();
            exact.solve(model, &mut x).unwrap();
            let mut f = Outcome::default();
            if float.solve(model, &mut f).is_err() {
                assert!(cond.cond * eps >= 1e-3, "{}: declared singular", scene.name);
                continue;
            }
            solved += 1;
            let b = Bounds::of(&exact, &cond, model, &x, eps);
            // Σ γ_i and Σ |P_i| s_i over the contacts, with unit normals.
            let (mut gamma, mut work) = (0.0, 0.0);
            for (i, frame) in exact.frames().iter().enumerate() {
                let axis = &frame.axes[0];
                let n2 = frame.norm2[0].clone();
                gamma += (axis.reciprocal(&body.response(axis)) / &n2).to_f64();
                let (r, n) = (&exact_problem.contacts()[i].point, axis.top());
                let mut s2 = dot(&n, &n) / &body.mass;
                for a in 0..3 {
                    let (p, q) = ((a + 1) % 3, (a + 2) % 3);
                    let m = (&r[p] * &n[q]).abs() + (&r[q] * &n[p]).abs();
                    s2 += &m * &m / &j[a];
                }
                let p2 = &x.impulses_hat[i] * &x.impulses_hat[i] * &n2;
                work += (p2 * s2 / &n2).to_f64().sqrt();
            }
            let n = exact.contacts() as f64;
            let bound =
                b.twist + gamma.sqrt() * b.impulses + (n + 6.0) * eps * (b.v0 + b.dv + work);
            let mut error = Screw::zero();
            for k in 0..6 {
                error.0[k] = Exact::from(f.constraint_wrench.0[k].exact_value().unwrap())
                    - &x.constraint_wrench.0[k];
            }
            let ratio = wrench_norm(body, &error) / bound;
            assert!(
                ratio <= 1.0,
                "{} {}, {}: error/bound {ratio:e}",
                scene.name,
                model.name(),
                T::NAME
            );
            worst = worst.max(ratio);
        }
    }
    (worst, solved)
}

/// `p` with its constraints in `T` (inputs rounded once, as a float solve reads them).
fn convert_held<T: Scalar>(p: &Problem<Exact>) -> Problem<T> {
    let c = p.constraints().expect("constrained");
    let screw = |s: &Screw<Exact>| Screw(s.0.map(|x| T::from_rational(&x.to_big_rational())));
    let free = c.free.iter().map(screw).collect();
    let blocked = (!c.derived_blocked).then(|| c.blocked.iter().map(screw).collect());
    convert::<T>(p)
        .with_constraints(free, blocked)
        .expect("rounding keeps the constraints valid")
}

/// Float solves (f32, f64, double-double) report the constraint wrench within
///
/// ```text
/// ‖δw‖_* ≤ B_v + (Σ_i γ_i)^½ B_P + (N + 6) ε (V + Σ_i |P_i| s_i)
/// ```
///
/// of the exact one. The wrench is formed as w = M Δv + Σ_i P_i E_i (unit normals), so its
/// error is M δΔv, within ‖δv‖_M ≤ B_v (the accuracy contract's twist bound, `analysis::
/// accuracy`; ‖·‖_* is the dual norm, ‖M x‖_* = ‖x‖_M), plus Σ δP_i E_i, within
/// ‖δP‖₂ (Σ ‖E_i‖_*²)^½ ≤ B_P (Σ γ_i)^½ by Cauchy–Schwarz (γ_i = ‖E_i‖_*², the free-body
/// inertance of contact i), plus the rounding of forming it: componentwise, each E_i's moment
/// is within 3ε of |r||n| (the contract's), each product P_i E_i adds ε, Δv = v − v⁰ and M Δv
/// one each, and the sum of N + 1 terms N ε — at most (N + 4) ε of the magnitudes, whose norm
/// is ‖|M Δv|‖_* + Σ |P_i| s_i (s_i = ‖|E_i|‖_*, as the contract's), with the inputs' own
/// rounding of v⁰ (ε‖v⁰‖_M) and 2ε for the first-order terms dropped: (N + 6) ε with
/// V = ‖v⁰‖_M + ‖Δv‖_M. B_v and B_P carry the conditioning (κ = cond G, μ = cond M_red, ℓ).
///
/// Measured: the largest error/bound is printed (10⁻³ or below in f64 when this was written);
/// every type solves the whole corpus except where it declares G singular, which it may only
/// at κ ε ≥ 10⁻³.
#[test]
fn float_reactions_meet_their_bound_against_the_exact_solve() {
    let scenes = float_corpus();
    let rows = [
        ("f32", worst_ratio::<f32>(&scenes)),
        ("f64", worst_ratio::<f64>(&scenes)),
        ("double-double", worst_ratio::<DoubleDouble>(&scenes)),
    ];
    for (name, (worst, solved)) in rows {
        eprintln!("{name}: {solved} solves, largest error/bound {worst:.1e}");
        assert!(solved >= 20, "{name}: only {solved} solves measured");
    }
}
