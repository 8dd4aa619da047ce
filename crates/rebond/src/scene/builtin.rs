//! The built-in scenes: JSON files under `scenes/` at the workspace root, embedded in the
//! library so that every program built on it (the command line, the Python module) runs them by
//! name. `python3 scenes/generate.py` (run from anywhere) regenerates them.

use super::{LoadError, Scene};

/// A scene shipped inside the library.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BuiltinScene {
    /// The name to run it by.
    pub name: &'static str,
    /// What it shows, in one line.
    pub description: &'static str,
    /// The scene file.
    pub json: &'static str,
    /// The mesh files the scene names, embedded too: the name the scene uses, the contents.
    pub files: &'static [(&'static str, &'static str)],
}

/// Every built-in scene, in the order `rebond scenes` lists them.
pub const BUILTIN_SCENES: &[BuiltinScene] = &[
    BuiltinScene {
        name: "showcase",
        description: "a bit of everything: pyramid, column, bouncing and rolling balls, \
                      capsules, cylinders and hulls on a ramp, a compound",
        json: include_str!("../../../../scenes/showcase.json"),
        files: &[],
    },
    BuiltinScene {
        name: "pyramid",
        description: "210 unit boxes in a 20-row pyramid on a ground box",
        json: include_str!("../../../../scenes/pyramid.json"),
        files: &[],
    },
    BuiltinScene {
        name: "column",
        description: "10 unit boxes stacked on a ground box",
        json: include_str!("../../../../scenes/column.json"),
        files: &[],
    },
    BuiltinScene {
        name: "rain",
        description: "4,096 unit boxes in a tilted 16x16x16 grid falling onto a ground box",
        json: include_str!("../../../../scenes/rain.json"),
        files: &[],
    },
    BuiltinScene {
        name: "ramp",
        description: "boxes and balls on a 20-degree incline, friction 0.1 to 0.9 by lane, \
                      halfspace floor",
        json: include_str!("../../../../scenes/ramp.json"),
        files: &[],
    },
    BuiltinScene {
        name: "cradle",
        description: "Newton's cradle: five touching balls with restitution 1, the first moving, \
                      zero gravity",
        json: include_str!("../../../../scenes/cradle.json"),
        files: &[],
    },
    BuiltinScene {
        name: "spinner",
        description: "free bodies spinning in zero gravity; the intermediate-axis box flips \
                      (Dzhanibekov effect)",
        json: include_str!("../../../../scenes/spinner.json"),
        files: &[],
    },
    BuiltinScene {
        name: "pendulum",
        description: "pendulums from fixed points: revolute and ball, small and large swings, \
                      a rod, a double pendulum",
        json: include_str!("../../../../scenes/pendulum.json"),
        files: &[],
    },
    BuiltinScene {
        name: "chain",
        description: "two chains of 16 links, on ball and on revolute joints, each with a 25 kg \
                      weight at the end, falling from horizontal",
        json: include_str!("../../../../scenes/chain.json"),
        files: &[],
    },
    BuiltinScene {
        name: "bridge",
        description: "14 planks on revolute joints hung between two pillars, crates and a ball \
                      dropped on them",
        json: include_str!("../../../../scenes/bridge.json"),
        files: &[],
    },
    BuiltinScene {
        name: "ragdolls",
        description: "30 ragdolls (ball shoulders, hips and necks with cone and twist limits, \
                      hinged elbows and knees) falling in piles onto a ground box",
        json: include_str!("../../../../scenes/ragdolls.json"),
        files: &[],
    },
    BuiltinScene {
        name: "car",
        description: "a box chassis on four cylinder wheels driven by revolute joint motors, \
                      over bumps",
        json: include_str!("../../../../scenes/car.json"),
        files: &[],
    },
    BuiltinScene {
        name: "cradle_hanging",
        description: "Newton's cradle on strings: five balls with restitution 1, each hung by \
                      two distance joints, the first pulled aside",
        json: include_str!("../../../../scenes/cradle_hanging.json"),
        files: &[],
    },
    BuiltinScene {
        name: "terrain",
        description: "500 balls, boxes, capsules, cylinders and hulls poured on hilly terrain \
                      (a 256x256 heightfield over 128 m)",
        json: include_str!("../../../../scenes/terrain.json"),
        files: &[],
    },
    BuiltinScene {
        name: "level",
        description: "150 mixed shapes dropped in a room of triangles (level.obj): stairs, \
                      a platform and a ramp",
        json: include_str!("../../../../scenes/level.json"),
        files: &[("level.obj", include_str!("../../../../scenes/level.obj"))],
    },
    BuiltinScene {
        name: "soak",
        description: "a motor-driven drum tumbling 30 mixed shapes above a heightfield bowl, \
                      knocking a chain of five capsules on ball joints; nothing sleeps (for \
                      `rebond soak`)",
        json: include_str!("../../../../scenes/soak.json"),
        files: &[],
    },
    BuiltinScene {
        name: "platformer",
        description: "a character to walk with WASD and Space in `rebond view`: stairs, slopes, \
                      one-way ledges, a conveyor, a moving platform, a hinged door, crates",
        json: include_str!("../../../../scenes/platformer.json"),
        files: &[],
    },
];

/// The built-in scene called `name`, or `None` when no built-in scene has that name.
pub fn builtin(name: &str) -> Option<&'static BuiltinScene> {
    BUILTIN_SCENES.iter().find(|scene| scene.name == name)
}

impl BuiltinScene {
    /// The scene, loaded with its embedded mesh files: [`Scene::from_json_with_files`].
    pub fn load(&self) -> Result<Scene, LoadError> {
        let files: Vec<(&str, &[u8])> = self
            .files
            .iter()
            .map(|(name, contents)| (*name, contents.as_bytes()))
            .collect();
        Scene::from_json_with_files(self.json.as_bytes(), &files)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_scene_loads_by_its_name() {
        for scene in BUILTIN_SCENES {
            let found = builtin(scene.name).expect("listed");
            assert_eq!(found, scene);
            let loaded = found
                .load()
                .unwrap_or_else(|error| panic!("{}: {error}", scene.name));
            assert!(loaded.body_handles().count() > 0, "{}", scene.name);
        }
        assert!(builtin("no such scene").is_none());
    }
}
