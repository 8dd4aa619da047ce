//! `rebond view`: the viewer opens a real window under Xvfb (Mesa's software OpenGL), takes a
//! screenshot after some steps, and the picture must show the scene: not blank, the ground's grey
//! over a good part of it, and each body's colour where the viewer says it drew the body.
//!
//! The tests that need a display run only when the build script found `xvfb-run` on the PATH
//! (the cfg `rebond_has_xvfb`); otherwise they are reported as ignored, with the reason. In CI
//! (`CI` set), where `.ci/run` installs Xvfb and Mesa, a missing `xvfb-run` is a failure.

use std::ffi::OsStr;
use std::fs::File;
use std::io::BufReader;
use std::path::Path;
use std::process::Command;
use std::sync::Mutex;

use crate::common::{assert_one_error_line, rebond, Outcome, TestDir};

/// The screen Xvfb gives the viewer: big enough for its 960×540 screenshot window, 24-bit colour
/// (GLX finds no visual at xvfb-run's default depth of 8).
const XVFB_SCREEN: &str = "-screen 0 1280x720x24";

/// Colour of static bodies, as `rebond view` prints it.
const STATIC_BODY_COLOUR: &str = "#b2b0aa";

/// Held while an Xvfb server runs: `xvfb-run -a` started by parallel tests can race for the same
/// display number.
static XVFB: Mutex<()> = Mutex::new(());

/// Runs `rebond ARGUMENTS` in a window under Xvfb.
fn rebond_under_xvfb<I, S>(arguments: I) -> Outcome
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let _one_at_a_time = XVFB.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    Command::new("xvfb-run")
        .args(["-a", "-s", XVFB_SCREEN])
        .arg(env!("CARGO_BIN_EXE_rebond"))
        .args(arguments)
        .output()
        .expect("run xvfb-run")
        .into()
}

/// A decoded RGB picture.
struct Picture {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Picture {
    fn read(path: &Path) -> Self {
        let file = File::open(path).expect("the screenshot exists");
        let mut reader = png::Decoder::new(BufReader::new(file))
            .read_info()
            .expect("the screenshot is a PNG");
        let mut buffer = vec![0; reader.output_buffer_size().expect("a buffer size")];
        let info = reader.next_frame(&mut buffer).expect("a frame");
        assert_eq!(info.color_type, png::ColorType::Rgb);
        assert_eq!(info.bit_depth, png::BitDepth::Eight);
        buffer.truncate(info.buffer_size());
        Self {
            width: info.width as usize,
            height: info.height as usize,
            rgb: buffer,
        }
    }

    fn pixel(&self, x: usize, y: usize) -> [u8; 3] {
        let start = 3 * (y * self.width + x);
        [self.rgb[start], self.rgb[start + 1], self.rgb[start + 2]]
    }

    fn pixels(&self) -> impl Iterator<Item = [u8; 3]> + '_ {
        self.rgb
            .chunks_exact(3)
            .map(|pixel| [pixel[0], pixel[1], pixel[2]])
    }

    /// Whether a pixel within `radius` of (`x`, `y`) satisfies `test`.
    fn any_near(&self, x: usize, y: usize, radius: usize, test: impl Fn([u8; 3]) -> bool) -> bool {
        let columns = x.saturating_sub(radius)..(x + radius + 1).min(self.width);
        let rows = y.saturating_sub(radius)..(y + radius + 1).min(self.height);
        rows.flat_map(|row| columns.clone().map(move |column| (column, row)))
            .any(|(column, row)| test(self.pixel(column, row)))
    }
}

/// Hue in degrees, saturation and value (0 to 1) of an RGB colour.
fn hsv([red, green, blue]: [u8; 3]) -> (f32, f32, f32) {
    let [red, green, blue] = [red, green, blue].map(|channel| f32::from(channel) / 255.0);
    let max = red.max(green).max(blue);
    let min = red.min(green).min(blue);
    let spread = max - min;
    let hue = if spread == 0.0 {
        0.0
    } else if max == red {
        60.0 * ((green - blue) / spread).rem_euclid(6.0)
    } else if max == green {
        60.0 * ((blue - red) / spread + 2.0)
    } else {
        60.0 * ((red - green) / spread + 4.0)
    };
    let saturation = if max == 0.0 { 0.0 } else { spread / max };
    (hue, saturation, max)
}

