//! The fuzzing harness (issue 16): structure-aware scenes (`fuzz/scenes.rs`) run against `solve`,
//! `analyze`, `derive` and `sweep`, in f64 and exactly, asserting the contract:
//!
//! - exit status 0, 2, 3 or 4 only; no panic (no `panicked` on stderr, no signal); nothing on
//!   stdout when the status is 2 or 3; status 4 (some model has no answer, the others are
//!   printed) names what has none on stderr;
//! - on status 0, no NaN, ∞ or `null` where a number belongs in the JSON (the documented
//!   exceptions: `angle_*_deg` is `null` when the tangential velocity is zero, `compressive`,
//!   `energy_gain` and an inadmissibility's `contact` may be `null`, `condition_number` may be
//!   `"inf"`), and no `NaN`/`inf` word in tables, text reports and CSV cells;
//! - `sweep` leaves no output file and no `.tmp` file when it fails;
//! - every run ends within [`TIMEOUT`] (a hang is a failure; no performance is asserted);
//! - **the oracle** (issue 28): where exact is cheap ([`cheap`]), the f64 report `solve`
//!   prints agrees with the exact solve of the same scene within the accuracy contract's
//!   bounds (`analysis::accuracy::Bounds::of`) — the impulses, the twist after impact and both
//!   energies — and f64 declares G singular only where cond₂ G · ε ≥ 10⁻³.
//!
//! The library functions the CLI calls (`Scene::parse`, `run`, `analyze_scene`, `derive`) are
//! driven in-process for most cases (fast: no process, no file); every [`BINARY_EVERY`]-th case,
//! and every corpus file, also goes through the binary with every command.
//!
//! Environment: `INERTANCE_FUZZ_SEED` (default a fixed seed), `INERTANCE_FUZZ_CASES` (cases of
//! the long run, `fuzz_long`, ignored by default), `INERTANCE_FUZZ_FINDINGS` (where the long run
//! writes failing scenes; default `target/fuzz-findings`). Corpus: `tests/fuzz_corpus/*.toml`
//! (regression inputs, run by `corpus_files_keep_the_contract`).
//! A corpus file may say `# symbols: m,k1` and `# vary: body.mass=1:2:3` in its first lines.

#[path = "fuzz/scenes.rs"]
mod scenes;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use inertance::analysis::accuracy::{Bounds, Conditioning, energy_norm};
use inertance::impact::solve::{Impact, Outcome, SolveError};
use inertance::impact::unilateral::Law;
use inertance::mechanics::contact::Surd;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::report::Report;
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;
use inertance::scene::pipeline::{RunError, prepare, run};
use inertance::scene::scale::{Units, scale};
use inertance::tools::analyze::analyze_scene;
use serde_json::Value as Json;

/// A run taking longer than this is a hang.
const TIMEOUT: Duration = Duration::from_secs(20);
/// The seed of the short run (and the default of the long one).
const SEED: u64 = 0x1617_2026_0016;
/// Cases of the short in-process run.
const SHORT_CASES: u64 = 600;
/// Cases of the short binary run (each runs up to ten processes).
const SHORT_BINARY_CASES: u64 = 40;
/// In a long run, every this-many-th case also goes through the binary.
const BINARY_EVERY: u64 = 10;

fn seed() -> u64 {
    std::env::var("INERTANCE_FUZZ_SEED")
        .ok()
        .and_then(|s| {
            let s = s.trim();
            s.strip_prefix("0x")
                .map_or_else(|| s.parse().ok(), |h| u64::from_str_radix(h, 16).ok())
        })
        .unwrap_or(SEED)
}

// ---------------------------------------------------------------------------------------------
// The contract on outputs.

/// Keys whose value may be `null` (guide/solving.md and guide/degenerate-cases.md, JSON sections).
const NULLABLE: &[&str] = &[
    "angle_before_deg",
    "angle_after_deg",
    "compressive",
    "energy_gain",
    "contact",
    // `derive --json`: no locus of Δ = 0, not a singular family.
    "det_locus",
    "singular",
    // `analyze --json`: coincident points whose normal's impulse the constraints absorb.
    "single_impulse",
];

/// Keys that are `null` when the system has no solution (see `json_faults`).
const NO_SOLUTION: &[&str] = &[
    "impulses",
    "twist_after",
    "particular_impulse_multiples",
    "null_directions",
];

