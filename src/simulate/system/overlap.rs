//! Whether two members overlap: a check that the contacts the system watches
//! ([`super::gaps`]) let no two bodies pass through each other. Every contact between spheres,
//! boxes and thin rods is watched — a feature (a corner, a rod's end, a sphere) on a plane or a
//! box's face, an edge (a box's, a rod's segment) on an edge, a sphere on a sphere, an edge or
//! a corner — so in exact arithmetic nothing is left for it to catch (cylinders, whose rims
//! have no contact with another body, are refused in a system). It stays as the guard of that
//! claim: a contact missed between two watched features (a step that jumped past the region
//! where its gap is defined, say) would let the bodies pass through each other silently; after
//! every step the run measures how deep each pair of members overlaps, and stops, naming them,
//! when one does beyond the tolerance (a wrong history is not printed as if it were right).
//!
//! Two boxes: the separating-axis test (Gottschalk, Lin and Manocha, *OBBTree*, SIGGRAPH 1996)
//! over the fifteen axes — the three face normals of each and the nine cross products of their
//! edges — gives the largest separation s = |T · L| − (r_a + r_b) over unit axes L (T the line of
//! the centres, r the box's projected half width); s < 0 on every axis is an overlap at least
//! −s deep along the best. A rod is a box of zero thickness (half edges (0, 0, L/2)): against a
//! box the axes the test needs — the box's face normals and the rod's direction crossed with the
//! box's edges — are among the fifteen, and the others it tries are separating axes too. A
//! sphere and a box: the distance from the sphere's centre to the box (the centre clamped into
//! the box in its axes) less the radius; a sphere and a rod: the distance from its centre to the
//! segment less the radius. Two thin rods have no volume to overlap: their crossing is the edge
//! contact's alone.

use nalgebra::Matrix3;

use super::super::body::{Shape, V3};
use super::members::{Member, SystemState};

/// The separation of boxes at `xa`, `ra` (rotation), half edges `ha` and `xb`, `rb`, `hb`: the
/// largest over the separating axes (negative: they overlap at least that deep).
pub fn boxes(xa: &V3, ra: &Matrix3<f64>, ha: &V3, xb: &V3, rb: &Matrix3<f64>, hb: &V3) -> f64 {
    let t = xb - xa;
    let width = |r: &Matrix3<f64>, h: &V3, l: &V3| -> f64 {
        (0..3).map(|k| h[k] * r.column(k).dot(l).abs()).sum()
    };
    let mut best = f64::NEG_INFINITY;
    let mut axis = |l: V3| {
        let len = l.norm();
        // an edge cross product of parallel edges is no axis (the face normals cover it)
        if len <= 1e-12 {
            return;
        }
        let l = l / len;
        best = best.max(t.dot(&l).abs() - width(ra, ha, &l) - width(rb, hb, &l));
    };
    for k in 0..3 {
        axis(ra.column(k).into());
        axis(rb.column(k).into());
    }
    for i in 0..3 {
        for j in 0..3 {
            axis(ra.column(i).cross(&rb.column(j)));
        }
    }
    best
}

/// The separation of a sphere (centre `c`, radius `r`) and the box at `xb`, `rb`, `hb`: the
/// distance from the centre to the box less the radius (negative: they overlap that deep).
pub fn sphere_box(c: &V3, r: f64, xb: &V3, rb: &Matrix3<f64>, hb: &V3) -> f64 {
    let local = rb.transpose() * (c - xb);
    let outside = V3::from_fn(|k, _| (local[k].abs() - hb[k]).max(0.0));
    if outside == V3::zeros() {
        // the centre inside the box: as deep as its nearest face, plus the radius
        let inside = (0..3)
            .map(|k| hb[k] - local[k].abs())
            .fold(f64::INFINITY, f64::min);
        -inside - r
    } else {
        outside.norm() - r
    }
}