/// Whether a drawn (lit, shaded) pixel shows the body colour `expected`: same hue to within 15°,
/// clearly coloured.
fn shows_colour(pixel: [u8; 3], expected: [u8; 3]) -> bool {
    let (hue, saturation, value) = hsv(pixel);
    let (expected_hue, _, _) = hsv(expected);
    let difference = (hue - expected_hue).abs();
    difference.min(360.0 - difference) <= 15.0 && saturation >= 0.35 && value >= 0.15
}

/// Whether a pixel is the lit grey of the ground: hardly coloured, and bright.
fn is_ground_grey(pixel: [u8; 3]) -> bool {
    let (_, saturation, value) = hsv(pixel);
    saturation < 0.12 && value > 0.45
}

/// The colour of `#rrggbb`.
fn parse_colour(text: &str) -> [u8; 3] {
    let hex = text.strip_prefix('#').expect("#rrggbb");
    let channel =
        |index: usize| u8::from_str_radix(&hex[2 * index..2 * index + 2], 16).expect("hex digits");
    [channel(0), channel(1), channel(2)]
}

/// One `body` line of the screenshot report.
struct BodyLine {
    name: String,
    colour: [u8; 3],
    pixel: Option<(usize, usize)>,
}

/// The report's `body #rrggbb X,Y NAME` lines.
fn body_lines(stdout: &str) -> Vec<BodyLine> {
    stdout
        .lines()
        .filter_map(|line| line.strip_prefix("body "))
        .map(|line| {
            let mut fields = line.splitn(3, ' ');
            let colour = fields.next().expect("a colour");
            let pixel = fields.next().expect("a pixel");
            let name = fields.next().expect("a name").to_owned();
            let pixel = pixel.split_once(',').map(|(x, y)| {
                (
                    x.parse().expect("an x pixel"),
                    y.parse().expect("a y pixel"),
                )
            });
            BodyLine {
                name,
                colour: parse_colour(colour),
                pixel,
            }
        })
        .collect()
}

/// Takes a screenshot of `scene` after `steps` steps under Xvfb and returns the report and the
/// picture.
fn screenshot(dir: &TestDir, scene: &OsStr, steps: &str) -> (String, Picture) {
    let path = dir.path("frame.png");
    let outcome = rebond_under_xvfb([
        OsStr::new("view"),
        scene,
        OsStr::new("--screenshot"),
        path.as_os_str(),
        OsStr::new("--steps"),
        OsStr::new(steps),
    ]);
    assert_eq!(outcome.status, 0, "stderr: {}", outcome.stderr);
    assert!(!outcome.stderr.contains("panicked"), "{}", outcome.stderr);
    assert!(
        outcome
            .stdout
            .contains(&format!("screenshot       {} (960x540)", path.display())),
        "{}",
        outcome.stdout
    );
    assert!(outcome
        .stdout
        .contains(&format!("steps            {steps}\n")));
    (outcome.stdout, Picture::read(&path))
}

/// Checks that the picture is not blank, shows the ground over at least `ground_share` of it,
/// and shows every moving body the report places on screen in its colour there (allowing for a
/// few hidden behind others); returns how many bodies were found.
fn assert_shows_scene(stdout: &str, picture: &Picture, ground_share: f32) -> usize {
    assert_eq!((picture.width, picture.height), (960, 540));
    let total = (picture.width * picture.height) as f32;
    let distinct: std::collections::HashSet<[u8; 3]> = picture.pixels().collect();
    assert!(
        distinct.len() > 500,
        "a blank picture: {} colours",
        distinct.len()
    );
    let ground = picture
        .pixels()
        .filter(|&pixel| is_ground_grey(pixel))
        .count() as f32;
    assert!(
        ground / total > ground_share,
        "the ground covers {:.0} % of the picture",
        100.0 * ground / total
    );
    let bodies = body_lines(stdout);
    assert!(!bodies.is_empty(), "no body lines in:\n{stdout}");
    let static_colour = parse_colour(STATIC_BODY_COLOUR);
    let on_screen: Vec<&BodyLine> = bodies
        .iter()
        .filter(|body| body.colour != static_colour && body.pixel.is_some())
        .collect();
    let missing: Vec<&str> = on_screen
        .iter()
        .filter(|body| {
            let (x, y) = body.pixel.expect("on screen");
            !picture.any_near(x, y, 6, |pixel| shows_colour(pixel, body.colour))
        })
        .map(|body| body.name.as_str())
        .collect();
    assert!(
        missing.len() * 10 <= on_screen.len(),
        "bodies not drawn where expected: {missing:?} of {}",
        on_screen.len()
    );
    on_screen.len() - missing.len()
}

