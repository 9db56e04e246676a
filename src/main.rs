//! The `inertance` command line: a thin layer over the library.
//!
//! Exit status: 0 success; 1 `check` found a disagreement not in ERRATA.md; 2 bad input (an
//! unreadable or invalid scene, a malformed derivation, a bad flag); 3 the collision has no
//! unique solution (Δ = 0; `derive` reports a singular family instead).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

use inertance::impact::friction::FrictionError;
use inertance::impact::restitution::Model;
use inertance::impact::solve::SolveError;
use inertance::impact::unilateral::Law;
use inertance::scalar::Exact;
use inertance::scalar::symbolic::RatFun;
use inertance::scene::Scene;
use inertance::scene::pipeline::{RunError, run};
use inertance::tools::analyze::analyze_scene;
use inertance::tools::check;

#[derive(Parser)]
#[command(
    name = "inertance",
    version,
    about = "Simultaneous collision of a rigid body at N points, exact and fast"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Overrides of a scene's parameters and output axes, shared by the commands that read one.
#[derive(clap::Args, Clone, Default)]
struct SceneOpts {
    /// Set a parameter of the scene's [params], e.g. --param theta="10 deg" (repeatable).
    #[arg(long = "param", value_name = "NAME=VALUE")]
    params: Vec<String>,
    /// The axes results are given in, for a scene with a pose: `world` (default) or `body`.
    #[arg(long, value_enum)]
    axes: Option<AxesArg>,
}

