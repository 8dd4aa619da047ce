//! Actuators (`motor`, `position`, `velocity` on joints) and fixed tendons (`couplings`).

use std::collections::HashMap;

use roxmltree::Node;
use serde_json::{json, Value};

use super::super::SceneError;
use super::parse::{attribute_error, check_attributes, check_children, element_error, Attributes};
use super::Importer;

/// The attributes of `motor`, `position` and `velocity`.
pub(super) const ACTUATOR: Attributes = Attributes {
    read: &[
        "name",
        "class",
        "joint",
        "gear",
        "ctrlrange",
        "ctrllimited",
        "kp",
        "kv",
    ],
    accepted: &[
        "forcerange",
        "forcelimited",
        "group",
        "user",
        "dampratio",
        "timeconst",
    ],
};

/// The attributes of a fixed tendon.
pub(super) const TENDON: Attributes = Attributes {
    read: &[
        "name",
        "class",
        "range",
        "limited",
        "stiffness",
        "damping",
        "springlength",
    ],
    accepted: &[
        "group",
        "user",
        "rgba",
        "material",
        "width",
        "margin",
        "solreflimit",
        "solimplimit",
        "solreffriction",
        "solimpfriction",
        "frictionloss",
    ],
};

/// The attributes of a tendon's joint.
const TENDON_JOINT: Attributes = Attributes {
    read: &["joint", "coef"],
    accepted: &[],
};

impl Importer {
    /// The scene's `actuators` from `<actuator>`.
    pub(super) fn actuators(&self, node: Node) -> Result<Vec<Value>, SceneError> {
        check_children(node, &["motor", "position", "velocity"], &[])?;
        let mut entries = Vec::new();
        for (index, child) in node.children().filter(Node::is_element).enumerate() {
            check_attributes(child, &ACTUATOR)?;
            self.defaults.check_class(child)?;
            let defaults = &self.defaults;
            let kind = child.tag_name().name();
            let joint = defaults.get(child, "joint").ok_or_else(|| {
                attribute_error(child, "joint", "required: rebond's actuators drive joints")
            })?;
            if !self.joint_names.contains(joint) {
                let message = format!("no hinge or slide joint is named \"{joint}\"");
                return Err(attribute_error(child, "joint", message));
            }
            let gear = defaults.numbers(child, "gear", None)?;
            let gear = match gear.as_deref() {
                None => 1.0,
                Some([gear, rest @ ..]) if rest.iter().all(|value| *value == 0.0) => *gear,
                Some(_) => {
                    let message = "rebond reads the first gear value only; the others must be 0";
                    return Err(attribute_error(child, "gear", message));
                }
            };
            let name = child
                .attribute("name")
                .map_or_else(|| format!("actuator{index}"), str::to_owned);
            let mut entry = json!({ "name": name, "joint": joint, "type": kind, "gear": gear });
            let range = defaults.numbers(child, "ctrlrange", Some(2))?;
            let limited = match (defaults.flag(child, "ctrllimited")?, &range) {
                (Some(true), None) => {
                    let message = "a limited actuator needs a `ctrlrange`";
                    return Err(attribute_error(child, "ctrllimited", message));
                }
                (Some(limited), _) => limited,
                (None, range) => range.is_some(),
            };
            if let (true, Some(range)) = (limited, range) {
                entry["ctrl_range"] = json!(range);
            }
            match kind {
                "position" => {
                    entry["kp"] = json!(defaults.number(child, "kp", 1.0)?);
                    entry["kv"] = json!(defaults.number(child, "kv", 0.0)?);
                }
                "velocity" => entry["kv"] = json!(defaults.number(child, "kv", 1.0)?),
                _ => {}
            }
            entries.push(entry);
        }
        Ok(entries)
    }

    /// The scene's `couplings` from `<tendon>`'s fixed tendons; `references` gives each joint's
    /// MuJoCo `ref`, which rebond's coordinates start from.
    pub(super) fn couplings(
        &self,
        node: Node,
        references: &HashMap<String, f64>,
    ) -> Result<Vec<Value>, SceneError> {
        check_children(node, &["fixed"], &[])?;
        let mut entries = Vec::new();
        for (index, tendon) in node.children().filter(Node::is_element).enumerate() {
            check_attributes(tendon, &TENDON)?;
            check_children(tendon, &["joint"], &[])?;
            self.defaults.check_class(tendon)?;
            let defaults = &self.defaults;
            let mut joints = Vec::new();
            // MuJoCo's length Σ cᵢ qᵢ counts from qpos = 0, rebond's from the pose as written.
            let mut offset = 0.0;
            for joint in tendon.children().filter(Node::is_element) {
                check_attributes(joint, &TENDON_JOINT)?;
                let name = joint
                    .attribute("joint")
                    .ok_or_else(|| attribute_error(joint, "joint", "required"))?;
                let reference = references.get(name).ok_or_else(|| {
                    attribute_error(
                        joint,
                        "joint",
                        format!("no hinge or slide joint is named \"{name}\""),
                    )
                })?;
                let coefficient = defaults.number(joint, "coef", 1.0)?;
                offset += coefficient * reference;
                joints.push(json!({ "joint": name, "coefficient": coefficient }));
            }
            if joints.is_empty() {
                return Err(element_error(
                    tendon,
                    "a fixed tendon needs at least one joint",
                ));
            }
            let name = tendon
                .attribute("name")
                .map_or_else(|| format!("tendon{index}"), str::to_owned);
            let mut entry = json!({ "name": name, "joints": joints });
            let range = defaults.numbers(tendon, "range", Some(2))?;
            let limited = match defaults.flag(tendon, "limited")? {
                Some(limited) => limited,
                None => range.is_some(),
            };
            if let (true, Some(range)) = (limited, range) {
                entry["limits"] = json!([range[0] - offset, range[1] - offset]);
            }
            let stiffness = defaults.number(tendon, "stiffness", 0.0)?;
            let damping = defaults.number(tendon, "damping", 0.0)?;
            if stiffness > 0.0 {
                entry["stiffness"] = json!(stiffness);
                // MuJoCo's springlength −1 (its default) is the length of the model as written.
                let length = defaults.number(tendon, "springlength", -1.0)?;
                if length >= 0.0 {
                    entry["length"] = json!(length - offset);
                }
            }
            if damping > 0.0 {
                entry["damping"] = json!(damping);
            }
            entries.push(entry);
        }
        Ok(entries)
    }
}
