//! A scene of several bodies brought to the scalar type a solve runs in: its
//! [`System`] ([`crate::mechanics::system`]), every failure named by the scene's key.

use crate::mechanics::body::RigidBody;
use crate::mechanics::constraint::Joint;
use crate::mechanics::screw::{Screw, Vec3};
use crate::mechanics::system::{System, SystemBody, SystemError, SystemJoint, SystemScrew};
use crate::scalar::Scalar;

use super::model::system::{SystemJointKind, SystemSpec};
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
            let vector = |v: &Option<[crate::number::Number; 3]>, k: &str| -> Result<Vec3<T>, SceneError> {
                match v {
                    Some(v) => self.vec3(v, &at(k)),
                    None => Ok(Vec3::zeros()),
                }
            };
            let (point, axis) = (vector(&joint.anchor, "anchor")?, vector(&joint.axis, "axis")?);
            joints.push(SystemJoint {
                joint: match joint.kind {
                    SystemJointKind::Revolute => Joint::Revolute { point, axis },
                    SystemJointKind::Prismatic => Joint::Prismatic { axis },
                    SystemJointKind::Cylindrical => Joint::Cylindrical { point, axis },
                    SystemJointKind::Spherical => Joint::Spherical { point },
                    SystemJointKind::Planar => Joint::Planar { normal: axis },
                    SystemJointKind::Fixed => Joint::Fixed { point },
                },
                pair: joint.pair,
            });
        }
        System::new(
            bodies,
            SystemScrew(twists),
            contacts,
            spec.pairs.clone(),
            joints,
        )
        .map_err(|e| self.system_error(spec, e))
    }

    /// A [`SystemError`] as a scene error at the key it concerns.
    fn system_error(&self, spec: &SystemSpec, e: SystemError) -> SceneError {
        let key = match &e {
            SystemError::Body { body, error } => {
                let field = error.field.to_string();
                format!("body[{body}].{}", field.strip_prefix("body.").unwrap_or(&field))
            }
            SystemError::Contact { error, .. } => error.field.to_string(),
            SystemError::NoContacts => "contact".into(),
            SystemError::UnknownBody { what, index, .. } | SystemError::SameBody { what, index, .. } => {
                format!("{what}[{index}].bodies")
            }
            SystemError::JointViolated { joint, .. } => format!("joint[{joint}]"),
            SystemError::NotSemidefinite(_) => "joint".into(),
        };
        let message = match &e {
            SystemError::Body { error, .. } | SystemError::Contact { error, .. } => {
                error.reason.to_string()
            }
            SystemError::JointViolated { joint, .. } => {
                let names = |p: &crate::mechanics::system::Pair| match p.second {
                    Some(b) => format!(
                        "\"{}\" and \"{}\"",
                        spec.bodies[p.first].name, spec.bodies[b].name
                    ),
                    None => format!("\"{}\" and the ground", spec.bodies[p.first].name),
                };
                format!(
                    "{e}: the bodies {} must move as the joint allows before impact (check their \
                     `velocity` and `angular_velocity`: a point shared by both moves with both)",
                    names(&spec.joints[*joint].pair)
                )
            }
            other => other.to_string(),
        };
        self.error(&key, None, message)
    }
}