#[test]
#[cfg_attr(not(rebond_has_xvfb), ignore = "needs xvfb-run (apt-get install xvfb)")]
fn the_showcase_screenshot_shows_the_ground_and_the_bodies_in_their_colours() {
    let dir = TestDir::new("view_showcase");
    let (stdout, picture) = screenshot(&dir, OsStr::new("showcase"), "120");
    assert!(stdout.starts_with("scene            showcase (built-in)\n"));
    assert!(stdout.contains("bodies           31\n"), "{stdout}");
    let found = assert_shows_scene(&stdout, &picture, 0.3);
    assert!(found >= 25, "only {found} bodies seen");
    let colours: std::collections::HashSet<[u8; 3]> =
        body_lines(&stdout).iter().map(|body| body.colour).collect();
    assert!(colours.len() >= 8, "bodies take distinct colours");
}

#[test]
#[cfg_attr(not(rebond_has_xvfb), ignore = "needs xvfb-run (apt-get install xvfb)")]
fn every_shape_is_drawn_and_a_halfspace_is_a_ground_grid() {
    let dir = TestDir::new("view_every_shape");
    let scene = dir.write(
        "shapes.json",
        r#"{"bodies": [
        {"name": "floor", "type": "static", "shape": {"type": "halfspace", "normal": [0, 1, 0]}},
        {"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "position": [-4, 0.5, 0]},
        {"name": "crate", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
         "position": [-2, 0.5, 0]},
        {"name": "pill", "shape": {"type": "capsule", "radius": 0.4, "half_height": 0.4},
         "position": [0, 0.8, 0]},
        {"name": "drum", "shape": {"type": "cylinder", "radius": 0.5, "half_height": 0.5},
         "position": [2, 0.5, 0]},
        {"name": "gem", "shape": {"type": "convex_hull", "points": [[-0.5, 0, -0.5], [0.5, 0, -0.5],
         [0.5, 0, 0.5], [-0.5, 0, 0.5], [0, 1.0, 0]]}, "position": [4, 0, 0]},
        {"name": "dumbbell", "shape": {"type": "compound", "children": [
            {"shape": {"type": "sphere", "radius": 0.4}, "position": [-0.6, 0, 0]},
            {"shape": {"type": "capsule", "radius": 0.15, "half_height": 0.5},
             "rotation": [0, 0, 0.7071068, 0.7071068]},
            {"shape": {"type": "box", "half_extents": [0.35, 0.35, 0.35]}, "position": [0.6, 0, 0]}
         ]}, "position": [0, 0.4, -2.5]}
    ]}"#,
    );
    let (stdout, picture) = screenshot(&dir, scene.as_os_str(), "5");
    assert!(
        stdout.contains(&format!("body {STATIC_BODY_COLOUR} off-screen floor\n")),
        "{stdout}"
    );
    let found = assert_shows_scene(&stdout, &picture, 0.25);
    assert_eq!(found, 6, "every shape is seen");
    // The grid's lines are a darker grey than the lit plane around them.
    let grid_lines = picture
        .pixels()
        .filter(|&pixel| {
            let (_, saturation, value) = hsv(pixel);
            saturation < 0.12 && (0.42..0.6).contains(&value)
        })
        .count();
    assert!(
        grid_lines > 2000,
        "the ground grid's lines: {grid_lines} pixels"
    );
}

#[test]
#[cfg_attr(not(rebond_has_xvfb), ignore = "needs xvfb-run (apt-get install xvfb)")]
fn joints_are_drawn_with_their_anchors_axes_and_limits() {
    // A bar on a limited hinge and a ball on a ball joint with swing and twist limits, both held
    // to the world above a floor: the picture shows the bodies, and the joint colours of the
    // palette (anchors green, axes magenta, limits lilac), drawn as unlit lines.
    let dir = TestDir::new("view_joints");
    let scene = dir.write(
        "joints.json",
        r#"{"bodies": [
        {"name": "floor", "type": "static", "shape": {"type": "box", "half_extents": [6, 0.5, 6]},
         "position": [0, -0.5, 0]},
        {"name": "bar", "shape": {"type": "box", "half_extents": [0.1, 0.6, 0.1]},
         "position": [-1, 1.4, 0]},
        {"name": "bob", "shape": {"type": "sphere", "radius": 0.3}, "position": [1.5, 1.2, 0]}
    ], "joints": [
        {"type": "revolute", "body_b": "bar", "anchor": [-1, 2, 0], "axis": [0, 0, 1],
         "limits": [-0.5, 1.0]},
        {"type": "ball", "body_b": "bob", "anchor": [1.5, 2, 0], "axis": [0, -1, 0],
         "swing_limit": 0.5, "twist_limits": [-0.4, 0.4]}
    ]}"#,
    );
    let (stdout, picture) = screenshot(&dir, scene.as_os_str(), "10");
    let found = assert_shows_scene(&stdout, &picture, 0.2);
    assert_eq!(found, 2, "both bodies seen");
    for (name, colour) in [
        ("anchors", [150, 255, 80]),
        ("axes", [255, 90, 220]),
        ("limits", [180, 150, 255]),
    ] {
        let drawn = picture.pixels().filter(|&pixel| pixel == colour).count();
        assert!(drawn >= 10, "{name}: {drawn} pixels of {colour:?}");
    }
}