/// Keys whose value may be the string `"inf"` (a condition number of a singular G, and the
/// forward error estimate made from it).
const MAY_BE_INF: &[&str] = &["condition_number", "forward_error_estimate"];

/// Every place a JSON report breaks the contract: a `null` outside [`NULLABLE`], a string that
/// spells NaN or an infinity (except `condition_number`).
fn json_faults(v: &Json, path: &str, key: &str, out: &mut Vec<String>) {
    match v {
        Json::Null if !NULLABLE.contains(&key) => out.push(format!("null at {path}")),
        Json::Number(n) if !n.as_f64().is_some_and(f64::is_finite) => {
            out.push(format!("non-finite number at {path}"))
        }
        Json::String(s) if !(MAY_BE_INF.contains(&key) && s == "inf") && bad_words(s) => {
            out.push(format!("{path} = {s:?}"))
        }
        Json::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                json_faults(x, &format!("{path}[{i}]"), key, out);
            }
        }
        Json::Object(o) => {
            // No solution, so nothing to report: `analyze` on a singular-incompatible system,
            // `derive`'s family where the system is not compatible identically.
            let unsolved = o.get("classification") == Some(&Json::from("singular-incompatible"))
                || o.get("compatible_identically") == Some(&Json::Bool(false));
            for (k, x) in o {
                if unsolved && x.is_null() && NO_SOLUTION.contains(&k.as_str()) {
                    continue;
                }
                json_faults(x, &format!("{path}.{k}"), k, out);
            }
        }
        _ => {}
    }
}

/// Does the text hold NaN or inf as a word (a number that is not one)?
fn bad_words(text: &str) -> bool {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .any(|w| matches!(w, "NaN" | "nan" | "inf" | "Inf" | "infinity" | "Infinity"))
}

/// The first offending line of a text report, if any.
fn text_fault(text: &str) -> Option<String> {
    text.lines()
        .find(|l| bad_words(l))
        .map(|l| format!("table line {l:?}"))
}

fn json_fault(v: &Json) -> Option<String> {
    let mut out = vec![];
    json_faults(v, "$", "", &mut out);
    (!out.is_empty()).then(|| out.join("; "))
}

// ---------------------------------------------------------------------------------------------
// The oracle: f64 against exact.

/// How many scenes the oracle compared (over every run of this process).
static COMPARED: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// The most contacts the oracle solves exactly: a regular G has at most six.
const ORACLE_CONTACTS: usize = 6;
/// The most bits (numerator and denominator) of any number of a scene the oracle solves
/// exactly: 1e±308 has about 1024, `"2^-99999"` and `"9^9^9"` far more.
const ORACLE_BITS: u64 = 2048;

/// Where exact is cheap: a rational scene of at most [`ORACLE_CONTACTS`] contacts, every
/// number within [`ORACLE_BITS`], under the simultaneous law without friction (what the
/// accuracy contract covers; its exact reference is then a few rational solves of order ≤ 6).
fn cheap(scene: &Scene) -> bool {
    scene.is_rational()
        && !scene.frictional()
        && scene.law == Law::Simultaneous
        && (1..=ORACLE_CONTACTS).contains(&scene.contacts.len())
        && scene.numbers().all(|(_, n)| {
            n.exact
                .as_ref()
                .is_ok_and(|q| q.numer().bits() + q.denom().bits() <= ORACLE_BITS)
        })
}

