//! An animation of a simulated run a person can look at: one SVG, the body drawn at every
//! sample of the trajectory and the obstacle planes as lines, each frame shown for its share of
//! the run's time by SMIL (`<animate attributeName="display" calcMode="discrete">`), looping.
//! Any browser plays it; no script.
//!
//! **The view.** The drawing plane is the plane of motion when the run is planar
//! (`[simulate] plane`), otherwise the vertical plane containing the world's x axis (or y
//! when gravity lies along x). Its vertical axis e_v is "up", −g projected into the plane and
//! normalised; its horizontal axis e_h = n × e_v (n the drawing plane's normal), so a planar
//! run in x–z is drawn with x to the right and z up. A world point p is drawn at
//!
//! ```text
//! (X, Y) = (o_x + s (e_h · p),  o_y − s (e_v · p))      (SVG pixels, y down)
//! ```
//!
//! with the scale s and the origin o written on the root element (`data-scale`,
//! `data-origin`, `data-horizontal`, `data-vertical`), so a reader (the tests) can map every
//! drawn vertex back to the world.
//!
//! **What is drawn.** A box as the convex hull of its eight projected corners; a sphere as its
//! circle with a radius drawn to a body-fixed point (so that its turning shows); a rod as the
//! segment between its ends. An obstacle plane as its trace in the drawing plane at the body's
//! depth, N_h X + N_v Y = N · P − N_n w, hatched on the obstacle's side (a plane parallel to the
//! drawing plane has no trace and is not drawn). Each frame carries its time (`data-t`) and the
//! number of impacts up to it.

use std::fmt::Write as _;

use nalgebra::Vector3;

use crate::simulate::run::Simulation;
use crate::simulate::world::Plane;
use crate::simulate::{Setup, Shape, State};

type V3 = Vector3<f64>;

/// The most frames drawn: a longer trajectory is sampled evenly (the first and last kept).
pub const MAX_FRAMES: usize = 1500;

/// The canvas (px).
const WIDTH: f64 = 800.0;
const HEIGHT: f64 = 600.0;

/// The drawing plane: its normal n, the horizontal and vertical axes e_h, e_v.
#[derive(Clone, Copy, Debug)]
pub struct View {
    /// n.
    pub normal: V3,
    /// e_h = n × e_v.
    pub horizontal: V3,
    /// e_v: up.
    pub vertical: V3,
}

impl View {
    /// The view of a run: its plane of motion, or the vertical plane through x (y when gravity
    /// lies along x).
    pub fn of(setup: &Setup) -> View {
        View::looking(setup.options.gravity, setup.plane)
    }

    /// The view of a run under `gravity` in the plane of motion `plane` (none: the vertical
    /// plane through x, or y when gravity lies along x).
    pub fn looking(gravity: V3, plane: Option<V3>) -> View {
        let g = gravity;
        let up_guess = if g.norm() > 0.0 {
            -g / g.norm()
        } else {
            V3::z()
        };
        let normal = match plane {
            Some(n) => n.normalize(),
            None => {
                let candidate = V3::y();
                if candidate.cross(&up_guess).norm() > 1e-6 {
                    candidate
                } else {
                    V3::x()
                }
            }
        };
        let mut vertical = up_guess - normal * normal.dot(&up_guess);
        if vertical.norm() < 1e-9 {
            // gravity along the view's normal (or none): any axis of the plane
            vertical = normal.cross(&V3::x());
            if vertical.norm() < 1e-9 {
                vertical = normal.cross(&V3::y());
            }
        }
        let vertical = vertical.normalize();
        View {
            normal,
            horizontal: normal.cross(&vertical),
            vertical,
        }
    }

    /// (e_h · p, e_v · p).
    pub fn project(&self, p: &V3) -> (f64, f64) {
        (self.horizontal.dot(p), self.vertical.dot(p))
    }
}

