//! `inertance check`: the paper's worked examples, reproduced value by value.
//!
//! A derivation is a Markdown file in `derivations/`: prose (what the paper says, what was
//! deduced, why a value differs) around machine-read fenced blocks, in the spirit of PROJ's
//! `gie` files.
//!
//! ````text
//! ```scene bar                 ← a scene (the TOML schema of `inertance solve`)
//! name = "…"
//! …
//! ```
//!
//! ```expect case1 bar          ← a case: its name, then the scene it runs
//! set contact[0].k = 1         ← optional overrides of scene values (TOML values)
//! mode = exact                 ← optional: exact | f64 (default: exact, with radicals if needed)
//! symbols = m, k               ← optional: a symbolic case (closed forms, see below)
//! law = unilateral             ← optional: the impact law (default: the scene's)
//! newton.P1 = 58.07            ← a value as printed in the paper
//! newton.P2 = 89/450           ← an exact value (a fraction or an expression with radicals)
//! newton.twist = [0, 0, 3, -0.375, 0, 0]
//! ```
//! ````
//!
//! **Comparison at the printed precision.** A printed value with d decimals agrees when
//! |computed − printed| ≤ ½·10⁻ᵈ. A printed integer is a claim of an exact value: in exact
//! mode it must be equal; in f64 mode it must agree to 10⁻⁹ relative. A value written as an
//! exact expression that is not a decimal (`89/450`, `-25*sqrt(2)`) is a claim of that exact
//! value: equal as exact numbers when the computation is exact, 10⁻⁹ relative in f64. Angles
//! in degrees are compared modulo 360°, by their f64 value (atan2 of exact cosines and sines).
//!
//! **Exact by default.** A case runs in exact rationals when every input is rational, and
//! with exact radicals (the symbolic field with √p and cos/sin of multiples of 15°) when its
//! inputs are such expressions (`"2/sqrt(5)"`, `"cos(30 deg)"`): then the bound above is
//! decided exactly, by refining rational enclosures of the radicals until the sign of
//! ½·10⁻ᵈ ∓ (computed − printed) is certain. `mode = f64` forces floating point.
//!
//! **Closed forms as identities.** A case with a line `symbols = m, Jz, y1, …` is symbolic:
//! its scene's values may name those symbols (`mass = "m"`), the solver runs over rational
//! functions of them, and each expectation is a closed form in the symbols
//! (`newton.P1 = m*(1 + k)*omega0*R`). The verdict is *proved* when the derived value and the
//! closed form are equal as rational functions (modulo the radical and angle relations;
//! cross-multiplication, no sampling), otherwise the closed form is refuted and must be in
//! ERRATA.md, whose `computed` column then holds the corrected closed form (itself proved).
//!
//! **Known errata.** `derivations/ERRATA.md` holds a table
//! `| derivation | case | quantity | printed | computed | reason |`. A disagreement listed
//! there is reported as a known erratum — and the row's `computed` column is itself checked
//! (at its own printed precision), so ERRATA.md cannot go stale silently. A listed erratum
//! that in fact agrees, or that names no checked value, fails the check. Any other
//! disagreement fails.
//!
//! **The impact law.** A case runs under its scene's `[solve] law`, or under the law its
//! `law = …` line names. The unilateral law (`crate::impact::unilateral`) is solved on a
//! singular G too (its velocities after impact are unique); the simultaneous law on a singular
//! G solves no model and only the model-independent values can be checked. A symbolic case is
//! derived under the simultaneous law only (`inertance derive`), so it may not name the
//! unilateral one.
//!
//! Quantity names (i, j count contacts from 1 as the paper does; vector entries from 0):
//! `det`, `g{i}{j}xx|yx|zx`, `v{i}x0|y0|z0`, `cos_a{i}_0`, `sin_a{i}_0`, `a{i}_0` (before
//! impact), `Mred` (M_red row by row, constrained scenes) and, after a `newton.` or `poisson.` prefix, `P{i}`, `P{i}c`, `twist` ([ω; v_C]),
//! `omega`, `vC` (one entry: `newton.omega[0]`), `v{i}x|y|z`, `cos_a{i}`, `sin_a{i}`, `a{i}`, `Ep`, `dEc`, `q` (constraint impulses),
//! and the verdicts as 1 (yes) or 0 (no): `admissible` (the outcome is physical: no
//! tensile impulse, separating contact under a law, contact still approaching or energy gain —
//! under the unilateral law only an energy gain can make it 0), `active{i}` (unilateral law: contact i takes an impulse,
//! P_i > 0; 0: it separates), `unique` (the report's `impulses_unique`: 1 when G is regular on the
//! contacts that meet their law with equality, so the impulses are unique; 0 when they may form a
//! set).

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::impact::friction::Restitution;
use crate::impact::restitution::Model;
use crate::impact::unilateral::Law;
use crate::number::{parse_decimal, parse_number};
use crate::report::FrictionReport;
use crate::report::{Report, Value};
use crate::scalar::symbolic::RatFun;
use crate::scalar::{Exact, Scalar as _};
use crate::scene::pipeline::{RunError, Solved, run_with};
use crate::scene::{Scene, parse_document, set_value};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;

/// One case of a derivation: a scene, overrides, and the values the paper prints.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// The case's name, unique in its file.
    pub name: String,
    /// The scene block it runs.
    pub scene: String,
    /// `set PATH = VALUE` overrides, in order.
    pub sets: Vec<(String, String)>,
    /// `Some(true)` for exact, `Some(false)` for f64, `None` for automatic.
    pub exact: Option<bool>,
    /// `symbols = m, Jz, …`: the case is symbolic — the scene's values may name these
    /// symbols, and every expectation is a closed form, proved or refuted as an identity.
    pub symbols: Vec<String>,
    /// `law = simultaneous | unilateral`: the impact law, in place of the scene's.
    pub law: Option<Law>,
    /// (quantity, printed text, line number).
    pub expects: Vec<(String, String, usize)>,
    /// The line of its ```expect header (1-based), for messages about the case itself.
    pub line: usize,
}