/// f64 against exact on `scene` where it is [`cheap`]: `Ok(true)` when compared, `Ok(false)`
/// when not cheap or the exact solve has nothing to compare; `Err` names a contradiction.
///
/// The f64 side is `run::<f64>`, the report `solve` prints. The exact side and the bounds
/// ([`Bounds::of`], unit-free) come from the exact solve of the scene in the units float
/// solves use (`scene::scale`, as `tools::accuracy` measures the contract): in the scene's own
/// units G or its inverse may leave f64, and the conditioning read from them in f64 with it
/// (the fuzz met cond₂ G = −∞). The f64 report is put into those units by its outputs'
/// dimensions, a power of two each, exactly. Each error is also allowed ε times its
/// reference, the rounding of the exact values read in f64. A bound beyond f64 (V² overflows:
/// a body spinning at 10³⁰⁸ rad/s) makes no claim, and that output is not compared. A refusal
/// (status 2 or 3) is not compared either — except a float "singular to working precision",
/// which the contract allows only where cond₂ G · ε ≥ 10⁻³ — and an answer where G is exactly
/// singular is a contradiction.
fn oracle(scene: &Scene) -> Result<bool, String> {
    if !cheap(scene) {
        return Ok(false);
    }
    let (reference, units) = match scale(scene) {
        Some((s, u)) => (s, Some(u)),
        None => (scene.clone(), None),
    };
    let Ok(problem) = prepare::<Exact>(&reference) else {
        return Ok(false);
    };
    let Ok(mut impact) = Impact::assemble(&problem) else {
        return Ok(false);
    };
    let float = run::<f64>(scene, None);
    let Some(cond) = Conditioning::of(&mut impact) else {
        return match float {
            Ok(_) => Err("f64 answered a scene whose G is exactly singular".into()),
            Err(_) => Ok(true),
        };
    };
    if !(cond.cond >= 1.0) {
        // Not read in f64 even in the scaled units (NaN): nothing to compare with.
        return Ok(false);
    }
    match float {
        Ok(s) => disagreement(&s.report, units.as_ref(), &mut impact, &cond).map_or(Ok(true), Err),
        Err(RunError::Solve(SolveError::Singular { rounded: true, .. }))
            if cond.cond * f64::EPSILON < 1e-3 =>
        {
            Err(format!(
                "f64 declared G singular at cond₂ G = {:.3e}",
                cond.cond
            ))
        }
        Err(_) => Ok(true),
    }
}

/// x·2^k, exactly unless it leaves f64.
fn times_two_to(x: f64, k: i64) -> f64 {
    let mut y = x;
    let mut k = k;
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        y *= 2f64.powi(step as i32);
        k -= step;
    }
    y
}

/// The first output of the f64 report `float` (in the scene's units) beyond the contract's
/// bound from the exact solve of the same scene in the units `units` (none: as written),
/// assembled as `impact` and conditioned as `cond` ([`oracle`]); `None` when every output
/// keeps it.
fn disagreement(
    float: &Report,
    units: Option<&Units>,
    impact: &mut Impact<Exact>,
    cond: &Conditioning,
) -> Option<String> {
    let eps = f64::EPSILON;
    // The powers of two of mass, length and time, and so of each output's dimension.
    let (a, b, c) = units.map_or((0, 0, 0), |u| (u.mass, u.length, u.time));
    let (impulse, omega, speed, energy) = (a + b - c, -c, b - c, a + 2 * b - 2 * c);
    let scaled = |x: f64, k: i64| times_two_to(x, -k);
    let body = impact.problem().body().clone();
    let norms: Vec<Exact> = impact.frames().iter().map(|f| f.norm2[0].clone()).collect();
    let to_exact = |x: f64| x.exact_value().map(Exact::from);
    for f in &float.models {
        let mut out = Outcome::default();
        if let Err(e) = impact.solve(f.model, &mut out) {
            return Some(format!("f64 answered, exact did not: {e}"));
        }
        let bounds = Bounds::of(impact, cond, f.model, &out, eps);
        let fail = |what: &str, error: f64, bound: f64, reference: f64| {
            (bound.is_finite() && !(error <= bound + eps * reference)).then(|| {
                format!(
                    "{:?} {what}: f64 is {error:.3e} from exact, beyond the contract's {bound:.3e} \
                     (cond₂ G = {:.3e}, in units 2^({a}, {b}, {c}) of kg, m, s)",
                    f.model, cond.cond
                )
            })
        };
        let (mut d2, mut p2) = (0.0, 0.0);
        for ((p, hat), norm) in f.impulses.iter().zip(&out.impulses_hat).zip(&norms) {
            let q = Surd::times_norm(hat, norm).to_f64();
            d2 += (scaled(p.f64, impulse) - q).powi(2);
            p2 += q * q;
        }
        let mut faults = vec![fail(
            "impulses ‖δP‖₂",
            d2.sqrt(),
            bounds.impulses,
            p2.sqrt(),
        )];
        let parts: Option<Vec<Exact>> = f
            .angular_velocity
            .iter()
            .map(|v| scaled(v.f64, omega))
            .chain(f.velocity.iter().map(|v| scaled(v.f64, speed)))
            .map(to_exact)
            .collect();
        if let Some(parts) = parts {
            let top = Vec3::new(parts[0].clone(), parts[1].clone(), parts[2].clone());
            let bottom = Vec3::new(parts[3].clone(), parts[4].clone(), parts[5].clone());
            let mut delta = Screw::new(top, bottom);
            delta.add_scaled(&-Exact::from(1), &out.velocity);
            let size = energy_norm(&body, &out.velocity);
            faults.push(fail(
                "twist ‖δv‖_M",
                energy_norm(&body, &delta),
                bounds.twist,
                size,
            ));
        }
        for (what, value, reference, bound) in [
            (
                "E_p",
                &f.lost_velocity_energy,
                &out.lost_velocity_energy,
                bounds.lost_velocity_energy,
            ),
            (
                "ΔE_c",
                &f.kinetic_energy_loss,
                &out.kinetic_energy_loss,
                bounds.kinetic_energy_loss,
            ),
        ] {
            if let Some(v) = to_exact(scaled(value.f64, energy)) {
                let error = (v - reference).abs().to_f64();
                faults.push(fail(what, error, bound, reference.to_f64().abs()));
            }
        }
        if let Some(f) = faults.into_iter().flatten().next() {
            return Some(f);
        }
    }
    None
}

