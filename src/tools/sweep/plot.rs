//! The SVG plot: x = the first varied input, y = the chosen outputs; colour by output, dash by
//! model, one line per value of a second varied input, a gap at each singular point.

use std::collections::BTreeMap;

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::SweepError;
use super::outputs::output_names;
use super::plan::Plan;
use super::stream::Plotted;
use crate::number::rational_to_f64;

/// Line colours, one per output (Tableau 10: distinct, readable on white).
const PALETTE: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

impl Plan {
    /// The SVG of the plotted series.
    pub(super) fn render(&self, plotted: &Plotted) -> Result<String, SweepError> {
        let err = |e: &dyn std::fmt::Display| SweepError::Plot(e.to_string());

        let v0 = &self.vary[0];
        let (a, b) = (rational_to_f64(&v0.start), rational_to_f64(&v0.stop));
        let (x0, x1) = (a.min(b), a.max(b));
        let (y0, y1) = y_range(plotted);
        // Colour by output, dash by model.
        let colours = self.colours();
        let names = output_names(self.contacts);
        let dots = v0.count <= 41;

        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (960, 600)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| err(&e))?;
            let mut caption = format!("{}: sweep over {}", self.name, v0.path);
            if let Some(v1) = self.vary.get(1) {
                caption.push_str(&format!(" (one line per {})", v1.path));
            }
            let mut chart = ChartBuilder::on(&root)
                .caption(caption, ("sans-serif", 20))
                .margin(15)
                .x_label_area_size(45)
                .y_label_area_size(80)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(|e| err(&e))?;
            chart
                .configure_mesh()
                .x_desc(v0.path.as_str())
                .y_desc("impulse P / velocity / energy (scene units)")
                .draw()
                .map_err(|e| err(&e))?;
            for (s, points) in self.series.iter().zip(plotted) {
                let k = colours.iter().position(|c| *c == s.output).unwrap_or(0);
                let (r, g, b) = PALETTE[k % PALETTE.len()];
                let colour = RGBColor(r, g, b).to_rgba();
                let label = format!("{} {}", self.models[s.model], names[s.output]);
                draw_series(&mut chart, points, colour, s.model > 0, label, dots)?;
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| err(&e))?;
            root.present().map_err(|e| err(&e))?;
        }
        Ok(svg)
    }

    /// The outputs plotted, in order of first appearance: an output's index here picks its
    /// colour, shared by every model.
    fn colours(&self) -> Vec<usize> {
        let mut colours: Vec<usize> = Vec::new();
        for s in &self.series {
            if !colours.contains(&s.output) {
                colours.push(s.output);
            }
        }
        colours
    }
}

/// The chart a sweep is drawn on: f64 × f64, in SVG.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draw one series in its colour (dashed for the second model, with dots when the points are
/// few), labelled once in the legend.
fn draw_series(
    chart: &mut Chart,
    points: &[(usize, f64, f64)],
    colour: RGBAColor,
    dashed: bool,
    label: String,
    dots: bool,
) -> Result<(), SweepError> {
    let err = |e: &dyn std::fmt::Display| SweepError::Plot(e.to_string());
    let style = colour.stroke_width(2);
    let mut labelled = false;
    for seg in segments(points) {
        let drawn = if dashed {
            chart.draw_series(DashedLineSeries::new(seg.clone(), 8, 5, style))
        } else {
            chart.draw_series(LineSeries::new(seg.clone(), style))
        }
        .map_err(|e| err(&e))?;
        if !labelled {
            drawn.label(label.clone()).legend(move |(x, y)| {
                plotters::element::DashedPathElement::new(
                    vec![(x, y), (x + 24, y)],
                    // Solid: one dash longer than the sample.
                    if dashed { 6 } else { 30 },
                    if dashed { 3 } else { 10 },
                    style,
                )
            });
            labelled = true;
        }
        if dots {
            chart
                .draw_series(
                    seg.iter()
                        .map(|&(x, y)| Circle::new((x, y), 2, colour.filled())),
                )
                .map_err(|e| err(&e))?;
        }
    }
    Ok(())
}

/// The y axis: every finite y with 5 % to spare (a flat line or no value at all still gets a
/// range).
fn y_range(plotted: &Plotted) -> (f64, f64) {
    let ys = plotted
        .iter()
        .flatten()
        .map(|t| t.2)
        .filter(|y| y.is_finite());
    let (mut y0, mut y1) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
        (lo.min(y), hi.max(y))
    });
    if !y0.is_finite() {
        (y0, y1) = (-1.0, 1.0);
    }
    let pad = if y1 > y0 {
        0.05 * (y1 - y0)
    } else {
        0.5 * y0.abs().max(1.0)
    };
    (y0 - pad, y1 + pad)
}

/// A series as lines to draw: one per value of the second input, broken at singular points.
fn segments(points: &[(usize, f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut slices: BTreeMap<usize, Vec<Vec<(f64, f64)>>> = BTreeMap::new();
    for &(j, x, y) in points {
        let segs = slices.entry(j).or_insert_with(|| vec![Vec::new()]);
        if y.is_finite() {
            if let Some(seg) = segs.last_mut() {
                seg.push((x, y));
            }
        } else if segs.last().is_some_and(|seg| !seg.is_empty()) {
            segs.push(Vec::new());
        }
    }
    slices
        .into_values()
        .flatten()
        .filter(|s| !s.is_empty())
        .collect()
}