/// A parsed derivation file.
#[derive(Clone, Debug, PartialEq)]
pub struct Derivation {
    /// The file.
    pub path: PathBuf,
    /// Scene blocks by name: (first line number, TOML text).
    pub scenes: BTreeMap<String, (usize, String)>,
    /// The cases, in file order.
    pub cases: Vec<Case>,
}

/// A malformed derivation or errata file (an authoring error, not a disagreement).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{file}:{line}: {message}")]
pub struct FormatError {
    /// The file.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl Derivation {
    /// Parse the derivation at `path`.
    pub fn load(path: &Path) -> Result<Derivation, FormatError> {
        let text = std::fs::read_to_string(path).map_err(|e| FormatError {
            file: path.display().to_string(),
            line: 0,
            message: format!("cannot read: {e}"),
        })?;
        Derivation::parse(&text, path)
    }

    /// Parse derivation text.
    pub fn parse(text: &str, path: &Path) -> Result<Derivation, FormatError> {
        let file = path.display().to_string();
        let err = |line: usize, message: String| FormatError {
            file: file.clone(),
            line,
            message,
        };
        let mut scenes = BTreeMap::new();
        let mut cases: Vec<Case> = Vec::new();
        let lines: Vec<&str> = text.lines().collect();
        let mut i = 0;
        while i < lines.len() {
            let Some(info) = lines[i].trim_start().strip_prefix("```") else {
                i += 1;
                continue;
            };
            let words: Vec<&str> = info.split_whitespace().collect();
            let start = i + 1;
            let mut end = start;
            while end < lines.len() && !lines[end].trim_start().starts_with("```") {
                end += 1;
            }
            if end == lines.len() {
                return Err(err(i + 1, "unclosed code block".into()));
            }
            let body = &lines[start..end];
            match words.as_slice() {
                ["scene", name] => {
                    if scenes.contains_key(*name) {
                        return Err(err(i + 1, format!("scene `{name}` defined twice")));
                    }
                    scenes.insert(name.to_string(), (start + 1, body.join("\n")));
                }
                ["expect", case, scene] => {
                    if cases.iter().any(|c| c.name == *case) {
                        return Err(err(i + 1, format!("case `{case}` defined twice")));
                    }
                    let mut c = Case {
                        name: case.to_string(),
                        scene: scene.to_string(),
                        sets: Vec::new(),
                        exact: None,
                        symbols: Vec::new(),
                        law: None,
                        expects: Vec::new(),
                        line: i + 1,
                    };
                    for (k, raw) in body.iter().enumerate() {
                        let line_no = start + k + 1;
                        let line = raw.split('#').next().unwrap_or("").trim();
                        if line.is_empty() {
                            continue;
                        }
                        let Some((lhs, rhs)) = line.split_once('=') else {
                            return Err(err(line_no, format!("expected `name = value`: `{line}`")));
                        };
                        let (lhs, rhs) = (lhs.trim(), rhs.trim());
                        if let Some(path) = lhs.strip_prefix("set ") {
                            c.sets.push((path.trim().to_string(), rhs.to_string()));
                        } else if lhs == "symbols" {
                            c.symbols = rhs
                                .split(',')
                                .map(|s| s.trim().to_string())
                                .filter(|s| !s.is_empty())
                                .collect();
                            if let Some(bad) = c
                                .symbols
                                .iter()
                                .find(|s| !crate::number::expr::is_symbol_name(s))
                            {
                                return Err(err(line_no, format!("`{bad}` is not a symbol name")));
                            }
                        } else if lhs == "law" {
                            c.law = Some(Law::from_name(rhs).ok_or_else(|| {
                                err(
                                    line_no,
                                    format!("law must be simultaneous or unilateral, not `{rhs}`"),
                                )
                            })?);
                        } else if lhs == "mode" {
                            c.exact = match rhs {
                                "exact" => Some(true),
                                "f64" => Some(false),
                                _ => {
                                    return Err(err(
                                        line_no,
                                        format!("mode must be exact or f64, not `{rhs}`"),
                                    ));
                                }
                            };
                        } else {
                            c.expects.push((lhs.to_string(), rhs.to_string(), line_no));
                        }
                    }
                    cases.push(c);
                }
                ["scene", ..] | ["expect", ..] => {
                    return Err(err(
                        i + 1,
                        format!("expected ```scene NAME or ```expect CASE SCENE, got ```{info}"),
                    ));
                }
                _ => {}
            }
            i = end + 1;
        }
        for c in &cases {
            if !scenes.contains_key(&c.scene) {
                return Err(err(
                    c.line,
                    format!(
                        "case `{}` runs scene `{}`, which is not defined",
                        c.name, c.scene
                    ),
                ));
            }
        }
        Ok(Derivation {
            path: path.to_path_buf(),
            scenes,
            cases,
        })
    }
}

/// One row of ERRATA.md.
#[derive(Clone, Debug, PartialEq)]
pub struct Erratum {
    /// Derivation file name (e.g. `example-3-planar-bar.md`).
    pub derivation: String,
    /// Case name.
    pub case: String,
    /// Quantity name.
    pub quantity: String,
    /// The value the paper prints.
    pub printed: String,
    /// The value computed (at the precision written).
    pub computed: String,
    /// Why they differ.
    pub reason: String,
}

