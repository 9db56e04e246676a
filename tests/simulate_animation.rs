//! `simulate --animation`: the SVG read back as XML and every frame checked against the run it
//! draws — the body's outline at each frame is the projection of the body at that sample
//! (recomputed here from the state, not from the drawing code), the frames are shown one at a
//! time and tile the run's time, the obstacle is the floor's trace.
//!
//! Tolerance: coordinates are written with three decimals (10⁻³ px), so a drawn vertex is
//! within 10⁻³ px of the projection; 2·10⁻³ allowed.

use inertance::report::animation::{View, to_svg};
use inertance::scene::SimulationScene;
use inertance::simulate::{Shape, simulate};
use nalgebra::Vector3;

fn attr_f64s(node: &roxmltree::Node, name: &str) -> Vec<f64> {
    node.attribute(name)
        .unwrap_or_else(|| panic!("attribute {name}"))
        .split([' ', ',', ';'])
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().expect("a number"))
        .collect()
}

/// The root's map from the world to the canvas: the view's projection, scaled and moved to the
/// origin written on the root (`data-scale`, `data-origin`).
fn to_canvas(root: &roxmltree::Node, view: View) -> impl Fn(&Vector3<f64>) -> (f64, f64) {
    let scale = attr_f64s(root, "data-scale")[0];
    let origin = attr_f64s(root, "data-origin");
    move |p| {
        let (h, v) = view.project(p);
        (origin[0] + scale * h, origin[1] - scale * v)
    }
}

