//! MuJoCo MJCF models (`.xml`) read as scenes: the model becomes the scene's JSON model, which
//! then goes through the ordinary loader, so every feature of the importer is one of the scene
//! format too. What is read, approximated and refused: `docs/mjcf.md`.
//!
//! The model is turned rigidly from MuJoCo's Z-up to rebond's Y-up by the rotation `C` (−90°
//! about X): each body's origin is `C` times its MJCF world position, its rotation `C` times its
//! MJCF world rotation, and what is given in a body's own frame (geoms, inertial, joint anchors
//! and axes) keeps the file's local coordinates.

mod actuators;
pub(super) mod frames;
pub(super) mod geoms;
mod joints;
pub(super) mod parse;

use std::collections::{HashMap, HashSet};
use std::path::Path;

use glam::DQuat;
use roxmltree::{Document, Node};
use serde_json::{json, Map, Value};

use super::{LoadError, SceneError};
use crate::mass::MassProperties;
use frames::{frame, z_up_to_y_up, Compiler, Frame, InertiaFromGeom};
use geoms::{read_mesh, rotation_json, MeshAsset};
use parse::{
    attribute_error, check_attributes, check_children, element_error, path, Attributes, Defaults,
};

/// A link body of a chain of joints carries this share of its body's mass and inertia.
const LINK_MASS_FRACTION: f32 = 0.01;

/// The radius of a link's or a geomless body's sphere, m: it collides with nothing.
const HIDDEN_SPHERE_RADIUS: f64 = 0.01;

/// The most seconds a substep lasts: rebond's default step of 1/60 s in 8 substeps.
const MAX_SUBSTEP: f64 = 1.0 / 480.0;

/// MuJoCo's default timestep, s.
const DEFAULT_TIMESTEP: f64 = 0.002;

/// Attributes of each element rebond reads (also in `<default>`).
fn attributes_of(tag: &str) -> Option<&'static Attributes> {
    Some(match tag {
        "geom" => &GEOM,
        "joint" => &JOINT,
        "motor" | "position" | "velocity" => &actuators::ACTUATOR,
        "fixed" | "tendon" => &actuators::TENDON,
        "site" | "camera" | "light" | "material" | "texture" => &VISUAL,
        "mesh" => &MESH,
        _ => return None,
    })
}

/// Every attribute: for the visual-only elements, which are not read at all.
const VISUAL: Attributes = Attributes {
    read: &[],
    accepted: &[
        "name",
        "class",
        "pos",
        "quat",
        "euler",
        "axisangle",
        "xyaxes",
        "zaxis",
        "size",
        "type",
        "rgba",
        "material",
        "group",
        "user",
        "fromto",
        "mode",
        "target",
        "fovy",
        "ipd",
        "directional",
        "castshadow",
        "active",
        "attenuation",
        "cutoff",
        "exponent",
        "ambient",
        "diffuse",
        "specular",
        "dir",
        "texture",
        "texrepeat",
        "texuniform",
        "emission",
        "shininess",
        "reflectance",
        "builtin",
        "rgb1",
        "rgb2",
        "mark",
        "markrgb",
        "random",
        "width",
        "height",
        "file",
        "gridsize",
        "gridlayout",
        "hflip",
        "vflip",
        "focal",
        "resolution",
        "sensorsize",
        "principal",
        "bodyactive",
    ],
};

const GEOM: Attributes = Attributes {
    read: &[
        "name",
        "class",
        "type",
        "size",
        "fromto",
        "pos",
        "quat",
        "euler",
        "axisangle",
        "xyaxes",
        "zaxis",
        "mass",
        "density",
        "friction",
        "contype",
        "conaffinity",
        "mesh",
    ],
    accepted: &[
        "rgba",
        "material",
        "group",
        "user",
        "condim",
        "margin",
        "gap",
        "solref",
        "solimp",
        "solmix",
        "priority",
        "fluidshape",
        "fluidcoef",
        "shellinertia",
    ],
};

const JOINT: Attributes = Attributes {
    read: &[
        "name",
        "class",
        "type",
        "pos",
        "axis",
        "range",
        "limited",
        "damping",
        "stiffness",
        "springref",
        "armature",
        "frictionloss",
        "ref",
    ],
    accepted: &[
        "group",
        "user",
        "margin",
        "solreflimit",
        "solimplimit",
        "solreffriction",
        "solimpfriction",
        "springdamper",
        "actuatorfrclimited",
        "actuatorfrcrange",
    ],
};

