//! Obstacles: planes in the world frame that contacts may name.
//!
//! An `[[obstacle]]` is a plane with the normal N pointing *out of the obstacle*, toward the
//! body, and optionally a point P on it. A contact that names it takes the body's outward
//! normal n = −N — the sign convention cannot be got wrong — and is checked against it: the
//! centre of mass must lie on the side N points to, the contact point on the plane (when P is
//! given), and a box's named corner must be one of its lowest along N (else the box would pass
//! through the plane). [`touching_corners`] lists a box's corners that touch a plane.

use toml_edit::{Item, Table};

use super::super::SceneError;
use super::super::read::{Reader, short};
use super::shape::Shape;
use super::term::{Mat3, Term, Vec3, add, apply, dot};

/// One obstacle plane.
#[derive(Clone, Debug)]
pub(crate) struct Obstacle {
    /// Its `name`, if given.
    pub(crate) name: Option<String>,
    /// N, out of the obstacle (world).
    pub(crate) normal: Vec3,
    /// A point P on the plane (world), if given.
    pub(crate) point: Option<Vec3>,
    /// `partial = true`: the contacts may name only some of the corners that touch it.
    pub(crate) partial: bool,
    /// `material = { young, poisson }`, for Hertz's stiffness ([`super::hertz`]).
    pub(crate) material: Option<super::hertz::Material>,
}

impl Obstacle {
    /// How messages call it: `obstacle "floor"` or `obstacle[1]`.
    pub(crate) fn label(&self, i: usize) -> String {
        match &self.name {
            Some(n) => format!("obstacle \"{n}\""),
            None => format!("obstacle[{i}]"),
        }
    }
}

impl Reader<'_> {
    /// The `[[obstacle]]` tables.
    pub(super) fn obstacles(&self, root: &Table) -> Result<Vec<Obstacle>, SceneError> {
        let arr = match root.get("obstacle") {
            None => return Ok(Vec::new()),
            Some(Item::ArrayOfTables(arr)) => arr,
            Some(other) => {
                return Err(self.err(
                    "obstacle",
                    Some(short(other)),
                    "must be [[obstacle]] tables (name, normal, point, partial)",
                ));
            }
        };
        let mut out: Vec<Obstacle> = Vec::with_capacity(arr.len());
        for (i, t) in arr.iter().enumerate() {
            let at = format!("obstacle[{i}]");
            self.only_keys(t, &at, &["name", "normal", "point", "partial", "material"])?;
            let partial = match t.get("partial") {
                None => false,
                Some(item) => item.as_bool().ok_or_else(|| {
                    self.err(
                        &format!("{at}.partial"),
                        Some(short(item)),
                        "must be true or false: whether the contacts may name only some of the \
                         corners that touch this obstacle",
                    )
                })?,
            };
            let name = match t.get("name") {
                None => None,
                Some(n) => {
                    let n = self.string(n, &format!("{at}.name"))?;
                    if out.iter().any(|o| o.name.as_deref() == Some(n.as_str())) {
                        return Err(self.err(
                            &format!("{at}.name"),
                            Some(format!("\"{n}\"")),
                            "two obstacles have this name",
                        ));
                    }
                    Some(n)
                }
            };
            let nk = format!("{at}.normal");
            let normal = self.triple(self.get(t, "normal", &at)?, &nk)?;
            self.nonzero(&normal, &nk, "an obstacle's normal")?;
            let point = match t.get("point") {
                None => None,
                Some(p) => Some(
                    self.triple(p, &format!("{at}.point"))?
                        .each_ref()
                        .map(Term::of),
                ),
            };
            out.push(Obstacle {
                name,
                normal: normal.each_ref().map(Term::of),
                point,
                partial,
                material: self.material(t, &at)?,
            });
        }
        Ok(out)
    }

    /// The obstacle a contact names (`obstacle = "floor"` or `obstacle = 0`).
    pub(super) fn obstacle_ref(
        &self,
        item: &Item,
        key: &str,
        obstacles: &[Obstacle],
    ) -> Result<usize, SceneError> {
        let names: Vec<String> = obstacles
            .iter()
            .enumerate()
            .map(|(i, o)| o.name.clone().map_or(i.to_string(), |n| format!("\"{n}\"")))
            .collect();
        let found = match (item.as_str(), item.as_integer()) {
            (Some(n), _) => obstacles.iter().position(|o| o.name.as_deref() == Some(n)),
            (_, Some(i)) => usize::try_from(i).ok().filter(|&i| i < obstacles.len()),
            _ => None,
        };
        found.ok_or_else(|| {
            self.err(
                key,
                Some(short(item)),
                if obstacles.is_empty() {
                    "there is no [[obstacle]] to name; declare one (normal out of the obstacle)"
                        .to_string()
                } else {
                    format!("no such obstacle; the scene has: {}", names.join(", "))
                },
            )
        })
    }
}

/// A box's corners (sign patterns) that touch the plane with normal `n` (world) when the body
/// has the pose `r`: those lowest along n. `cmp` compares two heights when it can.
pub(crate) fn touching_corners(
    dims: &Vec3,
    r: &Mat3,
    n: &Vec3,
    mut cmp: impl FnMut(&Term, &Term) -> Option<std::cmp::Ordering>,
) -> Vec<[i64; 3]> {
    let heights: Vec<([i64; 3], Term)> = Shape::corners()
        .into_iter()
        .map(|s| (s, dot(&apply(r, &Shape::corner(dims, s)), n)))
        .collect();
    let mut lowest: Vec<usize> = vec![0];
    for k in 1..heights.len() {
        match cmp(&heights[k].1, &heights[lowest[0]].1) {
            Some(std::cmp::Ordering::Less) => lowest = vec![k],
            Some(std::cmp::Ordering::Equal) => lowest.push(k),
            _ => {}
        }
    }
    lowest.into_iter().map(|k| heights[k].0).collect()
}

/// The world point of a body point p: position + R p.
pub(crate) fn world(position: &Vec3, r: &Mat3, p: &Vec3) -> Vec3 {
    add(position, &apply(r, p))
}
