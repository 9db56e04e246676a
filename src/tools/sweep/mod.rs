//! Parameter sweeps: one scene solved over a grid of one or two varied inputs, in parallel,
//! streamed to CSV, optionally plotted.
//!
//! ```text
//! inertance sweep scene.toml --vary 'contact[1].k=0:1:101' [--vary ...] [--exact] \
//!     --out results.csv [--plot results.svg] [--shard I/N]
//! ```
//!
//! ## The grid
//!
//! Each `--vary PATH=START:STOP:COUNT` ([`Vary`]) names one number of the scene by its key path
//! (as in [`crate::scene::set_value`]: `contact[1].k`, `body.mass`, `body.velocity[0]`;
//! `contact[i].k_newton` / `k_poisson` vary one model's coefficient only) and COUNT ≥ 2 points
//! from START to STOP, both ends included. START and STOP are read exactly, as scene numbers
//! are, so `0:1:101` gives exactly 0, 1/100, …, 1 (in f64 mode each point is the correctly
//! rounded value). A decreasing range (`1:0:5`) is allowed; START = STOP is refused.
//!
//! With two `--vary`, the first is the outer index i and the second the inner index j: global
//! point p (0-based) is (i, j) = (p / COUNT₂, p mod COUNT₂).
//!
//! Every `--vary` is checked before anything is solved: the path must name a number of the
//! scene, and the scene must be valid at both START and STOP (so `k` up to 1.5 fails naming
//! the key and the value); the grid corners are solved once as a check. A point whose G is
//! singular (Δ = 0) is not an error: its row has `status` = `singular` and empty outputs.
//!
//! ## CSV columns
//!
//! * `point`: the global point index p.
//! * per varied path, its value as f64 (column named by the path, e.g. `contact[1].k`), and in
//!   `--exact` mode `PATH_exact` with the exact value `p/q`.
//! * per model solved (the scene's `[solve] models`, in that order), prefixed `newton_` /
//!   `poisson_`: `P1 … PN` (impulses), `vCx vCy vCz` (v_C after impact), `wx wy wz` (ω after
//!   impact), `Ep` (E_p) and `dEc` (ΔE_c). In `--exact` mode these are the f64 values of the
//!   exact results, followed (so the f64 columns keep their order) by `P1_exact … PN_exact`,
//!   `Ep_exact`, `dEc_exact`: `p/q`, or `c*sqrt(r)` for an impulse along a non-unit normal.
//! * with `--sensitivity`, per varied path KEY (in `--vary` order), per model, per output
//!   column above: `d(newton_P1)/d(KEY)`, …, and in `--exact` mode `d(newton_P1)/d(KEY)_exact`
//!   for P_i, E_p, ΔE_c (see [Sensitivities](#sensitivities)).
//! * `status`: `ok` or `singular` (then every output column of the row is empty).
//!
//! f64 values are written with full round-trip precision (Rust's `{:?}`, e.g. `0.1`, `1e-7`).
//!
//! ## Sensitivities
//!
//! With `--sensitivity` ([`SweepOptions::sensitivity`]) every point is also solved once per
//! varied path KEY in dual numbers ([`crate::scalar::dual`]: `Dual<f64>`, or `Dual<Exact>`
//! with `--exact`), the scene there seeded with KEY's number carrying tangent 1
//! ([`crate::scene::seed::seeded`]), and the columns `d(OUTPUT)/d(KEY)` hold each output's
//! derivative with respect to KEY — forward-mode automatic differentiation through the
//! unchanged solver, exact in `--exact` mode (a surd `c*sqrt(r)` where the output is one), to
//! rounding in f64. It is the derivative of the branch the point's value takes (which contacts
//! take an impulse, which modes friction follows); at a branch point it is one-sided. Where a
//! law has no answer its derivative cells are empty like its outputs; where its answer is
//! inadmissible (`tensile`, …) both are written, the derivative that of that answer. A
//! derivative that does not exist (√ at 0) or is not finite is an empty cell. Frictional
//! scenes are differentiated when planar (event by event); a spatial one is refused before the
//! sweep starts. Without the flag nothing is solved twice and the columns are unchanged.
//!
//! ## Shards (array jobs)
//!
//! `--shard I/N` ([`Shard`], 1 ≤ I ≤ N, 1-based like Slurm's `--array=1-N` and
//! `$SLURM_ARRAY_TASK_ID`) solves the contiguous block of global points
//! `[⌊(I−1)·P/N⌋, ⌊I·P/N⌋)` of the P-point grid: the shards are disjoint, cover the grid, and
//! depend only on (I, N, P) (a shard is empty when N > P). **Every shard writes its own
//! header line**, so each file is a valid CSV on its own; concatenate in shard order dropping
//! all but the first header:
//!
//! ```sh
//! { cat out-1.csv; for i in $(seq 2 N); do tail -n +2 out-$i.csv; done; } > out.csv
//! ```
//!
//! which is byte-for-byte the unsharded CSV (`point` keeps the global index). A plot drawn
//! by a shard shows that shard's points only; plot the concatenated CSV instead.
//!
//! ## Memory, order, files
//!
//! Points are solved in parallel (rayon; a local pool of `threads` when given) in chunks of
//! [`CHUNK`] points; a chunk's rows are written in point order before the next chunk starts,
//! so memory is bounded by the chunk size and the CSV is in point order. The plot is the one
//! exception: it keeps (x, y) per point of each plotted series only, O(points × series).
//!
//! Files are written atomically: to `FILE.tmp`, renamed to `FILE` when complete; on error the
//! `.tmp` is removed and nothing half-written is left. The CSV is committed before the plot is
//! drawn, so a plot failure leaves the complete CSV in place.
//!
//! ## Plot
//!
//! An SVG (no fonts needed): x = the first varied input, y = the chosen outputs, one colour per
//! output, Newton solid and Poisson dashed, so the two models can be compared at a glance
//! (they coincide when every k_i is equal, eq. 50–55). Outputs are named like CSV columns
//! (`newton_P1`), or without the model prefix (`P1`, `dEc`) for every model solved; the
//! default is `P1 … PN` and `dEc` for every model. A 2-D sweep draws one line per value of
//! the second varied input, all in the output's colour. Singular points leave a gap. With
//! `--sensitivity` the default adds each plotted output's derivative with respect to the first
//! varied input (the slope of its curve) as a thin line in its colour; a derivative column may
//! also be named (`d(P1)/d(contact[1].k)`, `d(newton_P1)/d(contact[1].k)`).
//!
//! Where the regime switches, the plot says so: each x-range whose `status` is not `ok` is
//! shaded over the whole height, behind the lines, from the midpoint with the previous grid
//! point to the midpoint with the next, and labelled in the legend with its status and the x
//! of its first and last grid points (`status tensile: 0.4826…0.7495`): the simultaneous
//! answer is not physical there (the unilateral law's is), or G is singular (grey), or the
//! body jammed. In a 2-D sweep an x is shaded when some line there is not `ok`, with the
//! reasons of all its lines.
//!
//! ## Under the LZB law
//!
//! A scene under the LZB law (`[solve] law = "lzb"`, `--law lzb`) is swept by its own
//! integration, with its own columns (`P1 … PN`, `v1 … vN`, the energies and works, the twist,
//! `dEc`, the residual, the error estimate, the order the contacts came to rest): see
//! `lzb` (private; guide/multiple-impacts.md). A contact's `stiffness`, `exponent` and
//! `k_energetic` can be varied even when the scene does not write them.
//!
//! ## Progress
//!
//! With `progress`, a bar is drawn to stderr once a sweep has run for more than a second; never
//! when stderr is not a terminal.
//!
//! ## Where things live
//!
//! `axis` reads `--vary` and `--shard`; `plan` checks a sweep before anything is solved and
//! gives the scene and the solve at each point, with `slot` setting varied numbers straight
//! into the scene and `coefficients` setting coefficients of restitution straight into a
//! problem prepared once; `outputs` names the columns and the plotted series and builds a
//! point's row in `cells`, one buffer; `stream` solves the points in chunks and writes them
//! through `file`, which never leaves a file half-written; `plot` draws the SVG; `text`
//! writes exact values.