#[test]
fn every_frame_draws_the_body_where_the_run_has_it() {
    let scene = SimulationScene::load(std::path::Path::new("examples/simulate/tumbling-box.toml"))
        .expect("reads");
    let sim = simulate(&scene.setup).expect("runs");
    let svg = to_svg(&scene.name, &scene.setup, &sim);
    let doc = roxmltree::Document::parse(&svg).expect("the SVG is well-formed XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    let origin = attr_f64s(&root, "data-origin");
    let eh = attr_f64s(&root, "data-horizontal");
    let ev = attr_f64s(&root, "data-vertical");
    let view = View::of(&scene.setup);
    // the view written is the view of the run: a planar run in x–z, x right, z up
    assert_eq!(eh, vec![1.0, 0.0, 0.0]);
    assert_eq!(ev, vec![0.0, 0.0, 1.0]);
    let px = to_canvas(&root, view);
    let frames: Vec<_> = root
        .children()
        .filter(|n| n.attribute("class") == Some("frame"))
        .collect();
    assert_eq!(frames.len(), sim.samples.len(), "one frame per sample");
    assert_eq!(
        root.attribute("data-frames"),
        Some(frames.len().to_string().as_str())
    );
    let half = match &scene.setup.body.shape {
        Shape::Box { half } => *half,
        _ => unreachable!("a box"),
    };
    let mut previous_end = 0.0;
    for (k, (frame, sample)) in frames.iter().zip(&sim.samples).enumerate() {
        let t: f64 = frame.attribute("data-t").expect("t").parse().expect("t");
        assert_eq!(t, sample.t);
        // the outline: every drawn vertex is a projected corner, and every projected corner
        // lies inside or on the drawn polygon (it is their convex hull)
        let polygon = frame
            .children()
            .find(|n| n.attribute("class") == Some("body"))
            .expect("the body");
        let drawn: Vec<(f64, f64)> = attr_f64s(&polygon, "points")
            .chunks(2)
            .map(|c| (c[0], c[1]))
            .collect();
        let r = sample.state.rotation();
        let corners: Vec<(f64, f64)> = (0..8)
            .map(|i| {
                let c = Vector3::new(
                    if i & 1 == 0 { -half.x } else { half.x },
                    if i & 2 == 0 { -half.y } else { half.y },
                    if i & 4 == 0 { -half.z } else { half.z },
                );
                px(&(sample.state.x + r * c))
            })
            .collect();
        for d in &drawn {
            assert!(
                corners
                    .iter()
                    .any(|c| (c.0 - d.0).abs() < 2e-3 && (c.1 - d.1).abs() < 2e-3),
                "frame {k}: vertex {d:?} is no corner"
            );
        }
        for c in &corners {
            // inside a convex polygon drawn counter-clockwise in (h, v), i.e. clockwise on
            // the y-down canvas: every edge's cross product ≤ 0 (within the rounding)
            for e in 0..drawn.len() {
                let (a, b) = (drawn[e], drawn[(e + 1) % drawn.len()]);
                let cross = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
                let edge = (b.0 - a.0).hypot(b.1 - a.1);
                assert!(
                    cross <= 2e-3 * edge,
                    "frame {k}: corner {c:?} outside the outline"
                );
            }
        }
        // shown from its time to the next frame's: discrete keyTimes tiling the run
        let animate = frame
            .children()
            .find(|n| n.tag_name().name() == "animate")
            .expect("its animation");
        assert_eq!(animate.attribute("calcMode"), Some("discrete"));
        assert_eq!(animate.attribute("attributeName"), Some("display"));
        let times = attr_f64s(&animate, "keyTimes")
            .into_iter()
            .collect::<Vec<f64>>();
        let values: Vec<&str> = animate
            .attribute("values")
            .expect("values")
            .split(';')
            .collect();
        assert_eq!(times.len(), values.len());
        assert!(times.windows(2).all(|w| w[0] < w[1]), "keyTimes increase");
        let shown = values
            .iter()
            .position(|v| *v == "inline")
            .expect("shown once");
        assert_eq!(values.iter().filter(|v| **v == "inline").count(), 1);
        let from = times[shown];
        assert!((from - sample.t / sim.t_end).abs() < 1e-6);
        assert!(
            (from - previous_end).abs() < 1e-6,
            "frame {k} starts where {} ends",
            k.max(1) - 1
        );
        previous_end = times.get(shown + 1).copied().unwrap_or(1.0);
    }
    assert!(
        (previous_end - 1.0).abs() < 1e-12,
        "the last frame holds to the end"
    );
    // the floor: its trace is the horizontal line z = 0
    let floor = root
        .children()
        .find(|n| n.attribute("class") == Some("obstacle"))
        .expect("the floor");
    let line = floor
        .children()
        .find(|n| n.tag_name().name() == "line")
        .expect("a line");
    for y in ["y1", "y2"] {
        let y: f64 = line.attribute(y).expect("y").parse().expect("y");
        assert!((y - origin[1]).abs() < 2e-3, "the floor at z = 0");
    }
}

#[test]
fn the_cli_writes_the_animation_and_refuses_another_extension() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    let file = dir.join("ball.svg");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args([
            "simulate",
            "examples/simulate/bouncing-ball.toml",
            "--animation",
        ])
        .arg(&file)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(0));
    let svg = std::fs::read_to_string(&file).expect("written");
    let doc = roxmltree::Document::parse(&svg).expect("well-formed");
    let circles = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "circle")
        .count();
    assert!(circles > 10, "the ball in every frame");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args([
            "simulate",
            "examples/simulate/bouncing-ball.toml",
            "--animation",
        ])
        .arg(dir.join("ball.gif"))
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--animation"));
    assert!(!dir.join("ball.gif").exists(), "nothing written");
}