/// The world points drawn for the body at `s`: a box's or a cylinder's projected hull, a rod's
/// two ends, a sphere's centre and a body-fixed point of its rim.
fn outline(setup: &Setup, view: &View, s: &State) -> Vec<(f64, f64)> {
    let r = s.rotation();
    match &setup.body.shape {
        Shape::Box { half } => {
            let mut pts = Vec::with_capacity(8);
            for i in 0..8 {
                let c = V3::new(
                    if i & 1 == 0 { -half.x } else { half.x },
                    if i & 2 == 0 { -half.y } else { half.y },
                    if i & 4 == 0 { -half.z } else { half.z },
                );
                pts.push(view.project(&(s.x + r * c)));
            }
            hull(pts)
        }
        Shape::Rod { half_length } => {
            let a = r * V3::new(0.0, 0.0, *half_length);
            vec![view.project(&(s.x - a)), view.project(&(s.x + a))]
        }
        Shape::Cylinder {
            radius,
            half_height,
        } => {
            // the hull of sixteen points of each rim
            let mut pts = Vec::with_capacity(32);
            for z in [-half_height, *half_height] {
                for k in 0..16 {
                    let phi = std::f64::consts::PI * k as f64 / 8.0;
                    let c = V3::new(radius * phi.cos(), radius * phi.sin(), z);
                    pts.push(view.project(&(s.x + r * c)));
                }
            }
            hull(pts)
        }
        Shape::Sphere { radius } => {
            // a body-fixed point on the great circle of the drawing plane at the start
            let start_r = setup.start.rotation();
            let marker_body = start_r.transpose() * view.horizontal * *radius;
            vec![view.project(&s.x), view.project(&(s.x + r * marker_body))]
        }
    }
}

/// The convex hull (Andrew's monotone chain), counter-clockwise, of points in the plane.
pub(super) fn hull(mut p: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    p.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut lower: Vec<(f64, f64)> = Vec::new();
    for &q in &p {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], q) <= 0.0 {
            lower.pop();
        }
        lower.push(q);
    }
    let mut upper: Vec<(f64, f64)> = Vec::new();
    for &q in p.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], q) <= 0.0 {
            upper.pop();
        }
        upper.push(q);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// The frames drawn of `n` samples: every one, or [`MAX_FRAMES`] of them evenly.
pub(crate) fn frames(n: usize) -> Vec<usize> {
    if n <= MAX_FRAMES {
        return (0..n).collect();
    }
    let mut idx: Vec<usize> = (0..MAX_FRAMES)
        .map(|k| k * (n - 1) / (MAX_FRAMES - 1))
        .collect();
    idx.dedup();
    idx
}

pub(crate) fn f(x: f64) -> String {
    format!("{x:.3}")
}

/// World bounds (h₀, h₁, v₀, v₁) in the drawing plane.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bounds {
    h0: f64,
    h1: f64,
    v0: f64,
    v1: f64,
}

impl Bounds {
    /// Nothing yet.
    pub(crate) fn empty() -> Bounds {
        Bounds {
            h0: f64::MAX,
            h1: f64::MIN,
            v0: f64::MAX,
            v1: f64::MIN,
        }
    }

    /// Grown to hold the disc of radius `r` about (h, v) (a point: r = 0).
    pub(crate) fn hold(&mut self, (h, v): (f64, f64), r: f64) {
        self.h0 = self.h0.min(h - r);
        self.h1 = self.h1.max(h + r);
        self.v0 = self.v0.min(v - r);
        self.v1 = self.v1.max(v + r);
    }

    /// Grown by `m` on every side.
    pub(crate) fn grown(self, m: f64) -> Bounds {
        Bounds {
            h0: self.h0 - m,
            h1: self.h1 + m,
            v0: self.v0 - m,
            v1: self.v1 + m,
        }
    }
}

/// The canvas: a run's bounds fitted into it, centred, and the SVG being written.
pub(crate) struct Canvas {
    /// s (px per m).
    pub scale: f64,
    origin: (f64, f64),
    bounds: Bounds,
    view: View,
    /// The document so far.
    pub svg: String,
}

impl Canvas {
    /// The root element (with the view, the scale and the origin a reader maps the drawing
    /// back with), the title and the background, for `frames` frames over `t_total` seconds.
    pub(crate) fn open(name: &str, view: View, b: Bounds, t_total: f64, frames: usize) -> Canvas {
        let scale = (WIDTH / (b.h1 - b.h0)).min(HEIGHT / (b.v1 - b.v0));
        let origin = (
            (WIDTH - (b.h1 - b.h0) * scale) / 2.0 - b.h0 * scale,
            (HEIGHT - (b.v1 - b.v0) * scale) / 2.0 + b.v1 * scale,
        );
        let mut svg = String::new();
        let _ = writeln!(
            svg,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"0 0 {w} {h}\" data-scale=\"{scale:e}\" data-origin=\"{ox:e} {oy:e}\" \
             data-horizontal=\"{eh0:e} {eh1:e} {eh2:e}\" data-vertical=\"{ev0:e} {ev1:e} {ev2:e}\" \
             data-duration=\"{t_total:e}\" data-frames=\"{frames}\">",
            w = f(WIDTH),
            h = f(HEIGHT),
            ox = origin.0,
            oy = origin.1,
            eh0 = view.horizontal.x,
            eh1 = view.horizontal.y,
            eh2 = view.horizontal.z,
            ev0 = view.vertical.x,
            ev1 = view.vertical.y,
            ev2 = view.vertical.z,
        );
        let _ = writeln!(
            svg,
            "<title>{}</title>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>",
            escape(name)
        );
        Canvas {
            scale,
            origin,
            bounds: b,
            view,
            svg,
        }
    }

