//! The animation of a simulated system: the single body's ([`super::animation`]: its view,
//! canvas, obstacles and SMIL frames) with every sphere drawn as its circle and every box as
//! the outline of its projected corners (their convex hull) at every sample. A sphere's spin
//! is not integrated in a system (its frictionless contacts neither see nor change it,
//! [`crate::simulate::system::members`]), so no rim marker is drawn.
//!
//! The view is the single body's for the run's gravity and no plane of motion: the vertical
//! plane through x (y when gravity lies along x), x to the right when gravity is along −z or
//! absent. Each circle carries its sphere's name (`data-name`); the obstacles are traced at the
//! depth of the first sphere's centre at the start.

use std::fmt::Write as _;

use super::animation::{Bounds, Canvas, View, escape, f, frames, hull};
use crate::simulate::body::{Feature, V3};
use crate::simulate::system::{SystemSetup, SystemSimulation, SystemState};

/// The view of a system's run.
pub fn view(setup: &SystemSetup) -> View {
    View::looking(setup.options.gravity, None)
}

/// The animation of `sim` as one SVG document (see the module docs).
pub fn to_svg(name: &str, setup: &SystemSetup, sim: &SystemSimulation) -> String {
    let view = view(setup);
    let chosen = frames(sim.samples.len());
    let mut bounds = Bounds::empty();
    for &k in &chosen {
        for (b, m) in setup.members.iter().enumerate() {
            let x = &sim.samples[k].state.x[b];
            bounds.hold(view.project(x), m.body.reach());
        }
    }
    let largest = setup
        .members
        .iter()
        .map(|m| m.body.reach())
        .fold(0.0, f64::max);
    let bounds = bounds.grown(0.5 * largest.max(1e-9));
    let t_total = sim.t_end.max(f64::MIN_POSITIVE);
    let mut canvas = Canvas::open(name, view, bounds, t_total, chosen.len());
    let depth = setup.start.x.first().map_or(0.0, |x| view.normal.dot(x));
    canvas.obstacles(&setup.planes, depth);
    for (j, &k) in chosen.iter().enumerate() {
        let sample = &sim.samples[k];
        let next = chosen.get(j + 1).map(|&n| sim.samples[n].t);
        canvas.open_frame(j, sample.t, next, t_total);
        for (b, m) in setup.members.iter().enumerate() {
            let x = &sample.state.x[b];
            let name = escape(&m.name);
            if let Some(radius) = m.radius() {
                let c = canvas.px(view.project(x));
                let r = radius * canvas.scale;
                let _ = write!(
                    canvas.svg,
                    "<circle class=\"body\" data-name=\"{name}\" cx=\"{}\" cy=\"{}\" r=\"{}\" \
                     fill=\"#9ecae1\" stroke=\"#08519c\" stroke-width=\"2\"/>",
                    f(c.0),
                    f(c.1),
                    f(r)
                );
            } else {
                let hull = hull(
                    corners(setup, &sample.state, b)
                        .iter()
                        .map(|c| view.project(c))
                        .collect(),
                );
                let points: Vec<String> = hull
                    .iter()
                    .map(|p| {
                        let c = canvas.px(*p);
                        format!("{},{}", f(c.0), f(c.1))
                    })
                    .collect();
                let _ = write!(
                    canvas.svg,
                    "<polygon class=\"body\" data-name=\"{name}\" points=\"{}\" \
                     fill=\"#9ecae1\" stroke=\"#08519c\" stroke-width=\"2\"/>",
                    points.join(" ")
                );
            }
        }
        let impacts = sim.impacts.iter().filter(|r| r.t <= sample.t).count();
        canvas.close_frame(sample.t, impacts);
    }
    canvas.close()
}

/// Member `b`'s corners (world) at `s`.
pub fn corners(setup: &SystemSetup, s: &SystemState, b: usize) -> Vec<V3> {
    let r = s.rotation(b);
    setup.members[b]
        .body
        .features
        .iter()
        .filter_map(|f| match f {
            Feature::Point { at, .. } => Some(s.x[b] + r * at),
            _ => None,
        })
        .collect()
}