/// Read the errata table of `ERRATA.md`.
pub fn load_errata(path: &Path) -> Result<Vec<Erratum>, FormatError> {
    let file = path.display().to_string();
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => {
            return Err(FormatError {
                file,
                line: 0,
                message: format!("cannot read: {e}"),
            });
        }
    };
    let mut out = Vec::new();
    let mut in_table = false;
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if !t.starts_with('|') {
            in_table = false;
            continue;
        }
        let cells: Vec<String> = t
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().trim_matches('`').to_string())
            .collect();
        if cells.first().map(String::as_str) == Some("derivation") {
            in_table = true;
            continue;
        }
        if !in_table
            || cells
                .iter()
                .all(|c| c.chars().all(|ch| ch == '-' || ch == ':'))
        {
            continue;
        }
        if cells.len() != 6 {
            return Err(FormatError {
                file: file.clone(),
                line: k + 1,
                message: "an errata row has six cells: derivation | case | quantity | printed | computed | reason".into(),
            });
        }
        let [derivation, case, quantity, printed, computed, reason]: [String; 6] =
            cells.try_into().map_err(|_| FormatError {
                file: file.clone(),
                line: k + 1,
                message: "bad row".into(),
            })?;
        out.push(Erratum {
            derivation,
            case,
            quantity,
            printed,
            computed,
            reason,
        });
    }
    Ok(out)
}

/// The verdict on one printed value.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Reproduced at the printed precision.
    Reproduced,
    /// Disagrees, and ERRATA.md says why.
    KnownErratum(String),
    /// Disagrees (or an errata row is wrong): the check fails.
    Fail(String),
}

/// One checked value.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    /// Case name.
    pub case: String,
    /// Quantity name.
    pub quantity: String,
    /// As printed in the paper.
    pub printed: String,
    /// Whether the value is a closed form checked as an identity (a symbolic case).
    pub identity: bool,
    /// As computed (exact text when exact).
    pub computed: String,
    /// The verdict.
    pub verdict: Verdict,
}

/// The outcome of checking one derivation file.
#[derive(Clone, Debug, PartialEq)]
pub struct FileResult {
    /// The file.
    pub path: PathBuf,
    /// Per case: (name, scalar used, whether the energy identity held for every model —
    /// `None` when G is singular and no model was solved).
    pub cases: Vec<(String, &'static str, Option<bool>)>,
    /// Every value checked.
    pub lines: Vec<Line>,
}

/// Check every derivation in `dir` against `dir/ERRATA.md`.
pub fn check_dir(dir: &Path) -> Result<Vec<FileResult>, FormatError> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| FormatError {
            file: dir.display().to_string(),
            line: 0,
            message: format!("cannot read the directory: {e}"),
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension().is_some_and(|x| x == "md")
                && p.file_name()
                    .is_some_and(|n| n != "ERRATA.md" && n != "README.md")
        })
        .collect();
    files.sort();
    let errata = load_errata(&dir.join("ERRATA.md"))?;
    let mut results = Vec::new();
    let mut used = BTreeSet::new();
    for f in &files {
        let d = Derivation::load(f)?;
        results.push(check_derivation(&d, &errata, &mut used)?);
    }
    // Errata rows that name nothing that was checked are stale.
    for (k, e) in errata.iter().enumerate() {
        if !used.contains(&k) {
            let name = e.derivation.clone();
            let line = Line {
                case: e.case.clone(),
                quantity: e.quantity.clone(),
                printed: e.printed.clone(),
                computed: "—".into(),
                identity: false,
                verdict: Verdict::Fail(
                    "ERRATA.md lists this value, but no derivation checks it".into(),
                ),
            };
            match results.iter_mut().find(|r| {
                r.path
                    .file_name()
                    .is_some_and(|n| n.to_string_lossy() == name)
            }) {
                Some(r) => r.lines.push(line),
                None => results.push(FileResult {
                    path: dir.join(&name),
                    cases: Vec::new(),
                    lines: vec![line],
                }),
            }
        }
    }
    Ok(results)
}

