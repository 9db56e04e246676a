//! A scene of several bodies brought to the scalar type a solve runs in: its
//! [`System`] ([`crate::mechanics::system`]), every failure named by the scene's key.

use crate::mechanics::body::RigidBody;
use crate::mechanics::screw::{Screw, Vec3};
use crate::mechanics::system::{System, SystemBody, SystemError, SystemJoint, SystemScrew};
use crate::scalar::Scalar;

use super::model::system::SystemSpec;
use super::{Scene, SceneError};

impl Scene {
    /// The system of bodies this scene describes, in `T`.
    ///
    /// # Errors
    /// A [`SceneError`] naming the key: a number out of `T`'s range or without an exact value,
    /// a body or contact without physical meaning, a twist before impact a joint forbids.
    pub fn system<T: Scalar>(&self) -> Result<System<T>, SceneError> {
        let Some(spec) = &self.system else {
            return Err(self.error(
                "body",
                None,
                "not a scene of several bodies: write its bodies as [[body]] tables",
            ));
        };
        let mut bodies = Vec::with_capacity(spec.bodies.len());
        let mut twists = Vec::with_capacity(spec.bodies.len());
        for (b, body) in spec.bodies.iter().enumerate() {
            let at = |k: &str| format!("body[{b}].{k}");
            let mass = self.value::<T>(&body.mass, &at("mass"))?;
            let d = self.vec3::<T>(&body.inertia, &at("inertia"))?;
            let rigid = match &body.inertia_products {
                None => RigidBody::principal(mass, d),
                Some(p) => {
                    let p = self.vec3::<T>(p, &at("inertia_products"))?;
                    let (xy, xz, yz) = (p[0].clone(), p[1].clone(), p[2].clone());
                    RigidBody::with_tensor(
                        mass,
                        [
                            [d[0].clone(), xy.clone(), xz.clone()],
                            [xy, d[1].clone(), yz.clone()],
                            [xz, yz, d[2].clone()],
                        ],
                    )
                }
            };
            bodies.push(SystemBody {
                body: rigid,
                centre: self.vec3(&body.centre, &at("position"))?,
            });
            twists.push(Screw::new(
                self.vec3(&body.angular_velocity, &at("angular_velocity"))?,
                self.vec3(&body.velocity, &at("velocity"))?,
            ));
        }
        let mut contacts = Vec::with_capacity(self.contacts.len());
        for (i, c) in self.contacts.iter().enumerate() {
            let key = |k: &str| format!("contact[{i}].{k}");
            let point = self.vec3(&c.point, &key("point"))?;
            let normal = match &c.normal {
                Some(n) => self.vec3(n, &key("normal"))?,
                None => return Err(self.error(&key("normal"), None, "missing (required)")),
            };
            contacts.push(self.contact(i, c, point, normal)?);
        }
        let mut joints = Vec::with_capacity(spec.joints.len());
        for (j, joint) in spec.joints.iter().enumerate() {
            let at = |k: &str| format!("joint[{j}].{k}");
            let vector =
                |v: &Option<[crate::number::Number; 3]>, k: &str| -> Result<Vec3<T>, SceneError> {
                    match v {
                        Some(v) => self.vec3(v, &at(k)),
                        None => Ok(Vec3::zeros()),
                    }
                };
            let (point, axis) = (
                vector(&joint.anchor, "anchor")?,
                vector(&joint.axis, "axis")?,
            );
            joints.push(SystemJoint {
                joint: joint.kind.joint(point, axis),
                pair: joint.pair,
            });
        }
        let mut levers = Vec::with_capacity(spec.levers.len());
        for (i, (first, second)) in spec.levers.iter().enumerate() {
            let key = format!("contact[{i}].point");
            let second = second
                .as_ref()
                .map(|r| self.vec3::<T>(r, &key))
                .transpose()?;
            levers.push((self.vec3::<T>(first, &key)?, second));
        }
        let twists = SystemScrew(twists);
        System::new(
            bodies.clone(),
            twists.clone(),
            contacts,
            spec.pairs.clone(),
            joints.clone(),
        )
        .and_then(|s| s.with_lever_arms(levers))
        .map_err(|e| self.system_error(spec, e, (&bodies, &twists, &joints)))
    }

