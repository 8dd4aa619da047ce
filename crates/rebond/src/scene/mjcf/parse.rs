//! Reading the XML: element paths for errors, the attributes each element takes, `default`
//! classes (nested, with `class` and `childclass`), and numbers.

use std::collections::HashMap;

use roxmltree::Node;

use super::super::SceneError;

/// The path of an element in the file, for errors: `mujoco/worldbody/body[name=torso]/geom[2]`,
/// a named element by its name, an unnamed one by its place among its parent's children of the
/// same tag (from 1) when it has such siblings.
pub(in crate::scene) fn path(node: Node) -> String {
    let mut parts: Vec<String> = node
        .ancestors()
        .filter(Node::is_element)
        .map(|element| {
            let tag = element.tag_name().name();
            if let Some(name) = element.attribute("name") {
                return format!("{tag}[name={name}]");
            }
            let Some(parent) = element.parent_element() else {
                return tag.to_owned();
            };
            let same: Vec<_> = parent
                .children()
                .filter(|child| child.is_element() && child.tag_name().name() == tag)
                .collect();
            if same.len() < 2 {
                return tag.to_owned();
            }
            let index = same.iter().position(|child| *child == element).unwrap_or(0);
            format!("{tag}[{}]", index + 1)
        })
        .collect();
    parts.reverse();
    parts.join("/")
}

/// An error about the attribute `name` of `node`: `path@name`.
pub(in crate::scene) fn attribute_error(
    node: Node,
    name: &str,
    message: impl Into<String>,
) -> SceneError {
    SceneError::new(format!("{}@{name}", path(node)), message)
}

/// An error about the element `node` as a whole.
pub(in crate::scene) fn element_error(node: Node, message: impl Into<String>) -> SceneError {
    SceneError::new(path(node), message)
}

/// The attributes an element takes: those rebond reads, and those it accepts without reading
/// (visual-only, or physics it approximates: `docs/mjcf.md` lists which). Any other attribute is
/// refused.
pub(super) struct Attributes {
    /// Read and honoured.
    pub(super) read: &'static [&'static str],
    /// Accepted, not read: visual-only, or approximated.
    pub(super) accepted: &'static [&'static str],
}

/// Refuses an attribute of `node` that `attributes` does not list.
pub(super) fn check_attributes(node: Node, attributes: &Attributes) -> Result<(), SceneError> {
    for attribute in node.attributes() {
        let name = attribute.name();
        if !attributes.read.contains(&name) && !attributes.accepted.contains(&name) {
            let tag = node.tag_name().name();
            return Err(attribute_error(
                node,
                name,
                format!("unknown attribute `{name}` of <{tag}>"),
            ));
        }
    }
    Ok(())
}

/// Refuses an element of `node` whose tag is not among `known` (read) or `accepted` (not read).
pub(super) fn check_children(
    node: Node,
    known: &[&str],
    accepted: &[&str],
) -> Result<(), SceneError> {
    for child in node.children().filter(Node::is_element) {
        let tag = child.tag_name().name();
        if !known.contains(&tag) && !accepted.contains(&tag) {
            let parent = node.tag_name().name();
            return Err(element_error(
                child,
                format!("unknown or unsupported element <{tag}> in <{parent}>"),
            ));
        }
    }
    Ok(())
}

/// Default values by class: for each class, for each element tag, attribute name to value, the
/// parent classes' values already folded in.
#[derive(Debug, Default)]
pub(super) struct Defaults {
    classes: HashMap<String, HashMap<String, HashMap<String, String>>>,
}

/// The class of the top-level `<default>`.
const MAIN_CLASS: &str = "main";

impl Defaults {
    /// Reads every `<default>` of `root` (the `mujoco` element), checking each element's
    /// attributes against `attributes_of`.
    pub(super) fn read(
        root: Node,
        attributes_of: impl Fn(&str) -> Option<&'static Attributes>,
    ) -> Result<Self, SceneError> {
        let mut defaults = Self::default();
        defaults
            .classes
            .insert(MAIN_CLASS.to_owned(), HashMap::new());
        for node in root.children().filter(|node| node.has_tag_name("default")) {
            defaults.read_class(node, MAIN_CLASS, &attributes_of)?;
        }
        Ok(defaults)
    }