/// Check one derivation; `used` collects the indices of the errata rows that matched.
pub fn check_derivation(
    d: &Derivation,
    errata: &[Erratum],
    used: &mut BTreeSet<usize>,
) -> Result<FileResult, FormatError> {
    let file = d.path.display().to_string();
    let fname = d
        .path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut result = FileResult {
        path: d.path.clone(),
        cases: Vec::new(),
        lines: Vec::new(),
    };
    for case in &d.cases {
        let (line0, text) = &d.scenes[&case.scene];
        let label = format!("{file}#{}", case.name);
        let fmt_err = |message: String| FormatError {
            file: file.clone(),
            line: *line0,
            message,
        };
        let mut doc = parse_document(text, &label).map_err(|e| fmt_err(e.to_string()))?;
        for (path, value) in &case.sets {
            set_value(&mut doc, path, value)
                .map_err(|e| fmt_err(format!("case `{}`: set {e}", case.name)))?;
        }
        let mut scene = Scene::from_document_with(&doc, &label, &case.symbols)
            .map_err(|e| fmt_err(e.to_string()))?;
        if let Some(law) = case.law {
            scene.law = law;
        }
        let symbolic = !case.symbols.is_empty();
        if symbolic && scene.frictional() {
            return Err(fmt_err(format!(
                "case `{}`: a symbolic case is derived without friction only",
                case.name
            )));
        }
        if symbolic && scene.law == Law::Unilateral {
            return Err(fmt_err(format!(
                "case `{}`: a symbolic case is derived under the simultaneous law only",
                case.name
            )));
        }
        // Exact: in rationals when every input is rational, else with exact radicals.
        let radical = !symbolic && !scene.is_rational() && scene.problem::<RatFun>().is_ok();
        let exact = symbolic || case.exact.unwrap_or(scene.is_rational() || radical);
        // A symbolic case is derived (so a singular family has its compatibility conditions).
        let mut family = None;
        let solved: Result<Solved, RunError> = if symbolic {
            match crate::tools::derive::derive(&scene, &case.symbols, None) {
                Ok(crate::tools::derive::Derived {
                    report: crate::tools::derive::Readout::Body(report),
                    singular,
                    energy_identity,
                    ..
                }) => {
                    family = singular;
                    Ok(Solved {
                        energy_identity: energy_identity.iter().map(|(_, ok)| *ok).collect(),
                        report,
                    })
                }
                Ok(_) => {
                    return Err(fmt_err(format!(
                        "case `{}`: a case is one body's scene (a system of bodies is checked by \
                         its tests, tests/systems.rs)",
                        case.name
                    )));
                }
                Err(e) => Err(e),
            }
        } else if exact && radical {
            run_with::<RatFun>(&scene, None, true)
        } else if exact {
            run_with::<Exact>(&scene, None, true)
        } else {
            run_with::<f64>(&scene, None, true)
        };
        let solved = solved.map_err(|e| fmt_err(format!("case `{}`: {e}", case.name)))?;
        crate::scalar::symbolic::take_assumptions();
        result.cases.push((
            case.name.clone(),
            match (
                symbolic,
                solved.report.scalar,
                solved.report.friction.is_empty(),
            ) {
                (true, _, _) => "symbolic",
                (false, "symbolic", true) => "exact, radicals",
                (false, "symbolic", false) => "exact, radicals, friction",
                (false, "exact", false) => "exact, friction",
                (false, _, false) => "f64, friction",
                (false, s, true) => s,
            },
            if solved.report.models.is_empty() && solved.report.friction.is_empty() {
                None
            } else {
                Some(solved.energy_identity.iter().all(|&b| b))
            },
        ));
        for (quantity, printed, line_no) in &case.expects {
            let condition = quantity.ends_with(".compatibility");
            let values = if condition {
                compatibility(family.as_ref(), quantity)
            } else {
                lookup(&solved.report, quantity)
            };
            let values = values.map_err(|m| FormatError {
                file: file.clone(),
                line: *line_no,
                message: m,
            })?;
            let printed_items = split_printed(printed);
            if printed_items.len() != values.len() {
                return Err(FormatError {
                    file: file.clone(),
                    line: *line_no,
                    message: format!(
                        "`{quantity}` has {} entries, the expectation {}",
                        values.len(),
                        printed_items.len()
                    ),
                });
            }
            let angle = is_angle(quantity);
            for (k, (p, v)) in printed_items.iter().zip(&values).enumerate() {
                let q = if values.len() > 1 || printed.trim_start().starts_with('[') {
                    format!("{quantity}[{k}]")
                } else {
                    quantity.clone()
                };
                let judge = |p: &str| {
                    if symbolic && condition {
                        same_equation(p, v, &case.symbols)
                    } else if symbolic {
                        identical(p, v, &case.symbols)
                    } else {
                        agrees(p, v, angle)
                    }
                };
                let agreed = judge(p).map_err(|m| FormatError {
                    file: file.clone(),
                    line: *line_no,
                    message: m,
                })?;
                let computed = if symbolic {
                    v.exact.clone().unwrap_or_else(|| "(no exact form)".into())
                } else {
                    describe(v, p)
                };
                let listed = errata
                    .iter()
                    .enumerate()
                    .find(|(_, e)| e.derivation == fname && e.case == case.name && e.quantity == q);
                let verdict = match (agreed, listed) {
                    (true, None) => Verdict::Reproduced,
                    (true, Some((k, _))) => {
                        used.insert(k);
                        Verdict::Fail("listed in ERRATA.md, but the value is in fact reproduced: remove the row".into())
                    }
                    (false, None) => Verdict::Fail(
                        "disagrees with the computation and is not in ERRATA.md".into(),
                    ),
                    (false, Some((k, e))) => {
                        used.insert(k);
                        if e.printed != *p {
                            Verdict::Fail(format!(
                                "ERRATA.md says the paper prints {}, the derivation {}",
                                e.printed, p
                            ))
                        } else if !judge(&e.computed).unwrap_or(false) {
                            Verdict::Fail(format!(
                                "ERRATA.md's computed value {} is not what is computed",
                                e.computed
                            ))
                        } else {
                            Verdict::KnownErratum(e.reason.clone())
                        }
                    }
                };
                result.lines.push(Line {
                    case: case.name.clone(),
                    quantity: q,
                    printed: p.clone(),
                    computed,
                    verdict,
                    identity: symbolic,
                });
            }
        }
    }
    Ok(result)
}

fn is_angle(q: &str) -> bool {
    let name = q.rsplit('.').next().unwrap_or(q);
    name.starts_with('a') && name[1..].chars().next().is_some_and(|c| c.is_ascii_digit())
}

/// `[a, b, c]` → the items; a scalar → itself.
fn split_printed(p: &str) -> Vec<String> {
    let t = p.trim();
    match t.strip_prefix('[').and_then(|s| s.strip_suffix(']')) {
        Some(inner) => inner.split(',').map(|s| s.trim().to_string()).collect(),
        None => vec![t.to_string()],
    }
}

/// Is the closed form `p` (an expression in `symbols`) identical to the derived `v`? Exact:
/// both sides are read into the symbolic field and compared by cross-multiplication.
fn identical(p: &str, v: &Value, symbols: &[String]) -> Result<bool, String> {
    let printed = crate::scalar::symbolic::symbolic(p, symbols)
        .map_err(|e| format!("the closed form `{p}`: {e}"))?;
    let Some(derived) = v.exact.as_deref() else {
        return Ok(false);
    };
    Ok(crate::scalar::symbolic::symbolic(derived, symbols).is_ok_and(|d| d == printed))
}

