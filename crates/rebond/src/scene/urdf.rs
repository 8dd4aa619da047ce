//! URDF robots (`.urdf`) read as scenes: the robot becomes the scene's JSON model, which then
//! goes through the ordinary loader, as MJCF models do (`docs/urdf.md` lists what is read, what
//! is approximated and what is refused).
//!
//! Each link is a body named as the link, placed at its link frame (the root a static body
//! unless the base floats, [`UrdfOptions`]); each joint a rebond joint
//! named as the joint (a `floating` joint none: its child is a free body), a `mimic` a coupling
//! `q_f − m q_l` held at `o`. URDF is Z-up and rebond Y-up: the whole robot is turned by `C`, a
//! rotation of −90° about X (`(x, y, z)` becomes `(x, z, −y)`), while what is given in a link's
//! own frame (collisions, inertial, joint axes) keeps the file's local numbers. The element
//! paths of errors, the frames, the turn `C` and the mesh reader are the MJCF importer's
//! (`mjcf/parse.rs`, `mjcf/frames.rs`, `mjcf/geoms.rs`).

use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

use glam::{DMat3, DQuat, DVec3, EulerRot};
use roxmltree::{Document, Node};
use serde_json::{json, Value};

use super::mjcf::frames::{z_up_to_y_up, Frame};
use super::mjcf::geoms::{read_mesh, rotation_json};
use super::mjcf::parse::{attribute_error, element_error, path as path_of};
use super::{LoadError, SceneError};

/// How a URDF robot is read ([`super::Scene::from_urdf_with`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct UrdfOptions {
    /// Whether the root link is a free body (a walking robot, a drone); `false` (default): it is
    /// a static body, fixed where the file puts it (an arm on its base), its inertial unread.
    pub floating_base: bool,
}

/// Radius of the stand-in sphere of a link without collision geometry, m: the body needs a
/// shape, which collides with nothing (its collision groups are empty).
const NO_COLLISION_RADIUS: f64 = 0.01;

/// The scene model of the URDF robot `bytes`.
pub(super) fn import(
    bytes: &[u8],
    folder: &Path,
    options: UrdfOptions,
) -> Result<Value, LoadError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|error| SceneError::new("", format!("not UTF-8 text: {error}")))?;
    let document = Document::parse(text)
        .map_err(|error| SceneError::new("", format!("invalid XML: {error}")))?;
    let robot = document.root_element();
    if robot.tag_name().name() != "robot" {
        return Err(element_error(robot, "a URDF file's root element is `robot`").into());
    }
    Robot::read(robot)?.scene(options, folder)
}

/// Refuses an attribute of `node` not in `known`, and a child element not in `children`.
fn check_element(node: Node, known: &[&str], children: &[&str]) -> Result<(), SceneError> {
    if let Some(attribute) = (node.attributes()).find(|a| !known.contains(&a.name())) {
        return Err(attribute_error(
            node,
            attribute.name(),
            "unknown attribute (docs/urdf.md lists what is read)",
        ));
    }
    for child in node.children().filter(Node::is_element) {
        if !children.contains(&child.tag_name().name()) {
            return Err(element_error(
                child,
                "unknown element (docs/urdf.md lists what is read)",
            ));
        }
    }
    Ok(())
}

/// The one child element `tag` of `node`, if any; two are an error.
fn child<'a, 'input>(
    node: Node<'a, 'input>,
    tag: &str,
) -> Result<Option<Node<'a, 'input>>, SceneError> {
    let mut found = node
        .children()
        .filter(|child| child.is_element() && child.tag_name().name() == tag);
    let first = found.next();
    if let Some(second) = found.next() {
        return Err(element_error(second, format!("a second `{tag}`")));
    }
    Ok(first)
}