mod answer;
mod axis;
mod batch;
mod cells;
mod coefficients;
mod file;
mod lzb;
mod outputs;
mod plan;
mod plot;
mod slot;
mod stream;
mod target;
mod text;

use std::path::PathBuf;
use std::time::Instant;

use crate::scene::SceneError;
use plan::Plan;

pub use axis::{Shard, Vary};
pub use batch::{Batch, Varied, solve_batch};

/// Points solved in parallel before their rows are written (bounds memory).
pub const CHUNK: usize = 1024;

/// What to sweep and where to write it.
#[derive(Clone, Debug, Default)]
pub struct SweepOptions {
    /// The scene file.
    pub scene: PathBuf,
    /// One or two varied inputs; the first is the outer index (and the plot's x).
    pub vary: Vec<Vary>,
    /// Solve in exact rationals (adds `_exact` columns).
    pub exact: bool,
    /// The CSV to write.
    pub out: PathBuf,
    /// The SVG plot to write, if any.
    pub plot: Option<PathBuf>,
    /// Outputs to plot: column names (`newton_P1`) or per-model names (`P1`, `dEc`);
    /// empty = `P1 … PN` and `dEc` for every model.
    pub plot_outputs: Vec<String>,
    /// Solve only this slice of the grid.
    pub shard: Option<Shard>,
    /// Worker threads; `None` (or 0) = all cores.
    pub threads: Option<usize>,
    /// Draw a progress bar on stderr for long sweeps (only on a terminal).
    pub progress: bool,
    /// The impact law; `None`: the scene's `[solve] law`.
    pub law: Option<crate::impact::unilateral::Law>,
    /// Add the derivative of every output with respect to every varied input
    /// (`d(OUTPUT)/d(KEY)` columns; see [Sensitivities](crate::tools::sweep#sensitivities)).
    pub sensitivity: bool,
}