    fn read_class(
        &mut self,
        node: Node,
        parent: &str,
        attributes_of: &impl Fn(&str) -> Option<&'static Attributes>,
    ) -> Result<(), SceneError> {
        check_attributes(
            node,
            &Attributes {
                read: &["class"],
                accepted: &[],
            },
        )?;
        let is_top = node
            .parent_element()
            .is_some_and(|parent| parent.has_tag_name("mujoco"));
        let name = match node.attribute("class") {
            Some(name) => name.to_owned(),
            None if is_top => MAIN_CLASS.to_owned(),
            None => {
                return Err(attribute_error(
                    node,
                    "class",
                    "a nested <default> needs a class",
                ))
            }
        };
        let mut values = self.classes.get(parent).cloned().unwrap_or_default();
        for child in node.children().filter(Node::is_element) {
            let tag = child.tag_name().name();
            if tag == "default" {
                continue;
            }
            let attributes = attributes_of(tag).ok_or_else(|| {
                element_error(
                    child,
                    format!("unknown or unsupported element <{tag}> in <default>"),
                )
            })?;
            check_attributes(child, attributes)?;
            let entry = values.entry(tag.to_owned()).or_default();
            for attribute in child.attributes() {
                entry.insert(attribute.name().to_owned(), attribute.value().to_owned());
            }
        }
        self.classes.insert(name.clone(), values);
        for child in node
            .children()
            .filter(|child| child.has_tag_name("default"))
        {
            self.read_class(child, &name, attributes_of)?;
        }
        Ok(())
    }

    /// The class that applies to `node`: its `class`, else the `childclass` of the nearest
    /// enclosing body, else `main`.
    fn class_of<'a>(&self, node: Node<'a, '_>) -> &'a str {
        if let Some(class) = node.attribute("class") {
            return class;
        }
        node.ancestors()
            .skip(1)
            .find_map(|ancestor| ancestor.attribute("childclass"))
            .unwrap_or(MAIN_CLASS)
    }

    /// Refuses a `class` or `childclass` that names no class.
    pub(super) fn check_class(&self, node: Node) -> Result<(), SceneError> {
        for attribute in ["class", "childclass"] {
            if let Some(class) = node.attribute(attribute) {
                if !self.classes.contains_key(class) {
                    let message = format!("no default class is named \"{class}\"");
                    return Err(attribute_error(node, attribute, message));
                }
            }
        }
        Ok(())
    }

    /// The value of the attribute `name` of `node`, given or from its class.
    pub(super) fn get<'a>(&'a self, node: Node<'a, '_>, name: &str) -> Option<&'a str> {
        if let Some(value) = node.attribute(name) {
            return Some(value);
        }
        let class = self.classes.get(self.class_of(node))?;
        class
            .get(node.tag_name().name())?
            .get(name)
            .map(String::as_str)
    }

    /// The numbers of the attribute `name` of `node` (given or from its class), exactly `count`
    /// of them when `count` is given.
    pub(super) fn numbers(
        &self,
        node: Node,
        name: &str,
        count: Option<usize>,
    ) -> Result<Option<Vec<f64>>, SceneError> {
        let Some(text) = self.get(node, name) else {
            return Ok(None);
        };
        let numbers = text
            .split_ascii_whitespace()
            .map(str::parse::<f64>)
            .collect::<Result<Vec<_>, _>>()
            .ok()
            .filter(|numbers| numbers.iter().all(|value| value.is_finite()));
        let Some(numbers) = numbers else {
            return Err(attribute_error(
                node,
                name,
                format!("expected finite numbers, got \"{text}\""),
            ));
        };
        match count {
            Some(count) if numbers.len() != count => Err(attribute_error(
                node,
                name,
                format!("expected {count} numbers, got {}", numbers.len()),
            )),
            _ => Ok(Some(numbers)),
        }
    }

    /// One number, or `default`.
    pub(super) fn number(&self, node: Node, name: &str, default: f64) -> Result<f64, SceneError> {
        Ok(self
            .numbers(node, name, Some(1))?
            .map_or(default, |numbers| numbers[0]))
    }

    /// Three numbers, or `None`.
    pub(super) fn triple(&self, node: Node, name: &str) -> Result<Option<[f64; 3]>, SceneError> {
        Ok(self
            .numbers(node, name, Some(3))?
            .map(|numbers| [numbers[0], numbers[1], numbers[2]]))
    }

    /// A `true`/`false`/`auto` attribute: `Some(true)`, `Some(false)`, or `None` for `auto`
    /// and when absent.
    pub(super) fn flag(&self, node: Node, name: &str) -> Result<Option<bool>, SceneError> {
        match self.get(node, name) {
            None | Some("auto") => Ok(None),
            Some("true") => Ok(Some(true)),
            Some("false") => Ok(Some(false)),
            Some(other) => Err(attribute_error(
                node,
                name,
                format!("expected \"true\", \"false\" or \"auto\", got \"{other}\""),
            )),
        }
    }
}
