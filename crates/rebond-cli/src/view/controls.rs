//! The keys and mouse gestures of the viewer. One table binds keys to actions; the help overlay
//! is written from the same table, so it lists exactly the keys that work. In a scene that names
//! a character, W, A, S, D and Space drive it instead: P and M still pause and slow down.

use three_d::Key;

/// Something the user can ask for with a key.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Pause or resume the simulation.
    TogglePause,
    /// Pause and take exactly one step.
    StepOnce,
    /// Back to the scene as loaded.
    Reset,
    /// Slow motion on or off.
    ToggleSlowMotion,
    /// Show or hide contact points and their normals.
    ToggleContacts,
    /// Show or hide bounding boxes.
    ToggleBoundingBoxes,
    /// Show or hide joints.
    ToggleJoints,
    /// Tint sleeping bodies, or not.
    ToggleSleepingTint,
    /// Shoot a ball from the camera toward the cursor.
    ShootBall,
    /// Frame the scene again with the starting view.
    ResetCamera,
    /// Show or hide the help overlay.
    ToggleHelp,
    /// Close the viewer.
    Quit,
}

/// A key, what it is called in the help, and what it does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KeyBinding {
    /// The key.
    pub key: Key,
    /// Its name in the help.
    pub label: &'static str,
    /// What pressing it does.
    pub action: Action,
    /// The help's line for it.
    pub description: &'static str,
}

/// Every key the viewer answers to, in the order the help lists them.
pub const KEY_BINDINGS: &[KeyBinding] = &[
    KeyBinding {
        key: Key::Space,
        label: "Space",
        action: Action::TogglePause,
        description: "pause / resume",
    },
    KeyBinding {
        key: Key::P,
        label: "P",
        action: Action::TogglePause,
        description: "pause / resume",
    },
    KeyBinding {
        key: Key::N,
        label: "N",
        action: Action::StepOnce,
        description: "step one frame (pauses)",
    },
    KeyBinding {
        key: Key::R,
        label: "R",
        action: Action::Reset,
        description: "reset the scene",
    },
    KeyBinding {
        key: Key::S,
        label: "S",
        action: Action::ToggleSlowMotion,
        description: "slow motion (1/4 speed) on / off",
    },
    KeyBinding {
        key: Key::M,
        label: "M",
        action: Action::ToggleSlowMotion,
        description: "slow motion (1/4 speed) on / off",
    },
    KeyBinding {
        key: Key::C,
        label: "C",
        action: Action::ToggleContacts,
        description: "contact points and normals",
    },
    KeyBinding {
        key: Key::B,
        label: "B",
        action: Action::ToggleBoundingBoxes,
        description: "bounding boxes",
    },
    KeyBinding {
        key: Key::J,
        label: "J",
        action: Action::ToggleJoints,
        description: "joints (anchors, axes, limits)",
    },
    KeyBinding {
        key: Key::Z,
        label: "Z",
        action: Action::ToggleSleepingTint,
        description: "tint sleeping bodies",
    },
    KeyBinding {
        key: Key::F,
        label: "F",
        action: Action::ShootBall,
        description: "fire a ball at the cursor",
    },
    KeyBinding {
        key: Key::V,
        label: "V",
        action: Action::ResetCamera,
        description: "reset the view",
    },
    KeyBinding {
        key: Key::H,
        label: "H",
        action: Action::ToggleHelp,
        description: "this help",
    },
    KeyBinding {
        key: Key::F1,
        label: "F1",
        action: Action::ToggleHelp,
        description: "this help",
    },
    KeyBinding {
        key: Key::Escape,
        label: "Esc",
        action: Action::Quit,
        description: "quit",
    },
    KeyBinding {
        key: Key::Q,
        label: "Q",
        action: Action::Quit,
        description: "quit",
    },
];

/// The keys that walk a scene's character, each with the way it walks: forward (+1) or back
/// (−1) along the camera's heading on the ground, and right (+1) or left (−1) across it.
pub const WALK_KEYS: [(Key, f32, f32); 4] = [
    (Key::W, 1.0, 0.0),
    (Key::S, -1.0, 0.0),
    (Key::A, 0.0, -1.0),
    (Key::D, 0.0, 1.0),
];

/// The key that makes a scene's character jump.
pub const JUMP_KEY: Key = Key::Space;

/// The help's lines for a scene's character.
pub const CHARACTER_HELP: &[(&str, &str)] =
    &[("W A S D", "walk, as the camera faces"), ("Space", "jump")];

/// The help's lines for the mouse.
pub const MOUSE_HELP: &[(&str, &str)] = &[
    ("left drag", "on a body: pull it; elsewhere: turn"),
    ("right drag", "pan (also middle, or Shift + left)"),
    ("wheel", "zoom"),
];

/// The action bound to `key`, if any.
pub fn action_for_key(key: Key) -> Option<Action> {
    KEY_BINDINGS
        .iter()
        .find(|binding| binding.key == key)
        .map(|binding| binding.action)
}

/// The help overlay's text: one line a key (keys with the same action share a line), then the
/// mouse.
pub fn help_lines() -> Vec<String> {
    let mut lines = vec!["Keys".to_owned()];
    let mut listed: Vec<Action> = Vec::new();
    for binding in KEY_BINDINGS {
        if listed.contains(&binding.action) {
            continue;
        }
        listed.push(binding.action);
        let labels: Vec<&str> = KEY_BINDINGS
            .iter()
            .filter(|other| other.action == binding.action)
            .map(|other| other.label)
            .collect();
        lines.push(format!(
            "  {:<11}{}",
            labels.join(", "),
            binding.description
        ));
    }
    lines.push("Character (if the scene has one)".to_owned());
    lines.extend(
        CHARACTER_HELP
            .iter()
            .map(|(keys, description)| format!("  {keys:<11}{description}")),
    );
    lines.push("Mouse".to_owned());
    lines.extend(
        MOUSE_HELP
            .iter()
            .map(|(gesture, description)| format!("  {gesture:<11}{description}")),
    );
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_is_bound_once_and_listed_in_the_help() {
        let help = help_lines().join("\n");
        for (index, binding) in KEY_BINDINGS.iter().enumerate() {
            assert_eq!(action_for_key(binding.key), Some(binding.action));
            assert!(
                KEY_BINDINGS[..index]
                    .iter()
                    .all(|other| other.key != binding.key),
                "{} is bound twice",
                binding.label
            );
            assert!(
                help.contains(binding.label),
                "{} missing from:\n{help}",
                binding.label
            );
            assert!(help.contains(binding.description));
        }
        assert_eq!(action_for_key(Key::X), None);
    }

    #[test]
    fn the_characters_keys_leave_every_action_a_key() {
        // Space and S serve the character in a scene that has one: their actions keep P and M.
        let character_keys: Vec<Key> = (WALK_KEYS.iter().map(|(key, _, _)| *key))
            .chain([JUMP_KEY])
            .collect();
        for binding in KEY_BINDINGS {
            assert!(
                KEY_BINDINGS
                    .iter()
                    .any(|other| other.action == binding.action
                        && !character_keys.contains(&other.key)),
                "{:?} has no key beside the character's",
                binding.action
            );
        }
    }

    #[test]
    fn help_lines_fit_the_overlay() {
        for line in help_lines() {
            assert!(line.is_ascii(), "the overlay font is ASCII: {line}");
            assert!(line.chars().count() <= 50, "{line}");
        }
    }
}