const MESH: Attributes = Attributes {
    read: &["name", "file", "scale", "class"],
    accepted: &["content_type"],
};

const BODY: Attributes = Attributes {
    read: &[
        "name",
        "pos",
        "quat",
        "euler",
        "axisangle",
        "xyaxes",
        "zaxis",
        "childclass",
    ],
    accepted: &["user", "gravcomp_never"],
};

const INERTIAL: Attributes = Attributes {
    read: &[
        "pos",
        "quat",
        "euler",
        "axisangle",
        "xyaxes",
        "zaxis",
        "mass",
        "diaginertia",
        "fullinertia",
    ],
    accepted: &[],
};

/// The state of one import: the file's defaults and compiler settings, its mesh assets.
pub(super) struct Importer {
    defaults: Defaults,
    compiler: Compiler,
    meshes: HashMap<String, MeshAsset>,
    /// Names of the hinge and slide joints read so far (actuators name them).
    joint_names: HashSet<String>,
    /// `C`, from MuJoCo's Z-up to rebond's Y-up.
    turn: DQuat,
    /// Bodies read so far: the next one's MuJoCo id is one more (the world is 0).
    body_count: usize,
    /// Each body with a moving parent, and that parent: MuJoCo never lets them collide.
    parent_pairs: Vec<Value>,
}

/// A body read from the tree, before it is written.
struct BodySpec {
    name: String,
    /// World frame, MuJoCo's axes.
    frame: Frame,
    /// `None` for a body welded (through its ancestors) to the world: static.
    mass: Option<MassProperties>,
    children: Vec<Value>,
    joints: Vec<Value>,
    links: Vec<String>,
}

/// The scene model of the MJCF model `bytes`; files it names are found relative to `folder`.
pub(super) fn import(bytes: &[u8], folder: &Path) -> Result<Value, LoadError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|error| SceneError::new("", format!("not UTF-8 text: {error}")))?;
    let document = Document::parse(text)
        .map_err(|error| SceneError::new("", format!("invalid XML: {error}")))?;
    let root = document.root_element();
    if !root.has_tag_name("mujoco") {
        let message = format!(
            "expected a <mujoco> model, got <{}>",
            root.tag_name().name()
        );
        return Err(element_error(root, message).into());
    }
    check_attributes(
        root,
        &Attributes {
            read: &[],
            accepted: &["model"],
        },
    )?;
    check_children(
        root,
        &[
            "compiler",
            "option",
            "default",
            "asset",
            "worldbody",
            "actuator",
            "tendon",
        ],
        &[
            "size",
            "visual",
            "statistic",
            "custom",
            "extension",
            "keyframe",
            "sensor",
        ],
    )?;
    let defaults = Defaults::read(root, attributes_of)?;
    let compiler_node = root.children().find(|node| node.has_tag_name("compiler"));
    if let Some(node) = compiler_node {
        check_attributes(
            node,
            &Attributes {
                read: &[
                    "angle",
                    "coordinate",
                    "eulerseq",
                    "inertiafromgeom",
                    "settotalmass",
                    "meshdir",
                ],
                accepted: &[
                    "texturedir",
                    "assetdir",
                    "autolimits",
                    "boundmass",
                    "boundinertia",
                    "balanceinertia",
                    "strippath",
                    "discardvisual",
                    "usethread",
                    "fitaabb",
                    "inertiagrouprange",
                    "exactmeshinertia",
                    "alignfree",
                    "fusestatic",
                ],
            },
        )?;
    }
    let compiler = Compiler::read(compiler_node, &defaults)?;
    let mut importer = Importer {
        defaults,
        compiler,
        meshes: HashMap::new(),
        joint_names: HashSet::new(),
        turn: z_up_to_y_up(),
        body_count: 0,
        parent_pairs: Vec::new(),
    };
    let mut scene = Map::new();
    scene.insert("friction_combine".into(), json!("max"));
    importer.option(root, &mut scene)?;
    for asset in root.children().filter(|node| node.has_tag_name("asset")) {
        importer.assets(asset, folder)?;
    }
    let mut bodies = Vec::new();
    let mut statics = Vec::new();
    let mut references = HashMap::new();
    for world in root
        .children()
        .filter(|node| node.has_tag_name("worldbody"))
    {
        importer.world(world, &mut bodies, &mut statics, &mut references)?;
    }
    if let Some(total) = importer.compiler.total_mass {
        let sum: f32 = bodies
            .iter()
            .filter_map(|body: &BodySpec| body.mass)
            .map(|m| m.mass)
            .sum();
        if sum > 0.0 {
            for body in &mut bodies {
                if let Some(mass) = &mut body.mass {
                    *mass = mass.scaled_to_mass(mass.mass * total as f32 / sum);
                }
            }
        }
    }
    let mut body_entries = statics;
    let mut joint_entries = Vec::new();
    for body in bodies {
        importer.write_body(body, &mut body_entries, &mut joint_entries);
    }
    scene.insert("bodies".into(), Value::Array(body_entries));
    scene.insert("joints".into(), Value::Array(joint_entries));
    for node in root.children().filter(|node| node.has_tag_name("actuator")) {
        let actuators = importer.actuators(node)?;
        scene.insert("actuators".into(), Value::Array(actuators));
    }
    for node in root.children().filter(|node| node.has_tag_name("tendon")) {
        let couplings = importer.couplings(node, &references)?;
        scene.insert("couplings".into(), Value::Array(couplings));
    }
    if !importer.parent_pairs.is_empty() {
        scene.insert("ignored_pairs".into(), Value::Array(importer.parent_pairs));
    }
    Ok(Value::Object(scene))
}