/// `solve --precision`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum PrecisionArg {
    F64,
    DoubleDouble,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum AxesArg {
    World,
    Body,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a scene: impulses, velocities after impact, energies.
    Solve {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Compute exactly: in rationals (every number read exactly as written), or with exact
        /// radicals when the scene has them ("2/sqrt(5)", "cos(30 deg)").
        #[arg(long)]
        exact: bool,
        /// Which restitution model(s); default: the scene's `[solve] models`.
        #[arg(long, value_enum)]
        model: Option<ModelArg>,
        /// The impact law: the paper's `simultaneous` one, or `unilateral` (complementarity:
        /// contacts that would pull separate instead); default: the scene's `[solve] law`.
        #[arg(long, value_enum)]
        law: Option<LawArg>,
        /// Print the JSON report instead of the table.
        #[arg(long)]
        json: bool,
        /// Only these outputs, comma-separated: impulses, twist, normal-velocities,
        /// tangential, energies, constraint-impulses, or all; default: the scene's
        /// `[solve] outputs`.
        #[arg(long, value_delimiter = ',', value_name = "NAMES")]
        outputs: Option<Vec<String>>,
        /// The float type of a numerical integration: `f64` (default) or `double-double`
        /// (about 32 digits; the LZB law only, whose default tolerance there is 1.3e-21).
        #[arg(long, value_enum, value_name = "TYPE")]
        precision: Option<PrecisionArg>,
        /// The relative tolerance of a spatial frictional integration, between 0 and 1;
        /// default: the scene's `[solve] tolerance`, else ε^(2/3) (3.7e-11 in f64).
        #[arg(long, value_name = "TOL")]
        tolerance: Option<String>,
        /// Write the path of a frictional impact to FILE.csv or FILE.json: per sample s, the
        /// phase and, per contact, P_i, the tangential impulse, the slip velocity and the mode.
        /// Under the LZB law, its impulse history: per sample τ, the primary contact and per
        /// contact P_i, v_i, E_i (FILE.csv, FILE.json), or their plot (FILE.svg).
        #[arg(long, value_name = "FILE")]
        trajectory: Option<PathBuf>,
        #[command(flatten)]
        opts: SceneOpts,
    },
    /// Analyse a scene's degenerate cases: Δ, ranks, compatibility, families of solutions,
    /// admissibility, coincident points, Newton vs Poisson, conditioning.
    Analyze {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Decide every rank and sign exactly, in rationals (or with exact radicals).
        #[arg(long)]
        exact: bool,
        /// Which restitution model(s); default: the scene's `[solve] models`.
        #[arg(long, value_enum)]
        model: Option<ModelArg>,
        /// Print the JSON report instead of the text.
        #[arg(long)]
        json: bool,
        /// Compare the simultaneous law with the LZB law at these stiffness ratios r (contact
        /// 1's stiffness K₁ r), comma-separated; default for a scene under the LZB law:
        /// 0.01,0.1,0.25,0.5,1,2,4,10,100.
        #[arg(long, value_delimiter = ',', value_name = "R,R,…")]
        lzb_ratios: Option<Vec<String>>,
        #[command(flatten)]
        opts: SceneOpts,
    },
    /// Derive the closed forms of a scene whose values name symbols: impulses, velocities
    /// after impact, E_p, ΔE_c, Δ and q as expressions, with the conditions they hold under;
    /// for a singular family, the compatibility conditions.
    Derive {
        /// The scene file (TOML); values may be expressions in the symbols, e.g. mass = "m".
        scene: PathBuf,
        /// The symbols the scene's values may name, comma-separated (e.g. m,Jz,a,b,k1,k2);
        /// default: the scene's [params], each a symbol.
        #[arg(long, value_delimiter = ',')]
        symbols: Vec<String>,
        /// Which restitution model(s); default: the scene's `[solve] models`.
        #[arg(long, value_enum)]
        model: Option<ModelArg>,
        /// Print LaTeX (an aligned block) instead of plain text.
        #[arg(long, conflicts_with = "json")]
        latex: bool,
        /// Print JSON (the report's keys with expression strings, plus conditions).
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        opts: SceneOpts,
    },
    /// Solve a scene over a grid of one or two varied inputs, in parallel, streamed to CSV.
    Sweep {
        /// The scene file (TOML).
        scene: PathBuf,
        /// PATH=START:STOP:COUNT, e.g. 'contact[1].k=0:1:101' (once or twice).
        #[arg(long, required = true, value_name = "PATH=START:STOP:COUNT")]
        vary: Vec<String>,
        /// Solve in exact rationals (adds exact columns).
        #[arg(long)]
        exact: bool,
        /// The CSV file to write.
        #[arg(long, value_name = "FILE.csv")]
        out: PathBuf,
        /// Write an SVG plot of chosen outputs against the first varied input.
        #[arg(long, value_name = "FILE.svg")]
        plot: Option<PathBuf>,
        /// Outputs to plot, comma-separated (e.g. P1,P2,dEc or newton_P1); default P1…PN and dEc.
        #[arg(long, value_delimiter = ',')]
        outputs: Vec<String>,
        /// Solve only slice I of N (1-based), for array jobs; the CSVs concatenate.
        #[arg(long, value_name = "I/N")]
        shard: Option<String>,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// The impact law; default: the scene's `[solve] law`.
        #[arg(long, value_enum)]
        law: Option<LawArg>,
        /// Add d(OUTPUT)/d(PATH) columns: each output's derivative with respect to each
        /// varied input (dual numbers; exact with --exact).
        #[arg(long)]
        sensitivity: bool,
    },
    /// Show what accuracy costs in time: every scalar type on a corpus, against exact.
    Bench {
        /// A smaller corpus and shorter timings (under a minute).
        #[arg(long)]
        quick: bool,
        /// Print JSON instead of the tables.
        #[arg(long)]
        json: bool,
        /// Write an SVG plot of error versus time (and cost versus N, and a chain of bodies'
        /// cost versus N) to this file.
        #[arg(long, value_name = "FILE.svg")]
        plot: Option<PathBuf>,
        /// Also write the tables to this file (e.g. benches/results/bench.md), headed by when,
        /// on how many cores and under what load they were measured; written atomically
        /// (FILE.tmp renamed when complete).
        #[arg(long, value_name = "FILE.md", conflicts_with_all = ["scene", "corpus"])]
        out: Option<PathBuf>,
        /// Time only this scene, in every scalar type under its law (ns per solve, per body and
        /// per contact; a type without a time says why; JSON with --json). A scene of several
        /// bodies is timed from its data: System::new, assemble, its law.
        #[arg(long, value_name = "SCENE")]
        scene: Option<PathBuf>,
        /// With --scene: time the batch API (`tools::sweep::solve_batch`, what Python's
        /// `solve_batch` calls) instead, on the points START..STOP (COUNT of them, as f64; a
        /// second --batch varies another number at the same points): ns per point.
        #[arg(long, value_name = "PATH=START:STOP:COUNT", requires = "scene")]
        batch: Vec<String>,
        /// The hard-case corpus to include, when present.
        #[arg(long, default_value = "tests/hard_cases")]
        hard_cases: PathBuf,
        /// Time only the scenes of this corpus file (`benches/peers/corpus.txt`: one
        /// two-contact scene a line): ns per solve over the whole corpus, exact (and plain
        /// BigRational, the arithmetic it replaced) and f64.
        #[arg(long, value_name = "CORPUS.txt", conflicts_with_all = ["scene", "plot"])]
        corpus: Option<PathBuf>,
    },
    /// Simulate a body, or a system of spheres, boxes and rods, under gravity among obstacle
    /// planes through every impact, until rest or the end of `[simulate] duration`: the impact
    /// log (guide/simulate.md).
    Simulate {
        /// The scene file (TOML) with a `[simulate]` table.
        scene: PathBuf,
        /// The impact law at every impact instead of `[simulate] law`.
        #[arg(long, value_enum)]
        law: Option<LawArg>,
        /// Print the whole run as JSON instead of the log.
        #[arg(long)]
        json: bool,
        /// Write the trajectory to FILE.csv (per output time: C, the angle, v, ω, the
        /// energies; for a system each body's centre and velocity, and a box's attitude and ω)
        /// or its plot to FILE.svg (energies and the angle, or each body's height, against
        /// time, impacts marked).
        #[arg(long, value_name = "FILE")]
        trajectory: Option<PathBuf>,
        /// Write an animation of the run to FILE.svg: the body (or every body) at every
        /// sample and the obstacles, played by any browser (looping).
        #[arg(long, value_name = "FILE")]
        animation: Option<PathBuf>,
        /// Run exactly (a frictionless sphere among planes: every impact time and velocity and
        /// the accumulation time as exact radicals, no integration); refused, status 2, for a
        /// scene with no exact form.
        #[arg(long, conflicts_with_all = ["trajectory", "animation", "law"])]
        exact: bool,
    },
    /// Reproduce the paper's worked examples in a derivations directory.
    Check {
        /// The directory of derivations.
        #[arg(default_value = "derivations")]
        dir: PathBuf,
        /// Print only failures, errata and the summary.
        #[arg(long, short)]
        quiet: bool,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum ModelArg {
    Newton,
    Poisson,
    Both,
}

/// `--law`.
#[derive(Clone, Copy, ValueEnum)]
enum LawArg {
    Simultaneous,
    Unilateral,
    Lzb,
}

impl LawArg {
    fn law(self) -> Law {
        match self {
            LawArg::Simultaneous => Law::Simultaneous,
            LawArg::Unilateral => Law::Unilateral,
            LawArg::Lzb => Law::Lzb,
        }
    }
}

impl ModelArg {
    fn models(self) -> Vec<Model> {
        match self {
            ModelArg::Newton => vec![Model::Newton],
            ModelArg::Poisson => vec![Model::Poisson],
            ModelArg::Both => Model::ALL.to_vec(),
        }
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    match cli.command {
        Command::Sweep {
            scene,
            vary,
            exact,
            out,
            plot,
            outputs,
            shard,
            threads,
            law,
            sensitivity,
        } => run_sweep(
            scene,
            vary,
            exact,
            out,
            plot,
            outputs,
            shard,
            threads,
            law,
            sensitivity,
        ),
        Command::Solve {
            scene,
            exact,
            model,
            law,
            json,
            outputs,
            precision,
            tolerance,
            trajectory,
            opts,
        } => solve(
            scene,
            Flags {
                exact,
                model,
                law,
                json,
                outputs,
                precision,
                tolerance,
                trajectory,
            },
            &opts,
        ),
        Command::Analyze {
            scene,
            exact,
            model,
            json,
            lzb_ratios,
            opts,
        } => run_analyze(scene, exact, model, json, lzb_ratios, &opts),
        Command::Check { dir, quiet } => run_check(dir, quiet),
        Command::Simulate {
            scene,
            law: _,
            json,
            trajectory: _,
            animation: _,
            exact: true,
        } => run_simulate_exact(&scene, json),
        Command::Simulate {
            scene,
            law,
            json,
            trajectory,
            animation,
            exact: false,
        } => run_simulate(
            &scene,
            law,
            json,
            trajectory.as_deref(),
            animation.as_deref(),
        ),
        Command::Derive {
            scene,
            symbols,
            model,
            latex,
            json,
            opts,
        } => run_derive(scene, symbols, model, latex, json, &opts),
        Command::Bench {
            quick,
            json,
            plot,
            out,
            scene,
            batch,
            hard_cases,
            corpus,
        } => {
            if let Some(corpus) = corpus {
                run_bench_corpus(&corpus, quick, json)
            } else if let (Some(scene), false) = (&scene, batch.is_empty()) {
                run_bench_batch(scene, &batch, quick, json)
            } else {
                run_bench(quick, json, (plot, out), scene, hard_cases)
            }
        }
    }
}

/// `simulate --exact`: the exact run of a frictionless sphere among planes
/// ([`inertance::simulate::exact`]), in radicals. Status 0 at its end, 2 for bad input or a
/// scene with no exact form, 3 when the run leaves the exact path (a nested radical, two
/// planes at once) — the impacts up to there are printed.
fn run_simulate_exact(path: &std::path::Path, json: bool) -> ExitCode {
    use inertance::report::exact_run::{exact_json, exact_text};
    let (scene, sphere) = match inertance::scene::SimulationScene::load_exact::<RatFun>(path) {
        Ok(s) => s,
        Err(e) => return fail_input(e.to_string()),
    };
    let (run, error) = inertance::simulate::exact::run_exact_history(&sphere);
    if json {
        let mut t = serde_json::to_string_pretty(&exact_json(&scene.name, &sphere, &run))
            .unwrap_or_default();
        t.push('\n');
        print_out(&t);
    } else {
        print_out(&exact_text(&scene.name, &sphere, &run, error.as_ref()));
    }
    match error {
        Some(e) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(3)
        }
        None => ExitCode::SUCCESS,
    }
}

/// `--law` over the scene's law: the scene's restitution kept.
fn chosen_law(
    path: &std::path::Path,
    scene: inertance::simulate::Law,
    l: LawArg,
) -> Result<inertance::simulate::Law, ExitCode> {
    let name = match l {
        LawArg::Simultaneous => "simultaneous",
        LawArg::Unilateral => "unilateral",
        LawArg::Lzb => "lzb",
    };
    scene
        .chosen(name)
        .map_err(|e| fail_input(format!("{}: --law {name}: {e}", path.display())))
}

/// The files `simulate` writes, their extensions checked before the run (status 2 for
/// another): the trajectory as CSV or its plot (`svg`), the animation.
struct SimulateFiles<'a> {
    trajectory: Option<(&'a std::path::Path, bool)>,
    animation: Option<&'a std::path::Path>,
}

impl<'a> SimulateFiles<'a> {
    fn checked(
        trajectory: Option<&'a std::path::Path>,
        animation: Option<&'a std::path::Path>,
    ) -> Result<SimulateFiles<'a>, ExitCode> {
        let trajectory = match trajectory {
            None => None,
            Some(f) => match f.extension().and_then(|e| e.to_str()) {
                Some("csv") => Some((f, false)),
                Some("svg") => Some((f, true)),
                _ => {
                    return Err(fail_input(format!(
                        "--trajectory {}: write FILE.csv (the samples) or FILE.svg (their plot)",
                        f.display()
                    )));
                }
            },
        };
        if let Some(f) = animation
            && f.extension().and_then(|e| e.to_str()) != Some("svg")
        {
            return Err(fail_input(format!(
                "--animation {}: the animation is written as FILE.svg",
                f.display()
            )));
        }
        Ok(SimulateFiles {
            trajectory,
            animation,
        })
    }

    /// Write each file asked for, whole or not at all: the animation, then the plot or CSV.
    fn write(
        &self,
        animation: impl FnOnce() -> String,
        plot: impl FnOnce() -> Result<String, String>,
        csv: impl FnOnce() -> String,
    ) -> Result<(), ExitCode> {
        if let Some(file) = self.animation {
            write_whole_as("--animation", file, &animation())?;
        }
        if let Some((file, svg)) = self.trajectory {
            let text = if svg {
                plot().map_err(|e| {
                    eprintln!("error: --trajectory {}: {e}", file.display());
                    ExitCode::from(2)
                })?
            } else {
                csv()
            };
            write_whole(file, &text)?;
        }
        Ok(())
    }
}

/// A run's report on stdout (JSON or the log), and its status: 0 when it reached its end, 3
/// when it stopped on an error (said on stderr).
fn simulate_report(
    path: &std::path::Path,
    json: bool,
    to_json: impl FnOnce() -> serde_json::Value,
    to_text: impl FnOnce() -> String,
    stopped: Option<&inertance::simulate::SimulateError>,
) -> ExitCode {
    if json {
        let mut t = serde_json::to_string_pretty(&to_json()).unwrap_or_default();
        t.push('\n');
        print_out(&t);
    } else {
        print_out(&to_text());
    }
    match stopped {
        Some(e) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(3)
        }
        None => ExitCode::SUCCESS,
    }
}