/// The separation of a sphere (centre `c`, radius `r`) and the segment of half length `h` along
/// `d` (unit) about `x`: the distance from the centre to it less the radius.
pub fn sphere_segment(c: &V3, r: f64, x: &V3, d: &V3, h: f64) -> f64 {
    let t = d.dot(&(c - x)).clamp(-h, h);
    (c - x - d * t).norm() - r
}

/// A box's half edges, or a rod's as a box of zero thickness.
fn half_edges(shape: &Shape) -> Option<V3> {
    match shape {
        Shape::Box { half } => Some(*half),
        Shape::Rod { half_length } => Some(V3::new(0.0, 0.0, *half_length)),
        _ => None,
    }
}

/// The deepest overlap of two members at `s` beyond `tolerance` (m), as (a, b, depth); the
/// pairs `joined` holds together (a joint's members, which may overlap at their hinge) left
/// out.
pub fn deepest(
    members: &[Member],
    s: &SystemState,
    tolerance: f64,
    joined: impl Fn(usize, usize) -> bool,
) -> Option<(usize, usize, f64)> {
    let mut worst: Option<(usize, usize, f64)> = None;
    for a in 0..members.len() {
        for b in (a + 1..members.len()).filter(|&b| !joined(a, b)) {
            let (sa, sb) = (&members[a].body.shape, &members[b].body.shape);
            let segment = |rod: usize, half_length: f64, sphere: usize, radius: f64| {
                let d = s.rotation(rod).column(2).into();
                sphere_segment(&s.x[sphere], radius, &s.x[rod], &d, half_length)
            };
            let separation = match (sa, sb) {
                // two thin rods have no volume (module docs)
                (Shape::Rod { .. }, Shape::Rod { .. }) => continue,
                (Shape::Sphere { radius }, Shape::Box { half }) => {
                    sphere_box(&s.x[a], *radius, &s.x[b], &s.rotation(b), half)
                }
                (Shape::Box { half }, Shape::Sphere { radius }) => {
                    sphere_box(&s.x[b], *radius, &s.x[a], &s.rotation(a), half)
                }
                (Shape::Sphere { radius }, Shape::Rod { half_length }) => {
                    segment(b, *half_length, a, *radius)
                }
                (Shape::Rod { half_length }, Shape::Sphere { radius }) => {
                    segment(a, *half_length, b, *radius)
                }
                _ => match (half_edges(sa), half_edges(sb)) {
                    (Some(ha), Some(hb)) => {
                        boxes(&s.x[a], &s.rotation(a), &ha, &s.x[b], &s.rotation(b), &hb)
                    }
                    // two spheres are one watched contact; cylinders are not in systems
                    _ => continue,
                },
            };
            if separation < -tolerance && worst.is_none_or(|w| -separation > w.2) {
                worst = Some((a, b, -separation));
            }
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;

    fn turn(axis: V3, angle: f64) -> Matrix3<f64> {
        Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).into_inner()
    }

    /// Two unit cubes side by side along x: their separation is the gap between their faces,
    /// either way round, and an overlap is negative by its depth.
    #[test]
    fn aligned_cubes_are_as_far_apart_as_their_faces() {
        let h = V3::new(0.5, 0.5, 0.5);
        let i = Matrix3::identity();
        for (d, want) in [(1.25, 0.25), (1.0, 0.0), (0.9, -0.1)] {
            let s = boxes(&V3::zeros(), &i, &h, &V3::new(d, 0.0, 0.0), &i, &h);
            assert!((s - want).abs() < 1e-15, "{d}: {s}");
            let s = boxes(&V3::new(d, 0.0, 0.0), &i, &h, &V3::zeros(), &i, &h);
            assert!((s - want).abs() < 1e-15, "{d} swapped: {s}");
        }
    }

    /// Two cubes crossed edge on edge — a cube turned 45° about x above one turned 45° about
    /// y — are separated only along the cross product of the two edges (x × y = z): their
    /// lowest and highest edges are √2/2 from each centre, so at a distance d along z the
    /// separation is d − √2 exactly (no face normal separates them more).
    #[test]
    fn crossed_edges_are_separated_along_their_cross_product() {
        let h = V3::new(0.5, 0.5, 0.5);
        let (ra, rb) = (
            turn(V3::y(), std::f64::consts::FRAC_PI_4),
            turn(V3::x(), std::f64::consts::FRAC_PI_4),
        );
        for d in [1.5, 1.41, 1.3] {
            let s = boxes(&V3::zeros(), &ra, &h, &V3::new(0.0, 0.0, d), &rb, &h);
            assert!((s - (d - 2f64.sqrt())).abs() < 1e-12, "{d}: {s}");
        }
    }

    /// A rod as a box of zero thickness: lying across a box's top at a height d above it, its
    /// separation is d, beside the box's edge (crossing its line past the corner, tilted)
    /// the distance along the axis that separates them; a sphere beside its segment and past
    /// its end is as far as its nearest point.
    #[test]
    fn a_rod_is_a_box_of_zero_thickness() {
        let h = V3::new(0.5, 0.5, 0.5);
        let rod = V3::new(0.0, 0.0, 1.0);
        let i = Matrix3::identity();
        // the rod along x (body z turned onto x) over the box's top
        let along_x = turn(V3::y(), std::f64::consts::FRAC_PI_2);
        for d in [0.3, 0.0, -0.2] {
            let s = boxes(
                &V3::zeros(),
                &i,
                &h,
                &V3::new(0.2, 0.1, 0.5 + d),
                &along_x,
                &rod,
            );
            assert!((s - d).abs() < 1e-15, "{d}: {s}");
        }
        // the rod along y, 0.1 beyond the box's +x face and 0.1 above its top: √2·0.1 from the
        // box's edge, separated by 0.1 along x and along z (the test's value is the best axis',
        // a lower bound of the distance); moved to 0.05 inside both faces, it overlaps by 0.05
        // (every axis overlaps, x and z least)
        let along_y = turn(V3::x(), std::f64::consts::FRAC_PI_2);
        let s = boxes(
            &V3::zeros(),
            &i,
            &h,
            &V3::new(0.6, 0.0, 0.6),
            &along_y,
            &rod,
        );
        assert!((s - 0.1).abs() < 1e-15, "{s}");
        let s = boxes(
            &V3::zeros(),
            &i,
            &h,
            &V3::new(0.45, 0.0, 0.45),
            &along_y,
            &rod,
        );
        assert!((s + 0.05).abs() < 1e-15, "{s}");
        let x = V3::new(2.0, 0.0, 0.0);
        let beside = sphere_segment(&V3::new(2.3, 0.4, 0.0), 0.1, &x, &V3::x(), 1.0);
        assert!((beside - (0.4 - 0.1)).abs() < 1e-15, "{beside}");
        let past = sphere_segment(&V3::new(3.3, 0.4, 0.0), 0.1, &x, &V3::x(), 1.0);
        assert!((past - (0.5 - 0.1)).abs() < 1e-15, "{past}");
    }

    /// A sphere beside a box's face, off its edge and off its corner: the distance to the box
    /// less the radius.
    #[test]
    fn a_sphere_is_as_far_from_a_box_as_its_nearest_point() {
        let h = V3::new(1.0, 1.0, 1.0);
        let i = Matrix3::identity();
        let r = 0.5;
        let face = sphere_box(&V3::new(2.0, 0.0, 0.0), r, &V3::zeros(), &i, &h);
        assert!((face - 0.5).abs() < 1e-15);
        let edge = sphere_box(&V3::new(1.3, 1.4, 0.0), r, &V3::zeros(), &i, &h);
        assert!((edge - (0.5 - r)).abs() < 1e-15, "{edge}");
        let corner = sphere_box(&V3::new(1.2, 1.2, 1.1), r, &V3::zeros(), &i, &h);
        assert!((corner - ((0.04f64 + 0.04 + 0.01).sqrt() - r)).abs() < 1e-15);
        let inside = sphere_box(&V3::new(0.5, 0.0, 0.0), r, &V3::zeros(), &i, &h);
        assert!((inside - (-0.5 - r)).abs() < 1e-15);
    }
}