/// The numbers of attribute `name`, `count` of them, finite; `None` when it is absent.
fn numbers(node: Node, name: &str, count: usize) -> Result<Option<Vec<f64>>, SceneError> {
    let Some(text) = node.attribute(name) else {
        return Ok(None);
    };
    let values: Vec<f64> = text
        .split_whitespace()
        .map(str::parse::<f64>)
        .collect::<Result<_, _>>()
        .map_err(|_| attribute_error(node, name, format!("not a number list: \"{text}\"")))?;
    if values.len() != count {
        let message = format!("{count} numbers needed, {} given", values.len());
        return Err(attribute_error(node, name, message));
    }
    if values.iter().any(|value| !value.is_finite()) {
        return Err(attribute_error(node, name, "not finite"));
    }
    Ok(Some(values))
}

fn number(node: Node, name: &str) -> Result<Option<f64>, SceneError> {
    Ok(numbers(node, name, 1)?.map(|values| values[0]))
}

fn required_number(node: Node, name: &str) -> Result<f64, SceneError> {
    number(node, name)?.ok_or_else(|| attribute_error(node, name, "required attribute is missing"))
}

fn vector(node: Node, name: &str) -> Result<Option<DVec3>, SceneError> {
    Ok(numbers(node, name, 3)?.map(|values| DVec3::new(values[0], values[1], values[2])))
}

/// The `origin` child of `node` (`xyz`, `rpy`: roll about X, pitch about Y, yaw about Z, applied
/// in that order about the fixed axes) as a frame in `node`'s parent's; identity when absent.
fn origin(node: Node) -> Result<Frame, SceneError> {
    let Some(origin) = child(node, "origin")? else {
        return Ok(Frame::IDENTITY);
    };
    check_element(origin, &["xyz", "rpy"], &[])?;
    let position = vector(origin, "xyz")?.unwrap_or(DVec3::ZERO);
    let rpy = vector(origin, "rpy")?.unwrap_or(DVec3::ZERO);
    let rotation = DQuat::from_euler(EulerRot::ZYX, rpy.z, rpy.y, rpy.x);
    Ok(Frame { position, rotation })
}

fn vector_json(vector: DVec3) -> Value {
    json!([vector.x, vector.y, vector.z])
}

/// A link as read.
struct Link<'a, 'input> {
    node: Node<'a, 'input>,
    name: String,
}

/// A joint as read.
struct Joint<'a, 'input> {
    node: Node<'a, 'input>,
    name: String,
    kind: String,
    parent: usize,
    child: usize,
    origin: Frame,
}

/// The robot's links and joints, the joints' tree checked.
struct Robot<'a, 'input> {
    links: Vec<Link<'a, 'input>>,
    joints: Vec<Joint<'a, 'input>>,
    /// The joint whose child each link is.
    parent_joint: Vec<Option<usize>>,
    root: usize,
}