/// `simulate` on a system: the log or JSON, the trajectory, its plot and the
/// animation; statuses as for one body.
fn run_simulate_system(
    path: &std::path::Path,
    mut scene: inertance::scene::SimulatedSystemScene,
    law: Option<LawArg>,
    json: bool,
    files: &SimulateFiles,
) -> ExitCode {
    use inertance::report::{animation_system, simulation_system};
    if let Some(l) = law {
        scene.setup.law = match chosen_law(path, scene.setup.law, l) {
            Ok(l) => l,
            Err(code) => return code,
        };
    }
    let (name, setup) = (&scene.name, &scene.setup);
    let sim = inertance::simulate::system::simulate_system(setup);
    if let Err(code) = files.write(
        || animation_system::to_svg(name, setup, &sim),
        || simulation_system::to_svg(name, setup, &sim),
        || simulation_system::to_csv(setup, &sim),
    ) {
        return code;
    }
    simulate_report(
        path,
        json,
        || simulation_system::to_json(name, setup, &sim),
        || simulation_system::to_text(name, setup, &sim),
        sim.stopped.as_ref(),
    )
}

/// `simulate`: status 0 when the run reached its end, 2 for bad input, 3 when an impact had no
/// answer under the law or persistent contact could not be decided (the message says where).
fn run_simulate(
    path: &std::path::Path,
    law: Option<LawArg>,
    json: bool,
    trajectory: Option<&std::path::Path>,
    animation: Option<&std::path::Path>,
) -> ExitCode {
    use inertance::report::{animation, simulation};
    let scene = match inertance::scene::AnySimulation::load(path) {
        Ok(s) => s,
        Err(e) => return fail_input(e.to_string()),
    };
    let files = match SimulateFiles::checked(trajectory, animation) {
        Ok(f) => f,
        Err(code) => return code,
    };
    let mut scene = match scene {
        inertance::scene::AnySimulation::Body(s) => *s,
        inertance::scene::AnySimulation::System(s) => {
            return run_simulate_system(path, *s, law, json, &files);
        }
    };
    if let Some(l) = law {
        scene.setup.law = match chosen_law(path, scene.setup.law, l) {
            Ok(l) => l,
            Err(code) => return code,
        };
    }
    let (name, setup) = (&scene.name, &scene.setup);
    // A run that stopped on an error still reports its history up to there (status 3).
    let sim = inertance::simulate::run::simulate_history(setup);
    if let Err(code) = files.write(
        || animation::to_svg(name, setup, &sim),
        || simulation::to_svg(name, setup, &sim),
        || simulation::to_csv(setup, &sim),
    ) {
        return code;
    }
    simulate_report(
        path,
        json,
        || simulation::to_json(name, setup, &sim),
        || simulation::to_text(name, setup, &sim),
        sim.stopped.as_ref(),
    )
}

