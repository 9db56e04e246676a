//! The plot of a simulated run, one body's or a system's (`--trajectory FILE.svg`): kinetic,
//! potential and total energy against time on top, the run's other series below (one body's
//! angle, each sphere's height), a vertical mark at every impact in both.

use plotters::prelude::*;

/// One line of the lower chart.
pub(crate) struct Series {
    /// Its legend (shown when there are several).
    pub label: String,
    /// (t, y) per sample.
    pub points: Vec<(f64, f64)>,
}

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

/// The plot (SVG, 960×720): `energies` as (t, kinetic, potential) per sample over
/// [0, `t_end`], titled `caption`; `lower` against time under the axis label `lower_label`;
/// the `impacts`' times marked. Non-finite values are left out of the axes' ranges.
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
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let t1 = t_end.max(f64::MIN_POSITIVE);
    let e = range(
        energies.iter().flat_map(|&(_, k, p)| [k, p, k + p]),
        0.0,
        f64::MIN_POSITIVE,
    );
    let a = range(
        lower.iter().flat_map(|s| s.points.iter().map(|p| p.1)),
        0.0,
        1e-9,
    );
    let red = RGBColor(214, 39, 40);
    let marks = |y: &std::ops::Range<f64>| {
        let (lo, hi) = (y.start, y.end);
        impacts
            .iter()
            .map(move |&t| PathElement::new(vec![(t, lo), (t, hi)], red.mix(0.4)))
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 720)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let (top, bottom) = root.split_vertically(360);
        let mut chart = ChartBuilder::on(&top)
            .caption(caption, ("sans-serif", 20))
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(0.0..t1, e.clone())
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc("energy [J]")
            .draw()
            .map_err(|e| err(&e))?;
        let series: [(&str, RGBColor, fn(&(f64, f64, f64)) -> f64); 3] = [
            ("kinetic", RGBColor(31, 119, 180), |e| e.1),
            ("potential", RGBColor(44, 160, 44), |e| e.2),
            ("total", RGBColor(0, 0, 0), |e| e.1 + e.2),
        ];
        for (label, colour, pick) in series {
            chart
                .draw_series(LineSeries::new(
                    energies.iter().map(|s| (s.0, pick(s))),
                    colour.stroke_width(2),
                ))
                .map_err(|e| err(&e))?
                .label(label)
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 2), (x + 20, y + 2)], colour.filled())
                });
        }
        chart
            .draw_series(marks(&e))
            .map_err(|e| err(&e))?
            .label("impact")
            .legend(move |(x, y)| Rectangle::new([(x, y - 2), (x + 20, y + 2)], red.filled()));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| err(&e))?;
        let mut chart = ChartBuilder::on(&bottom)
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(0.0..t1, a.clone())
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc(lower_label)
            .draw()
            .map_err(|e| err(&e))?;
        for (k, s) in lower.iter().enumerate() {
            let colour = PALETTE[k % PALETTE.len()];
            chart
                .draw_series(LineSeries::new(
                    s.points.iter().copied(),
                    colour.stroke_width(2),
                ))
                .map_err(|e| err(&e))?
                .label(s.label.as_str())
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 2), (x + 20, y + 2)], colour.filled())
                });
        }
        chart.draw_series(marks(&a)).map_err(|e| err(&e))?;
        if lower.len() > 1 {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| err(&e))?;
        }
        root.present().map_err(|e| err(&e))?;
    }
    Ok(svg)
}
