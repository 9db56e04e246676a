//! The SVG plot: x = the first varied input, y = the chosen outputs; colour by output, dash by
//! model, one line per value of a second varied input, a gap at each singular point; behind the
//! lines, a shaded band over each x-range whose `status` is not `ok` (the simultaneous answer
//! is not physical there, or G is singular, or the body jammed), labelled in the legend, so a
//! sweep that leaves the simultaneous regime shows where.

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
        let (y0, y1) = y_range(&plotted.series);
        // Colour by output, dash by model.
        let colours = self.colours();
        let names = output_names(self.contacts, self.friction, &self.bodies);
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
            let y_desc = if self.series.iter().any(|s| s.wrt.is_some()) {
                "P / velocity / energy, and thin: their derivatives (scene units)"
            } else {
                "impulse P / velocity / energy (scene units)"
            };
            chart
                .configure_mesh()
                .x_desc(v0.path.as_str())
                .y_desc(y_desc)
                .draw()
                .map_err(|e| err(&e))?;
            draw_regimes(&mut chart, &regimes(&plotted.status, x0, x1), (y0, y1))?;
            for (s, points) in self.series.iter().zip(&plotted.series) {
                let k = colours.iter().position(|c| *c == s.output).unwrap_or(0);
                let (r, g, b) = PALETTE[k % PALETTE.len()];
                let colour = RGBColor(r, g, b).to_rgba();
                let (label, width) = match s.wrt {
                    None => (format!("{} {}", self.models[s.model], names[s.output]), 2),
                    Some(k) => (
                        format!(
                            "{} d({})/d({})",
                            self.models[s.model], names[s.output], self.vary[k].path
                        ),
                        1,
                    ),
                };
                let style = Style {
                    colour,
                    width,
                    dashed: s.model > 0,
                    dots,
                };
                draw_series(&mut chart, points, style, label)?;
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

/// How a series is drawn: its output's colour, 2 px (an output) or 1 px (a derivative), dashed
/// for the second model, with dots when the points are few.
struct Style {
    colour: RGBAColor,
    width: u32,
    dashed: bool,
    dots: bool,
}

/// Draw one series in its style, labelled once in the legend.
fn draw_series(
    chart: &mut Chart,
    points: &[(usize, f64, f64)],
    style: Style,
    label: String,
) -> Result<(), SweepError> {
    let err = |e: &dyn std::fmt::Display| SweepError::Plot(e.to_string());
    let Style {
        colour,
        width,
        dashed,
        dots,
    } = style;
    let style = colour.stroke_width(width);
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

/// The order statuses' parts are named in: the two without an answer, then the verdicts on a
/// simultaneous answer in the order of the `status` column.
const REASONS: [&str; 6] = [
    "singular",
    "jammed",
    "tensile",
    "separating",
    "still-approaching",
    "energy-gain",
];

/// Band fills (light, drawn under the lines): grey for `singular`, brown for `jammed`, then one
/// per distinct inadmissible status in order of appearance.
const BAND_SINGULAR: (u8, u8, u8) = (127, 127, 127);
const BAND_JAMMED: (u8, u8, u8) = (140, 86, 75);
const BAND_PALETTE: [(u8, u8, u8); 4] = [
    (214, 39, 40),
    (255, 127, 14),
    (148, 103, 189),
    (188, 189, 34),
];

/// A shaded x-range: its status, the band's edges and the x of its first and last grid point.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Regime {
    pub(super) status: String,
    pub(super) band: (f64, f64),
    pub(super) points: (f64, f64),
}

/// The x-ranges whose status is not `ok`. Points sharing an x (a 2-D sweep's line values) are
/// one x whose status joins their reasons (so a band there means "at some value of the second
/// input"). Each x owns the interval up to the midpoints with its neighbours (the plot's ends at
/// the ends); neighbours with the same status merge into one band.
pub(super) fn regimes(status: &[(f64, String)], x0: f64, x1: f64) -> Vec<Regime> {
    let mut per_x: Vec<(f64, Vec<&str>)> = Vec::new();
    for (x, s) in status {
        if per_x.last().is_none_or(|(lx, _)| lx != x) {
            per_x.push((*x, Vec::new()));
        }
        let reasons = &mut per_x.last_mut().expect("pushed above").1;
        for r in s.split('+').filter(|r| *r != "ok") {
            if !reasons.contains(&r) {
                reasons.push(r);
            }
        }
    }
    per_x.sort_by(|a, b| a.0.total_cmp(&b.0));
    let joined: Vec<(f64, String)> = per_x
        .into_iter()
        .map(|(x, mut reasons)| {
            reasons.sort_by_key(|r| REASONS.iter().position(|n| n == r).unwrap_or(REASONS.len()));
            (x, reasons.join("+"))
        })
        .collect();
    let mut out: Vec<Regime> = Vec::new();
    for (k, (x, s)) in joined.iter().enumerate() {
        if s.is_empty() {
            continue;
        }
        let lo = if k == 0 {
            x0
        } else {
            0.5 * (joined[k - 1].0 + x)
        };
        let hi = joined.get(k + 1).map_or(x1, |(next, _)| 0.5 * (x + next));
        match out.last_mut() {
            Some(r) if r.status == *s && k > 0 && joined[k - 1].1 == *s => {
                r.band.1 = hi;
                r.points.1 = *x;
            }
            _ => out.push(Regime {
                status: s.clone(),
                band: (lo, hi),
                points: (*x, *x),
            }),
        }
    }
    out
}

/// A number for a legend: four significant digits, no trailing zeros.
fn short(x: f64) -> String {
    let s = format!("{x:.3e}");
    let v: f64 = s.parse().unwrap_or(x);
    format!("{v}")
}

/// Shade the regimes over the whole height, one legend entry per distinct status naming its
/// x-ranges (by their first and last grid points).
fn draw_regimes(
    chart: &mut Chart,
    regimes: &[Regime],
    (y0, y1): (f64, f64),
) -> Result<(), SweepError> {
    let err = |e: &dyn std::fmt::Display| SweepError::Plot(e.to_string());
    let mut statuses: Vec<&str> = Vec::new();
    for r in regimes {
        if !statuses.contains(&r.status.as_str()) {
            statuses.push(&r.status);
        }
    }
    let mut inadmissible = 0;
    for status in statuses {
        let (r, g, b) = match status {
            "singular" => BAND_SINGULAR,
            "jammed" => BAND_JAMMED,
            _ => {
                inadmissible += 1;
                BAND_PALETTE[(inadmissible - 1) % BAND_PALETTE.len()]
            }
        };
        let fill = RGBColor(r, g, b).mix(0.15);
        let mine: Vec<&Regime> = regimes.iter().filter(|x| x.status == status).collect();
        let ranges: Vec<String> = mine
            .iter()
            .map(|x| {
                if x.points.0 == x.points.1 {
                    short(x.points.0)
                } else {
                    format!("{}…{}", short(x.points.0), short(x.points.1))
                }
            })
            .collect();
        chart
            .draw_series(
                mine.iter()
                    .map(|x| Rectangle::new([(x.band.0, y0), (x.band.1, y1)], fill.filled())),
            )
            .map_err(|e| err(&e))?
            .label(format!("status {status}: {}", ranges.join(", ")))
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 24, y + 5)], fill.filled()));
    }
    Ok(())
}