/// Read the scene at `path` with the overrides `opts` and the `symbols`; `-` reads it from
/// standard input (named `<stdin>` in messages). A scene that cannot be read is status 2.
fn load_with(
    path: &std::path::Path,
    opts: &SceneOpts,
    symbols: &[String],
) -> Result<Scene, ExitCode> {
    let (doc, file) = read_document(path, opts)?;
    scene_of(&doc, &file, symbols)
}

/// The scene document at `path` (`-`: standard input) and its name for messages, with the
/// overrides `opts` applied; status 2 when it cannot be read.
fn read_document(
    path: &std::path::Path,
    opts: &SceneOpts,
) -> Result<(toml_edit::DocumentMut, String), ExitCode> {
    let (text, file) = if path.as_os_str() == "-" {
        let mut text = String::new();
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut text)
            .map_err(|e| fail_input(format!("<stdin>: cannot read the scene: {e}")))?;
        (text, "<stdin>".to_string())
    } else {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path)
            .map_err(|e| fail_input(format!("{file}: cannot read the file: {e}")))?;
        (text, file)
    };
    let mut doc =
        inertance::scene::parse_document(&text, &file).map_err(|e| fail_input(e.to_string()))?;
    for p in &opts.params {
        let (name, value) = p.split_once('=').ok_or_else(|| {
            fail_input(format!(
                "--param {p}: expected NAME=VALUE, e.g. theta=\"10 deg\""
            ))
        })?;
        inertance::scene::set_param(&mut doc, name.trim(), value)
            .map_err(|e| fail_input(format!("{file}: {e}")))?;
    }
    if let Some(axes) = opts.axes {
        inertance::scene::set_axes(
            &mut doc,
            match axes {
                AxesArg::World => "world",
                AxesArg::Body => "body",
            },
        );
    }
    Ok((doc, file))
}

/// The scene of a document read by [`read_document`], its values naming `symbols`.
fn scene_of(
    doc: &toml_edit::DocumentMut,
    file: &str,
    symbols: &[String],
) -> Result<Scene, ExitCode> {
    let scene =
        Scene::from_document_with(doc, file, symbols).map_err(|e| fail_input(e.to_string()))?;
    for note in scene.notes() {
        eprintln!("{note}");
    }
    Ok(scene)
}

/// An input error: the message on stderr, status 2.
fn fail_input(message: String) -> ExitCode {
    eprintln!("error: {message}");
    ExitCode::from(2)
}

/// Read a scene, or report why not (status 2).
fn load(path: &std::path::Path) -> Result<Scene, ExitCode> {
    load_with(path, &SceneOpts::default(), &[])
}

/// `solve`'s flags.
struct Flags {
    exact: bool,
    model: Option<ModelArg>,
    law: Option<LawArg>,
    json: bool,
    outputs: Option<Vec<String>>,
    precision: Option<PrecisionArg>,
    tolerance: Option<String>,
    trajectory: Option<PathBuf>,
}