// ---------------------------------------------------------------------------------------------
// In-process runs, each on its own thread under the time limit.

/// Run `f` on a thread; `Err` names a panic or a timeout.
fn bounded<T: Send + 'static, F: FnOnce() -> T + Send + 'static>(f: F) -> Result<T, String> {
    let (tx, rx) = mpsc::channel();
    let handle = std::thread::Builder::new()
        .stack_size(16 << 20)
        .spawn(move || {
            let r = f();
            let _ = tx.send(r);
        })
        .map_err(|e| e.to_string())?;
    match rx.recv_timeout(TIMEOUT) {
        Ok(r) => {
            let _ = handle.join();
            Ok(r)
        }
        Err(mpsc::RecvTimeoutError::Timeout) => Err(format!("no answer in {TIMEOUT:?}")),
        Err(mpsc::RecvTimeoutError::Disconnected) => Err("panicked".into()),
    }
}

fn check_solved(r: Result<inertance::scene::pipeline::Solved, RunError>) -> Result<(), String> {
    if let Ok(s) = r {
        if let Some(f) = json_fault(&s.report.to_json()) {
            return Err(format!("solve json: {f}"));
        }
        if let Some(f) = text_fault(&s.report.to_table()) {
            return Err(format!("solve table: {f}"));
        }
    }
    Ok(())
}

fn check_analyzed(
    r: Result<inertance::tools::analyze::AnalysisReport, RunError>,
) -> Result<(), String> {
    if let Ok(a) = r {
        if let Some(f) = json_fault(&a.to_json()) {
            return Err(format!("analyze json: {f}"));
        }
        if let Some(f) = text_fault(&a.to_text()) {
            return Err(format!("analyze text: {f}"));
        }
    }
    Ok(())
}

/// One in-process command, run under the time limit.
type Job = Box<dyn FnOnce() -> Result<(), String> + Send>;