impl Importer {
    /// `<option>`: `timestep` and `gravity`; substeps so that none lasts over [`MAX_SUBSTEP`].
    fn option(&self, root: Node, scene: &mut Map<String, Value>) -> Result<(), SceneError> {
        let option = root.children().find(|node| node.has_tag_name("option"));
        let mut timestep = DEFAULT_TIMESTEP;
        let mut gravity = [0.0, 0.0, -9.81];
        if let Some(node) = option {
            check_attributes(
                node,
                &Attributes {
                    read: &["timestep", "gravity"],
                    accepted: &[
                        "integrator",
                        "iterations",
                        "solver",
                        "tolerance",
                        "cone",
                        "impratio",
                        "noslip_iterations",
                        "noslip_tolerance",
                        "ls_iterations",
                        "ls_tolerance",
                        "jacobian",
                        "o_margin",
                        "o_solref",
                        "o_solimp",
                        "o_friction",
                        "viscosity",
                        "density",
                        "wind",
                        "magnetic",
                        "apirate",
                        "ccd_iterations",
                        "ccd_tolerance",
                        "sdf_iterations",
                        "sdf_initpoints",
                        "actuatorgroupdisable",
                    ],
                },
            )?;
            check_children(node, &[], &["flag"])?;
            timestep = self.defaults.number(node, "timestep", DEFAULT_TIMESTEP)?;
            if let Some(value) = self.defaults.triple(node, "gravity")? {
                gravity = value;
            }
        }
        let gravity = self.turn * glam::DVec3::from_array(gravity);
        scene.insert("timestep".into(), json!(timestep));
        scene.insert("gravity".into(), json!(gravity.to_array()));
        let substeps = (timestep / MAX_SUBSTEP).ceil().clamp(1.0, 64.0);
        scene.insert("substeps".into(), json!(substeps as u32));
        Ok(())
    }

    /// `<asset>`: meshes are read; textures and materials are visual.
    fn assets(&mut self, node: Node, folder: &Path) -> Result<(), LoadError> {
        check_children(node, &["mesh"], &["texture", "material"])?;
        for child in node.children().filter(Node::is_element) {
            check_attributes(
                child,
                attributes_of(child.tag_name().name()).unwrap_or(&VISUAL),
            )?;
            if !child.has_tag_name("mesh") {
                continue;
            }
            let file = child
                .attribute("file")
                .ok_or_else(|| attribute_error(child, "file", "required"))?;
            let name = child.attribute("name").map_or_else(
                || {
                    Path::new(file)
                        .file_stem()
                        .and_then(|stem| stem.to_str())
                        .unwrap_or(file)
                        .to_owned()
                },
                str::to_owned,
            );
            let scale = self.defaults.triple(child, "scale")?.unwrap_or([1.0; 3]);
            let directory = folder.join(self.compiler.mesh_dir.as_deref().unwrap_or(""));
            let place = format!("{}@file", path(child));
            let (vertices, indices) = read_mesh(&directory.join(file), &place)?;
            let scale = glam::DVec3::from_array(scale);
            self.meshes.insert(
                name,
                MeshAsset {
                    vertices,
                    indices,
                    scale,
                },
            );
        }
        Ok(())
    }