    /// The pixel of the drawing-plane point (h, v).
    pub(crate) fn px(&self, (h, v): (f64, f64)) -> (f64, f64) {
        (
            self.origin.0 + self.scale * h,
            self.origin.1 - self.scale * v,
        )
    }

    /// The obstacle planes' traces at the depth `depth` along the view's normal, hatched on
    /// the obstacle's side.
    pub(crate) fn obstacles(&mut self, planes: &[Plane], depth: f64) {
        let view = self.view;
        let b = self.bounds;
        for plane in planes {
            let n = plane.normal;
            let (nh, nv) = (view.horizontal.dot(&n), view.vertical.dot(&n));
            let len = (nh * nh + nv * nv).sqrt();
            if len < 1e-9 {
                continue;
            }
            let c = n.dot(&plane.point) - view.normal.dot(&n) * depth;
            // the trace's nearest point to the world origin, and its direction
            let foot = (nh * c / (len * len), nv * c / (len * len));
            let dir = (-nv / len, nh / len);
            let span = 4.0 * (b.h1 - b.h0).max(b.v1 - b.v0);
            let a = self.px((foot.0 - span * dir.0, foot.1 - span * dir.1));
            let e = self.px((foot.0 + span * dir.0, foot.1 + span * dir.1));
            let _ = writeln!(
                self.svg,
                "<g class=\"obstacle\" data-name=\"{}\"><line x1=\"{}\" y1=\"{}\" x2=\"{}\" \
                 y2=\"{}\" stroke=\"black\" stroke-width=\"2\"/>",
                escape(&plane.name),
                f(a.0),
                f(a.1),
                f(e.0),
                f(e.1)
            );
            // hatching on the obstacle's side (−N), every 20 px along the trace
            let into = (-nh / len, nv / len); // −N in pixels (y down)
            let length = (e.0 - a.0).hypot(e.1 - a.1);
            let along = ((e.0 - a.0) / length, (e.1 - a.1) / length);
            // only where the drawing is: the trace's stretch inside the canvas
            let steps = (length / 20.0).min(4000.0) as usize;
            for k in 0..=steps {
                let u = k as f64 / steps.max(1) as f64;
                let p = (a.0 + u * (e.0 - a.0), a.1 + u * (e.1 - a.1));
                if p.0 < -20.0 || p.0 > WIDTH + 20.0 || p.1 < -20.0 || p.1 > HEIGHT + 20.0 {
                    continue;
                }
                let _ = writeln!(
                    self.svg,
                    "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"gray\"/>",
                    f(p.0),
                    f(p.1),
                    f(p.0 + 10.0 * into.0 + 6.0 * along.0),
                    f(p.1 + 10.0 * into.1 + 6.0 * along.1)
                );
            }
            self.svg.push_str("</g>\n");
        }
    }

    /// Open the `j`-th frame, the sample at `t`, shown from `t` to `next` (the next frame's
    /// time; none: to the end) of a run of `t_total` seconds.
    pub(crate) fn open_frame(&mut self, j: usize, t: f64, next: Option<f64>, t_total: f64) {
        let start = t / t_total;
        let (values, times) = match (start > 0.0, next.map(|n| n / t_total)) {
            (false, Some(e)) => ("inline;none".to_string(), format!("0;{e:.6}")),
            (true, Some(e)) => (
                "none;inline;none".to_string(),
                format!("0;{start:.6};{e:.6}"),
            ),
            (false, None) => ("inline".to_string(), "0".to_string()),
            (true, None) => ("none;inline".to_string(), format!("0;{start:.6}")),
        };
        let _ = write!(
            self.svg,
            "<g class=\"frame\" data-t=\"{t:e}\" display=\"{d}\">\
             <animate attributeName=\"display\" values=\"{values}\" keyTimes=\"{times}\" \
             dur=\"{t_total:e}s\" calcMode=\"discrete\" repeatCount=\"indefinite\"/>",
            d = if j == 0 { "inline" } else { "none" },
        );
    }