fn solve(path: PathBuf, flags: Flags, opts: &SceneOpts) -> ExitCode {
    let mut scene = match load_with(&path, opts, &[]) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if let Some(law) = flags.law
        && let Err(e) = scene.set_law(law.law(), &format!("`--law {}`", law.law()))
    {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    if let Some(names) = flags.outputs {
        match inertance::Outputs::parse(names.iter().map(String::as_str)) {
            Ok(set) if !set.is_empty() => scene.outputs = set,
            Ok(_) => {
                eprintln!("error: --outputs: list at least one output");
                return ExitCode::from(2);
            }
            Err(e) => {
                eprintln!("error: --outputs: {e}");
                return ExitCode::from(2);
            }
        }
    }
    if let Some(text) = &flags.tolerance {
        match text.trim().parse::<f64>() {
            Ok(x) if inertance::scene::valid_tolerance(x) => scene.tolerance = Some(x),
            _ => {
                eprintln!(
                    "error: --tolerance = {text}: {}",
                    inertance::scene::TOLERANCE_RULE
                );
                return ExitCode::from(2);
            }
        }
    }
    let double = flags.precision == Some(PrecisionArg::DoubleDouble);
    if scene.law == Law::Lzb {
        let asked = LzbFlags {
            exact: flags.exact,
            json: flags.json,
            trajectory: flags.trajectory,
            model: flags.model.is_some(),
            double,
        };
        return solve_lzb(&path, &scene, asked);
    }
    if double {
        eprintln!(
            "error: {}: --precision double-double: the {} law is solved in f64 or exactly \
             (`--exact`); double-double is the LZB law's (`--law lzb`)",
            path.display(),
            scene.law
        );
        return ExitCode::from(2);
    }
    let format = match &flags.trajectory {
        None => None,
        Some(file) => match trajectory_format(&path, &scene, file) {
            Ok(f) => Some(f),
            Err(code) => return code,
        },
    };
    let models = flags.model.map(ModelArg::models);
    if scene.system.is_some() {
        return solve_system(&path, &scene, flags.exact, flags.json, models.as_deref());
    }
    let solved = if flags.exact && !scene.is_rational() {
        // Radicals ("2/sqrt(5)", "cos(30 deg)") run exactly in the symbolic field.
        run::<RatFun>(&scene, models.as_deref())
    } else if flags.exact {
        run::<Exact>(&scene, models.as_deref())
    } else {
        run::<f64>(&scene, models.as_deref())
    };
    match solved {
        Ok(s) => {
            if let (Some(file), Some(format)) = (&flags.trajectory, format)
                && let Err(code) = write_trajectory(file, format, &s.report)
            {
                return code;
            }
            warn(&path, &s.report);
            tolerance_floor(&path, scene.tolerance, &s.report);
            let code = emit(flags.json, || s.report.to_json(), || s.report.to_table());
            if s.report.partial() {
                // Some model or law has no answer; the others were printed.
                ExitCode::from(4)
            } else {
                code
            }
        }
        Err(e) => fail(&path, e),
    }
}

/// The flags of `solve` under the LZB law.
struct LzbFlags {
    exact: bool,
    json: bool,
    trajectory: Option<PathBuf>,
    model: bool,
    /// `--precision double-double`.
    double: bool,
}

/// `solve` under the LZB law: f64 or double-double, its own table or JSON report, and its impulse history
/// with `--trajectory FILE.csv|.json|.svg`.
fn solve_lzb(path: &std::path::Path, scene: &Scene, flags: LzbFlags) -> ExitCode {
    let refused = if flags.exact {
        Some(
            "--exact: the LZB law is integrated numerically (adaptive Runge–Kutta in f64, or \
             double-double with `--precision double-double`), so its result is never exact: \
             drop --exact",
        )
    } else if flags.model {
        Some(
            "--model: the LZB law has no Newton or Poisson model (its restitution is each \
             contact's energetic coefficient, `k_energetic` or `k`): drop --model",
        )
    } else {
        None
    };
    if let Some(message) = refused {
        eprintln!("error: {}: {message}", path.display());
        return ExitCode::from(2);
    }
    let history = match &flags.trajectory {
        None => None,
        Some(file) => match history_format(file) {
            Ok(f) => Some((file, f)),
            Err(code) => return code,
        },
    };
    let solved = if flags.double {
        inertance::scene::lzb::run_lzb_in::<inertance::scalar::dd::DoubleDouble>(scene)
    } else {
        inertance::scene::lzb::run_lzb(scene)
    };
    match solved {
        Ok(report) => {
            if let Some((file, format)) = history {
                let text = match format {
                    HistoryFormat::Csv => Ok(report.history_csv()),
                    HistoryFormat::Json => Ok(serde_json::to_string_pretty(&report.history_json())
                        .unwrap_or_default()
                        + "\n"),
                    HistoryFormat::Svg => report.history_svg(),
                };
                let written = match text {
                    Ok(text) => write_whole(file, &text),
                    Err(e) => {
                        eprintln!(
                            "error: --trajectory {}: cannot draw the plot: {e}",
                            file.display()
                        );
                        Err(ExitCode::from(1))
                    }
                };
                if let Err(code) = written {
                    return code;
                }
            }
            emit(flags.json, || report.to_json(), || report.to_table())
        }
        Err(e) => fail(path, e),
    }
}

/// How `--trajectory` writes the LZB law's impulse history.
#[derive(Clone, Copy)]
enum HistoryFormat {
    Csv,
    Json,
    Svg,
}

/// `--trajectory FILE`'s format under the LZB law, from its extension (status 2 for another).
fn history_format(file: &std::path::Path) -> Result<HistoryFormat, ExitCode> {
    let ext = file
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("csv") => Ok(HistoryFormat::Csv),
        Some("json") => Ok(HistoryFormat::Json),
        Some("svg") => Ok(HistoryFormat::Svg),
        _ => {
            eprintln!(
                "error: --trajectory {}: under the LZB law the impulse history is written to a \
                 file ending in .csv, .json or .svg (a plot)",
                file.display()
            );
            Err(ExitCode::from(2))
        }
    }
}

/// How `--trajectory` writes.
#[derive(Clone, Copy)]
enum PathFormat {
    Csv,
    Json,
}

/// `--trajectory FILE`'s format from its extension; refused (status 2) for another extension
/// or a scene without friction, whose impact has no path.
fn trajectory_format(
    path: &std::path::Path,
    scene: &Scene,
    file: &std::path::Path,
) -> Result<PathFormat, ExitCode> {
    if !scene.frictional() {
        eprintln!(
            "error: --trajectory {}: {} has no friction to integrate (no contact with `mu` > 0, \
             no `[solve] restitution`): a frictionless impact is solved in one step and has no path",
            file.display(),
            path.display()
        );
        return Err(ExitCode::from(2));
    }
    let ext = file
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("csv") => Ok(PathFormat::Csv),
        Some("json") => Ok(PathFormat::Json),
        _ => {
            eprintln!(
                "error: --trajectory {}: the file must end in .csv or .json",
                file.display()
            );
            Err(ExitCode::from(2))
        }
    }
}

/// Write the frictional paths of `report` to `file`, whole or not at all: into a temporary
/// file beside it, renamed over it once written (status 2 when it cannot be written).
fn write_trajectory(
    file: &std::path::Path,
    format: PathFormat,
    report: &inertance::report::Report,
) -> Result<(), ExitCode> {
    use inertance::report::trajectory;
    let text = match format {
        PathFormat::Csv => trajectory::to_csv(&report.friction),
        PathFormat::Json => {
            let mut t = serde_json::to_string_pretty(&trajectory::to_json(&report.friction))
                .unwrap_or_default();
            t.push('\n');
            t
        }
    };
    write_whole(file, &text)
}

/// Write `text` to `--trajectory`'s `file`, whole or not at all: into a temporary file beside
/// it, renamed over it once written (status 2 when it cannot be written).
fn write_whole(file: &std::path::Path, text: &str) -> Result<(), ExitCode> {
    write_whole_as("--trajectory", file, text)
}

/// [`write_whole`], the error naming the option `flag` that asked for the file.
fn write_whole_as(flag: &str, file: &std::path::Path, text: &str) -> Result<(), ExitCode> {
    let name = file
        .file_name()
        .map_or_else(|| "trajectory".into(), |n| n.to_string_lossy().into_owned());
    let temp = file.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    let written = std::fs::write(&temp, text).and_then(|()| std::fs::rename(&temp, file));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&temp);
        eprintln!("error: {flag} {}: cannot write it: {e}", file.display());
        return Err(ExitCode::from(2));
    }
    Ok(())
}

