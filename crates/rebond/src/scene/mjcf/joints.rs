//! Joints: `hinge`, `slide`, `ball` (one rebond joint each; several in one body chained through
//! light links) and `free` (no joint: a free body).

use glam::DVec3;
use roxmltree::Node;
use serde_json::{json, Map, Value};

use super::super::SceneError;
use super::frames::Frame;
use super::parse::{attribute_error, element_error};
use super::Importer;

/// A joint read from the file, in its body's frame.
pub(super) struct JointSpec {
    /// Its name: the file's, or `<body>/joint<k>` (from 1) for an unnamed one.
    pub(super) name: String,
    /// `"revolute"`, `"prismatic"` or `"ball"`; `None` for a free joint.
    pub(super) kind: Option<&'static str>,
    /// The entry's fields other than the names of its bodies, the anchor and the axis.
    pub(super) fields: Map<String, Value>,
    /// Anchor, body frame.
    pub(super) position: DVec3,
    /// Axis, body frame, unit.
    pub(super) axis: DVec3,
    /// MuJoCo's `ref`: the joint coordinate of the pose as written (rad or m).
    pub(super) reference: f64,
}

impl Importer {
    /// Reads the joint `node` of the body named `body` (the `k`-th joint of it, from 1).
    pub(super) fn joint(&self, node: Node, body: &str, k: usize) -> Result<JointSpec, SceneError> {
        let defaults = &self.defaults;
        let name = node
            .attribute("name")
            .map_or_else(|| format!("{body}/joint{k}"), str::to_owned);
        let kind_name = if node.has_tag_name("freejoint") {
            "free"
        } else {
            defaults.get(node, "type").unwrap_or("hinge")
        };
        let kind = match kind_name {
            "hinge" => Some("revolute"),
            "slide" => Some("prismatic"),
            "ball" => Some("ball"),
            "free" => None,
            other => {
                let message = format!("expected hinge, slide, ball or free, got \"{other}\"");
                return Err(attribute_error(node, "type", message));
            }
        };
        let angular = kind_name == "hinge";
        // An angle of a hinge is in the compiler's unit; a slide's values are lengths.
        let coordinate = |value: f64| {
            if angular {
                self.compiler.angle(value)
            } else {
                value
            }
        };
        let position = defaults
            .triple(node, "pos")?
            .map_or(DVec3::ZERO, DVec3::from_array);
        let axis = defaults
            .triple(node, "axis")?
            .map_or(DVec3::Z, DVec3::from_array);
        let axis = axis.try_normalize().ok_or_else(|| {
            attribute_error(node, "axis", "a joint axis must not be of zero length")
        })?;
        let reference = coordinate(defaults.number(node, "ref", 0.0)?);
        let mut fields = Map::new();
        let non_negative = |field: &str| -> Result<f64, SceneError> {
            let value = defaults.number(node, field, 0.0)?;
            if value < 0.0 {
                let message = format!("must not be negative, got {value}");
                return Err(attribute_error(node, field, message));
            }
            Ok(value)
        };
        let stiffness = non_negative("stiffness")?;
        let damping = non_negative("damping")?;
        let armature = non_negative("armature")?;
        let friction = non_negative("frictionloss")?;
        if kind.is_none() {
            return Ok(JointSpec {
                name,
                kind,
                fields,
                position,
                axis,
                reference,
            });
        }
        let range = defaults.numbers(node, "range", Some(2))?;
        let limited = match (defaults.flag(node, "limited")?, &range) {
            (Some(true), None) => {
                return Err(attribute_error(
                    node,
                    "limited",
                    "a limited joint needs a `range`",
                ))
            }
            (Some(limited), _) => limited,
            (None, range) => range.is_some(),
        };
        if let (true, Some(range)) = (limited, &range) {
            let (low, high) = (coordinate(range[0]), coordinate(range[1]));
            if low > high {
                let message = format!("min must not exceed max, got [{}, {}]", range[0], range[1]);
                return Err(attribute_error(node, "range", message));
            }
            if kind == Some("ball") {
                // MuJoCo limits a ball joint's whole rotation angle to range[1]; rebond limits
                // its swing away from the axis by that angle.
                fields.insert("swing_limit".into(), json!(high));
            } else {
                fields.insert("limits".into(), json!([low - reference, high - reference]));
            }
        }
        if kind != Some("ball") {
            if stiffness > 0.0 || damping > 0.0 {
                let spring_reference = coordinate(defaults.number(node, "springref", 0.0)?);
                fields.insert(
                    "spring".into(),
                    json!({
                        "stiffness": stiffness,
                        "damping": damping,
                        "reference": spring_reference - reference,
                    }),
                );
            }
            if armature > 0.0 {
                fields.insert("armature".into(), json!(armature));
            }
        } else if stiffness > 0.0 || damping > 0.0 || armature > 0.0 {
            let field = if stiffness > 0.0 {
                "stiffness"
            } else if damping > 0.0 {
                "damping"
            } else {
                "armature"
            };
            let message = "rebond's ball joints take no spring, damping or armature";
            return Err(attribute_error(node, field, message));
        }
        if friction > 0.0 {
            fields.insert("friction".into(), json!(friction));
        }
        Ok(JointSpec {
            name,
            kind,
            fields,
            position,
            axis,
            reference,
        })
    }

    /// The joint entries of a body named `body` at `frame` (world, MuJoCo's frame) with the
    /// `joints` read from it, hung from `parent` (`None` for the world): one joint, or a chain
    /// through light links `<body>/<joint>` (their bodies are in `links`, in order). Returns
    /// the links' names.
    pub(super) fn joint_entries(
        &self,
        node: Node,
        body: &str,
        frame: &Frame,
        parent: Option<&str>,
        joints: &[JointSpec],
    ) -> Result<(Vec<Value>, Vec<String>), SceneError> {
        if joints.iter().any(|joint| joint.kind.is_none()) {
            if joints.len() > 1 {
                return Err(element_error(
                    node,
                    "a free joint must be the body's only joint",
                ));
            }
            return Ok((Vec::new(), Vec::new()));
        }
        let turn = self.turn;
        let mut entries = Vec::new();
        let mut links = Vec::new();
        let mut previous = parent.map(str::to_owned);
        for (index, joint) in joints.iter().enumerate() {
            let next = if index + 1 == joints.len() {
                body.to_owned()
            } else {
                let link = format!("{body}/{}", joint.name);
                links.push(link.clone());
                link
            };
            let anchor = turn * frame.point(joint.position);
            let axis = turn * (frame.rotation * joint.axis);
            let mut entry = json!({
                "name": joint.name,
                "type": joint.kind,
                "body_b": next,
                "anchor": anchor.to_array(),
            });
            if let Some(previous) = &previous {
                entry["body_a"] = json!(previous);
            }
            if joint.kind != Some("ball") || joint.fields.contains_key("swing_limit") {
                entry["axis"] = json!(axis.to_array());
            }
            for (key, value) in &joint.fields {
                entry[key] = value.clone();
            }
            entries.push(entry);
            previous = Some(next);
        }
        Ok((entries, links))
    }
}