    /// `<worldbody>`: its geoms become static bodies, its bodies are read depth first.
    fn world(
        &mut self,
        node: Node,
        bodies: &mut Vec<BodySpec>,
        statics: &mut Vec<Value>,
        references: &mut HashMap<String, f64>,
    ) -> Result<(), LoadError> {
        check_children(node, &["geom", "body"], &["site", "camera", "light"])?;
        self.static_geoms(node, &Frame::IDENTITY, "world", statics)?;
        for child in node.children().filter(|child| child.has_tag_name("body")) {
            self.body(child, None, &Frame::IDENTITY, bodies, statics, references)?;
        }
        Ok(())
    }

    /// The geoms of a static body (the world, or bodies welded to it) at `frame`: each its own
    /// static body, named after the geom or `<body>/geom<k>`.
    fn static_geoms(
        &self,
        node: Node,
        frame: &Frame,
        owner: &str,
        statics: &mut Vec<Value>,
    ) -> Result<(), LoadError> {
        for (index, child) in node
            .children()
            .filter(|child| child.has_tag_name("geom"))
            .enumerate()
        {
            check_attributes(child, &GEOM)?;
            self.defaults.check_class(child)?;
            let geom = self.geom(child, true)?;
            let name = child
                .attribute("name")
                .map_or_else(|| format!("{owner}/geom{}", index + 1), str::to_owned);
            // A static body takes the geom's shape itself (a halfspace or a trimesh may not be a
            // compound's child), at the geom's frame.
            let world = frame.then(&geom.frame);
            statics.push(json!({
                "name": name,
                "type": "static",
                "shape": geom.child["shape"],
                "position": (self.turn * world.position).to_array(),
                "rotation": rotation_json(self.turn * world.rotation),
                "friction": geom.child["friction"],
                "collision_groups": geom.child["collision_groups"],
            }));
        }
        Ok(())
    }