/// What the CLI's `solve`, `analyze` and `derive` do, through the library.
fn in_process(text: &str, symbols: &[String], large: bool) -> Vec<String> {
    let mut faults = vec![];
    let scene = match bounded({
        let text = text.to_string();
        move || Scene::parse(&text, "fuzz.toml").ok()
    }) {
        Ok(s) => s,
        Err(e) => return vec![format!("parse: {e}")],
    };
    if let Some(scene) = scene {
        let exact_too = !large || scene.contacts.len() <= 24;
        let mut jobs: Vec<(&str, Job)> = vec![];
        let s = scene.clone();
        jobs.push((
            "solve f64",
            Box::new(move || check_solved(run::<f64>(&s, None))),
        ));
        let s = scene.clone();
        if !skip_analyze(scene.contacts.len()) {
            jobs.push((
                "analyze f64",
                Box::new(move || check_analyzed(analyze_scene::<f64>(&s, None))),
            ));
        }
        let s = scene.clone();
        jobs.push((
            "oracle f64 = exact",
            Box::new(move || {
                let compared = oracle(&s)?;
                if compared {
                    COMPARED.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                }
                Ok(())
            }),
        ));
        if exact_too {
            let s = scene.clone();
            jobs.push((
                "solve --exact",
                Box::new(move || {
                    check_solved(if s.is_rational() {
                        run::<Exact>(&s, None)
                    } else {
                        run::<RatFun>(&s, None)
                    })
                }),
            ));
            let s = scene.clone();
            jobs.push((
                "analyze --exact",
                Box::new(move || {
                    check_analyzed(if s.is_rational() {
                        analyze_scene::<Exact>(&s, None)
                    } else {
                        analyze_scene::<RatFun>(&s, None)
                    })
                }),
            ));
        }
        for (name, job) in jobs {
            if let Err(e) = bounded(job).and_then(|r| r) {
                faults.push(format!("{name}: {e}"));
            }
        }
    }
    if !symbols.is_empty() && text.len() < 4000 {
        let text = text.to_string();
        let symbols = symbols.to_vec();
        let r = bounded(move || {
            if symbols
                .iter()
                .any(|s| !inertance::number::expr::is_symbol_name(s))
            {
                return Ok(()); // the CLI refuses these before reading the scene
            }
            let Ok(scene) = Scene::parse_with(&text, "fuzz.toml", &symbols) else {
                return Ok(());
            };
            if let Ok(d) = inertance::tools::derive::derive(&scene, &symbols, None) {
                if let Some(f) = json_fault(&d.to_json()) {
                    return Err(format!("json: {f}"));
                }
                let _ = d.to_text(true);
                if let Some(f) = text_fault(&d.to_text(false)) {
                    return Err(format!("text: {f}"));
                }
            }
            Ok(())
        });
        if let Err(e) = r.and_then(|r| r) {
            faults.push(format!("derive: {e}"));
        }
    }
    faults
}

// ---------------------------------------------------------------------------------------------
// The binary.

struct Ran {
    status: Option<i32>,
    stdout: String,
    stderr: String,
    timed_out: bool,
}

fn exe(args: &[&str], dir: &Path) -> Ran {
    let mut child = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    // Drain the pipes on threads so a large report cannot block the child.
    let mut so = child.stdout.take().unwrap();
    let mut se = child.stderr.take().unwrap();
    let to = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = std::io::Read::read_to_end(&mut so, &mut s);
        s
    });
    let te = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = std::io::Read::read_to_end(&mut se, &mut s);
        s
    });
    let start = Instant::now();
    let mut timed_out = false;
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break s;
        }
        if start.elapsed() > TIMEOUT {
            let _ = child.kill();
            timed_out = true;
            break child.wait().expect("wait");
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    Ran {
        status: status.code(),
        stdout: String::from_utf8_lossy(&to.join().unwrap()).into_owned(),
        stderr: String::from_utf8_lossy(&te.join().unwrap()).into_owned(),
        timed_out,
    }
}

/// The contract on one process run; `json` says stdout is JSON.
fn contract(args: &[&str], r: &Ran, json: bool) -> Option<String> {
    let what = args.join(" ");
    if r.timed_out {
        return Some(format!("`{what}`: killed after {TIMEOUT:?}"));
    }
    let Some(code) = r.status else {
        return Some(format!("`{what}`: ended by a signal; stderr: {}", r.stderr));
    };
    if r.stderr.contains("panicked") {
        return Some(format!("`{what}`: panicked: {}", r.stderr));
    }
    if !matches!(code, 0 | 2 | 3 | 4) {
        return Some(format!("`{what}`: status {code}; stderr: {}", r.stderr));
    }
    if code == 4 && r.stderr.trim().is_empty() {
        return Some(format!(
            "`{what}`: status 4 without naming what has no answer"
        ));
    }
    if matches!(code, 2 | 3) {
        if !r.stdout.is_empty() {
            return Some(format!(
                "`{what}`: status {code} with stdout {:?}",
                r.stdout
            ));
        }
        if r.stderr.trim().is_empty() {
            return Some(format!("`{what}`: status {code} and no message"));
        }
        return None;
    }
    if json {
        match serde_json::from_str::<Json>(&r.stdout) {
            Ok(v) => json_fault(&v).map(|f| format!("`{what}`: {f}")),
            Err(e) => Some(format!("`{what}`: stdout is not JSON: {e}")),
        }
    } else {
        text_fault(&r.stdout).map(|f| format!("`{what}`: {f}"))
    }
}