#[test]
#[cfg_attr(not(rebond_has_xvfb), ignore = "needs xvfb-run (apt-get install xvfb)")]
fn the_platformer_screenshot_shows_its_level_and_character() {
    // A second in: the crates ride the belt, the platform has set off, the door hangs on its
    // hinge. The picture is not blank, its static level and ground cover a good part of it, and
    // the moving bodies the report places on screen are drawn there in their colours.
    let dir = TestDir::new("view_platformer");
    let (stdout, picture) = screenshot(&dir, OsStr::new("platformer"), "60");
    assert!(stdout.starts_with("scene            platformer (built-in)\n"));
    assert!(stdout.contains("bodies           19\n"), "{stdout}");
    let found = assert_shows_scene(&stdout, &picture, 0.2);
    let player = body_lines(&stdout)
        .into_iter()
        .find(|body| body.name == "player")
        .expect("the player's line");
    assert!(player.pixel.is_some(), "the player is on screen");
    assert!(found >= 6, "only {found} bodies seen");
}

#[test]
#[cfg_attr(not(rebond_has_xvfb), ignore = "needs xvfb-run (apt-get install xvfb)")]
fn an_unwritable_screenshot_is_an_error_line() {
    let dir = TestDir::new("view_unwritable");
    let path = dir.path("missing-directory").join("frame.png");
    let outcome = rebond_under_xvfb([
        OsStr::new("view"),
        OsStr::new("column"),
        OsStr::new("--screenshot"),
        path.as_os_str(),
    ]);
    let line = assert_one_error_line(&outcome, 1, &path);
    assert!(line.contains("cannot write screenshot"), "{line}");
}

/// CI must run the tests above, not ignore them.
#[test]
#[cfg(not(rebond_has_xvfb))]
fn ci_has_xvfb_run() {
    let in_ci = std::env::var("CI").is_ok_and(|value| !value.is_empty() && value != "false");
    assert!(
        !in_ci,
        "xvfb-run is missing in CI: .ci/run should have installed xvfb"
    );
}

#[test]
fn without_a_display_the_viewer_says_so() {
    let outcome: Outcome = Command::new(env!("CARGO_BIN_EXE_rebond"))
        .args(["view", "showcase"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run rebond")
        .into();
    assert_eq!(outcome.status, 1, "{}", outcome.stderr);
    assert_eq!(outcome.stdout, "");
    let lines: Vec<&str> = outcome.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "{}", outcome.stderr);
    assert!(lines[0].starts_with("error: cannot open the viewer: no display"));
    assert!(lines[0].contains("xvfb-run"));
}

#[test]
fn a_bad_scene_is_refused_before_any_window_opens() {
    let dir = TestDir::new("view_bad_scene");
    let scene = dir.write(
        "bad.json",
        r#"{"bodies": [{"shape": {"type": "sphere", "radius": -1}}]}"#,
    );
    let outcome = rebond(["view".as_ref(), scene.as_os_str()]);
    let line = assert_one_error_line(&outcome, 2, &scene);
    assert!(line.contains("bodies[0].shape.radius"), "{line}");
    let unknown = rebond(["view", "no-such-scene"]);
    assert_eq!(unknown.status, 1);
    assert!(unknown
        .stderr
        .starts_with("error: no-such-scene: cannot read scene"));
}

#[test]
fn steps_need_a_screenshot() {
    let outcome = rebond(["view", "showcase", "--steps", "10"]);
    assert_eq!(outcome.status, 2, "{}", outcome.stderr);
    assert!(
        outcome.stderr.contains("--screenshot"),
        "{}",
        outcome.stderr
    );
}
