//! Colours for drawing bodies: one per body, chosen from its name, so that every run, every
//! screenshot of the viewer (`rebond view`) and every picture from the Python module
//! (`World.render`) paints a scene's bodies alike.

use std::fmt;

use crate::body::BodyType;

/// An sRGB colour, 8 bits a channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Rgb(pub [u8; 3]);

impl Rgb {
    /// Black.
    pub const BLACK: Rgb = Rgb([0, 0, 0]);
    /// White.
    pub const WHITE: Rgb = Rgb([255, 255, 255]);

    /// The colour `amount` (0 to 1) of the way from `self` to `other`, channel by channel:
    /// `self + (other - self) · amount`, rounded.
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

/// The colour of a body: static bodies are stone grey ([`STATIC_BODY`]); the others take one of
/// ten saturated colours picked by a hash (FNV-1a) of their name.
pub fn body_colour(name: &str, body_type: BodyType) -> Rgb {
    if body_type == BodyType::Static {
        return STATIC_BODY;
    }
    let hash = name.bytes().fold(0x811c_9dc5_u32, |hash, byte| {
        (hash ^ u32::from(byte)).wrapping_mul(0x0100_0193)
    });
    BODY_PALETTE[hash as usize % BODY_PALETTE.len()]
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
    fn colours_mix_channel_by_channel() {
        assert_eq!(
            Rgb([200, 0, 10]).mix(Rgb([100, 255, 10]), 0.5),
            Rgb([150, 128, 10])
        );
        assert_eq!(Rgb::BLACK.mix(Rgb::WHITE, 0.0), Rgb::BLACK);
        assert_eq!(Rgb::BLACK.mix(Rgb::WHITE, 1.0), Rgb::WHITE);
    }

    #[test]
    fn colours_print_as_hex() {
        assert_eq!(Rgb([255, 8, 16]).to_string(), "#ff0810");
    }
}
