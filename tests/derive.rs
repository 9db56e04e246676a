//! `inertance derive` and symbolic `check` cases, end to end: closed forms derived from scene
//! files whose values name symbols, proved equal to hand-derived forms, equal to the exact
//! solver at random rational points, singular families with their compatibility conditions,
//! and bad input named by file, key and value.

use std::collections::HashMap;
use std::path::PathBuf;
use std::process::{Command, Output};

use inertance::impact::restitution::Model;
use inertance::scalar::Exact;
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::symbolic::symbolic;
use inertance::scene::Scene;
use inertance::scene::pipeline::run;
use inertance::tools::derive::derive;
use num_rational::BigRational;
use proptest::prelude::*;

/// The planar two-contact bar of §5 (eq. 16–20), every input a symbol.
const PLANAR: &str = r#"
name = "planar bar"
[body]
mass = "m"
inertia = ["Jx", "Jy", "Jz"]
velocity = ["vx", "vy", 0]
angular_velocity = [0, 0, "w"]
[[contact]]
point = [0, "y1", 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = "k1"
[[contact]]
point = [0, "y2", 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = "k2"
"#;

const PLANAR_SYMBOLS: [&str; 11] = [
    "m", "Jx", "Jy", "Jz", "vx", "vy", "w", "y1", "y2", "k1", "k2",
];

/// Example 5: a bar turning about OZ at O = (0, −l, 0), with the twist the joint allows.
const EXAMPLE_5: &str = r#"
name = "Example 5"
[body]
mass = "m"
inertia = ["Jx", "Jy", "Jz"]
velocity = ["-l*omega", 0, 0]
angular_velocity = [0, 0, "omega"]
[[contact]]
point = [0, "-a", 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = "k1"
[[contact]]
point = [0, "b", 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = "k2"
[[constraints.joint]]
kind = "revolute"
point = [0, "-l", 0]
axis = [0, 0, 1]
"#;

const EXAMPLE_5_SYMBOLS: [&str; 10] = ["m", "Jx", "Jy", "Jz", "l", "a", "b", "k1", "k2", "omega"];

fn names(s: &[&str]) -> Vec<String> {
    s.iter().map(|x| x.to_string()).collect()
}

/// The value of an expression in `symbols`.
fn expr(text: &str, symbols: &[String]) -> RatFun {
    symbolic(text, symbols).unwrap_or_else(|e| panic!("{text}: {e}"))
}

/// A derived quantity, read back from its reported text.
fn derived(report: &inertance::tools::derive::Readout, q: &str, symbols: &[String]) -> RatFun {
    let report = report.body().expect("one body's derivation");
    let v = inertance::tools::check::lookup(report, q).unwrap();
    assert_eq!(v.len(), 1, "{q}");
    expr(v[0].exact.as_deref().expect("an exact text"), symbols)
}

#[test]
fn planar_closed_forms_are_derived() {
    let symbols = names(&PLANAR_SYMBOLS);
    let scene = Scene::parse_with(PLANAR, "planar.toml", &symbols).unwrap();
    let d = derive(&scene, &symbols, None).unwrap();
    let r = &d.report;
    let e = |t: &str| expr(t, &symbols);
    // eq. 17: g_ij = 1/m + y_i y_j / J_z; Δ = (y1 − y2)²/(m J_z).
    assert_eq!(derived(r, "g11xx", &symbols), e("1/m + y1^2/Jz"));
    assert_eq!(derived(r, "g12xx", &symbols), e("1/m + y1*y2/Jz"));
    assert_eq!(derived(r, "det", &symbols), e("(y1 - y2)^2/(m*Jz)"));
    assert_eq!(d.det, e("(y1 - y2)^2/(m*Jz)"));
    // Poisson (eq. 21–23): P_i = (1 + k_i) P_i^c with P^c = G⁻¹ v⁰ (Cramer's rule).
    let g11 = e("1/m + y1^2/Jz");
    let g12 = e("1/m + y1*y2/Jz");
    let g22 = e("1/m + y2^2/Jz");
    let (v1, v2) = (e("vx - w*y1"), e("vx - w*y2"));
    let det = g11.clone() * &g22 - g12.clone() * &g12;
    let p1c = (g22.clone() * &v1 - g12.clone() * &v2) / &det;
    let p2c = (g11.clone() * &v2 - g12.clone() * &v1) / &det;
    assert_eq!(derived(r, "poisson.P1c", &symbols), p1c);
    assert_eq!(derived(r, "poisson.P1", &symbols), (e("1 + k1")) * &p1c);
    assert_eq!(derived(r, "poisson.P2", &symbols), (e("1 + k2")) * &p2c);
    // The readable form the derivation prints (factored, the common factor cancelled).
    assert_eq!(
        derived(r, "poisson.P1", &symbols),
        e("-(1 + k1)*(m*vx*y2 + Jz*w)/(y1 - y2)")
    );
    // Newton: the normal velocities after impact are −k_i v_ix⁰ (eq. 14).
    assert_eq!(derived(r, "newton.v1x", &symbols), e("-k1*(vx - w*y1)"));
    assert_eq!(derived(r, "newton.v2x", &symbols), e("-k2*(vx - w*y2)"));
    // The energy identity (eq. 34) holds identically for both models.
    assert_eq!(
        d.energy_identity,
        vec![(Model::Newton, true), (Model::Poisson, true)]
    );
    // The conditions include Δ ≠ 0 (through the second pivot) and nothing about vy: the
    // formulas need no tangential speed.
    let conditions: Vec<String> = d.conditions.iter().map(|c| c.to_string()).collect();
    assert!(
        conditions
            .iter()
            .any(|c| c.contains("y1^2 - 2*y1*y2 + y2^2") && c.ends_with("≠ 0")),
        "{conditions:?}"
    );
    assert!(
        !conditions.iter().any(|c| c.contains("vy")),
        "{conditions:?}"
    );
    // The degenerate locus is (y1 − y2)² = 0.
    assert_eq!(d.locus.as_ref().unwrap().to_text(), "(y1 - y2)^2");
    assert!(d.singular.is_none());
}

#[test]
fn a_singular_family_gets_its_compatibility_conditions() {
    let symbols = names(&EXAMPLE_5_SYMBOLS);
    let scene = Scene::parse_with(EXAMPLE_5, "ex5.toml", &symbols).unwrap();
    let d = derive(&scene, &symbols, None).unwrap();
    assert_eq!(d.det, RatFun::from_integer(0));
    let s = d.singular.as_ref().expect("Δ ≡ 0: a singular family");
    assert_eq!((s.rank, s.contacts), (1, 2));
    let e = |t: &str| expr(t, &symbols);
    for f in &s.models {
        match f.model {
            Model::Newton => {
                // Compatible iff ω (b + l)(k1 − k2) = 0: the same equation up to a constant.
                assert_eq!(f.conditions.len(), 1);
                let ratio = f.conditions[0].clone() / e("omega*(b + l)*(k1 - k2)");
                assert!(ratio.is_constant() && !num_traits::Zero::is_zero(&ratio));
                assert_eq!(f.factored[0].expand(), f.conditions[0].numer().clone());
                assert!(f.solution.is_none());
            }
            Model::Poisson => {
                // b = v⁰ is a multiple of G's column: compatible for every value.
                assert!(f.conditions.iter().all(num_traits::Zero::is_zero));
                let out = f.outcome.as_ref().unwrap();
                let twist: Vec<RatFun> = out.twist.clone();
                let expect = ["0", "0", "-k1*omega", "k1*l*omega", "0", "0"].map(e);
                assert_eq!(twist, expect.to_vec());
                // … but with P_i = (1 + k_i) P_i^c the twist moves along the family unless
                // k1 = k2: per unit parameter, δω_z = −(b + l)(k1 − k2)/(J_z + m l²).
                assert_eq!(f.twist_change.len(), 1);
                assert_eq!(f.twist_change[0][2], e("-(b + l)*(k1 - k2)/(Jz + m*l^2)"));
            }
        }
    }
}

/// A surface with a symbolic coefficient: the sphere x² + y² + z² = R² hit at (R, 0, 0) and
/// (0, R, 0); ∇f = (2R, 0, 0) has the exact norm 2R (assuming R > 0, listed).
#[test]
fn normals_from_a_symbolic_surface() {
    let text = r#"
name = "sphere, symbolic surface"
[body]
mass = "m"
inertia = ["2*m*R^2/5", "2*m*R^2/5", "2*m*R^2/5"]
velocity = ["v0", 0, 0]
angular_velocity = [0, 0, 0]
[surface]
f = "x^2 + y^2 + z^2 - R^2"
[[contact]]
point = ["R", 0, 0]
k = "k1"
[[contact]]
point = [0, "R", 0]
k = "k2"
[solve]
models = ["newton"]
"#;
    let symbols = names(&["m", "R", "v0", "k1", "k2"]);
    let scene = Scene::parse_with(text, "sphere.toml", &symbols).unwrap();
    let d = derive(&scene, &symbols, None).unwrap();
    let e = |t: &str| expr(t, &symbols);
    assert_eq!(
        derived(&d.report, "newton.P1", &symbols),
        e("m*(1 + k1)*v0")
    );
    assert_eq!(derived(&d.report, "newton.P2", &symbols), e("0"));
    assert_eq!(derived(&d.report, "g11xx", &symbols), e("1/m"));
    let conditions: Vec<String> = d.conditions.iter().map(|c| c.to_string()).collect();
    assert!(conditions.contains(&"R > 0".to_string()), "{conditions:?}");
    // A point off the surface is named, with f there as an expression.
    let off = text.replace("point = [\"R\", 0, 0]", "point = [\"2*R\", 0, 0]");
    let err = Scene::parse_with(&off, "sphere.toml", &symbols)
        .and_then(|s| s.problem::<RatFun>())
        .unwrap_err();
    assert!(
        err.to_string().contains("contact[0].point")
            && err.to_string().contains("f(point) = 3*R^2"),
        "{err}"
    );
}

/// Substitute rational values for the symbols of a scene template (whole-word names).
fn instantiate(template: &str, values: &HashMap<String, BigRational>) -> String {
    let mut out = String::new();
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        match values.get(word.as_str()) {
            Some(q) => out.push_str(&format!("({}/{})", q.numer(), q.denom())),
            None => out.push_str(word),
        }
        word.clear();
    };
    for ch in template.chars() {
        if ch.is_ascii_alphanumeric() || ch == '_' {
            word.push(ch);
        } else {
            flush(&mut word, &mut out);
            out.push(ch);
        }
    }
    flush(&mut word, &mut out);
    out
}

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(n.into(), d.into())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// The derived closed forms, printed, read back and evaluated at a random rational point,
    /// equal the exact rational solver on the same scene file with those numbers written in.
    #[test]
    fn derived_text_equals_the_exact_solver(
        m in 1i64..9, jx in 1i64..9, jy in 1i64..9, jz in 1i64..9,
        vx in 1i64..9, vy in -5i64..5, w in -5i64..5,
        y1 in -6i64..0, y2 in 1i64..7, k1 in 0i64..5, k2 in 0i64..5,
    ) {
        let symbols = names(&PLANAR_SYMBOLS);
        let scene = Scene::parse_with(PLANAR, "planar.toml", &symbols).unwrap();
        let d = derive(&scene, &symbols, None).unwrap();
        let values: HashMap<String, BigRational> = [
            ("m", q(m, 1)), ("Jx", q(jx, 1)), ("Jy", q(jy, 1)), ("Jz", q(jz, 2)),
            ("vx", q(vx, 1)), ("vy", q(vy, 3)), ("w", q(w, 2)),
            ("y1", q(y1, 2)), ("y2", q(y2, 1)), ("k1", q(k1, 4)), ("k2", q(k2, 4)),
        ].into_iter().map(|(k, v)| (k.to_string(), v)).collect();
        // k_i in the symbolic template are strings; in the numeric one, expressions.
        let numeric = Scene::parse(&instantiate(PLANAR, &values), "numeric.toml").unwrap();
        let exact = run::<Exact>(&numeric, None).unwrap().report;
        for q in ["det", "g12xx", "newton.P1", "newton.P2", "poisson.P1", "poisson.P2c",
                  "newton.omega[2]", "poisson.vC[0]", "newton.Ep", "poisson.dEc", "newton.v2x"] {
            let f = derived(&d.report, q, &symbols);
            let at = f.eval(&values).expect("rational at a rational point");
            let want = inertance::tools::check::lookup(&exact, q).unwrap()[0].exact.clone().unwrap();
            let want = inertance::number::parse_number(&want).unwrap().exact.unwrap();
            prop_assert_eq!(at, want, "{}", q);
        }
    }
}

// ---------------------------------------------------------------------------------------
// The command line.

struct Dir(PathBuf);

impl Dir {
    fn new(name: &str) -> Dir {
        let d =
            std::env::temp_dir().join(format!("inertance-derive-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        Dir(d)
    }
    fn file(&self, name: &str, text: &str) -> String {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn inertance(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(args)
        .output()
        .unwrap()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn derive_prints_text_latex_and_json() {
    let dir = Dir::new("formats");
    let path = dir.file("planar.toml", PLANAR);
    let symbols = PLANAR_SYMBOLS.join(",");
    let out = inertance(&["derive", &path, "--symbols", &symbols]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("det = (y1 - y2)^2/(Jz*m)"), "{text}");
    assert!(
        text.contains("poisson.P1 = -(k1 + 1)*(m*vx*y2 + Jz*w)/(y1 - y2)"),
        "{text}"
    );
    assert!(text.contains("holds identically"), "{text}");
    assert!(
        text.contains("conditions (the formulas hold where all of these do):"),
        "{text}"
    );

    let out = inertance(&[
        "derive",
        &path,
        "--symbols",
        &symbols,
        "--latex",
        "--model",
        "newton",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let latex = stdout(&out);
    assert!(
        latex.contains("\\begin{aligned}") && latex.contains("\\end{aligned}"),
        "{latex}"
    );
    assert!(latex.contains("P_{1}^{N} &= "), "{latex}");
    assert!(
        latex.contains("\\Delta &= \\frac{\\left(y_{1} - y_{2}\\right)^{2}}{J_{z} m}"),
        "{latex}"
    );
    assert!(
        !latex.contains("poisson"),
        "only the model asked for: {latex}"
    );

    let out = inertance(&["derive", &path, "--symbols", &symbols, "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let j: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(j["det"], "(y1 - y2)^2/(Jz*m)");
    assert_eq!(j["det_locus"], "(y1 - y2)^2");
    assert_eq!(j["energy_identity"]["newton"], true);
    assert!(j["singular"].is_null());
    assert!(j["conditions"].as_array().is_some_and(|c| !c.is_empty()));
    // Every value in the JSON report is an expression that reads back.
    let p1 = j["models"]["newton"]["impulses"][0]
        .as_str()
        .unwrap()
        .to_string();
    symbolic(&p1, &names(&PLANAR_SYMBOLS)).unwrap();
}

#[test]
fn derive_reports_a_singular_family() {
    let dir = Dir::new("singular");
    let path = dir.file("ex5.toml", EXAMPLE_5);
    let out = inertance(&["derive", &path, "--symbols", &EXAMPLE_5_SYMBOLS.join(",")]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains("det = 0 identically: rank G = 1 of 2"),
        "{text}"
    );
    assert!(text.contains("omega*(b + l)*(k1 - k2) = 0"), "{text}");
    assert!(
        text.contains("poisson: compatible for every value of the symbols"),
        "{text}"
    );
    let out = inertance(&[
        "derive",
        &path,
        "--symbols",
        &EXAMPLE_5_SYMBOLS.join(","),
        "--json",
    ]);
    let j: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(j["singular"]["rank"], 1);
    assert_eq!(j["singular"]["models"][0]["compatible_identically"], false);
}

#[test]
fn bad_symbolic_input_is_named() {
    let dir = Dir::new("bad");
    let path = dir.file("planar.toml", PLANAR);
    // A symbol the command line does not declare: file, key and value named, status 2.
    let out = inertance(&["derive", &path, "--symbols", "m,Jx,Jy,Jz,vx,vy,w,y1,y2,k1"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(
        err.contains(&path) && err.contains("contact[1].k") && err.contains("'k2'"),
        "{err}"
    );
    assert!(err.contains("declared symbols"), "{err}");
    // Not a symbol name.
    let out = inertance(&["derive", &path, "--symbols", "m,sqrt"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("'sqrt' is not a symbol name"),
        "{}",
        stderr(&out)
    );
    // No exact form: cos 20° is not a radical.
    let bad = dir.file("cos20.toml", &PLANAR.replace("\"k1\"", "\"cos(20 deg)\""));
    let out = inertance(&["derive", &bad, "--symbols", &PLANAR_SYMBOLS.join(",")]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("only multiples of 15°"),
        "{}",
        stderr(&out)
    );
    // Values that are zero in disguise are refused like their numeric forms.
    let bad = dir.file(
        "m0.toml",
        &PLANAR.replace("mass = \"m\"", "mass = \"m - m\""),
    );
    let out = inertance(&["derive", &bad, "--symbols", &PLANAR_SYMBOLS.join(",")]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("body.mass") && stderr(&out).contains("positive"),
        "{}",
        stderr(&out)
    );
    let bad = dir.file(
        "n0.toml",
        &PLANAR.replacen("normal = [1, 0, 0]", "normal = [\"y1 - y1\", 0, 0]", 1),
    );
    let out = inertance(&["derive", &bad, "--symbols", &PLANAR_SYMBOLS.join(",")]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("contact[0].normal") && stderr(&out).contains("zero vector"),
        "{}",
        stderr(&out)
    );
    // A symbolic scene handed to `solve`: named, with a pointer to derive.
    let out = inertance(&["solve", &path]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    // The key named is the first symbolic value read (`contact[0].point[1]` = "y1" since the
    // reader takes the contacts before the body).
    assert!(
        err.contains("key `") && err.contains("inertance derive"),
        "{err}"
    );
    // --symbols is required.
    let out = inertance(&["derive", &path]);
    assert_eq!(out.status.code(), Some(2));
}

/// A derivation directory with one symbolic case: proved, refuted, and refuted with an
/// ERRATA row whose corrected form is itself checked.
#[test]
fn check_proves_and_refutes_closed_forms() {
    let dir = Dir::new("check");
    let scene = format!("```scene bar\n{}\n```\n", PLANAR.trim());
    let case = |lines: &str| {
        format!(
            "# t\n{scene}\n```expect sym bar\nsymbols = {}\n{lines}\n```\n",
            PLANAR_SYMBOLS.join(", ")
        )
    };
    let header = "| derivation | case | quantity | printed | computed | reason |\n|---|---|---|---|---|---|\n";
    dir.file("ERRATA.md", &format!("# errata\n\n{header}"));
    dir.file(
        "t.md",
        &case("g12xx = 1/m + y1*y2/Jz\ndet = (y1 - y2)^2/(m*Jz)"),
    );
    let out = inertance(&["check", dir.0.to_str().unwrap()]);
    let text = stdout(&out);
    assert!(out.status.success(), "{text}{}", stderr(&out));
    assert!(text.contains("proved  g12xx"), "{text}");
    assert!(text.contains("2 closed forms proved identities"), "{text}");

    // A wrong closed form (J_z missing, as in Remark 2) fails without an ERRATA row…
    dir.file("t.md", &case("g12xx = (Jz + m*y1*y2)/m"));
    let out = inertance(&["check", dir.0.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    // … is a known erratum with one whose corrected form is right …
    let row = "| t.md | sym | g12xx | (Jz + m*y1*y2)/m | (Jz + m*y1*y2)/(m*Jz) | J_z missing |\n";
    dir.file("ERRATA.md", &format!("# errata\n\n{header}{row}"));
    let out = inertance(&["check", dir.0.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stdout(&out));
    assert!(stdout(&out).contains("erratum g12xx"), "{}", stdout(&out));
    // … and fails again when the "corrected" form is wrong too.
    let row = "| t.md | sym | g12xx | (Jz + m*y1*y2)/m | (Jz - m*y1*y2)/(m*Jz) | J_z missing |\n";
    dir.file("ERRATA.md", &format!("# errata\n\n{header}{row}"));
    let out = inertance(&["check", dir.0.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    assert!(
        stdout(&out).contains("is not what is computed"),
        "{}",
        stdout(&out)
    );
}
