//! Systems in floats are solved in units of mass, length and time that are powers of two chosen
//! from the scene's own numbers (`scene::scale::system`), and the report is scaled back:
//!
//! - a scene rewritten in units that differ from its own by powers of two (mass ×2⁴⁰, lengths
//!   ×2⁻³⁰, time ×2⁷) gives every f64 output scaled exactly by its dimension, bit for bit —
//!   the cradle, the double pendulum with its joints' reactions, and the rough pendulum's
//!   frictional path: the units chosen differ by exactly those powers, so the solves in them
//!   are the same solve;
//! - a double pendulum of 10²⁰⁰ kg and 10⁻²⁰⁰ m, whose r²/J underflows in f64 as written
//!   (r² ≈ 10⁻⁴⁰⁰), is solved and agrees with the exact solve to 10⁻¹² relative, output by
//!   output;
//! - a cradle whose impulses are beyond f64 (balls of 5·10³¹⁹ kg at 10⁻¹⁰ m/s: P ≈ 10³¹⁰ N s,
//!   while its energies, 10³⁰⁰ J, are not) is refused, naming the impulses and the mass, the
//!   input farthest from 1.

use inertance::report::Value;
use inertance::report::system::SystemReport;
use inertance::scalar::Exact;
use inertance::scene::Scene;
use inertance::scene::system_pipeline::run_system;

/// Powers of two of the rewritten units: mass 2^A kg, length 2^B m, time 2^C s.
const A: i64 = 40;
const B: i64 = -30;
const C: i64 = 7;

/// How a quantity of dimension M^d₀ L^d₁ T^d₂ is written in the rewritten units.
type Units = dyn Fn(&str, [i64; 3]) -> String;

/// Units 2^A kg, 2^B m, 2^C s (all zero: the scene's own): `x` times 2^(d · (a, b, c)),
/// exactly.
fn binary(a: i64, b: i64, c: i64) -> impl Fn(&str, [i64; 3]) -> String {
    move |x, d| format!("\"({x})*2^({})\"", d[0] * a + d[1] * b + d[2] * c)
}

/// Units 10^a kg, 10^b m, 10^c s, written as decimals.
fn decimal(a: i64, b: i64, c: i64) -> impl Fn(&str, [i64; 3]) -> String {
    move |x, d| format!("\"({x})*10^({})\"", d[0] * a + d[1] * b + d[2] * c)
}

const MASS: [i64; 3] = [1, 0, 0];
const INERTIA: [i64; 3] = [1, 2, 0];
const LENGTH: [i64; 3] = [0, 1, 0];
const SPEED: [i64; 3] = [0, 1, -1];
const RATE: [i64; 3] = [0, 0, -1];

fn triple(u: &Units, x: [&str; 3], d: [i64; 3]) -> String {
    format!("[{}, {}, {}]", u(x[0], d), u(x[1], d), u(x[2], d))
}

/// Newton's cradle of three balls (examples/cradle-3.toml, spheres written as their mass
/// properties), in the units `u`.
fn cradle(u: &Units) -> String {
    let mut text = String::from("name = \"cradle\"\n");
    let names = ["striker", "ball 2", "ball 3"];
    for (k, name) in names.iter().enumerate() {
        let x = ["0", "0.05", "0.1"][k];
        let v = if k == 0 { "1" } else { "0" };
        text += &format!(
            "[[body]]\nname = \"{name}\"\nmass = {}\ninertia = {}\nposition = {}\nvelocity = {}\nangular_velocity = {}\n",
            u("0.5", MASS),
            triple(u, ["0.000125", "0.000125", "0.000125"], INERTIA),
            triple(u, [x, "0", "0"], LENGTH),
            triple(u, [v, "0", "0"], SPEED),
            triple(u, ["0", "0", "0"], RATE),
        );
    }
    for (k, x) in ["0.025", "0.075"].iter().enumerate() {
        text += &format!(
            "[[contact]]\nbodies = [\"{}\", \"{}\"]\npoint = {}\nnormal = [1, 0, 0]\nk = 1\n",
            names[k],
            names[k + 1],
            triple(u, [x, "0", "0"], LENGTH)
        );
    }
    text + "[solve]\nmodels = [\"newton\", \"poisson\"]\n"
}