/// Is the printed condition `p` = 0 the derived compatibility condition `v` = 0, up to a
/// nonzero constant factor (the same equation, however it is scaled or signed)?
fn same_equation(p: &str, v: &Value, symbols: &[String]) -> Result<bool, String> {
    let printed = crate::scalar::symbolic::symbolic(p, symbols)
        .map_err(|e| format!("the condition `{p}`: {e}"))?;
    if printed.is_zero() {
        return Ok(v.exact.as_deref() == Some("0"));
    }
    let Some(derived) = v.exact.as_deref() else {
        return Ok(false);
    };
    Ok(
        crate::scalar::symbolic::symbolic(derived, symbols).is_ok_and(|d| {
            let ratio = d / printed;
            ratio.is_constant() && !ratio.is_zero()
        }),
    )
}

/// `newton.compatibility`, `poisson.compatibility`: for a singular family, the derived
/// compatibility conditions z_kᵀ b = 0 (their left sides, factored), one per null vector.
fn compatibility(
    family: Option<&crate::tools::derive::Singular>,
    q: &str,
) -> Result<Vec<Value>, String> {
    let s = family.ok_or_else(|| {
        format!("`{q}`: the collision is not singular for every value of the symbols")
    })?;
    let model = q.split('.').next().and_then(Model::from_name);
    let f = s
        .models
        .iter()
        .find(|f| Some(f.model) == model)
        .ok_or_else(|| format!("`{q}`: unknown model or model not solved"))?;
    Ok(f.factored
        .iter()
        .map(|c| Value {
            f64: f64::NAN,
            exact: Some(c.to_text()),
            latex: Some(c.to_latex()),
            derivative: None,
            wide: None,
        })
        .collect())
}

/// The exact verdict |x − q| ≤ ½·10⁻ᵈ for a computed exact value `x` (a rational or a
/// constant with radicals) and a printed decimal `q` with `d` decimals (`d` = 0: x = q).
/// `None` when the value has no exact form.
fn agrees_exactly(v: &Value, q: &BigRational, decimals: usize) -> Option<bool> {
    let x = crate::scalar::symbolic::symbolic(v.exact.as_deref()?, &[]).ok()?;
    if !x.is_constant() {
        return None;
    }
    let diff = x - RatFun::constant(q.clone());
    if decimals == 0 {
        return Some(diff.is_zero());
    }
    let half = RatFun::constant(BigRational::new(
        1.into(),
        BigInt::from(2) * BigInt::from(10).pow(decimals as u32),
    ));
    let above = (diff.clone() - &half).constant_sign()?;
    let below = (diff + &half).constant_sign()?;
    Some(above <= 0 && below >= 0)
}

/// Does the computed `v` agree with the printed text `p` at the printed precision? Decided
/// exactly when the computation was exact (rationals or radicals); angles, which are
/// transcendental, and f64 runs by the f64 value.
fn agrees(p: &str, v: &Value, angle: bool) -> Result<bool, String> {
    let text = p.trim();
    let Some(decimals) = printed_decimals(text) else {
        return agrees_with_expression(text, v, angle);
    };
    let printed = parse_number(text).map_err(|e| e.to_string())?;
    if !angle
        && let Ok(q) = &printed.exact
        && let Some(verdict) = agrees_exactly(v, q, decimals)
    {
        return Ok(verdict);
    }
    let pv = printed.approx;
    let mut diff = v.f64 - pv;
    if angle {
        diff = (diff + 180.0).rem_euclid(360.0) - 180.0;
    }
    if decimals == 0 && !angle {
        // A printed integer claims an exact value.
        return Ok(match (&v.exact, &printed.exact) {
            (Some(t), Ok(q)) => {
                parse_number(t).ok().and_then(|n| n.exact.ok()).as_ref() == Some(q)
                    || (t.contains("sqrt") && diff.abs() <= 1e-12 * pv.abs().max(1.0))
            }
            _ => diff.abs() <= 1e-9 * pv.abs().max(1.0),
        });
    }
    let half_unit = 0.5 * 10f64.powi(-(decimals as i32));
    Ok(diff.abs() <= half_unit * (1.0 + 1e-9))
}

/// Does the computed `v` equal the exact value written as the expression `text` (a fraction
/// such as `89/450`, or with radicals: `-25*sqrt(2)`)? Exactly when the computation was exact;
/// to 10⁻⁹ relative in f64.
fn agrees_with_expression(text: &str, v: &Value, angle: bool) -> Result<bool, String> {
    let not_a_value = || format!("`{text}` is neither a printed decimal nor an exact number");
    if angle {
        return Err(format!(
            "`{text}`: an angle is written as a decimal number of degrees"
        ));
    }
    let claimed = crate::scalar::symbolic::symbolic(text, &[]).map_err(|_| not_a_value())?;
    if !claimed.is_constant() {
        return Err(not_a_value());
    }
    if let Some(computed) = v
        .exact
        .as_deref()
        .and_then(|t| crate::scalar::symbolic::symbolic(t, &[]).ok())
        .filter(RatFun::is_constant)
    {
        return Ok(computed == claimed);
    }
    let c = claimed.to_f64();
    Ok((v.f64 - c).abs() <= 1e-9 * c.abs().max(1.0))
}

/// A verdict as a value: 1 (yes) or 0 (no), exact.
fn flag(b: bool) -> Value {
    let x = Exact::from_integer(BigInt::from(u8::from(b)));
    Value::of(&x)
}

