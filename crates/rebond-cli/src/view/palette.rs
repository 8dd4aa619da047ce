//! The viewer's colours: one per body (the engine's [`rebond::palette`], shared with the Python
//! module's pictures), and the colours of the ground, the sky and the debug drawings.

pub use rebond::palette::{body_colour, Rgb, STATIC_BODY};

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
    fn sleeping_tint_applies_only_when_asked() {
        let colour = Rgb([200, 0, 0]);
        assert_eq!(shown_colour(colour, true, false), colour);
        assert_eq!(shown_colour(colour, false, true), colour);
        let tinted = shown_colour(colour, true, true);
        assert_ne!(tinted, colour);
        assert_eq!(tinted, colour.mix(SLEEPING_TINT, SLEEPING_TINT_AMOUNT));
    }
}