/// The double pendulum striking a wall (examples/double-pendulum-wall.toml, its rods written
/// in world axes), in the units `u`; `mu` > 0 makes it the rough pendulum's frictional
/// impact (examples/rough-pendulum.toml). The second hinge's axis is written 2⁵⁰ long (a
/// direction: any length serves).
fn pendulum(u: &Units, mu: &str) -> String {
    let body = |name: &str, at: [&str; 3], v: [&str; 3], w: &str| {
        format!(
            "[[body]]\nname = \"{name}\"\nmass = {}\ninertia = {}\nposition = {}\nvelocity = {}\nangular_velocity = {}\n",
            u("1", MASS),
            triple(u, ["1/3", "1/3", "1/3"], INERTIA),
            triple(u, at, LENGTH),
            triple(u, v, SPEED),
            triple(u, ["0", "0", w], RATE),
        )
    };
    let mut text = String::from("name = \"pendulum\"\n");
    text += &body("upper", ["3/5", "-4/5", "0"], ["4/5", "3/5", "0"], "1");
    text += &body("lower", ["2", "-11/5", "0"], ["14/5", "14/5", "0"], "2");
    text += &format!(
        "[[joint]]\nkind = \"revolute\"\nbodies = [\"upper\"]\nanchor = [0, 0, 0]\naxis = [0, 0, 1]\n\
         [[joint]]\nkind = \"revolute\"\nbodies = [\"upper\", \"lower\"]\nanchor = {}\naxis = [0, 0, \"2^50\"]\n\
         [[obstacle]]\nname = \"wall\"\nnormal = [-1, 0, 0]\npoint = {}\n\
         [[contact]]\nbody = \"lower\"\nobstacle = \"wall\"\npoint = {}\nk = 0.5\nmu = {mu}\n\
         [solve]\nmodels = [\"newton\", \"poisson\"]\n",
        triple(u, ["6/5", "-8/5", "0"], LENGTH),
        triple(u, ["14/5", "0", "0"], LENGTH),
        triple(u, ["14/5", "-14/5", "0"], LENGTH),
    );
    text
}

