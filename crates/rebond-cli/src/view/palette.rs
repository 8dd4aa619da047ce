//! The viewer's colours: one per body, chosen from its name so that every run and every
//! screenshot of a scene paints it alike, and the colours of the ground, the sky and the debug
//! drawings.

use std::fmt;

use rebond::BodyType;

/// An sRGB colour, 8 bits a channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Rgb(pub [u8; 3]);

impl Rgb {
    /// Black.
    pub const BLACK: Rgb = Rgb([0, 0, 0]);
    /// White.
    pub const WHITE: Rgb = Rgb([255, 255, 255]);

    /// The colour `amount` (0 to 1) of the way from `self` to `other`.
    pub fn mix(self, other: Rgb, amount: f32) -> Rgb {
        let channel = |index: usize| {
            let from = f32::from(self.0[index]);
            let to = f32::from(other.0[index]);
            (from + (to - from) * amount).round().clamp(0.0, 255.0) as u8
        };
        Rgb([channel(0), channel(1), channel(2)])
    }
}

impl fmt::Display for Rgb {
    /// `#rrggbb`.
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [red, green, blue] = self.0;
        write!(formatter, "#{red:02x}{green:02x}{blue:02x}")
    }
}

/// Saturated colours of well-separated hues for moving bodies.
const BODY_PALETTE: [Rgb; 10] = [
    Rgb([230, 57, 70]),  // red
    Rgb([244, 140, 6]),  // orange
    Rgb([240, 200, 8]),  // yellow
    Rgb([112, 193, 42]), // green
    Rgb([22, 160, 133]), // teal
    Rgb([30, 150, 230]), // sky blue
    Rgb([67, 97, 238]),  // blue
    Rgb([131, 56, 236]), // violet
    Rgb([214, 51, 184]), // magenta
    Rgb([160, 100, 60]), // brown
];

/// Static bodies: a light stone grey, so the ground reads as ground.
pub const STATIC_BODY: Rgb = Rgb([178, 176, 170]);
/// Brightness of the one-metre grid lines drawn on static bodies and halfspaces, relative to
/// their colour.
pub const GRID_LINE_SHADE: f32 = 0.62;
/// The clear colour behind the scene.
pub const BACKGROUND: Rgb = Rgb([40, 44, 52]);
/// What sleeping bodies are tinted toward when the sleeping tint is on.
pub const SLEEPING_TINT: Rgb = Rgb([70, 80, 110]);
/// How far a sleeping body's colour goes toward [`SLEEPING_TINT`].
pub const SLEEPING_TINT_AMOUNT: f32 = 0.7;
/// Contact points where the surfaces overlap.
pub const CONTACT_POINT: Rgb = Rgb([255, 40, 40]);
/// Speculative contact points, where the surfaces are still apart.
pub const SPECULATIVE_POINT: Rgb = Rgb([255, 170, 60]);
/// Contact normals.
pub const CONTACT_NORMAL: Rgb = Rgb([255, 240, 80]);
/// Bounding boxes.
pub const BOUNDING_BOX: Rgb = Rgb([80, 230, 255]);
/// The spring of a dragged body.
pub const DRAG_SPRING: Rgb = Rgb([255, 255, 255]);
/// Joint anchors, and the spokes fixed to a joint's second body that show its angle.
pub const JOINT_ANCHOR: Rgb = Rgb([150, 255, 80]);
/// Hinge, slide and twist axes.
pub const JOINT_AXIS: Rgb = Rgb([255, 90, 220]);
/// Joint limits: a hinge's limit directions, a swing cone, a range of slide.
pub const JOINT_LIMIT: Rgb = Rgb([180, 150, 255]);
/// The line between the anchors of a joint that has come apart.
pub const JOINT_GAP: Rgb = Rgb([255, 40, 40]);
/// The line between a distance joint's anchors, or a slider's.
pub const JOINT_LINK: Rgb = Rgb([235, 235, 235]);

/// The colour of a body: static bodies are stone grey; the others take a palette colour picked
/// by a hash (FNV-1a) of their name.
pub fn body_colour(name: &str, body_type: BodyType) -> Rgb {
    if body_type == BodyType::Static {
        return STATIC_BODY;
    }
    let hash = name.bytes().fold(0x811c_9dc5_u32, |hash, byte| {
        (hash ^ u32::from(byte)).wrapping_mul(0x0100_0193)
    });
    BODY_PALETTE[hash as usize % BODY_PALETTE.len()]
}

/// The colour a body is drawn in this frame: its own, or tinted when it sleeps and the tint is on.
pub fn shown_colour(colour: Rgb, sleeping: bool, tint_sleeping: bool) -> Rgb {
    if sleeping && tint_sleeping {
        colour.mix(SLEEPING_TINT, SLEEPING_TINT_AMOUNT)
    } else {
        colour
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_follow_names_and_static_bodies_are_grey() {
        let first = body_colour("crate", BodyType::Dynamic);
        assert_eq!(first, body_colour("crate", BodyType::Dynamic));
        assert_eq!(body_colour("ground", BodyType::Static), STATIC_BODY);
        let distinct: std::collections::HashSet<Rgb> = (0..40)
            .map(|index| body_colour(&format!("box{index}"), BodyType::Dynamic))
            .collect();
        assert!(distinct.len() >= 8, "names spread over the palette");
    }

    #[test]
    fn sleeping_tint_applies_only_when_asked() {
        let colour = Rgb([200, 0, 0]);
        assert_eq!(shown_colour(colour, true, false), colour);
        assert_eq!(shown_colour(colour, false, true), colour);
        let tinted = shown_colour(colour, true, true);
        assert_ne!(tinted, colour);
        assert_eq!(tinted, colour.mix(SLEEPING_TINT, SLEEPING_TINT_AMOUNT));
    }

    #[test]
    fn colours_print_as_hex() {
        assert_eq!(Rgb([255, 8, 16]).to_string(), "#ff0810");
    }
}