/// Every command on the scene file in `dir`.
fn through_binary(
    dir: &Path,
    symbols: &[String],
    vary: &str,
    large: bool,
    contacts: usize,
) -> Vec<String> {
    let mut faults = vec![];
    let sym = symbols.join(",");
    let mut runs: Vec<(Vec<&str>, bool)> = vec![
        (vec!["solve", "scene.toml", "--json"], true),
        (vec!["solve", "scene.toml"], false),
        (
            vec!["solve", "scene.toml", "--law", "unilateral", "--json"],
            true,
        ),
    ];
    if !skip_analyze(contacts) {
        runs.push((vec!["analyze", "scene.toml", "--json"], true));
    }
    if !large {
        runs.push((vec!["solve", "scene.toml", "--exact", "--json"], true));
        runs.push((vec!["solve", "scene.toml", "--exact"], false));
        runs.push((vec!["analyze", "scene.toml", "--exact"], false));
    }
    if !symbols.is_empty() && !large {
        runs.push((
            vec!["derive", "scene.toml", "--symbols", &sym, "--json"],
            true,
        ));
        runs.push((vec!["derive", "scene.toml", "--symbols", &sym], false));
    }
    for (args, json) in &runs {
        let r = exe(args, dir);
        faults.extend(contract(args, &r, *json));
    }
    let sweeps: &[&[&str]] = if large {
        &[&["--threads", "2"]]
    } else {
        &[&["--threads", "2"], &["--exact", "--threads", "1"]]
    };
    for extra in sweeps {
        let out = dir.join("out.csv");
        let _ = std::fs::remove_file(&out);
        let mut args = vec!["sweep", "scene.toml", "--vary", vary, "--out", "out.csv"];
        args.extend_from_slice(extra);
        let r = exe(&args, dir);
        if let Some(f) = contract(&args, &r, false) {
            faults.push(f);
            continue;
        }
        let leftovers: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n != "scene.toml" && n != "out.csv")
            .collect();
        if !leftovers.is_empty() {
            faults.push(format!("`{}`: left {leftovers:?}", args.join(" ")));
        }
        match (r.status, out.exists()) {
            (Some(0), false) => faults.push(format!("`{}`: status 0, no CSV", args.join(" "))),
            (Some(0), true) => {
                let csv = std::fs::read_to_string(&out).unwrap_or_default();
                if let Some(l) = csv.lines().find(|l| bad_words(l)) {
                    faults.push(format!("`{}`: CSV row {l:?}", args.join(" ")));
                }
            }
            (_, true) => faults.push(format!("`{}`: failed but left out.csv", args.join(" "))),
            _ => {}
        }
    }
    faults
}

