//! The text overlays: the statistics panel and the help panel, written with the public-domain
//! 8×8 bitmap font of `font8x8` into RGBA images that the renderer lays over the scene.

use font8x8::legacy::BASIC_LEGACY;

use super::simulation::{Stats, SLOW_MOTION_RATE};

/// Each font pixel becomes a square of this many screen pixels.
const FONT_SCALE: usize = 2;
/// Width and height of a glyph in font pixels.
const GLYPH_SIZE: usize = 8;
/// Vertical distance between lines of text, screen pixels.
const LINE_HEIGHT: usize = GLYPH_SIZE * FONT_SCALE + 4;
/// Empty space around the text, screen pixels.
const PADDING: usize = 8;
/// Panel background: dark and mostly opaque.
const PANEL_BACKGROUND: [u8; 4] = [16, 18, 24, 200];
/// Text colour.
const TEXT_COLOUR: [u8; 4] = [236, 236, 236, 255];

/// An RGBA image, top row first.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width, pixels.
    pub width: usize,
    /// Height, pixels.
    pub height: usize,
    /// `width · height` pixels, row by row from the top.
    pub pixels: Vec<[u8; 4]>,
}

/// Writes `lines` on a dark panel; characters outside ASCII show as `?`.
pub fn text_panel(lines: &[String]) -> Image {
    let columns = lines
        .iter()
        .map(|line| line.chars().count())
        .max()
        .unwrap_or(0);
    let width = 2 * PADDING + columns * GLYPH_SIZE * FONT_SCALE;
    let height = 2 * PADDING + lines.len() * LINE_HEIGHT;
    let mut image = Image {
        width,
        height,
        pixels: vec![PANEL_BACKGROUND; width * height],
    };
    for (row, line) in lines.iter().enumerate() {
        let top = PADDING + row * LINE_HEIGHT + (LINE_HEIGHT - GLYPH_SIZE * FONT_SCALE) / 2;
        for (column, character) in line.chars().enumerate() {
            let left = PADDING + column * GLYPH_SIZE * FONT_SCALE;
            draw_glyph(&mut image, character, left, top);
        }
    }
    image
}

/// Draws one character with its top-left corner at (`left`, `top`).
fn draw_glyph(image: &mut Image, character: char, left: usize, top: usize) {
    let code = if character.is_ascii() {
        character as usize
    } else {
        usize::from(b'?')
    };
    let glyph = BASIC_LEGACY[code];
    for (glyph_row, bits) in glyph.iter().enumerate() {
        for glyph_column in 0..GLYPH_SIZE {
            if bits & (1 << glyph_column) == 0 {
                continue;
            }
            for dy in 0..FONT_SCALE {
                for dx in 0..FONT_SCALE {
                    let x = left + glyph_column * FONT_SCALE + dx;
                    let y = top + glyph_row * FONT_SCALE + dy;
                    if x < image.width && y < image.height {
                        image.pixels[y * image.width + x] = TEXT_COLOUR;
                    }
                }
            }
        }
    }
}

/// The statistics panel's lines for a scene called `scene`, with the name of the body being
/// dragged, if any.
pub fn stats_lines(
    scene: &str,
    stats: &Stats,
    paused: bool,
    slow_motion: bool,
    dragged: Option<&str>,
) -> Vec<String> {
    let mut state = format!("t {:.2} s  step {}", stats.time, stats.steps);
    if paused {
        state.push_str("  PAUSED");
    }
    if slow_motion {
        state.push_str(&format!("  SLOW x{SLOW_MOTION_RATE}"));
    }
    let mut lines = vec![
        shortened(scene),
        state,
        format!("ms per step {:.3}", stats.ms_per_step),
        format!("bodies      {}", stats.bodies),
        format!("contacts    {}", stats.contacts),
        format!("islands     {}", stats.islands),
        format!("sleeping    {}", stats.sleeping),
    ];
    if let Some(name) = dragged {
        lines.push(format!("dragging    {name}"));
    }
    lines.push("H: help".to_owned());
    lines
}

/// Longest scene name shown whole; longer ones keep their end.
const MAX_SCENE_NAME: usize = 30;

/// `name`, or its last characters after `...` when it is too long for the panel.
fn shortened(name: &str) -> String {
    let length = name.chars().count();
    if length <= MAX_SCENE_NAME {
        return name.to_owned();
    }
    let tail: String = name.chars().skip(length + 3 - MAX_SCENE_NAME).collect();
    format!("...{tail}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_panel_fits_its_text_and_draws_glyphs() {
        let image = text_panel(&["Hi".to_owned(), "rebond".to_owned()]);
        assert_eq!(image.width, 2 * PADDING + 6 * 16);
        assert_eq!(image.height, 2 * PADDING + 2 * LINE_HEIGHT);
        assert_eq!(image.pixels.len(), image.width * image.height);
        let lit = image
            .pixels
            .iter()
            .filter(|&&pixel| pixel == TEXT_COLOUR)
            .count();
        assert!(lit > 100, "{lit} text pixels");
        assert_eq!(image.pixels[0], PANEL_BACKGROUND, "the padding stays empty");
    }

    #[test]
    fn glyphs_are_drawn_left_to_right_and_top_down() {
        let image = text_panel(&["|".to_owned()]);
        let lit: Vec<(usize, usize)> = (0..image.height)
            .flat_map(|y| (0..image.width).map(move |x| (x, y)))
            .filter(|&(x, y)| image.pixels[y * image.width + x] == TEXT_COLOUR)
            .collect();
        let xs: std::collections::BTreeSet<usize> = lit.iter().map(|&(x, _)| x).collect();
        assert_eq!(xs.len(), 2 * FONT_SCALE, "a bar two font pixels wide");
        let ys: std::collections::BTreeSet<usize> = lit.iter().map(|&(_, y)| y).collect();
        assert!(ys.len() >= 6 * FONT_SCALE, "and tall");
    }

    #[test]
    fn stats_lines_show_counts_and_state() {
        let stats = Stats {
            ms_per_step: 1.25,
            bodies: 31,
            contacts: 57,
            islands: 3,
            sleeping: 10,
            steps: 120,
            time: 2.0,
        };
        let text = stats_lines("showcase (built-in)", &stats, true, true, Some("crate")).join("\n");
        for expected in [
            "showcase",
            "ms per step 1.250",
            "bodies      31",
            "contacts    57",
            "islands     3",
            "sleeping    10",
            "PAUSED",
            "SLOW x0.25",
            "step 120",
            "dragging    crate",
        ] {
            assert!(text.contains(expected), "{expected} in:\n{text}");
        }
        let long = stats_lines(
            "some/long/directory/and/a/scene.json",
            &stats,
            false,
            false,
            None,
        );
        assert_eq!(long[0], ".../directory/and/a/scene.json");
        assert_eq!(long[0].len(), MAX_SCENE_NAME);
        let running = stats_lines("s", &stats, false, false, None).join("\n");
        assert!(!running.contains("PAUSED") && !running.contains("SLOW"));
        assert!(!running.contains("dragging"));
    }
}