fn parse(text: &str) -> Scene {
    Scene::parse(text, "generated").unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// Every output of a system report with its dimension as powers (mass, length, time), in a
/// fixed order: G, Δ, velocities, energies, impulses, twists, reactions, momenta.
fn outputs(r: &SystemReport) -> Vec<(&Value, [i64; 3], String)> {
    let mut out: Vec<(&Value, [i64; 3], String)> = Vec::new();
    let n = r.inertance.len() as i64;
    fn push<'a>(
        out: &mut Vec<(&'a Value, [i64; 3], String)>,
        v: &str,
        d: [i64; 3],
        values: Vec<&'a Value>,
    ) {
        for (k, x) in values.into_iter().enumerate() {
            out.push((x, d, format!("{v}[{k}]")));
        }
    }
    const IMPULSE: [i64; 3] = [1, 1, -1];
    const MOMENT: [i64; 3] = [1, 2, -1];
    const ENERGY: [i64; 3] = [1, 2, -2];
    push(
        &mut out,
        "G",
        [-1, 0, 0],
        r.inertance.iter().flatten().collect(),
    );
    push(&mut out, "Δ", [-n, 0, 0], vec![&r.det]);
    push(
        &mut out,
        "before",
        SPEED,
        r.contacts_before
            .iter()
            .flat_map(|p| &p.components)
            .collect(),
    );
    push(
        &mut out,
        "T⁰",
        ENERGY,
        r.kinetic_energy_before.iter().collect(),
    );
    push(
        &mut out,
        "p⁰",
        IMPULSE,
        r.momentum_before.0.iter().collect(),
    );
    push(&mut out, "L⁰", MOMENT, r.momentum_before.1.iter().collect());
    for m in &r.models {
        push(&mut out, "P", IMPULSE, m.impulses.iter().collect());
        push(
            &mut out,
            "ω",
            RATE,
            m.twists.iter().flat_map(|t| &t.0).collect(),
        );
        push(
            &mut out,
            "v_C",
            SPEED,
            m.twists.iter().flat_map(|t| &t.1).collect(),
        );
        push(
            &mut out,
            "v_i",
            SPEED,
            m.contacts.iter().flat_map(|p| &p.components).collect(),
        );
        push(
            &mut out,
            "E",
            ENERGY,
            [&m.lost_velocity_energy, &m.kinetic_energy_loss]
                .into_iter()
                .chain(&m.kinetic_energy_after)
                .collect(),
        );
        push(
            &mut out,
            "F",
            IMPULSE,
            m.joint_reactions.iter().flat_map(|w| &w.force).collect(),
        );
        push(
            &mut out,
            "M",
            MOMENT,
            m.joint_reactions.iter().flat_map(|w| &w.moment).collect(),
        );
        push(
            &mut out,
            "anchor",
            LENGTH,
            m.joint_reactions.iter().flat_map(|w| &w.point).collect(),
        );
        push(&mut out, "p", IMPULSE, m.momentum_after.0.iter().collect());
        push(&mut out, "L", MOMENT, m.momentum_after.1.iter().collect());
    }
    for f in &r.friction {
        for c in &f.contacts {
            push(
                &mut out,
                "P",
                IMPULSE,
                [&c.normal_impulse, &c.compression_impulse]
                    .into_iter()
                    .chain(&c.tangential_impulse)
                    .collect(),
            );
            push(
                &mut out,
                "v_i",
                SPEED,
                std::iter::once(&c.normal_velocity)
                    .chain(&c.velocity)
                    .collect(),
            );
        }
        push(
            &mut out,
            "ω",
            RATE,
            f.twists.iter().flat_map(|t| &t.0).collect(),
        );
        push(
            &mut out,
            "v_C",
            SPEED,
            f.twists.iter().flat_map(|t| &t.1).collect(),
        );
        push(
            &mut out,
            "E",
            ENERGY,
            [
                &f.lost_velocity_energy,
                &f.kinetic_energy_loss,
                &f.friction_dissipation,
            ]
            .into_iter()
            .chain(&f.kinetic_energy_after)
            .collect(),
        );
        push(
            &mut out,
            "F",
            IMPULSE,
            f.joint_reactions.iter().flat_map(|w| &w.force).collect(),
        );
        push(
            &mut out,
            "M",
            MOMENT,
            f.joint_reactions.iter().flat_map(|w| &w.moment).collect(),
        );
        push(&mut out, "p", IMPULSE, f.momentum_after.0.iter().collect());
        push(&mut out, "L", MOMENT, f.momentum_after.1.iter().collect());
    }
    out
}

/// The f64 report of `scaled` is that of `si` with every output times 2^(dimension · (A, B,
/// C)), bit for bit.
fn assert_scaled_exactly(si: &str, scaled: &str) {
    let r0 = run_system::<f64>(&parse(si), None).expect("solves").report;
    let r1 = run_system::<f64>(&parse(scaled), None)
        .expect("solves")
        .report;
    let (o0, o1) = (outputs(&r0), outputs(&r1));
    assert_eq!(o0.len(), o1.len());
    assert!(o0.len() > 20, "the reports hold outputs");
    for ((x, d, name), (y, _, _)) in o0.iter().zip(&o1) {
        let k = d[0] * A + d[1] * B + d[2] * C;
        let expected = x.f64 * 2f64.powi(k as i32);
        assert_eq!(
            expected.to_bits(),
            y.f64.to_bits(),
            "{name}: {} × 2^{k} = {expected:e}, scaled scene {:e}",
            x.f64,
            y.f64
        );
    }
}

#[test]
fn the_cradle_in_scaled_units_is_the_cradle_scaled_bit_for_bit() {
    assert_scaled_exactly(&cradle(&binary(0, 0, 0)), &cradle(&binary(A, B, C)));
}

#[test]
fn the_double_pendulum_and_its_reactions_scale_bit_for_bit() {
    assert_scaled_exactly(
        &pendulum(&binary(0, 0, 0), "0"),
        &pendulum(&binary(A, B, C), "0"),
    );
}

#[test]
fn the_frictional_path_scales_bit_for_bit() {
    let (si, scaled) = (
        pendulum(&binary(0, 0, 0), "3"),
        pendulum(&binary(A, B, C), "3"),
    );
    let r = run_system::<f64>(&parse(&si), None).expect("solves").report;
    assert!(!r.friction.is_empty(), "a frictional solve");
    assert_scaled_exactly(&si, &scaled);
}

/// Each output of `float` within `tol` of `exact`'s, relative to the largest magnitude of
/// its group (the outputs of one name).
fn assert_close(exact: &SystemReport, float: &SystemReport, tol: f64) {
    let (e, f) = (outputs(exact), outputs(float));
    assert_eq!(e.len(), f.len());
    for ((x, _, name), (y, _, _)) in e.iter().zip(&f) {
        let group = name.split('[').next().unwrap_or_default();
        let largest = |group: &str| {
            e.iter()
                .filter(|(_, _, n)| n.split('[').next() == Some(group))
                .map(|(v, _, _)| v.f64.abs())
                .fold(0.0, f64::max)
        };
        // A reaction's moment at its anchor is a force times a lever: its scale is theirs
        // (a hinge's moment about its own axis is 0 exactly).
        let scale = match group {
            "M" => largest("M").max(largest("F") * largest("anchor")),
            _ => largest(group),
        };
        assert!(
            (x.f64 - y.f64).abs() <= tol * scale,
            "{name}: exact {:e}, f64 {:e}",
            x.f64,
            y.f64
        );
    }
}

#[test]
fn a_system_at_1e200_is_solved_in_f64_and_agrees_with_the_exact_solve() {
    // 10²⁰⁰ kg, 10⁻²⁰⁰ m, seconds: r² ≈ 10⁻⁴⁰⁰ is below f64 (as written, G's r²/J term
    // flushed); the impulses (≈ 1 N s), energies (10⁻²⁰⁰ J) and velocities are representable.
    let text = pendulum(&decimal(200, -200, 0), "0");
    let scene = parse(&text);
    let exact = run_system::<Exact>(&scene, None).expect("exact").report;
    let float = run_system::<f64>(&scene, None)
        .expect("f64 solves it")
        .report;
    assert_close(&exact, &float, 1e-12);
}

#[test]
fn impulses_beyond_f64_are_refused_naming_them() {
    let text = cradle(&decimal(320, 0, 10));
    let scene = parse(&text);
    let e = run_system::<f64>(&scene, None).expect_err("beyond f64");
    let message = e.to_string();
    assert!(
        message.contains("impulses are beyond the range of f64"),
        "{message}"
    );
    assert!(message.contains("scaled to the scene"), "{message}");
    assert!(message.contains("].mass` = 5000"), "{message}");
    // The exact solve answers.
    run_system::<Exact>(&scene, None).expect("exact");
}