    /// Close a frame at `t` with its caption: the time and the impacts up to it.
    pub(crate) fn close_frame(&mut self, t: f64, impacts: usize) {
        let _ = writeln!(
            self.svg,
            "<text x=\"10\" y=\"20\" font-family=\"sans-serif\" font-size=\"14\">t = {t:.4} s, \
             {impacts} impact{}</text></g>",
            if impacts == 1 { "" } else { "s" }
        );
    }

    /// The finished document.
    pub(crate) fn close(mut self) -> String {
        self.svg.push_str("</svg>\n");
        self.svg
    }
}

/// The animation of `sim` as one SVG document (see the module docs).
pub fn to_svg(name: &str, setup: &Setup, sim: &Simulation) -> String {
    let view = View::of(setup);
    let chosen = frames(sim.samples.len());
    let outlines: Vec<Vec<(f64, f64)>> = chosen
        .iter()
        .map(|&k| outline(setup, &view, &sim.samples[k].state))
        .collect();
    // world bounds of the drawn body over the run, with its size as margin
    let mut bounds = Bounds::empty();
    let reach = match &setup.body.shape {
        Shape::Box { half } => half.norm(),
        Shape::Rod { half_length } => *half_length,
        Shape::Cylinder {
            radius,
            half_height,
        } => radius.hypot(*half_height),
        Shape::Sphere { radius } => *radius,
    };
    for o in &outlines {
        match &setup.body.shape {
            // its circle about the centre (the rim's marker on it)
            Shape::Sphere { radius } => bounds.hold(o[0], *radius),
            _ => o.iter().for_each(|&p| bounds.hold(p, 0.0)),
        }
    }
    let bounds = bounds.grown(0.5 * reach.max(1e-9));
    let t_total = sim.t_end.max(f64::MIN_POSITIVE);
    let mut canvas = Canvas::open(name, view, bounds, t_total, chosen.len());
    // the obstacles, at the body's depth at the start
    canvas.obstacles(&setup.planes, view.normal.dot(&setup.start.x));
    for (j, (&k, o)) in chosen.iter().zip(&outlines).enumerate() {
        let sample = &sim.samples[k];
        let next = chosen.get(j + 1).map(|&n| sim.samples[n].t);
        canvas.open_frame(j, sample.t, next, t_total);
        let px: Vec<(f64, f64)> = o.iter().map(|&p| canvas.px(p)).collect();
        let svg = &mut canvas.svg;
        match &setup.body.shape {
            Shape::Box { .. } | Shape::Cylinder { .. } => {
                let pts: Vec<String> = px
                    .iter()
                    .map(|p| format!("{},{}", f(p.0), f(p.1)))
                    .collect();
                let _ = write!(
                    svg,
                    "<polygon class=\"body\" points=\"{}\" fill=\"#9ecae1\" stroke=\"#08519c\" \
                     stroke-width=\"2\"/>",
                    pts.join(" ")
                );
            }
            Shape::Rod { .. } => {
                let _ = write!(
                    svg,
                    "<line class=\"body\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" \
                     stroke=\"#08519c\" stroke-width=\"4\"/>",
                    f(px[0].0),
                    f(px[0].1),
                    f(px[1].0),
                    f(px[1].1)
                );
            }
            Shape::Sphere { radius } => {
                let _ = write!(
                    svg,
                    "<circle class=\"body\" cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#9ecae1\" \
                     stroke=\"#08519c\" stroke-width=\"2\"/><line x1=\"{}\" y1=\"{}\" x2=\"{}\" \
                     y2=\"{}\" stroke=\"#08519c\"/>",
                    f(px[0].0),
                    f(px[0].1),
                    f(radius * canvas.scale),
                    f(px[0].0),
                    f(px[0].1),
                    f(px[1].0),
                    f(px[1].1)
                );
            }
        }
        let impacts = sim.impacts.iter().filter(|r| r.t <= sample.t).count();
        canvas.close_frame(sample.t, impacts);
    }
    canvas.close()
}

pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