    /// A [`SystemError`] as a scene error at the key it concerns; the system as read, to say
    /// how a joint's bodies move when their twists break it.
    fn system_error<T: Scalar>(
        &self,
        spec: &SystemSpec,
        e: SystemError,
        (bodies, twists, joints): (&[SystemBody<T>], &SystemScrew<T>, &[SystemJoint<T>]),
    ) -> SceneError {
        let key = match &e {
            SystemError::Body { body, error } => {
                let field = error.field.to_string();
                format!(
                    "body[{body}].{}",
                    field.strip_prefix("body.").unwrap_or(&field)
                )
            }
            SystemError::Contact { error, .. } => error.field.to_string(),
            SystemError::NoContacts | SystemError::PairsMismatch { .. } => "contact".into(),
            SystemError::UnknownBody { what, index, .. }
            | SystemError::SameBody { what, index, .. } => {
                format!("{what}[{index}].bodies")
            }
            SystemError::JointViolated { joint, .. } => format!("joint[{joint}]"),
            SystemError::NotSemidefinite(_) => "joint".into(),
        };
        let message = match &e {
            SystemError::Body { error, .. } | SystemError::Contact { error, .. } => {
                error.reason.to_string()
            }
            SystemError::JointViolated { joint, kind, .. } => {
                joint_violation(spec, kind, bodies, twists, &joints[*joint])
            }
            other => other.to_string(),
        };
        let value = match &e {
            SystemError::JointViolated { joint, kind, .. } => {
                let pair = spec.joints[*joint].pair;
                let mut names = vec![format!("\"{}\"", spec.bodies[pair.first].name)];
                names.extend(pair.second.map(|b| format!("\"{}\"", spec.bodies[b].name)));
                Some(format!(
                    "{{ kind = \"{kind}\", bodies = [{}] }}",
                    names.join(", ")
                ))
            }
            _ => None,
        };
        self.error(&key, value, message)
    }
}

/// Why the twists before impact break `joint` (of kind `kind`): how its bodies move where
/// they are joined — the velocity of its anchor counted on each body, and their angular
/// velocities — and which keys to change.
fn joint_violation<T: Scalar>(
    spec: &SystemSpec,
    kind: &str,
    bodies: &[SystemBody<T>],
    twists: &SystemScrew<T>,
    joint: &SystemJoint<T>,
) -> String {
    // Exact and symbolic values as written (a symbolic speed has no f64: it printed NaN).
    let show = |v: &Vec3<T>| {
        let t = |x: &T| {
            let v = crate::report::Value::of(x);
            v.exact.unwrap_or_else(|| format!("{}", v.f64))
        };
        format!("({}, {}, {})", t(&v[0]), t(&v[1]), t(&v[2]))
    };
    let name = |b: Option<usize>| match b {
        Some(b) => format!("\"{}\"", spec.bodies[b].name),
        None => "the ground".to_string(),
    };
    let (first, second) = (joint.pair.first, joint.pair.second);
    let omega = |b: Option<usize>| b.map_or_else(Vec3::zeros, |b| twists.0[b].top());
    let mut how = Vec::new();
    if let Some(p) = joint.joint.anchor() {
        let at = |b: Option<usize>| {
            b.map_or_else(Vec3::zeros, |b| {
                let v = &twists.0[b];
                v.bottom() + v.top().cross(&(p.clone() - bodies[b].centre.clone()))
            })
        };
        how.push(format!(
            "at its anchor {}, {} moves at {} m/s and {} at {} m/s",
            show(p),
            name(Some(first)),
            show(&at(Some(first))),
            name(second),
            show(&at(second))
        ));
    }
    how.push(format!(
        "{} turns at {} rad/s and {} at {} rad/s",
        name(Some(first)),
        show(&omega(Some(first))),
        name(second),
        show(&omega(second))
    ));
    let mut keys = vec![format!(
        "`body[{first}].velocity`, `body[{first}].angular_velocity`"
    )];
    keys.extend(second.map(|b| format!("`body[{b}].velocity`, `body[{b}].angular_velocity`")));
    format!(
        "the velocities before impact break this {kind} joint: its bodies move relative to each \
         other along a motion it blocks ({}). Give {} values the joint allows: the anchor moves \
         with both bodies, and a hinge lets them turn relative to each other about its axis only",
        how.join("; "),
        keys.join(" and ")
    )
}