/// A tolerance below what the scalar resolves is raised to 4ε by the integrator: say so.
fn tolerance_floor(path: &std::path::Path, asked: Option<f64>, report: &inertance::report::Report) {
    let Some(asked) = asked else { return };
    for f in &report.friction {
        if let Some(used) = f.tolerance.filter(|&used| used > asked) {
            eprintln!(
                "warning: {}: {} with friction: the tolerance {asked:e} is below what {} \
                 resolves; integrated to {used:e}",
                path.display(),
                f.law,
                report.scalar
            );
        }
    }
}

/// `solve` on a scene of several bodies: its system report, the same warnings and statuses.
fn solve_system(
    path: &std::path::Path,
    scene: &Scene,
    exact: bool,
    json: bool,
    models: Option<&[inertance::Model]>,
) -> ExitCode {
    use inertance::scene::system_pipeline::run_system;
    let solved = if exact && !scene.is_rational() {
        run_system::<RatFun>(scene, models)
    } else if exact {
        run_system::<Exact>(scene, models)
    } else {
        run_system::<f64>(scene, models)
    };
    match solved {
        Ok(s) => {
            let report = &s.report;
            for m in &report.models {
                for v in &m.inadmissible {
                    eprintln!("warning: {}: {}: {v}", path.display(), m.model);
                }
                if !m.inadmissible.is_empty() && m.law == inertance::Law::Simultaneous {
                    eprintln!(
                        "  the simultaneous-collision hypothesis fails for this scene: `--law \
                         unilateral` gives the physical answer, in which such contacts separate"
                    );
                }
            }
            for (model, message, _) in &report.model_failures {
                eprintln!(
                    "warning: {}: {model} under the unilateral law has no answer: {message}",
                    path.display()
                );
            }
            for f in &report.friction {
                for v in &f.verdicts {
                    eprintln!("warning: {}: {} with friction: {v}", path.display(), f.law);
                }
            }
            for (law, message, _) in &report.friction_failures {
                eprintln!(
                    "warning: {}: {law} with friction has no answer: {message}",
                    path.display()
                );
            }
            for ((f, energy), momentum) in report
                .friction
                .iter()
                .zip(&s.friction_energy_balance)
                .zip(&s.friction_momentum_conserved)
            {
                if !energy || !momentum {
                    eprintln!(
                        "warning: {}: {} with friction: the solve's checks failed ({}): this \
                         answer may be wrong",
                        path.display(),
                        f.law,
                        if *energy {
                            "momentum not conserved"
                        } else {
                            "energy balance"
                        }
                    );
                }
            }
            for ((m, energy), momentum) in report
                .models
                .iter()
                .zip(&s.energy_identity)
                .zip(&s.momentum_conserved)
            {
                if !energy || !momentum {
                    eprintln!(
                        "warning: {}: {}: the solve's checks failed ({}): this answer may be \
                         wrong; `--exact` decides",
                        path.display(),
                        m.model,
                        if *energy {
                            "momentum not conserved"
                        } else {
                            "energy identity, eq. 34"
                        }
                    );
                }
            }
            let code = emit(json, || report.to_json(), || report.to_table());
            if report.model_failures.is_empty() && report.friction_failures.is_empty() {
                code
            } else {
                ExitCode::from(4)
            }
        }
        Err(e) => fail(path, e),
    }
}

/// Never a silent inadmissible number: say on stderr why a simultaneous answer is not
/// physical, and when every contact separates, that the normals may point the wrong way.
fn warn(path: &std::path::Path, report: &inertance::report::Report) {
    for m in &report.models {
        for v in &m.inadmissible {
            eprintln!("warning: {}: {}: {v}", path.display(), m.model);
        }
        if !m.inadmissible.is_empty() {
            eprintln!(
                "  the simultaneous-collision hypothesis fails for this scene: `--law unilateral` \
                 (or `[solve] law = \"unilateral\"`) gives the physical answer, in which such \
                 contacts separate"
            );
        }
    }
    for f in &report.friction {
        for v in &f.verdicts {
            eprintln!("warning: {}: {} with friction: {v}", path.display(), f.law);
        }
    }
    for (law, message, _) in &report.friction_failures {
        eprintln!(
            "warning: {}: {law} with friction has no answer: {message}",
            path.display()
        );
    }
    for (model, message, _) in &report.model_failures {
        eprintln!(
            "warning: {}: {model} under the unilateral law has no answer: {message}",
            path.display()
        );
    }
    let before = &report.contacts_before;
    if !before.is_empty() && before.iter().all(|v| v.components[0].f64 < 0.0) {
        eprintln!(
            "note: {}: every contact is separating before impact (v_ix⁰ < 0): nothing collides. \
             `normal` is the body's outward normal at the contact (the impulse acts along \
             −normal); if the obstacle's normal was given, reverse it.",
            path.display()
        );
    }
}

fn run_analyze(
    path: PathBuf,
    exact: bool,
    model: Option<ModelArg>,
    json: bool,
    lzb_ratios: Option<Vec<String>>,
    opts: &SceneOpts,
) -> ExitCode {
    let scene = match load_with(&path, opts, &[]) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let ratios = match lzb_ratios {
        Some(list) => {
            let mut ratios = Vec::new();
            for text in list {
                match text.trim().parse::<f64>() {
                    Ok(r) if r.is_finite() && r > 0.0 => ratios.push(r),
                    _ => {
                        eprintln!(
                            "error: --lzb-ratios {text}: a stiffness ratio is a finite number > 0 \
                             (e.g. --lzb-ratios 0.1,1,10)"
                        );
                        return ExitCode::from(2);
                    }
                }
            }
            Some(ratios)
        }
        // With friction the comparison (frictionless on its simultaneous side) is not made
        // unless asked for, where it is refused by key.
        None if scene.law == Law::Lzb && scene.first_rough_contact().is_none() => {
            Some(inertance::tools::lzb_compare::DEFAULT_RATIOS.to_vec())
        }
        None => None,
    };
    // Under the LZB law (or asked for): the simultaneous law against it over the ratios.
    let models = model.map(ModelArg::models);
    let comparison = match ratios {
        Some(r) => match inertance::tools::lzb_compare::compare(&scene, &r, models.as_deref()) {
            Ok(c) => Some(c),
            Err(e) => return fail(&path, e),
        },
        None => None,
    };
    let report = if exact && !scene.is_rational() {
        analyze_scene::<RatFun>(&scene, models.as_deref())
    } else if exact {
        analyze_scene::<Exact>(&scene, models.as_deref())
    } else {
        analyze_scene::<f64>(&scene, models.as_deref())
    };
    match report {
        Ok(r) => emit(
            json,
            || {
                let mut j = r.to_json();
                if let (Some(c), Some(obj)) = (&comparison, j.as_object_mut()) {
                    obj.insert("lzb".into(), c.to_json());
                }
                j
            },
            || {
                let mut t = r.to_text();
                if let Some(c) = &comparison {
                    t.push_str(&c.to_text());
                }
                t
            },
        ),
        Err(e) => fail(&path, e),
    }
}

