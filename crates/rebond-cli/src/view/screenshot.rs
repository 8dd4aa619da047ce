//! `--screenshot`: the frame saved as PNG, and the summary printed after it: the counts, and
//! where each body is drawn in which colour, so that scripts and tests can check the picture.

use std::fmt;
use std::fs::File;
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};

use glam::Vec2;

use super::palette::Rgb;
use super::viewer::Viewer;
use crate::failure::Failure;

/// Where one body shows in the picture.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyLegend {
    /// Its name.
    pub name: String,
    /// The colour it is drawn in.
    pub colour: Rgb,
    /// The pixel (from the top left) its centre of mass is drawn at, or `None` when that is off
    /// the screen or behind the camera.
    pub pixel: Option<Vec2>,
}

/// What `rebond view --screenshot` prints.
#[derive(Debug, Clone, PartialEq)]
pub struct ScreenshotReport {
    /// How the scene is named.
    pub scene: String,
    /// Steps taken before the picture.
    pub steps: u64,
    /// The PNG written.
    pub path: PathBuf,
    /// Its size, pixels.
    pub width: u32,
    /// Its height, pixels.
    pub height: u32,
    /// Bodies in the world.
    pub bodies: usize,
    /// Contact points.
    pub contacts: usize,
    /// Islands.
    pub islands: usize,
    /// Bodies asleep.
    pub sleeping: usize,
    /// Every body, in scene order.
    pub legend: Vec<BodyLegend>,
}

impl ScreenshotReport {
    /// The report for the picture of `viewer` just saved to `path`.
    pub fn new(scene: String, viewer: &Viewer, path: &Path, width: u32, height: u32) -> Self {
        let simulation = &viewer.simulation;
        let world = simulation.world();
        let stats = simulation.stats();
        let viewport = Vec2::new(width as f32, height as f32);
        let legend = simulation
            .bodies()
            .iter()
            .map(|info| BodyLegend {
                name: info.name.clone(),
                colour: info.colour,
                pixel: world
                    .body(info.handle)
                    .ok()
                    .filter(|body| body.shape().is_bounded())
                    .and_then(|body| viewer.camera.project(body.center_of_mass(), viewport)),
            })
            .collect();
        Self {
            scene,
            steps: stats.steps,
            path: path.to_owned(),
            width,
            height,
            bodies: stats.bodies,
            contacts: stats.contacts,
            islands: stats.islands,
            sleeping: stats.sleeping,
            legend,
        }
    }
}

impl fmt::Display for ScreenshotReport {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(formatter, "scene            {}", self.scene)?;
        writeln!(formatter, "steps            {}", self.steps)?;
        writeln!(
            formatter,
            "screenshot       {} ({}x{})",
            self.path.display(),
            self.width,
            self.height
        )?;
        writeln!(formatter, "bodies           {}", self.bodies)?;
        writeln!(formatter, "contacts         {}", self.contacts)?;
        writeln!(formatter, "islands          {}", self.islands)?;
        writeln!(formatter, "sleeping bodies  {}", self.sleeping)?;
        for body in &self.legend {
            let pixel = body.pixel.map_or_else(
                || "off-screen".to_owned(),
                |pixel| format!("{:.0},{:.0}", pixel.x, pixel.y),
            );
            writeln!(formatter, "body {} {pixel} {}", body.colour, body.name)?;
        }
        Ok(())
    }
}

/// Writes `pixels` (RGBA, top row first, `width · height` of them) to `path` as an RGB PNG.
pub fn save_png(path: &Path, width: u32, height: u32, pixels: &[[u8; 4]]) -> Result<(), Failure> {
    let failure = |error: io::Error| Failure::io(path, "cannot write screenshot", error);
    let file = File::create(path).map_err(failure)?;
    let mut encoder = png::Encoder::new(BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::High);
    let rgb: Vec<u8> = pixels
        .iter()
        .flat_map(|&[red, green, blue, _]| [red, green, blue])
        .collect();
    let encoding = |error: png::EncodingError| match error {
        png::EncodingError::IoError(error) => failure(error),
        other => failure(io::Error::other(other)),
    };
    let mut writer = encoder.write_header().map_err(encoding)?;
    writer.write_image_data(&rgb).map_err(encoding)?;
    writer.finish().map_err(encoding)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_saved_png_reads_back_the_same() {
        let directory = std::env::temp_dir().join(format!("rebond-view-{}", std::process::id()));
        std::fs::create_dir_all(&directory).expect("a scratch directory");
        let path = directory.join("frame.png");
        let pixels: Vec<[u8; 4]> = (0..6u8)
            .map(|index| [index * 40, 255 - index, 7, 255])
            .collect();
        save_png(&path, 3, 2, &pixels).expect("saved");
        let decoder = png::Decoder::new(io::BufReader::new(File::open(&path).expect("the file")));
        let mut reader = decoder.read_info().expect("a PNG");
        let mut buffer = vec![0; reader.output_buffer_size().expect("a size")];
        let info = reader.next_frame(&mut buffer).expect("a frame");
        assert_eq!((info.width, info.height), (3, 2));
        let expected: Vec<u8> = pixels
            .iter()
            .flat_map(|pixel| pixel[..3].to_vec())
            .collect();
        assert_eq!(&buffer[..info.buffer_size()], &expected[..]);
        std::fs::remove_dir_all(&directory).expect("cleaned up");
    }

    #[test]
    fn an_unwritable_path_is_an_io_failure() {
        let path = Path::new("/nonexistent-directory/frame.png");
        let failure = save_png(path, 1, 1, &[[0, 0, 0, 255]]).expect_err("cannot write");
        let message = failure.to_string();
        assert!(message.starts_with("/nonexistent-directory/frame.png: cannot write screenshot"));
        assert_eq!(failure.exit_status(), crate::failure::EXIT_IO);
    }
}
