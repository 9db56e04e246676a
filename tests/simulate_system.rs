//! Systems of spheres through sequences of impacts (`src/simulate/system/`): Newton's cradle
//! against its closed forms, and Siconos' ColumnOfBeads against its reference trajectory
//! (derivations/siconos-column.md).

use inertance::scene::AnySimulation;
use inertance::simulate::Law;
use inertance::simulate::system::{
    SystemSetup, SystemSimulation, after_first_impact, simulate_system,
};

fn setup(path: &str) -> SystemSetup {
    match AnySimulation::load(std::path::Path::new(path)).expect("scene") {
        AnySimulation::System(s) => s.setup,
        AnySimulation::Body(_) => panic!("{path}: not a system"),
    }
}

fn run(setup: &SystemSetup) -> SystemSimulation {
    let sim = simulate_system(setup);
    assert!(sim.stopped.is_none(), "stopped: {:?}", sim.stopped);
    sim
}

/// The striker reaches ball 2 after 0.01 m at 1 m/s; the simultaneous law (k = 1, the closed
/// contact of balls 2 and 3 held at zero relative speed) gives (−1/3, 2/3, 2/3), and no impact
/// follows. Ballistic flight without gravity is exact to rounding and the impact is found
/// within the gap tolerance 10⁻¹¹ L (L = 0.06 m) of contact, so times to 10⁻¹² s and
/// positions to 10⁻¹² m.
#[test]
fn cradle_under_the_simultaneous_law_is_the_closed_form() {
    let s = setup("examples/simulate/cradle-3.toml");
    let sim = run(&s);
    assert_eq!(sim.impacts.len(), 1);
    let i = &sim.impacts[0];
    assert!((i.t - 0.01).abs() <= 1e-12, "t = {}", i.t);
    assert_eq!(
        i.contacts.len(),
        2,
        "the striker's contact and the closed one"
    );
    assert!(i.contacts[1].persisting);
    let v = after_first_impact(&sim).expect("after");
    for (got, want) in v.iter().zip([-1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0]) {
        assert!((got.x - want).abs() <= 1e-12, "{got} vs {want}");
    }
    let dt = 0.05 - 0.01;
    let x = &sim.state.x;
    let want = [
        -0.01 + 0.01 - dt / 3.0,
        0.05 + 2.0 * dt / 3.0,
        0.1 + 2.0 * dt / 3.0,
    ];
    for (got, want) in x.iter().zip(want) {
        assert!((got.x - want).abs() <= 1e-12, "{got} vs {want}");
    }
}

/// Under LZB (equal Hertz contacts, e = 1) the outcome is the single-impact scene's
/// (derivations/lzb.md: −0.0710, 0.0764, 0.9945, to the four digits printed there, so to
/// 5·10⁻⁵), momentum is kept to rounding and energy to the LZB tolerance; the balls then
/// separate and nothing strikes again.
#[test]
fn cradle_under_lzb_the_striker_nearly_stops() {
    let mut s = setup("examples/simulate/cradle-3.toml");
    s.law = Law::Lzb;
    let sim = run(&s);
    assert_eq!(sim.impacts.len(), 1);
    let v = after_first_impact(&sim).expect("after");
    for (got, want) in v.iter().zip([-0.0710, 0.0764, 0.9945]) {
        assert!((got.x - want).abs() <= 5e-5, "{got} vs {want}");
    }
    let p: f64 = v.iter().map(|v| 0.5 * v.x).sum();
    assert!((p - 0.5).abs() <= 1e-12, "momentum {p}");
    let i = &sim.impacts[0];
    assert!(
        (i.kinetic_before - i.kinetic_after).abs() <= 1e-9 * i.kinetic_before,
        "energy {} → {}",
        i.kinetic_before,
        i.kinetic_after
    );
}

/// Siconos' BeadColumnED_LZBModel.ref: t, q1..q10, v1..v10 (heights and vertical velocities).
fn siconos() -> Vec<Vec<f64>> {
    let text = include_str!("data/siconos-BeadColumnED_LZBModel.ref");
    text.lines()
        .skip(1)
        .map(|l| {
            l.split_whitespace()
                .map(|x| x.parse().expect("number"))
                .collect()
        })
        .collect()
}

/// Siconos' impacts: the pairs of rows at one time (before, after), with the beads whose
/// velocity changed.
fn siconos_impacts(rows: &[Vec<f64>]) -> Vec<(f64, Vec<usize>, usize)> {
    (1..rows.len())
        .filter(|&i| rows[i][0] == rows[i - 1][0] && rows[i][0] > 0.0)
        .map(|i| {
            let moved = (0..10)
                .filter(|&k| (rows[i][11 + k] - rows[i - 1][11 + k]).abs() > 1e-9)
                .collect();
            (rows[i][0], moved, i)
        })
        .collect()
}

/// The beads an impact of ours moved.
fn moved(sim: &SystemSimulation, k: usize) -> Vec<usize> {
    let t = sim.impacts[k].t;
    let at: Vec<_> = sim.samples.iter().filter(|s| s.t == t).collect();
    (0..10)
        .filter(|&b| (at[1].state.v[b].z - at[0].state.v[b].z).abs() > 1e-9)
        .collect()
}