impl<'a, 'input> Robot<'a, 'input> {
    fn read(robot: Node<'a, 'input>) -> Result<Self, SceneError> {
        check_element(robot, &["name"], &["link", "joint", "material"])?;
        let mut links = Vec::new();
        let mut link_index = HashMap::new();
        for node in robot.children().filter(|n| n.has_tag_name("link")) {
            let name = (node.attribute("name"))
                .ok_or_else(|| attribute_error(node, "name", "required attribute is missing"))?;
            if link_index.insert(name.to_owned(), links.len()).is_some() {
                return Err(attribute_error(node, "name", "a second link of this name"));
            }
            links.push(Link {
                node,
                name: name.to_owned(),
            });
        }
        let mut joints = Vec::new();
        let mut parent_joint = vec![None; links.len()];
        for node in robot.children().filter(|n| n.has_tag_name("joint")) {
            check_element(
                node,
                &["name", "type"],
                &[
                    "origin", "parent", "child", "axis", "limit", "dynamics", "mimic",
                ],
            )?;
            let name = (node.attribute("name"))
                .ok_or_else(|| attribute_error(node, "name", "required attribute is missing"))?;
            let kind = (node.attribute("type"))
                .ok_or_else(|| attribute_error(node, "type", "required attribute is missing"))?;
            let link_of = |tag: &str| -> Result<usize, SceneError> {
                let element = child(node, tag)?.ok_or_else(|| {
                    element_error(node, format!("required element `{tag}` is missing"))
                })?;
                check_element(element, &["link"], &[])?;
                let link = (element.attribute("link")).ok_or_else(|| {
                    attribute_error(element, "link", "required attribute is missing")
                })?;
                (link_index.get(link).copied()).ok_or_else(|| {
                    attribute_error(element, "link", format!("no link is named \"{link}\""))
                })
            };
            let (parent, child_link) = (link_of("parent")?, link_of("child")?);
            if let Some(other) = parent_joint[child_link] {
                let other: &Joint = &joints[other];
                let message = format!(
                    "link \"{}\" is already the child of joint \"{}\"",
                    links[child_link].name, other.name
                );
                return Err(element_error(node, message));
            }
            parent_joint[child_link] = Some(joints.len());
            joints.push(Joint {
                node,
                name: name.to_owned(),
                kind: kind.to_owned(),
                parent,
                child: child_link,
                origin: origin(node)?,
            });
        }
        let mut roots = (0..links.len()).filter(|&link| parent_joint[link].is_none());
        let root = roots
            .next()
            .ok_or_else(|| element_error(robot, "no root link: the joints make a loop"))?;
        if let Some(second) = roots.next() {
            let message = format!(
                "two root links, \"{}\" and \"{}\": every link but one must be a joint's child",
                links[root].name, links[second].name
            );
            return Err(element_error(robot, message));
        }
        Ok(Self {
            links,
            joints,
            parent_joint,
            root,
        })
    }