/// What a sweep did.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepSummary {
    /// Points solved (in this shard).
    pub points: usize,
    /// Of which singular (Δ = 0).
    pub singular: usize,
    /// Wall time, seconds.
    pub seconds: f64,
}

/// Why a sweep failed.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// A bad `--vary`.
    #[error("--vary {spec}: {reason}")]
    Vary {
        /// The spec as given.
        spec: String,
        /// What is wrong and how to fix it.
        reason: String,
    },
    /// A bad `--shard`.
    #[error("--shard {spec}: {reason}")]
    Shard {
        /// The spec as given.
        spec: String,
        /// What is wrong and how to fix it.
        reason: String,
    },
    /// The scene itself is unreadable or invalid.
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// An output to plot that the sweep does not produce.
    #[error("plot output `{name}`: {reason}")]
    Output {
        /// The name as given.
        name: String,
        /// What is wrong, and the names available.
        reason: String,
    },
    /// Other inconsistent options.
    #[error("{0}")]
    Options(String),
    /// The scene is invalid, or cannot be solved, at one point of the grid.
    #[error("point {point} ({at}): {message}")]
    Point {
        /// The global point index.
        point: usize,
        /// The varied values there, e.g. `contact[1].k = 0.3`.
        at: String,
        /// What went wrong.
        message: String,
    },
    /// A file could not be written.
    #[error("{}: {message}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// The plot could not be drawn.
    #[error("plot: {0}")]
    Plot(String),
    /// The worker threads could not be started.
    #[error("cannot start the worker threads: {0}")]
    Threads(String),
}

impl SweepError {
    /// Exit status: 2 for bad input (options, scene, a point where the scene is invalid),
    /// 1 for I/O, plot and thread failures.
    pub fn exit_code(&self) -> u8 {
        match self {
            SweepError::Vary { .. }
            | SweepError::Shard { .. }
            | SweepError::Scene(_)
            | SweepError::Output { .. }
            | SweepError::Options(_)
            | SweepError::Point { .. } => 2,
            SweepError::Io { .. } | SweepError::Plot(_) | SweepError::Threads(_) => 1,
        }
    }
}

/// Run a sweep: validate everything, then solve the (shard's) points and write the CSV and
/// the plot. See the module docs for the conventions.
pub fn sweep(opts: &SweepOptions) -> Result<SweepSummary, SweepError> {
    let started = Instant::now();
    if let Ok((_, _, base)) = plan::read_scene(opts)
        && lzb::runs_lzb(opts, &base)
    {
        return lzb::sweep_lzb(opts, started);
    }
    let plan = Plan::new(opts)?;
    let range = match opts.shard {
        Some(s) => s.range(plan.points),
        None => 0..plan.points,
    };
    let singular = match opts.threads {
        Some(n) if n > 0 => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| SweepError::Threads(e.to_string()))?;
            pool.install(|| plan.execute(opts, range.clone(), started))?
        }
        _ => plan.execute(opts, range.clone(), started)?,
    };
    Ok(SweepSummary {
        points: range.len(),
        singular,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// p/q, for the tests.
#[cfg(test)]
fn q(n: i64, d: i64) -> num_rational::BigRational {
    num_rational::BigRational::new(n.into(), d.into())
}