/// Ours and Siconos' impacts paired in order, where two consecutive impacts of disjoint beads
/// may come in either order (they commute: neither changes what the other strikes); `None` at
/// the first that does not pair.
fn pair_impacts(
    ours: &[(f64, Vec<usize>)],
    theirs: &[(f64, Vec<usize>)],
) -> (Vec<(usize, usize)>, Option<usize>) {
    let mut pairs = Vec::new();
    let mut k = 0;
    while k < ours.len().min(theirs.len()) {
        if ours[k].1 == theirs[k].1 {
            pairs.push((k, k));
            k += 1;
        } else if k + 1 < ours.len().min(theirs.len())
            && ours[k].1 == theirs[k + 1].1
            && ours[k + 1].1 == theirs[k].1
            && !ours[k].1.iter().any(|b| ours[k + 1].1.contains(b))
        {
            pairs.extend([(k, k + 1), (k + 1, k)]);
            k += 2;
        } else {
            return (pairs, Some(k));
        }
    }
    (pairs, None)
}

/// The column falls as one for h = 0.05 m and strikes at t = √(2h/g) with v = −√(2gh) on all
/// ten contacts; our LZB answer agrees with Siconos' to within Siconos' own error, which is
/// about one primary-impulse step per contact: DelPest/m = 10⁻⁶/4.07·10⁻³ = 2.5·10⁻⁴ m/s,
/// ten contacts 2.5·10⁻³ m/s (derivations/siconos-column.md; its two-ball impacts, whose exact
/// answer is an exchange, are off by up to 2·10⁻⁴ m/s).
#[test]
fn column_of_beads_first_impact_is_siconos_within_its_step() {
    let s = setup("examples/simulate/column-of-beads.toml");
    let sim = run(&s);
    let rows = siconos();
    let theirs = siconos_impacts(&rows);
    let t_c = (2.0 * 0.05 / 9.81f64).sqrt();
    let first = &sim.impacts[0];
    assert_eq!(first.contacts.len(), 10);
    assert!((first.t - t_c).abs() <= 2e-12, "t = {} vs {t_c}", first.t);
    assert!((first.t - theirs[0].0).abs() <= 1e-9);
    let before = -(2.0 * 9.81 * 0.05f64).sqrt();
    assert!((first.contacts[0].before - before).abs() <= 1e-9);
    let v = after_first_impact(&sim).expect("after");
    let row = &rows[theirs[0].2];
    let worst = (0..10)
        .map(|b| (v[b].z - row[11 + b]).abs())
        .fold(0.0, f64::max);
    let step = 1e-6 / s.members[0].mass();
    println!("first impact: max |Δv| = {worst:e} m/s (DelPest/m = {step:e})");
    assert!(worst <= 10.0 * step, "{worst}");
}

/// After the first impact the beads fly apart and re-collide, two at a time (or one on the
/// wall). Both runs make 138 impacts, and they strike the same beads in the same order — but
/// for nine pairs of consecutive impacts on disjoint beads, which come within the time shift of
/// each other and are taken in opposite orders (they commute). The event times are shifted by
/// less than Siconos' output step: each of Siconos' impacts errs by about DelPest/m, which moves
/// the later flights. At Siconos' output times more than 1 ms (and twice the largest shift)
/// from every impact of either run, each bead's velocity differs by at most the errors it has
/// carried: the first impact's 10 DelPest/m plus DelPest/m for each later impact it took part
/// in; its height by that over the 0.4 s of the run plus the fastest bead (1.6 m/s) over the
/// largest shift. Energy (e = 1, frictionless) is kept to the LZB tolerance 10⁻¹⁰ per impact,
/// 138 of them: 2·10⁻⁸ of it (derivations/siconos-column.md).
#[test]
fn column_of_beads_follows_siconos_to_the_end() {
    let s = setup("examples/simulate/column-of-beads.toml");
    let sim = run(&s);
    let rows = siconos();
    let theirs: Vec<(f64, Vec<usize>)> = siconos_impacts(&rows)
        .into_iter()
        .map(|(t, b, _)| (t, b))
        .collect();
    let ours: Vec<(f64, Vec<usize>)> = (0..sim.impacts.len())
        .map(|k| (sim.impacts[k].t, moved(&sim, k)))
        .collect();
    assert_eq!(ours.len(), theirs.len());
    let (pairs, unpaired) = pair_impacts(&ours, &theirs);
    let swapped = pairs.iter().filter(|(a, b)| a != b).count() / 2;
    let dt = pairs
        .iter()
        .map(|&(a, b)| (ours[a].0 - theirs[b].0).abs())
        .fold(0.0, f64::max);
    println!(
        "paired {} impacts ({swapped} swaps), largest time shift {dt:e} s",
        pairs.len()
    );
    assert_eq!(
        unpaired,
        None,
        "{:?}",
        unpaired.map(|k| (&ours[k], &theirs[k]))
    );
    assert!(dt < 1e-3, "{dt}");
    let step = 1e-6 / s.members[0].mass();
    let allowance: Vec<f64> = (0..10)
        .map(|b| (10 + theirs.iter().skip(1).filter(|i| i.1.contains(&b)).count()) as f64 * step)
        .collect();
    let near = |t: f64| {
        ours.iter()
            .chain(&theirs)
            .any(|i| (t - i.0).abs() <= 2.0 * dt + 1e-3)
    };
    let (mut dq, mut dv, mut compared) = (0.0f64, 0.0f64, 0);
    for r in &rows {
        if near(r[0]) {
            continue;
        }
        let Some(o) = sim.samples.iter().find(|s| (s.t - r[0]).abs() <= 1e-9) else {
            continue;
        };
        compared += 1;
        for b in 0..10 {
            let (eq, ev) = (
                (o.state.x[b].z - r[1 + b]).abs(),
                (o.state.v[b].z - r[11 + b]).abs(),
            );
            assert!(
                ev <= allowance[b],
                "t = {}, bead {}: |Δv| = {ev:e}",
                r[0],
                b + 1
            );
            assert!(
                eq <= allowance[b] * 0.4 + 1.6 * dt,
                "t = {}, bead {}: |Δq| = {eq:e}",
                r[0],
                b + 1
            );
            dq = dq.max(eq);
            dv = dv.max(ev);
        }
    }
    println!("compared {compared} rows: max |Δq| = {dq:e} m, max |Δv| = {dv:e} m/s");
    assert!(compared > 150);
    let e0 = sim.samples[0].kinetic + sim.samples[0].potential;
    let drift = sim
        .samples
        .iter()
        .map(|s| (s.kinetic + s.potential - e0).abs())
        .fold(0.0, f64::max);
    println!(
        "energy {e0:e} J, largest drift {drift:e} J ({:e} relative)",
        drift / e0
    );
    assert!(drift <= 2e-8 * e0);
}