/// Number of decimals printed, `None` if not a plain decimal.
fn printed_decimals(t: &str) -> Option<usize> {
    parse_decimal(t)?;
    if t.contains(['e', 'E']) {
        return None;
    }
    Some(t.split_once('.').map_or(0, |(_, frac)| frac.len()))
}

/// The computed value as shown next to a printed one: two more decimals than printed (at
/// least six), plus the exact text when there is one.
fn describe(v: &Value, printed: &str) -> String {
    let d = (printed_decimals(printed.trim()).unwrap_or(6) + 2).max(6);
    let approx = format!("{:.*}", d.min(15), v.f64);
    match &v.exact {
        Some(t) if *t != approx => format!("{approx} (= {t})"),
        _ => approx,
    }
}

/// A quantity of a frictional readout (see the module docs for the names).
fn friction_value(
    f: &FrictionReport,
    name: &str,
    idx: &dyn Fn(&str) -> Option<usize>,
) -> Option<Vec<Value>> {
    match name {
        "Ep" => return Some(vec![f.lost_velocity_energy.clone()]),
        "dEc" => return Some(vec![f.kinetic_energy_loss.clone()]),
        "Ef" => return Some(vec![f.friction_dissipation.clone()]),
        "omega" => return Some(f.angular_velocity.to_vec()),
        "vC" => return Some(f.velocity.to_vec()),
        "twist" => {
            return Some(
                f.angular_velocity
                    .iter()
                    .chain(&f.velocity)
                    .cloned()
                    .collect(),
            );
        }
        "events" => return Some(f.events.clone()),
        "end" => return Some(vec![f.end.clone()]),
        "admissible" => return Some(vec![flag(f.verdicts.is_empty())]),
        _ => {}
    }
    let contact = |prefix: &str| {
        name.strip_prefix(prefix)
            .and_then(idx)
            .map(|i| &f.contacts[i])
    };
    if let Some(c) = contact("Pt") {
        return Some(c.tangential_impulse.to_vec());
    }
    if let Some(c) = name
        .strip_suffix('c')
        .and_then(|n| n.strip_prefix('P'))
        .and_then(idx)
    {
        return Some(vec![f.contacts[c].compression_impulse.clone()]);
    }
    if let Some(c) = contact("P") {
        return Some(vec![c.normal_impulse.clone()]);
    }
    if let Some(c) = contact("stick") {
        return Some(vec![flag(c.sticks)]);
    }
    if let Some(c) = name
        .strip_suffix('x')
        .and_then(|n| n.strip_prefix('v'))
        .and_then(idx)
    {
        return Some(vec![f.contacts[c].normal_velocity.clone()]);
    }
    contact("v").map(|c| c.velocity.to_vec())
}