/// A system of spheres: Newton's cradle under LZB, one frame per sample, every ball's circle
/// at the projection of its centre at that sample (the view recomputed here from the run's
/// gravity: none, so x to the right), of its radius; the striker nearly stops at the impact
/// and the last ball carries on with nearly all of its velocity (derivations/lzb.md: −0.0710
/// and 0.9945 m/s).
#[test]
fn every_frame_of_a_system_draws_each_sphere_where_the_run_has_it() {
    use inertance::report::animation_system;
    use inertance::scene::AnySimulation;
    use inertance::simulate::Law;
    use inertance::simulate::system::simulate_system;
    let path = std::path::Path::new("examples/simulate/cradle-3.toml");
    let (name, mut setup) = match AnySimulation::load(path).expect("reads") {
        AnySimulation::System(s) => (s.name, s.setup),
        AnySimulation::Body(_) => unreachable!("a system"),
    };
    setup.law = Law::Lzb;
    let sim = simulate_system(&setup);
    assert!(sim.stopped.is_none());
    let svg = animation_system::to_svg(&name, &setup, &sim);
    let doc = roxmltree::Document::parse(&svg).expect("the SVG is well-formed XML");
    let root = doc.root_element();
    let scale = attr_f64s(&root, "data-scale")[0];
    let view = View::looking(setup.options.gravity, None);
    assert_eq!(attr_f64s(&root, "data-horizontal"), vec![1.0, 0.0, 0.0]);
    let px = to_canvas(&root, view);
    let frames: Vec<_> = root
        .children()
        .filter(|n| n.attribute("class") == Some("frame"))
        .collect();
    assert_eq!(frames.len(), sim.samples.len(), "one frame per sample");
    let mut drawn_x: Vec<Vec<f64>> = Vec::new();
    for (k, (frame, sample)) in frames.iter().zip(&sim.samples).enumerate() {
        let t: f64 = frame.attribute("data-t").expect("t").parse().expect("t");
        assert_eq!(t, sample.t);
        let circles: Vec<_> = frame
            .children()
            .filter(|n| n.attribute("class") == Some("body"))
            .collect();
        assert_eq!(circles.len(), setup.members.len(), "frame {k}: every ball");
        let mut xs = Vec::new();
        for ((c, x), sphere) in circles.iter().zip(&sample.state.x).zip(&setup.members) {
            assert_eq!(c.tag_name().name(), "circle");
            assert_eq!(c.attribute("data-name"), Some(sphere.name.as_str()));
            let (cx, cy, r) = (
                attr_f64s(c, "cx")[0],
                attr_f64s(c, "cy")[0],
                attr_f64s(c, "r")[0],
            );
            let want = px(x);
            assert!(
                (cx - want.0).abs() < 2e-3 && (cy - want.1).abs() < 2e-3,
                "frame {k}: {} at ({cx}, {cy}), the run has {want:?}",
                sphere.name
            );
            assert!((r - sphere.radius().expect("a ball") * scale).abs() < 2e-3);
            xs.push(cx);
        }
        drawn_x.push(xs);
    }
    // after the impact (the sample after it, to the end): the drawn displacements
    let t_impact = sim.impacts[0].t;
    let after = sim
        .samples
        .iter()
        .rposition(|s| s.t == t_impact)
        .expect("the sample after the impact");
    let last = drawn_x.len() - 1;
    let moved = |b: usize| drawn_x[last][b] - drawn_x[after][b];
    let flight = (sim.t_end - t_impact) * scale;
    assert!(
        (moved(2) - 0.9945 * flight).abs() < 1e-3 * flight,
        "the last ball moves on: {} px vs {} px",
        moved(2),
        0.9945 * flight
    );
    assert!(
        moved(0).abs() < 0.08 * flight,
        "the striker nearly stops: {} px",
        moved(0)
    );
    assert!(moved(0) < 0.0, "and recoils a little");
}