/// A scene of spheres with a mistake: the error names the file, the key and what to do.
#[test]
fn bad_sphere_systems_name_the_key_and_the_value() {
    let scene = |body2: &str, simulate: &str| {
        format!(
            "[[body]]\nname = \"a\"\nshape = {{ sphere = 0.01 }}\nmass = 1\nposition = [0, 0, 0.02]\n\
             velocity = [0, 0, 0]\nmaterial = {{ young = 2e11, poisson = 0.3 }}\n\
             [[body]]\nname = \"b\"\nshape = {{ sphere = 0.01 }}\nmass = 1\n{body2}velocity = [0, 0, 0]\n\
             [[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\n\
             [simulate]\nduration = 1\n{simulate}"
        )
    };
    let err = |text: String| {
        AnySimulation::parse(&text, "s.toml")
            .map(|_| ())
            .expect_err("refused")
            .to_string()
    };
    let e = err(scene(
        "position = [0, 0, 0.04]\n",
        "law = \"lzb\"\ncontact = { stiffness = \"hertz\" }\n",
    ));
    assert!(
        e.contains("s.toml") && e.contains("simulate.contact.stiffness"),
        "{e}"
    );
    // the first contact watched without both materials: the floor has none
    assert!(e.contains("material of obstacle \"floor\""), "{e}");
    // friction is taken (tests/simulate_rough_systems.rs), and spins the spheres it touches
    match AnySimulation::parse(
        &scene("position = [0, 0, 0.04]\n", "contact = { mu = 0.3 }\n"),
        "s.toml",
    )
    .expect("friction in a system")
    {
        AnySimulation::System(s) => assert!(s.setup.members.iter().all(|m| m.turns())),
        AnySimulation::Body(_) => panic!("a system"),
    }
    let e = err(scene("position = [0, 0, 0.025]\n", ""));
    assert!(e.contains("\"a\" starts inside \"b\""), "{e}");
    let e = err(scene(
        "position = [0, 0, 0.04]\n",
        "[[simulate.pair]]\nbodies = [\"a\", \"c\"]\nk = 0.5\n",
    ));
    assert!(
        e.contains("simulate.pair[0].bodies") && e.contains("a, b"),
        "{e}"
    );
    let e = err(scene("position = [0, 0, 0.04]\n", "plane = [0, 1, 0]\n"));
    assert!(e.contains("simulate.plane"), "{e}");
}

#[test]
fn a_system_whose_energy_overflows_stops_with_status_3() {
    // a striker at 1e200 m/s: ½ m v² overflows f64; the run stops (status 3, "overflowed"),
    // never "ended at rest" with an `inf` energy and status 0
    let text = std::fs::read_to_string("examples/simulate/cradle-3.toml")
        .expect("reads")
        .replacen("velocity = [1, 0, 0]", "velocity = [1e200, 0, 0]", 1);
    let path = std::env::temp_dir().join("inertance-overflowing-cradle.toml");
    std::fs::write(&path, text).expect("writes");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .arg("simulate")
        .arg(&path)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(3));
    let log = String::from_utf8_lossy(&out.stdout);
    assert!(
        log.contains("ended at an error") && !log.contains("inf"),
        "{log}"
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("overflowed f64"));
}