/// The y axis: every finite y with 5 % to spare (a flat line or no value at all still gets a
/// range).
pub(super) fn y_range(plotted: &[Vec<(usize, f64, f64)>]) -> (f64, f64) {
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
pub(super) fn segments(points: &[(usize, f64, f64)]) -> Vec<Vec<(f64, f64)>> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn st(v: &[(f64, &str)]) -> Vec<(f64, String)> {
        v.iter().map(|(x, s)| (*x, s.to_string())).collect()
    }

    #[test]
    fn regimes_cover_the_non_ok_points_to_the_midpoints() {
        // x = 0, 1, 2, 3, 4: ok ok tensile tensile singular.
        let s = st(&[
            (0.0, "ok"),
            (1.0, "ok"),
            (2.0, "tensile"),
            (3.0, "tensile"),
            (4.0, "singular"),
        ]);
        let r = regimes(&s, 0.0, 4.0);
        assert_eq!(
            r,
            vec![
                Regime {
                    status: "tensile".into(),
                    band: (1.5, 3.5),
                    points: (2.0, 3.0)
                },
                Regime {
                    status: "singular".into(),
                    band: (3.5, 4.0),
                    points: (4.0, 4.0)
                },
            ]
        );
        // A decreasing sweep gives the same bands; an all-ok sweep none.
        let mut rev = s.clone();
        rev.reverse();
        assert_eq!(regimes(&rev, 0.0, 4.0), r);
        assert!(regimes(&st(&[(0.0, "ok"), (1.0, "ok")]), 0.0, 1.0).is_empty());
        // The same status twice, apart: two bands.
        let r = regimes(
            &st(&[(0.0, "jammed"), (1.0, "ok"), (2.0, "jammed")]),
            0.0,
            2.0,
        );
        assert_eq!(
            r.iter().map(|r| r.band).collect::<Vec<_>>(),
            vec![(0.0, 0.5), (1.5, 2.0)]
        );
    }

    #[test]
    fn a_two_dimensional_x_joins_its_lines_reasons_in_column_order() {
        // Two lines (j = 0, 1) per x.
        let s = st(&[
            (0.0, "ok"),
            (0.0, "ok"),
            (1.0, "separating"),
            (1.0, "tensile"),
            (2.0, "tensile+separating"),
            (2.0, "ok"),
        ]);
        let r = regimes(&s, 0.0, 2.0);
        assert_eq!(r.len(), 1);
        assert_eq!(
            (r[0].status.as_str(), r[0].band),
            ("tensile+separating", (0.5, 2.0))
        );
    }

    #[test]
    fn legend_numbers_are_short() {
        assert_eq!(short(0.48256880733944955), "0.4826");
        assert_eq!(short(1.2), "1.2");
        assert_eq!(short(-3.0), "-3");
    }
}