/// A system of boxes: the box dropped on the box on the floor, one frame per sample, each box
/// a polygon whose vertices are projected corners of the box at that sample (the view recomputed
/// here: gravity along −z, so the vertical plane through x) and which holds every projected
/// corner (a convex outline: no corner outside it); the base drawn at the same place in every
/// frame, and the top box drawn resting on it in the last.
#[test]
fn every_frame_of_a_system_draws_each_box_where_the_run_has_it() {
    use inertance::report::animation_system;
    use inertance::scene::AnySimulation;
    use inertance::simulate::system::simulate_system;
    let path = std::path::Path::new("examples/simulate/box-on-box.toml");
    let (name, setup) = match AnySimulation::load(path).expect("reads") {
        AnySimulation::System(s) => (s.name, s.setup),
        AnySimulation::Body(_) => unreachable!("a system"),
    };
    let sim = simulate_system(&setup);
    assert!(sim.stopped.is_none());
    let svg = animation_system::to_svg(&name, &setup, &sim);
    let doc = roxmltree::Document::parse(&svg).expect("the SVG is well-formed XML");
    let root = doc.root_element();
    let view = View::looking(setup.options.gravity, None);
    let px = to_canvas(&root, view);
    let frames: Vec<_> = root
        .children()
        .filter(|n| n.attribute("class") == Some("frame"))
        .collect();
    assert_eq!(frames.len(), sim.samples.len(), "one frame per sample");
    let mut base_drawn: Option<Vec<f64>> = None;
    for (k, (frame, sample)) in frames.iter().zip(&sim.samples).enumerate() {
        let polygons: Vec<_> = frame
            .children()
            .filter(|n| n.attribute("class") == Some("body"))
            .collect();
        assert_eq!(polygons.len(), 2, "frame {k}: both boxes");
        for (b, (p, member)) in polygons.iter().zip(&setup.members).enumerate() {
            assert_eq!(p.tag_name().name(), "polygon");
            assert_eq!(p.attribute("data-name"), Some(member.name.as_str()));
            let points = attr_f64s(p, "points");
            let corners: Vec<(f64, f64)> = animation_system::corners(&setup, &sample.state, b)
                .iter()
                .map(|c| px(c))
                .collect();
            assert_eq!(corners.len(), 8);
            let vertices: Vec<(f64, f64)> = points.chunks(2).map(|v| (v[0], v[1])).collect();
            for v in &vertices {
                assert!(
                    corners
                        .iter()
                        .any(|c| (c.0 - v.0).abs() < 2e-3 && (c.1 - v.1).abs() < 2e-3),
                    "frame {k}: {} vertex {v:?} is no corner",
                    member.name
                );
            }
            // every corner inside or on the outline (counter-clockwise in the canvas' mirror:
            // the sign of the turns is one for all edges)
            let n = vertices.len();
            for c in &corners {
                let sides: Vec<f64> = (0..n)
                    .map(|i| {
                        let (a, b) = (vertices[i], vertices[(i + 1) % n]);
                        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
                    })
                    .collect();
                let scale = 1e-3 * (1.0 + sides.iter().fold(0.0f64, |m, s| m.max(s.abs())));
                assert!(
                    sides.iter().all(|s| *s >= -scale) || sides.iter().all(|s| *s <= scale),
                    "frame {k}: {} corner {c:?} outside its outline",
                    member.name
                );
            }
            if member.name == "base" {
                match &base_drawn {
                    None => base_drawn = Some(points.clone()),
                    Some(first) => assert_eq!(first, &points, "frame {k}: the base moved"),
                }
            }
        }
    }
    // the last frame: the top box's lowest drawn vertex on the base's highest
    let last = frames.last().expect("frames");
    let lowest_top = |name: &str| {
        let p = last
            .children()
            .find(|n| n.attribute("data-name") == Some(name))
            .expect("drawn");
        let ys: Vec<f64> = attr_f64s(&p, "points").chunks(2).map(|v| v[1]).collect();
        (
            ys.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            ys.iter().copied().fold(f64::INFINITY, f64::min),
        )
    };
    // canvas y grows downwards: the top box's largest y is its lowest point, the base's
    // smallest its highest
    let (top_low, _) = lowest_top("top");
    let (_, base_high) = lowest_top("base");
    assert!(
        (top_low - base_high).abs() < 2e-3,
        "{top_low} vs {base_high}"
    );
}