    /// The links in tree order (each after its parent) with their world frames, URDF axes.
    fn frames(&self) -> Result<Vec<(usize, Frame)>, SceneError> {
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); self.links.len()];
        for (index, joint) in self.joints.iter().enumerate() {
            children[joint.parent].push(index);
        }
        let mut order = vec![(self.root, Frame::IDENTITY)];
        let mut next = 0;
        while next < order.len() {
            let (link, frame) = order[next];
            for &joint in &children[link] {
                let joint = &self.joints[joint];
                order.push((joint.child, frame.then(&joint.origin)));
            }
            next += 1;
        }
        if order.len() < self.links.len() {
            let lost = (0..self.links.len()).find(|link| order.iter().all(|(l, _)| l != link));
            let node = lost.map_or(self.links[self.root].node, |link| self.links[link].node);
            return Err(element_error(
                node,
                "this link is in a loop of joints, not in the tree",
            ));
        }
        Ok(order)
    }

    /// The scene model.
    /// The scene model; mesh files are found relative to `folder`.
    fn scene(&self, options: UrdfOptions, folder: &Path) -> Result<Value, LoadError> {
        let turn = z_up_to_y_up();
        let order = self.frames()?;
        let mut world_frames = vec![Frame::IDENTITY; self.links.len()];
        let mut bodies = Vec::new();
        for &(link, frame) in &order {
            world_frames[link] = frame;
            let fixed = link == self.root && !options.floating_base;
            bodies.push(self.body(link, frame, turn, fixed, folder)?);
        }
        let mut joints = Vec::new();
        let mut actuators = Vec::new();
        let mut couplings = Vec::new();
        for &(link, _) in &order {
            let Some(index) = self.parent_joint[link] else {
                continue;
            };
            let joint = &self.joints[index];
            let frame = world_frames[joint.child];
            if let Some(entry) = self.joint(joint, frame, turn, &mut actuators)? {
                joints.push(entry);
            }
            if let Some(mimic) = child(joint.node, "mimic")? {
                couplings.push(self.mimic(joint, mimic)?);
            }
        }
        Ok(json!({
            "bodies": bodies, "joints": joints, "actuators": actuators, "couplings": couplings,
        }))
    }

    /// The body of link `index`, whose frame is `frame` (URDF world): static when `fixed` (a
    /// root fixed to the world: a static body rather than a light dynamic one held by a joint,
    /// whose coupling rows would spin it against the joint's), dynamic otherwise.
    fn body(
        &self,
        index: usize,
        frame: Frame,
        turn: DQuat,
        fixed: bool,
        folder: &Path,
    ) -> Result<Value, LoadError> {
        let link = &self.links[index];
        let node = link.node;
        check_element(node, &["name"], &["inertial", "visual", "collision"])?;
        let mut children = Vec::new();
        for collision in node.children().filter(|n| n.has_tag_name("collision")) {
            children.push(collision_child(collision, folder)?);
        }
        let mut body = json!({
            "name": link.name,
            "position": vector_json(turn * frame.position),
            "rotation": rotation_json((turn * frame.rotation).normalize()),
        });
        body["shape"] = if children.is_empty() {
            body["collision_groups"] = json!({"memberships": 0, "filter": 0});
            json!({"type": "sphere", "radius": NO_COLLISION_RADIUS})
        } else {
            json!({"type": "compound", "children": children})
        };
        let inertial = child(node, "inertial")?;
        if fixed {
            body["type"] = json!("static");
            // Checked all the same: a bad inertial is a bad file.
            inertial.map(mass_properties).transpose()?;
        } else if let Some(inertial) = inertial {
            body["mass_properties"] = mass_properties(inertial)?;
        }
        Ok(body)
    }

    /// The rebond joint of `joint` (none for a `floating` one), its child's frame `frame` (URDF
    /// world); an `effort` limit adds a torque actuator to `actuators`.
    fn joint(
        &self,
        joint: &Joint,
        frame: Frame,
        turn: DQuat,
        actuators: &mut Vec<Value>,
    ) -> Result<Option<Value>, SceneError> {
        let node = joint.node;
        let mut entry = json!({
            "name": joint.name,
            "body_a": self.links[joint.parent].name,
            "body_b": self.links[joint.child].name,
            "anchor": vector_json(turn * frame.position),
        });
        let needs_axis = matches!(
            joint.kind.as_str(),
            "revolute" | "continuous" | "prismatic" | "planar"
        );
        let axis = match child(node, "axis")? {
            Some(axis) => {
                check_element(axis, &["xyz"], &[])?;
                let local = vector(axis, "xyz")?
                    .ok_or_else(|| attribute_error(axis, "xyz", "required attribute is missing"))?;
                if local.length() < 1.0e-9 {
                    return Err(attribute_error(axis, "xyz", "a zero axis"));
                }
                Some(local.normalize())
            }
            None if needs_axis => {
                let message = format!("a {} joint needs an `axis`", joint.kind);
                return Err(element_error(node, message));
            }
            None => None,
        };
        let world_axis = axis.map(|axis| turn * (frame.rotation * axis));
        match joint.kind.as_str() {
            "revolute" | "continuous" => entry["type"] = json!("revolute"),
            "prismatic" => entry["type"] = json!("prismatic"),
            "fixed" => entry["type"] = json!("fixed"),
            "floating" => return Ok(None),
            "planar" => {
                // A joint frame whose Z is the axis: the plane is its X and Y.
                let local = axis.unwrap_or(DVec3::Z);
                let to_axis = DQuat::from_rotation_arc(DVec3::Z, local);
                entry["type"] = json!("generic");
                entry["frame"] = rotation_json((turn * frame.rotation * to_axis).normalize());
                entry["axes"] = json!({"x": "free", "y": "free", "rz": "free"});
            }
            other => {
                let message = format!(
                    "unknown joint type \"{other}\" (revolute, continuous, prismatic, fixed, \
                     floating, planar)"
                );
                return Err(attribute_error(node, "type", message));
            }
        }
        if let (Some(axis), false) = (world_axis, joint.kind == "planar") {
            entry["axis"] = vector_json(axis);
        }
        let takes_limit = matches!(joint.kind.as_str(), "revolute" | "prismatic");
        if let Some(limit) = child(node, "limit")? {
            check_element(limit, &["lower", "upper", "effort", "velocity"], &[])?;
            if takes_limit {
                let lower = number(limit, "lower")?.unwrap_or(0.0);
                let upper = number(limit, "upper")?.unwrap_or(0.0);
                entry["limits"] = json!([lower, upper]);
            } else if limit.attribute("lower").is_some() || limit.attribute("upper").is_some() {
                let message = format!("a {} joint has no position limits", joint.kind);
                return Err(element_error(limit, message));
            }
            if let Some(effort) = number(limit, "effort")? {
                if effort < 0.0 {
                    return Err(attribute_error(limit, "effort", "negative"));
                }
                if effort > 0.0 && joint.kind != "planar" {
                    actuators.push(json!({
                        "name": joint.name, "joint": joint.name, "type": "motor",
                        "ctrl_range": [-effort, effort],
                    }));
                }
            }
            if number(limit, "velocity")?.is_some_and(|velocity| velocity < 0.0) {
                return Err(attribute_error(limit, "velocity", "negative"));
            }
        } else if takes_limit {
            let message = format!("a {} joint needs a `limit`", joint.kind);
            return Err(element_error(node, message));
        }
        if let Some(dynamics) = child(node, "dynamics")? {
            check_element(dynamics, &["damping", "friction"], &[])?;
            if !needs_axis || joint.kind == "planar" {
                let message = format!("a {} joint takes no `dynamics`", joint.kind);
                return Err(element_error(dynamics, message));
            }
            if let Some(damping) = number(dynamics, "damping")? {
                entry["spring"] = json!({"stiffness": 0.0, "damping": damping});
            }
            if let Some(friction) = number(dynamics, "friction")? {
                entry["friction"] = json!(friction);
            }
        }
        Ok(Some(entry))
    }

    /// The coupling of a `mimic` element of `joint`: `q_f − m q_l` held at `o`.
    fn mimic(&self, joint: &Joint, mimic: Node) -> Result<Value, SceneError> {
        check_element(mimic, &["joint", "multiplier", "offset"], &[])?;
        let leader = (mimic.attribute("joint"))
            .ok_or_else(|| attribute_error(mimic, "joint", "required attribute is missing"))?;
        let leads = self.joints.iter().find(|other| other.name == leader);
        let Some(leads) = leads else {
            let message = format!("no joint is named \"{leader}\"");
            return Err(attribute_error(mimic, "joint", message));
        };
        for coupled in [joint, leads] {
            if !matches!(
                coupled.kind.as_str(),
                "revolute" | "continuous" | "prismatic"
            ) {
                let message = format!("a {} joint cannot mimic or be mimicked", coupled.kind);
                return Err(element_error(mimic, message));
            }
        }
        let multiplier = number(mimic, "multiplier")?.unwrap_or(1.0);
        let offset = number(mimic, "offset")?.unwrap_or(0.0);
        Ok(json!({
            "name": format!("{}/mimic", joint.name),
            "joints": [
                {"joint": joint.name, "coefficient": 1.0},
                {"joint": leader, "coefficient": -multiplier},
            ],
            "limits": [offset, offset],
        }))
    }
}