    /// A body and, depth first, its descendants; `parent` is the name of the dynamic body it
    /// hangs from, `None` for the world (or a static body).
    fn body(
        &mut self,
        node: Node,
        parent: Option<&str>,
        parent_frame: &Frame,
        bodies: &mut Vec<BodySpec>,
        statics: &mut Vec<Value>,
        references: &mut HashMap<String, f64>,
    ) -> Result<(), LoadError> {
        check_attributes(node, &BODY)?;
        self.defaults.check_class(node)?;
        check_children(
            node,
            &["inertial", "joint", "freejoint", "geom", "body"],
            &["site", "camera", "light"],
        )?;
        self.body_count += 1;
        let name = match node.attribute("name") {
            Some(name) => name.to_owned(),
            None => format!("body{}", self.body_count),
        };
        if let Some(parent) = parent {
            self.parent_pairs.push(json!([name, parent]));
        }
        let frame = parent_frame.then(&frame(node, &self.defaults, &self.compiler)?);
        let mut joints = Vec::new();
        for child in node
            .children()
            .filter(|child| child.has_tag_name("joint") || child.has_tag_name("freejoint"))
        {
            let attributes = if child.has_tag_name("freejoint") {
                &Attributes {
                    read: &["name"],
                    accepted: &["group", "align"],
                }
            } else {
                &JOINT
            };
            check_attributes(child, attributes)?;
            self.defaults.check_class(child)?;
            let joint = self.joint(child, &name, joints.len() + 1)?;
            if joint.kind.is_some() && joint.kind != Some("ball") {
                self.joint_names.insert(joint.name.clone());
                references.insert(joint.name.clone(), joint.reference);
            }
            joints.push(joint);
        }
        let moves = parent.is_some() || !joints.is_empty();
        if !moves {
            // Welded to the world: its geoms are static.
            self.static_geoms(node, &frame, &name, statics)?;
            for child in node.children().filter(|child| child.has_tag_name("body")) {
                self.body(child, None, &frame, bodies, statics, references)?;
            }
            return Ok(());
        }
        let mut children = Vec::new();
        let mut geom_mass: Option<MassProperties> = None;
        for child in node.children().filter(|child| child.has_tag_name("geom")) {
            check_attributes(child, &GEOM)?;
            self.defaults.check_class(child)?;
            let geom = self.geom(child, false)?;
            if geom.plane {
                let message = "a plane is static: it belongs to the world or a body welded to it";
                return Err(element_error(child, message).into());
            }
            children.push(geom.child);
            if let Some(mass) = geom.mass {
                geom_mass = Some(geom_mass.map_or(mass, |total| total.combine(&mass)));
            }
        }
        let inertial = node.children().find(|child| child.has_tag_name("inertial"));
        let inertial = match inertial {
            Some(inertial) => {
                check_attributes(inertial, &INERTIAL)?;
                Some(self.inertial(inertial)?)
            }
            None => None,
        };
        let mass = match (self.compiler.inertia_from_geom, inertial) {
            (InertiaFromGeom::Always, _) | (InertiaFromGeom::Auto, None) => geom_mass,
            (_, Some(inertial)) => Some(inertial),
            (InertiaFromGeom::Never, None) => None,
        };
        let mass = mass.filter(|mass| mass.mass > 0.0).ok_or_else(|| {
            element_error(
                node,
                "a moving body needs a mass: geoms with volume or an <inertial>",
            )
        })?;
        let (joint_entries, links) = if joints.is_empty() {
            let weld = json!({
                "name": format!("{name}/weld"),
                "type": "fixed",
                "body_a": parent,
                "body_b": name,
                "anchor": (self.turn * frame.position).to_array(),
            });
            (vec![weld], Vec::new())
        } else {
            self.joint_entries(node, &name, &frame, parent, &joints)?
        };
        bodies.push(BodySpec {
            name: name.clone(),
            frame,
            mass: Some(mass),
            children,
            joints: joint_entries,
            links,
        });
        for child in node.children().filter(|child| child.has_tag_name("body")) {
            self.body(child, Some(&name), &frame, bodies, statics, references)?;
        }
        Ok(())
    }

    /// Writes a body read from the tree: its links first, then itself, then its joints.
    fn write_body(&self, body: BodySpec, bodies: &mut Vec<Value>, joints: &mut Vec<Value>) {
        let position = (self.turn * body.frame.position).to_array();
        let rotation = rotation_json(self.turn * body.frame.rotation);
        let properties = |mass: &MassProperties| {
            let i = mass.inertia;
            json!({
                "mass": mass.mass,
                "center_of_mass": mass.center_of_mass.to_array(),
                "inertia": [i.x_axis.x, i.y_axis.y, i.z_axis.z, i.x_axis.y, i.x_axis.z, i.y_axis.z],
            })
        };
        let hidden = json!({
            "type": "sphere",
            "radius": HIDDEN_SPHERE_RADIUS,
        });
        let nothing = json!({ "memberships": 0, "filter": 0 });
        let mass = body.mass.unwrap_or(MassProperties::ZERO);
        for link in &body.links {
            let link_mass = MassProperties {
                mass: mass.mass * LINK_MASS_FRACTION,
                center_of_mass: mass.center_of_mass,
                inertia: mass.inertia * LINK_MASS_FRACTION,
            };
            bodies.push(json!({
                "name": link,
                "shape": hidden,
                "collision_groups": nothing,
                "position": position,
                "rotation": rotation,
                "mass_properties": properties(&link_mass),
            }));
        }
        let shape = if body.children.is_empty() {
            hidden
        } else {
            json!({ "type": "compound", "children": body.children })
        };
        let mut entry = json!({
            "name": body.name,
            "shape": shape,
            "position": position,
            "rotation": rotation,
            "mass_properties": properties(&mass),
        });
        if entry["shape"]["type"] == "sphere" {
            entry["collision_groups"] = nothing;
        }
        bodies.push(entry);
        joints.extend(body.joints);
    }
}