/// The reported value(s) of a quantity.
pub fn lookup(r: &Report, q: &str) -> Result<Vec<Value>, String> {
    // One entry of a vector quantity: `newton.omega[0]`.
    if let Some((base, index)) = q.strip_suffix(']').and_then(|s| s.rsplit_once('[')) {
        let k: usize = index.parse().map_err(|_| format!("bad index in `{q}`"))?;
        let all = lookup(r, base)?;
        let n = all.len();
        return all
            .into_iter()
            .nth(k)
            .map(|v| vec![v])
            .ok_or_else(|| format!("`{q}`: `{base}` has {n} entries"));
    }
    let unknown = || format!("unknown quantity `{q}` (see `inertance check --help` for the names)");
    let n = r.inertance.len();
    let idx = |s: &str| -> Option<usize> {
        s.parse::<usize>()
            .ok()
            .filter(|&i| i >= 1 && i <= n)
            .map(|i| i - 1)
    };
    let axis = |c: char| "xyz".find(c);
    if let (false, Some((law, rest))) = (r.friction.is_empty(), q.split_once('.')) {
        let law = Restitution::from_name(law).ok_or_else(unknown)?;
        let f = r.friction.iter().find(|f| f.law == law).ok_or_else(|| {
            match r.friction_failures.iter().find(|(l, _, _)| *l == law) {
                Some((_, message, _)) => format!("`{q}`: the {law} law has no answer: {message}"),
                None => format!("`{q}`: the {law} law was not integrated"),
            }
        })?;
        return friction_value(f, rest, &idx).ok_or_else(unknown);
    }
    let (model, name) = match q.split_once('.') {
        Some((m, rest)) => (Some(Model::from_name(m).ok_or_else(unknown)?), rest),
        None => (None, q),
    };
    match model {
        None => {
            if name == "det" {
                return Ok(vec![r.det.clone()]);
            }
            if name == "Mred" {
                let c = r
                    .constraints
                    .as_ref()
                    .ok_or_else(|| format!("`{q}`: the scene has no constraints"))?;
                return Ok(c.reduced_mass.iter().flatten().cloned().collect());
            }
            if let Some(rest) = name.strip_prefix('g') {
                // g{i}{j}{a}x with single-digit i, j.
                let c: Vec<char> = rest.chars().collect();
                if c.len() == 4 && c[3] == 'x' {
                    let (i, j, a) = (idx(&c[0].to_string()), idx(&c[1].to_string()), axis(c[2]));
                    if let (Some(i), Some(j), Some(a)) = (i, j, a) {
                        let m = [&r.inertance, &r.inertance_yx, &r.inertance_zx][a];
                        return Ok(vec![m[i][j].clone()]);
                    }
                }
            }
            if let Some(rest) = name.strip_suffix("_0") {
                return angle_value(&r.contacts_before, rest, &idx).ok_or_else(unknown);
            }
            if let Some(rest) = name.strip_prefix('v').and_then(|s| s.strip_suffix('0')) {
                let (i, a) = rest.split_at(rest.len().saturating_sub(1));
                if let (Some(i), Some(a)) = (idx(i), a.chars().next().and_then(axis)) {
                    return Ok(vec![r.contacts_before[i].components[a].clone()]);
                }
            }
            Err(unknown())
        }
        Some(m) => {
            let mr = r
                .model(m)
                .ok_or_else(|| format!("`{q}`: the {m} model was not solved"))?;
            // Joint j's reaction about its anchor: `J{j}.F`, `J{j}.M`.
            if let Some((j, part)) = name.strip_prefix('J').and_then(|n| n.split_once('.')) {
                let w = j
                    .parse::<usize>()
                    .ok()
                    .and_then(|j| mr.joint_reactions.get(j.checked_sub(1)?))
                    .ok_or_else(|| format!("`{q}`: no joint {j}"))?;
                match part {
                    "F" => return Ok(w.force.to_vec()),
                    "M" => return Ok(w.moment.to_vec()),
                    _ => return Err(unknown()),
                }
            }
            match name {
                "Ep" => return Ok(vec![mr.lost_velocity_energy.clone()]),
                "dEc" => return Ok(vec![mr.kinetic_energy_loss.clone()]),
                "omega" => return Ok(mr.angular_velocity.to_vec()),
                "vC" => return Ok(mr.velocity.to_vec()),
                "q" if r.constraints.is_some() => return Ok(mr.constraint_impulses.clone()),
                "F" | "MC" => {
                    let w = mr.constraint_wrench.as_ref().ok_or_else(|| {
                        format!("`{q}`: the scene has no constraints (or they were not solved)")
                    })?;
                    return Ok(match name {
                        "F" => w.force.to_vec(),
                        _ => w.moment.to_vec(),
                    });
                }
                "admissible" => return Ok(vec![flag(mr.inadmissible.is_empty())]),
                "unique" => {
                    return Ok(vec![flag(
                        mr.activity.as_ref().is_none_or(|a| a.impulses_unique),
                    )]);
                }
                "twist" => {
                    return Ok(mr
                        .angular_velocity
                        .iter()
                        .chain(&mr.velocity)
                        .cloned()
                        .collect());
                }
                _ => {}
            }
            if let Some(rest) = name.strip_prefix('P') {
                if let Some(i) = rest.strip_suffix('c').and_then(idx) {
                    let c = mr.compression_impulses.as_ref().ok_or_else(|| {
                        format!("`{q}`: compression impulses exist for Poisson only")
                    })?;
                    return Ok(vec![c[i].clone()]);
                }
                if let Some(i) = idx(rest) {
                    return Ok(vec![mr.impulses[i].clone()]);
                }
            }
            if let Some(i) = name.strip_prefix("active").and_then(idx) {
                if mr.activity.is_none() {
                    return Err(format!(
                        "`{q}`: which contacts are active is said by the unilateral law only"
                    ));
                }
                let a = mr
                    .active
                    .get(i)
                    .ok_or_else(|| format!("`{q}`: no contact {}", i + 1))?;
                return Ok(vec![flag(*a)]);
            }
            if let Some(v) = angle_value(&mr.contacts, name, &idx) {
                return Ok(v);
            }
            if let Some(rest) = name.strip_prefix('v') {
                let (i, a) = rest.split_at(rest.len().saturating_sub(1));
                if let (Some(i), Some(a)) = (idx(i), a.chars().next().and_then(axis)) {
                    return Ok(vec![mr.contacts[i].components[a].clone()]);
                }
            }
            Err(unknown())
        }
    }
}

/// `cos_a{i}`, `sin_a{i}`, `a{i}` of a list of point velocities.
fn angle_value(
    points: &[crate::report::PointVelocity],
    name: &str,
    idx: &dyn Fn(&str) -> Option<usize>,
) -> Option<Vec<Value>> {
    let (kind, i) = if let Some(i) = name.strip_prefix("cos_a") {
        (0, i)
    } else if let Some(i) = name.strip_prefix("sin_a") {
        (1, i)
    } else {
        (2, name.strip_prefix('a')?)
    };
    let a = points.get(idx(i)?)?.angle.as_ref();
    let v = match (kind, a) {
        (_, None) => Value {
            f64: f64::NAN,
            exact: Some("undefined (no tangential velocity)".into()),
            latex: None,
            derivative: None,
            wide: None,
        },
        (0, Some(a)) => a.cos.clone(),
        (1, Some(a)) => a.sin.clone(),
        (_, Some(a)) => Value::float(a.degrees),
    };
    Some(vec![v])
}