fn run_derive(
    path: PathBuf,
    symbols: Vec<String>,
    model: Option<ModelArg>,
    latex: bool,
    json: bool,
    opts: &SceneOpts,
) -> ExitCode {
    let (doc, file) = match read_document(&path, opts) {
        Ok(read) => read,
        Err(code) => return code,
    };
    let mut symbols: Vec<String> = symbols.iter().map(|s| s.trim().to_string()).collect();
    if symbols.is_empty() {
        // Default: every parameter of the scene is a symbol (those set by --param excepted).
        let set: Vec<&str> = opts
            .params
            .iter()
            .filter_map(|p| p.split('=').next().map(str::trim))
            .collect();
        symbols = inertance::tools::derive::default_symbols(&doc, &set);
        if symbols.is_empty() {
            eprintln!(
                "error: {file}: give --symbols NAME,… (the names the scene's values use as symbols), or \
                 declare [params], which derive takes as symbols"
            );
            return ExitCode::from(2);
        }
    }
    if let Some(bad) = symbols
        .iter()
        .find(|s| !inertance::number::expr::is_symbol_name(s))
    {
        eprintln!(
            "error: --symbols: '{bad}' is not a symbol name (a letter or '_', then letters, digits, '_'; \
             not one of the grammar's names pi, deg, sqrt, sin, cos, tan, nan, inf)"
        );
        return ExitCode::from(2);
    }
    let scene = match scene_of(&doc, &file, &symbols) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let models = model.map(ModelArg::models);
    match inertance::tools::derive::derive(&scene, &symbols, models.as_deref()) {
        Ok(d) => emit(json, || d.to_json(), || d.to_text(latex)),
        Err(e) => fail(&path, e),
    }
}

/// Print a report as pretty JSON or as text; status 0.
fn emit(
    json: bool,
    to_json: impl FnOnce() -> serde_json::Value,
    to_text: impl FnOnce() -> String,
) -> ExitCode {
    let text = if json {
        serde_json::to_string_pretty(&to_json()).unwrap_or_default() + "\n"
    } else {
        to_text()
    };
    print_out(&text);
    ExitCode::SUCCESS
}

/// Write to stdout; a closed pipe (`inertance derive … | head`) ends the output quietly.
fn print_out(text: &str) {
    use std::io::Write;
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}

/// A failed run: bad input is status 2; no unique solution (or a frame that cannot be
/// built) is status 3, with a pointer to `analyze` for a singular G.
fn fail(path: &std::path::Path, error: RunError) -> ExitCode {
    match error {
        RunError::Scene(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
        RunError::Solve(e @ SolveError::Singular { rounded: true, .. }) => {
            eprintln!(
                "error: {}: {e}.\n  A pivot of G fell within the rounding tolerance: G is singular, or \
                 so ill-conditioned that this precision cannot split the impulses between the \
                 contacts.\n  Run `inertance solve {} --exact` to decide exactly, `inertance \
                 analyze {}` for the conditioning and the family of solutions, or `inertance \
                 solve {} --law unilateral` for the velocities after impact, which the \
                 complementarity law fixes.",
                path.display(),
                path.display(),
                path.display(),
                path.display()
            );
            ExitCode::from(3)
        }
        RunError::Solve(e @ SolveError::Singular { .. }) => {
            eprintln!(
                "error: {}: {e}.\n  The simultaneous-collision hypothesis does not fix the impulses here \
                 (§8 of the paper: Δ = 0, e.g. coincident contact points or a body that cannot move along \
                 the normals independently).\n  Run `inertance analyze {}` to see whether the system is compatible, \
                 the family of solutions and what stays fixed along it, or `inertance solve {} --law \
                 unilateral` for the velocities after impact, which the complementarity law fixes.",
                path.display(),
                path.display(),
                path.display()
            );
            ExitCode::from(3)
        }
        RunError::Solve(e) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(3)
        }
        RunError::Unilateral(
            e @ inertance::impact::unilateral::UnilateralError::TooManyContacts { .. },
        ) => {
            // A limit, refused before any work: as the other limits, status 2.
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(2)
        }
        RunError::Unilateral(
            e @ inertance::impact::unilateral::UnilateralError::Jammed { rounded: false, .. },
        ) => {
            eprintln!(
                "error: {}: {e}.\n  No impulses P ≥ 0 satisfy the law: the contacts hold the body \
                 so that it cannot leave them as the law demands (a verdict, not a number).",
                path.display()
            );
            ExitCode::from(3)
        }
        RunError::Unilateral(e) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(3)
        }
        RunError::Friction(e @ FrictionError::NotPlanar) => {
            eprintln!("error: {}: {e} (drop --exact)", path.display());
            ExitCode::from(2)
        }
        RunError::Friction(e @ inertance::impact::friction::FrictionError::NeedsRadical { .. }) => {
            // A limit of the number type, not of the physics: bad input for this scalar.
            eprintln!(
                "error: {}: {e}: the stop lies at the root of a quadratic whose discriminant is \
                 itself irrational (a nested square root), which the exact radical field does not \
                 hold.\n  Solve in floating point (drop `--exact`), or give the scene rational \
                 inputs (a rational rotation, rational normals) so that one square root suffices.",
                path.display()
            );
            ExitCode::from(2)
        }
        RunError::Friction(e) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(3)
        }
        RunError::Lzb(
            e @ (inertance::impact::multiple::LzbError::Runaway { .. }
            | inertance::impact::multiple::LzbError::NotFinite),
        ) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(3)
        }
        RunError::Lzb(e) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(2)
        }
    }
}

