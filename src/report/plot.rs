//! The plot of a simulated run, one body's or a system's (`--trajectory FILE.svg`): kinetic,
//! potential and total energy against time on top, the run's other series below (one body's
//! angle, each sphere's height), a vertical mark at every impact in both.

use plotters::coord::Shift;
use plotters::prelude::*;

/// One line of the lower chart.
pub(crate) struct Series {
    /// Its legend (shown when there are several).
    pub label: String,
    /// (t, y) per sample.
    pub points: Vec<(f64, f64)>,
}

/// A line as a chart draws it: its legend, colour and points.
type Line<'a> = (&'a str, RGBColor, Vec<(f64, f64)>);

/// The colours of the lower chart's lines, in turn.
const PALETTE: [RGBColor; 8] = [
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(23, 190, 207),
];

/// The range of the finite `ys` and `base`, padded by 5 % (at least `least`).
fn range(ys: impl Iterator<Item = f64>, base: f64, least: f64) -> std::ops::Range<f64> {
    let (lo, hi) = ys
        .filter(|y| y.is_finite())
        .fold((base, base), |(lo, hi), y| (lo.min(y), hi.max(y)));
    let pad = 0.05 * (hi - lo).max(least);
    (lo - pad)..(hi + pad)
}

/// One chart of the plot on `area`: the `lines` (legend, colour, points) against time over
/// [0, `t1`], the `impacts` marked, the y axis labelled `y_label` and ranged over the lines and
/// zero (padded by 5 %, at least `least`), the legend drawn when `legend`.
#[allow(clippy::too_many_arguments)]
fn panel(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    caption: Option<&str>,
    t1: f64,
    y_label: &str,
    least: f64,
    lines: &[Line],
    impacts: &[f64],
    legend: bool,
) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let y = range(
        lines.iter().flat_map(|l| l.2.iter().map(|p| p.1)),
        0.0,
        least,
    );
    let mut builder = ChartBuilder::on(area);
    if let Some(c) = caption {
        builder.caption(c, ("sans-serif", 20));
    }
    let mut chart = builder
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..t1, y.clone())
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc(y_label)
        .draw()
        .map_err(|e| err(&e))?;
    let swatch = |colour: RGBColor| {
        move |(x, y): (i32, i32)| Rectangle::new([(x, y - 2), (x + 20, y + 2)], colour.filled())
    };
    for (label, colour, points) in lines {
        chart
            .draw_series(LineSeries::new(
                points.iter().copied(),
                colour.stroke_width(2),
            ))
            .map_err(|e| err(&e))?
            .label(*label)
            .legend(swatch(*colour));
    }
    let red = RGBColor(214, 39, 40);
    chart
        .draw_series(
            impacts
                .iter()
                .map(|&t| PathElement::new(vec![(t, y.start), (t, y.end)], red.mix(0.4))),
        )
        .map_err(|e| err(&e))?
        .label("impact")
        .legend(swatch(red));
    if legend {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| err(&e))?;
    }
    Ok(())
}

/// The plot (SVG, 960×720): `energies` as (t, kinetic, potential) per sample over
/// [0, `t_end`], titled `caption`; `lower` against time under the axis label `lower_label`
/// (its legend drawn when it has several lines); the `impacts`' times marked. Non-finite values
/// are left out of the axes' ranges.
///
/// # Errors
/// What the plotting library reports.
pub(crate) fn energies_and(
    caption: &str,
    t_end: f64,
    energies: &[(f64, f64, f64)],
    impacts: &[f64],
    lower_label: &str,
    lower: &[Series],
) -> Result<String, String> {
    let t1 = t_end.max(f64::MIN_POSITIVE);
    let energy = |pick: fn(&(f64, f64, f64)) -> f64| -> Vec<(f64, f64)> {
        energies.iter().map(|e| (e.0, pick(e))).collect()
    };
    let top = [
        ("kinetic", RGBColor(31, 119, 180), energy(|e| e.1)),
        ("potential", RGBColor(44, 160, 44), energy(|e| e.2)),
        ("total", RGBColor(0, 0, 0), energy(|e| e.1 + e.2)),
    ];
    let bottom: Vec<Line> = lower
        .iter()
        .enumerate()
        .map(|(k, s)| {
            (
                s.label.as_str(),
                PALETTE[k % PALETTE.len()],
                s.points.clone(),
            )
        })
        .collect();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 720)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (upper, under) = root.split_vertically(360);
        panel(
            &upper,
            Some(caption),
            t1,
            "energy [J]",
            f64::MIN_POSITIVE,
            &top,
            impacts,
            true,
        )?;
        panel(
            &under,
            None,
            t1,
            lower_label,
            1e-9,
            &bottom,
            impacts,
            lower.len() > 1,
        )?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}