/// The scene's `mass_properties` of an `inertial` element: mass, centre of mass at the origin,
/// the inertia turned from the origin's axes to the link's (`R I Rᵀ`).
fn mass_properties(inertial: Node) -> Result<Value, SceneError> {
    check_element(inertial, &[], &["origin", "mass", "inertia"])?;
    let origin = origin(inertial)?;
    let mass_node = child(inertial, "mass")?
        .ok_or_else(|| element_error(inertial, "required element `mass` is missing"))?;
    check_element(mass_node, &["value"], &[])?;
    let mass = required_number(mass_node, "value")?;
    if mass <= 0.0 {
        return Err(element_error(
            mass_node,
            format!("the mass {mass} is not positive"),
        ));
    }
    let inertia_node = child(inertial, "inertia")?
        .ok_or_else(|| element_error(inertial, "required element `inertia` is missing"))?;
    let names = ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"];
    check_element(inertia_node, &names, &[])?;
    let mut values = [0.0; 6];
    for (value, name) in values.iter_mut().zip(names) {
        *value = required_number(inertia_node, name)?;
    }
    let [ixx, ixy, ixz, iyy, iyz, izz] = values;
    let local = DMat3::from_cols_array(&[ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz]);
    let turn = DMat3::from_quat(origin.rotation);
    let link = turn * local * turn.transpose();
    Ok(json!({
        "mass": mass,
        "center_of_mass": vector_json(origin.position),
        "inertia": [
            link.x_axis.x, link.y_axis.y, link.z_axis.z,
            link.y_axis.x, link.z_axis.x, link.z_axis.y,
        ],
    }))
}