#[allow(clippy::too_many_arguments)] // one argument per command-line flag
fn run_sweep(
    scene: PathBuf,
    vary: Vec<String>,
    exact: bool,
    out: PathBuf,
    plot: Option<PathBuf>,
    outputs: Vec<String>,
    shard: Option<String>,
    threads: Option<usize>,
    law: Option<LawArg>,
    sensitivity: bool,
) -> ExitCode {
    use inertance::tools::sweep::{Shard, SweepOptions, Vary, sweep};
    let parsed = vary
        .iter()
        .map(|v| Vary::parse(v))
        .collect::<Result<Vec<_>, _>>();
    let shard = shard.as_deref().map(Shard::parse).transpose();
    let (vary, shard) = match (parsed, shard) {
        (Ok(v), Ok(s)) => (v, s),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("error: {e}");
            return ExitCode::from(e.exit_code());
        }
    };
    let opts = SweepOptions {
        scene,
        vary,
        exact,
        out: out.clone(),
        plot,
        plot_outputs: outputs,
        shard,
        threads,
        progress: true,
        law: law.map(LawArg::law),
        sensitivity,
    };
    match sweep(&opts) {
        Ok(s) => {
            eprintln!(
                "{} points ({} without an answer: see `status`) in {:.2} s → {}",
                s.points,
                s.singular,
                s.seconds,
                out.display()
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

/// `inertance bench --scene SCENE --batch PATH=START:STOP:COUNT …`: the batch API's time per
/// point on that grid (the points zipped, not crossed: every --batch needs the same COUNT).
fn run_bench_batch(path: &std::path::Path, specs: &[String], quick: bool, json: bool) -> ExitCode {
    use inertance::tools::sweep::{Varied, Vary};
    let file = path.display().to_string();
    let doc = match std::fs::read_to_string(path)
        .map_err(|e| format!("{file}: cannot read the file: {e}"))
        .and_then(|text| inertance::scene::parse_document(&text, &file).map_err(|e| e.to_string()))
    {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let vary = match specs
        .iter()
        .map(|s| Vary::parse(s))
        .collect::<Result<Vec<_>, _>>()
    {
        Ok(v) => v,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(e.exit_code());
        }
    };
    let varied: Vec<Varied> = vary
        .iter()
        .map(|v| Varied {
            path: v.path.clone(),
            values: (0..v.count)
                .map(|i| inertance::number::rational_to_f64(&v.value(i)))
                .collect(),
        })
        .collect();
    let runs = if quick { 3 } else { 7 };
    let t = match inertance::tools::bench::time_batch(&doc, &file, &varied, runs) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(e.exit_code());
        }
    };
    if json {
        println!(
            "{}",
            serde_json::json!({
                "scene": file,
                "batch": {
                    "vary": specs,
                    "points": t.points,
                    "runs": t.runs,
                    "threads": t.threads,
                    "ns_per_point": t.ns_per_point,
                }
            })
        );
    } else {
        println!(
            "solve_batch: {:.0} ns per point ({} points of {}; median of {} runs, {} threads)",
            t.ns_per_point,
            t.points,
            specs.join(", "),
            t.runs,
            t.threads
        );
    }
    ExitCode::SUCCESS
}

/// `inertance bench --corpus FILE`: ns per solve over a corpus file, per type.
fn run_bench_corpus(path: &std::path::Path, quick: bool, json: bool) -> ExitCode {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {}: {e}", path.display());
            return ExitCode::from(2);
        }
    };
    let scenes = match inertance::tools::corpus::parse(&text) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {}: {e}", path.display());
            return ExitCode::from(2);
        }
    };
    let times = inertance::tools::corpus::time(&scenes, if quick { 1 } else { 5 });
    if json {
        let ns: serde_json::Map<String, serde_json::Value> = times
            .iter()
            .map(|(name, t)| (name.to_string(), serde_json::json!(t)))
            .collect();
        println!(
            "{}",
            serde_json::json!({"corpus": path.display().to_string(), "scenes": scenes.len(), "ns_per_solve": ns})
        );
    } else {
        println!(
            "{}: {} scenes, one solve = assemble + Newton + Poisson, every output",
            path.display(),
            scenes.len()
        );
        for (name, t) in times {
            println!(
                "{name:>12}: {}",
                t.map_or("singular".to_string(), |x| format!("{x:.0} ns per solve"))
            );
        }
    }
    ExitCode::SUCCESS
}

fn run_bench(
    quick: bool,
    json: bool,
    (plot, out): (Option<PathBuf>, Option<PathBuf>),
    scene: Option<PathBuf>,
    hard_cases: PathBuf,
) -> ExitCode {
    if let Some(path) = scene {
        let scene = match load(&path) {
            Ok(s) => s,
            Err(code) => return code,
        };
        let timing = inertance::tools::bench::time_scene(&scene, quick);
        if json {
            println!("{}", timing.to_json());
        } else {
            print!("{}", timing.to_text());
        }
        return ExitCode::SUCCESS;
    }
    let measured = inertance::tools::bench::Measured::now(quick);
    let report = inertance::tools::bench::run(&inertance::tools::bench::BenchOptions {
        quick,
        hard_cases: Some(hard_cases),
    });
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&report.to_json()).unwrap_or_default()
        );
    } else {
        print!("{}", report.to_text());
    }
    if let Some(path) = out {
        let text = format!("{}\n\n{}", measured.to_text(), report.to_text());
        if let Err(e) = inertance::tools::bench::write_atomically(&path, &text) {
            eprintln!("error: cannot write the report: {e}");
            return ExitCode::from(1);
        }
        eprintln!("report written to {}", path.display());
    }
    if let Some(path) = plot {
        if let Err(e) = report.plot(&path) {
            eprintln!("error: cannot write the plot: {e}");
            return ExitCode::from(1);
        }
        eprintln!("plot written to {}", path.display());
    }
    ExitCode::SUCCESS
}

fn run_check(dir: PathBuf, quiet: bool) -> ExitCode {
    if !dir.is_dir() {
        eprintln!("error: {}: not a directory of derivations", dir.display());
        return ExitCode::from(2);
    }
    let results = match check::check_dir(&dir) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if results.is_empty() {
        eprintln!(
            "error: {}: no derivation files (*.md besides README.md and ERRATA.md): nothing to check",
            dir.display()
        );
        return ExitCode::from(2);
    }
    let (text, passed) = check::render(&results);
    if quiet {
        let mut kept = String::new();
        for line in text.lines() {
            let t = line.trim_start();
            if !t.starts_with("ok ") && !t.starts_with("proved ") && !t.starts_with("case ") {
                kept += line;
                kept.push('\n');
            }
        }
        print_out(&kept);
    } else {
        print_out(&text);
    }
    if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