/// A scratch directory, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(tag: &str) -> Scratch {
        let d = std::env::temp_dir().join(format!("inertance-fuzz-{}-{tag}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        Scratch(d)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

// ---------------------------------------------------------------------------------------------
// Runs.

/// `analyze` on more than this many contacts is left to release builds (the long run): in a
/// debug build its f64 Lemke pivots (the unilateral part of the report) take up to 30 s at
/// 200 contacts (0.3 s in release). Beyond `tools::analyze::MAX_EXACT_CONTACTS` (exact) and
/// `MAX_FLOAT_CONTACTS` it refuses at once (tests/regression_analyze_many_contacts.rs).
/// `INERTANCE_FUZZ_ALL` runs it in debug too.
const ANALYZE_MAX_CONTACTS: usize = 64;

fn skip_analyze(contacts: usize) -> bool {
    cfg!(debug_assertions)
        && contacts > ANALYZE_MAX_CONTACTS
        && std::env::var_os("INERTANCE_FUZZ_ALL").is_none()
}

/// Run cases `range` of `seed`; the binary on every `binary_every`-th (0: never). Returns the
/// findings as (case, scene text, faults).
fn fuzz(
    seed: u64,
    range: std::ops::Range<u64>,
    binary_every: u64,
    in_proc: bool,
) -> Vec<(u64, String, Vec<String>)> {
    let scratch = Scratch::new(&format!("{seed:x}-{}", range.start));
    let mut findings = vec![];
    for i in range {
        let c = scenes::case(seed, i);
        let text = c.render();
        let large = c.contacts > 24;
        let mut faults = if in_proc {
            in_process(&text, &c.symbols, large)
        } else {
            vec![]
        };
        if binary_every > 0 && i % binary_every == 0 {
            let dir = scratch.0.join(i.to_string());
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(dir.join("scene.toml"), &text).unwrap();
            faults.extend(through_binary(&dir, &c.symbols, &c.vary, large, c.contacts));
            let _ = std::fs::remove_dir_all(&dir);
        }
        if !faults.is_empty() {
            let header = format!(
                "# fuzz finding: seed {seed:#x}, case {i}\n# mutations: {}\n# symbols: {}\n# vary: {}\n{}",
                c.mutations.join(" | "),
                c.symbols.join(","),
                c.vary,
                faults
                    .iter()
                    .map(|f| format!("# {}\n", f.replace('\n', " ")))
                    .collect::<String>()
            );
            findings.push((i, header + &text, faults));
        }
    }
    findings
}

fn report(findings: &[(u64, String, Vec<String>)], dir: Option<&Path>) {
    if findings.is_empty() {
        return;
    }
    let from_env = std::env::var_os("INERTANCE_FUZZ_FINDINGS").map(PathBuf::from);
    let dir = dir.or(from_env.as_deref());
    let mut msg = format!("{} fuzz finding(s):\n", findings.len());
    for (n, (i, text, faults)) in findings.iter().enumerate() {
        if let Some(d) = dir {
            let _ = std::fs::create_dir_all(d);
            let _ = std::fs::write(d.join(format!("case-{i}.toml")), text);
        }
        if n < 10 {
            msg += &format!("case {i}: {}\n", faults.join("\n    "));
            if dir.is_none() {
                msg += &format!("--- scene ---\n{text}\n");
            }
        }
    }
    if let Some(d) = dir {
        msg += &format!("scenes written to {}\n", d.display());
    }
    panic!("{msg}");
}

#[test]
fn short_run_in_process() {
    // Two halves on two threads (the suite runs on 2 cores).
    let s = seed();
    let a = std::thread::spawn(move || fuzz(s, 0..SHORT_CASES / 2, 0, true));
    let mut f = fuzz(s, SHORT_CASES / 2..SHORT_CASES, 0, true);
    f.extend(a.join().unwrap());
    report(&f, None);
    // The generator mutates most scenes: about a fifth are cheap and keep a regular G.
    let compared = COMPARED.load(std::sync::atomic::Ordering::Relaxed);
    assert!(
        compared >= SHORT_CASES as usize / 10,
        "the oracle compared only {compared} of {SHORT_CASES} cases"
    );
}

#[test]
fn short_run_through_the_binary() {
    // Cases of the same generator not run in-process above.
    let s = seed();
    let f = fuzz(s, 1_000_000..1_000_000 + SHORT_BINARY_CASES, 1, false);
    report(&f, None);
}

/// The long run: `INERTANCE_FUZZ_CASES=100000 cargo test --release --test fuzz -- --ignored`.
#[test]
#[ignore = "long run: INERTANCE_FUZZ_CASES=N cargo test --release --test fuzz -- --ignored"]
fn fuzz_long() {
    let n: u64 = std::env::var("INERTANCE_FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100_000);
    let s = seed();
    let dir = std::env::var_os("INERTANCE_FUZZ_FINDINGS")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/fuzz-findings"));
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()) as u64;
    let handles: Vec<_> = (0..threads)
        .map(|t| {
            std::thread::spawn(move || {
                let lo = n * t / threads;
                let hi = n * (t + 1) / threads;
                fuzz(s, lo..hi, BINARY_EVERY, true)
            })
        })
        .collect();
    let mut f = vec![];
    for h in handles {
        f.extend(h.join().unwrap());
    }
    eprintln!("fuzz_long: {n} cases, seed {s:#x}, {} finding(s)", f.len());
    report(&f, Some(&dir));
}

/// Read `# key: value` from the first comment lines of a corpus file.
fn directive(text: &str, key: &str) -> Option<String> {
    text.lines()
        .take_while(|l| l.starts_with('#'))
        .find_map(|l| {
            l.strip_prefix(&format!("# {key}:"))
                .map(|v| v.trim().to_string())
        })
        .filter(|v| !v.is_empty())
}

#[test]
fn corpus_files_keep_the_contract() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_corpus");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/fuzz_corpus")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    let scratch = Scratch::new("corpus");
    let mut failures = vec![];
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        let symbols: Vec<String> = directive(&text, "symbols")
            .map(|s| s.split(',').map(str::to_string).collect())
            .unwrap_or_default();
        let vary = directive(&text, "vary").unwrap_or_else(|| "body.mass=1:2:3".into());
        let mut faults = in_process(&text, &symbols, false);
        let d = scratch.0.join(f.file_stem().unwrap());
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("scene.toml"), &text).unwrap();
        faults.extend(through_binary(&d, &symbols, &vary, false, 0));
        if !faults.is_empty() {
            failures.push(format!("{}:\n    {}", f.display(), faults.join("\n    ")));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `tests/fuzz_corpus/large/`: findings too large for the every-command pass above (hundreds
/// to a thousand contacts), each through the binary with `solve` (f64, `--exact`, the
/// unilateral law) and `analyze` (left to release builds beyond 64 contacts, as in the random
/// run: its f64 Lemke path takes 30 s at 200 contacts in a debug build, 0.3 s in release),
/// under the same contract.
#[test]
fn large_corpus_files_keep_the_contract() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_corpus/large");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/fuzz_corpus/large")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    let scratch = Scratch::new("large");
    let runs: [(&[&str], bool); 5] = [
        (&["solve", "scene.toml"], false),
        (&["solve", "scene.toml", "--json"], true),
        (&["solve", "scene.toml", "--exact", "--json"], true),
        (
            &["solve", "scene.toml", "--law", "unilateral", "--json"],
            true,
        ),
        (&["analyze", "scene.toml", "--json"], true),
    ];
    let mut failures = vec![];
    for f in &files {
        let d = scratch.0.join(f.file_stem().unwrap());
        std::fs::create_dir_all(&d).unwrap();
        std::fs::copy(f, d.join("scene.toml")).unwrap();
        let contacts = Scene::load(f).map_or(0, |s| s.contacts.len());
        for (args, json) in runs {
            if args[0] == "analyze" && skip_analyze(contacts) {
                continue;
            }
            if let Some(fault) = contract(args, &exe(args, &d), json) {
                failures.push(format!("{}: {fault}", f.display()));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_generator_is_deterministic_and_mostly_parses() {
    let a: Vec<String> = (0..50).map(|i| scenes::case(SEED, i).render()).collect();
    let b: Vec<String> = (0..50).map(|i| scenes::case(SEED, i).render()).collect();
    assert_eq!(a, b);
    // The unmutated scenes are valid: the generator exercises the solver, not only the reader.
    let mut valid = 0;
    for i in 0..200 {
        if Scene::parse(&scenes::case(SEED, i).render(), "x").is_ok() {
            valid += 1;
        }
    }
    assert!(valid >= 40, "only {valid} of 200 generated scenes parse");
}

/// The oracle sees a wrong number: the planar bar's f64 report agrees with exact, and the
/// same report with E_p or ω_z moved by 10⁻⁹ of itself (10⁴ times the contract's bound) does
/// not.
#[test]
fn the_oracle_catches_a_wrong_number() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_corpus/valid-planar-bar.toml");
    let scene = Scene::load(&path).unwrap();
    assert!(cheap(&scene));
    assert_eq!(oracle(&scene), Ok(true));
    let (reference, units) = scale(&scene).expect("scaled: a length unit of 4 m");
    let mut impact = Impact::assemble(&prepare::<Exact>(&reference).unwrap()).unwrap();
    let cond = Conditioning::of(&mut impact).unwrap();
    let float = run::<f64>(&scene, None).unwrap().report;
    let check = |r: &Report, i: &mut Impact<Exact>| disagreement(r, Some(&units), i, &cond);
    assert_eq!(check(&float, &mut impact), None);
    let mut moved = float.clone();
    moved.models[0].lost_velocity_energy.f64 *= 1.0 + 1e-9;
    let found = check(&moved, &mut impact).unwrap_or_default();
    assert!(found.contains("E_p"), "{found}");
    let mut moved = float;
    moved.models[1].angular_velocity[2].f64 *= 1.0 + 1e-9;
    let found = check(&moved, &mut impact).unwrap_or_default();
    assert!(found.contains("twist"), "{found}");
}

#[test]
fn the_checks_catch_what_they_should() {
    assert!(json_fault(&serde_json::json!({"det": null})).is_some());
    assert!(json_fault(&serde_json::json!({"det": "NaN"})).is_some());
    assert!(json_fault(&serde_json::json!({"x": ["1/2", "-inf"]})).is_some());
    assert!(
        json_fault(&serde_json::json!({"angle_before_deg": null, "condition_number": "inf"}))
            .is_none()
    );
    assert!(text_fault("  E_p [J]   NaN").is_some());
    assert!(text_fault("cond₂(G) = ∞, information").is_none());
}