/// The compound child of a `collision` element: its geometry at its origin, link frame; a mesh
/// file (STL or OBJ, relative to `folder`) is the convex hull of its vertices.
fn collision_child(collision: Node, folder: &Path) -> Result<Value, LoadError> {
    check_element(collision, &["name"], &["origin", "geometry"])?;
    let mut frame = origin(collision)?;
    let geometry = child(collision, "geometry")?
        .ok_or_else(|| element_error(collision, "required element `geometry` is missing"))?;
    check_element(geometry, &[], &["box", "cylinder", "sphere", "mesh"])?;
    let mut shapes = geometry.children().filter(Node::is_element);
    let shape = shapes
        .next()
        .ok_or_else(|| element_error(geometry, "a geometry needs a shape"))?;
    if let Some(second) = shapes.next() {
        return Err(element_error(second, "a geometry holds one shape").into());
    }
    let positive = |name: &str| -> Result<f64, SceneError> {
        let value = required_number(shape, name)?;
        if value <= 0.0 {
            return Err(attribute_error(
                shape,
                name,
                format!("{value} is not positive"),
            ));
        }
        Ok(value)
    };
    let json_shape = match shape.tag_name().name() {
        "box" => {
            check_element(shape, &["size"], &[])?;
            let size = vector(shape, "size")?
                .ok_or_else(|| attribute_error(shape, "size", "required attribute is missing"))?;
            if size.min_element() <= 0.0 {
                return Err(attribute_error(shape, "size", "a size is not positive").into());
            }
            json!({"type": "box", "half_extents": vector_json(0.5 * size)})
        }
        "sphere" => {
            check_element(shape, &["radius"], &[])?;
            json!({"type": "sphere", "radius": positive("radius")?})
        }
        "cylinder" => {
            check_element(shape, &["radius", "length"], &[])?;
            // URDF's cylinder runs along its Z, rebond's along Y: turned +90° about X.
            frame.rotation = (frame.rotation * DQuat::from_rotation_x(FRAC_PI_2)).normalize();
            let (radius, length) = (positive("radius")?, positive("length")?);
            json!({"type": "cylinder", "radius": radius, "half_height": 0.5 * length})
        }
        _ => {
            check_element(shape, &["filename", "scale"], &[])?;
            let name = (shape.attribute("filename")).ok_or_else(|| {
                attribute_error(shape, "filename", "required attribute is missing")
            })?;
            if name.contains("://") && !name.starts_with("file://") {
                let message = "only paths relative to the URDF file (or file://) are read: \
                               package:// and other URLs are not resolved";
                return Err(attribute_error(shape, "filename", message).into());
            }
            let file = folder.join(name.trim_start_matches("file://"));
            let place = format!("{}@filename", path_of(shape));
            let scale = vector(shape, "scale")?.unwrap_or(DVec3::ONE);
            if scale.min_element() <= 0.0 {
                return Err(attribute_error(shape, "scale", "a scale is not positive").into());
            }
            let points: Vec<Value> = read_mesh(&file, &place)?
                .0
                .into_iter()
                .map(|vertex| vector_json(vertex.as_dvec3() * scale))
                .collect();
            json!({"type": "convex_hull", "points": points})
        }
    };
    Ok(json!({
        "shape": json_shape,
        "position": vector_json(frame.position),
        "rotation": rotation_json(frame.rotation),
    }))
}