/// Render the results as the `check` report; returns the text and whether everything passed.
pub fn render(results: &[FileResult]) -> (String, bool) {
    let mut out = String::new();
    let (mut ok, mut proved, mut errata, mut fail, mut identity_fail) = (0, 0, 0, 0, 0);
    for r in results {
        let _ = writeln!(out, "{}", r.path.display());
        for (case, scalar, identity) in &r.cases {
            let friction = scalar.ends_with("friction");
            let identity_text = match identity {
                Some(true) if friction => "energy balance Σ∫v·dΛ = T⁰ − T holds",
                Some(false) if friction => "energy balance Σ∫v·dΛ = T⁰ − T FAILS",
                Some(true) => "energy identity (eq. 34) holds",
                Some(false) => "energy identity (eq. 34) FAILS",
                None => "G is singular (Δ = 0): model-independent values only",
            };
            let _ = writeln!(out, "  case {case} [{scalar}]: {identity_text}");
            if *identity == Some(false) {
                identity_fail += 1;
            }
            for l in r.lines.iter().filter(|l| &l.case == case) {
                let (tag, note) = match &l.verdict {
                    Verdict::Reproduced if l.identity => {
                        proved += 1;
                        ("proved ", String::new())
                    }
                    Verdict::Reproduced => {
                        ok += 1;
                        ("ok     ", String::new())
                    }
                    Verdict::KnownErratum(why) => {
                        errata += 1;
                        ("erratum", format!("  — {why}"))
                    }
                    Verdict::Fail(why) => {
                        fail += 1;
                        ("FAIL   ", format!("  — {why}"))
                    }
                };
                let _ = writeln!(
                    out,
                    "    {tag} {:<16} printed {:<12} computed {}{note}",
                    l.quantity, l.printed, l.computed
                );
            }
        }
        for l in r
            .lines
            .iter()
            .filter(|l| !r.cases.iter().any(|c| c.0 == l.case))
        {
            fail += 1;
            let _ = writeln!(
                out,
                "    FAIL    {:<16} case {}  — {}",
                l.quantity,
                l.case,
                match &l.verdict {
                    Verdict::Fail(w) | Verdict::KnownErratum(w) => w.as_str(),
                    Verdict::Reproduced => "",
                }
            );
        }
    }
    let _ = writeln!(
        out,
        "\n{} values checked: {ok} reproduced, {proved} closed forms proved identities, {errata} known errata (derivations/ERRATA.md), {fail} failed{}",
        ok + proved + errata + fail,
        if identity_fail > 0 {
            format!("; energy identity failed in {identity_fail} cases")
        } else {
            String::new()
        }
    );
    let passed = fail == 0 && identity_fail == 0;
    (out, passed)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exact(text: &str) -> Value {
        let x = crate::scalar::symbolic::symbolic(text, &[]).unwrap();
        Value::of(&x)
    }

    /// Printed decimals of radicals are judged exactly: √2 = 1.41421356…, so 1.4142136 (7
    /// decimals, |error| ≈ 3.8·10⁻⁸ ≤ 5·10⁻⁸) agrees and 1.4142135 (≈ 6.2·10⁻⁸) does not.
    #[test]
    fn radicals_against_printed_decimals() {
        let r2 = exact("sqrt(2)");
        assert_eq!(agrees("1.4142136", &r2, false), Ok(true));
        assert_eq!(agrees("1.4142135", &r2, false), Ok(false));
        assert_eq!(agrees("1.41421", &r2, false), Ok(true));
        assert_eq!(agrees("1.41422", &r2, false), Ok(false));
        // A printed integer claims equality.
        assert_eq!(agrees("2", &exact("sqrt(2)*sqrt(2)"), false), Ok(true));
        assert_eq!(
            agrees("1", &exact("cos(30 deg)^2 + sin(30 deg)^2"), false),
            Ok(true)
        );
        assert_eq!(agrees("1", &r2, false), Ok(false));
    }

    /// The bound is decided exactly, even where the f64 value sits on the boundary: the exact
    /// 1/8 + 10⁻³⁰ lies just outside ½·10⁻² of the printed 0.13 — f64 cannot see the
    /// difference — and exactly 1/8 lies on the bound, which agrees (≤).
    #[test]
    fn the_half_unit_bound_is_exact() {
        let on = exact("1/8");
        assert_eq!(agrees("0.13", &on, false), Ok(true));
        assert_eq!(agrees("0.12", &on, false), Ok(true));
        let below = exact("1/8 - 10^(-30)");
        assert_eq!(below.f64, 0.125);
        assert_eq!(agrees("0.13", &below, false), Ok(false));
        assert_eq!(agrees("0.12", &below, false), Ok(true));
    }

    /// A value written as an exact number claims that number: equality, never a rounding.
    #[test]
    fn exact_numbers_claim_equality() {
        assert_eq!(agrees("89/450", &exact("89/450"), false), Ok(true));
        assert_eq!(
            agrees("89/450", &exact("89/450 + 10^(-30)"), false),
            Ok(false)
        );
        assert_eq!(
            agrees("-25*sqrt(2)", &exact("-50/sqrt(2)"), false),
            Ok(true)
        );
        assert_eq!(agrees("-25*sqrt(2)", &exact("-35.36"), false), Ok(false));
        // In f64 (no exact text), 10⁻⁹ relative.
        assert_eq!(agrees("1/3", &Value::float(1.0 / 3.0), false), Ok(true));
        assert_eq!(agrees("1/3", &Value::float(0.3333), false), Ok(false));
        assert!(agrees("1/x", &exact("1"), false).is_err());
        assert!(agrees("1/3", &exact("1"), true).is_err());
        assert_eq!(flag(true).exact.as_deref(), Some("1"));
        assert_eq!(flag(false).exact.as_deref(), Some("0"));
    }

    #[test]
    fn closed_forms_are_compared_as_rational_functions() {
        let syms: Vec<String> = ["m", "Jz", "y1"].iter().map(|s| s.to_string()).collect();
        let derived =
            Value::of(&crate::scalar::symbolic::symbolic("(m*y1^2 + Jz)/(Jz*m)", &syms).unwrap());
        assert_eq!(identical("1/m + y1^2/Jz", &derived, &syms), Ok(true));
        assert_eq!(identical("1/m + y1/Jz", &derived, &syms), Ok(false));
        assert!(identical("1/m +", &derived, &syms).is_err());
        // Conditions: the same equation up to a nonzero constant factor.
        let c = Value::of(&crate::scalar::symbolic::symbolic("2*m*(y1 - Jz)", &syms).unwrap());
        assert_eq!(same_equation("Jz*m - m*y1", &c, &syms), Ok(true));
        assert_eq!(same_equation("y1 - Jz", &c, &syms), Ok(false));
    }
}
