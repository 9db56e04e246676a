//! Running a plan: points solved in parallel a chunk at a time, each chunk's rows written in
//! point order before the next starts (so memory is bounded and the CSV is ordered), the CSV
//! committed, then the plot drawn from what was kept of each plotted series.

use std::io::{BufWriter, IsTerminal, Write};
use std::path::Path;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;

use super::file::Staged;
use super::outputs::Row;
use super::plan::Plan;
use super::{CHUNK, SweepError, SweepOptions};

/// A sweep this long (and still running) gets a progress bar, when asked for and on a terminal.
const PROGRESS_AFTER: Duration = Duration::from_secs(1);

/// What the plot keeps of the solved points.
pub(super) struct Plotted {
    /// Per plotted series, (j, x, y) in point order.
    pub(super) series: Vec<Vec<(usize, f64, f64)>>,
    /// Per point, in point order: x and its `status` (kept only when a plot is drawn).
    pub(super) status: Vec<(f64, String)>,
}

impl Plan {
    /// Solve `range`, write the CSV (and the plot); the number of singular points.
    pub(super) fn execute(
        &self,
        opts: &SweepOptions,
        range: std::ops::Range<usize>,
        started: Instant,
    ) -> Result<usize, SweepError> {
        let (singular, plotted) = self.write_csv(opts, range, started)?;
        if let Some(path) = &opts.plot {
            self.write_plot(path, &plotted)?;
        }
        Ok(singular)
    }

    /// Solve `range` chunk by chunk into the committed CSV; the singular points and the
    /// plotted values.
    fn write_csv(
        &self,
        opts: &SweepOptions,
        range: std::ops::Range<usize>,
        started: Instant,
    ) -> Result<(usize, Plotted), SweepError> {
        let csv_file = Staged::create(&opts.out)?;
        let io_err = |e: &dyn std::fmt::Display| SweepError::Io {
            path: opts.out.clone(),
            message: format!("cannot write {}: {e}", csv_file.tmp.display()),
        };
        let file = csv_file.open()?;
        let mut writer = csv::Writer::from_writer(BufWriter::new(file));
        writer.write_record(self.header()).map_err(|e| io_err(&e))?;

        let bar = progress_bar(range.len());
        let mut bar_shown = false;
        let may_show = opts.progress && std::io::stderr().is_terminal();

        let mut plotted = Plotted {
            series: vec![Vec::new(); self.series.len()],
            status: Vec::new(),
        };
        let keep_status = opts.plot.is_some();
        let mut singular = 0;
        let mut lo = range.start;
        while lo < range.end {
            let hi = (lo + CHUNK).min(range.end);
            let rows = (lo..hi)
                .into_par_iter()
                .map(|p| {
                    let r = self.row(p);
                    bar.inc(1);
                    r
                })
                .collect::<Result<Vec<Row>, SweepError>>()?;
            for row in rows {
                writer
                    .write_record(row.fields.iter())
                    .map_err(|e| io_err(&e))?;
                singular += usize::from(row.singular);
                for (s, y) in row.ys.iter().enumerate() {
                    plotted.series[s].push((row.j, row.x, *y));
                }
                if keep_status {
                    plotted.status.push((row.x, row.status));
                }
            }
            if may_show && !bar_shown && started.elapsed() > PROGRESS_AFTER && hi < range.end {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                bar_shown = true;
            }
            lo = hi;
        }
        bar.finish_and_clear();

        let buffered = writer.into_inner().map_err(|e| io_err(&e.error()))?;
        let file = buffered.into_inner().map_err(|e| io_err(&e.error()))?;
        file.sync_all().map_err(|e| io_err(&e))?;
        drop(file);
        csv_file.commit()?;
        Ok((singular, plotted))
    }

    /// Draw the plot and commit it to `path`.
    fn write_plot(&self, path: &Path, plotted: &Plotted) -> Result<(), SweepError> {
        let svg = self.render(plotted)?;
        let staged = Staged::create(path)?;
        let mut f = staged.open()?;
        f.write_all(svg.as_bytes())
            .and_then(|()| f.sync_all())
            .map_err(|e| SweepError::Io {
                path: path.to_path_buf(),
                message: format!("cannot write {}: {e}", staged.tmp.display()),
            })?;
        drop(f);
        staged.commit()
    }
}

/// A hidden bar over `len` points, shown only once the sweep has run a while.
fn progress_bar(len: usize) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::hidden());
    if let Ok(style) = ProgressStyle::with_template(
        "sweep {bar:40} {pos}/{len} points, {elapsed} elapsed, ~{eta} left",
    ) {
        bar.set_style(style);
    }
    bar
}
