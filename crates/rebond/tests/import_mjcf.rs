//! The MJCF importer (`Scene::from_mjcf`, `docs/mjcf.md`): Gymnasium's MuJoCo models load with
//! MuJoCo's masses and poses and step; defaults, orientations, a pendulum's period; bad files
//! are refused at their path in the file.

use std::path::{Path, PathBuf};

use rebond::scene::{LoadError, Scene};
use rebond::{Quat, Vec3};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mjcf")
}

/// A model given as text, read with `data()` as its folder.
fn model(xml: &str) -> Result<Scene, LoadError> {
    Scene::from_mjcf(xml.as_bytes(), &data())
}

/// The error message of a model that must be refused.
fn refused(xml: &str) -> String {
    match model(xml) {
        Ok(_) => panic!("accepted: {xml}"),
        Err(error) => error.to_string(),
    }
}

/// A MuJoCo world position from a rebond one: `C⁻¹ p`, `(x, y, z)` → `(x, −z, y)`.
fn mujoco_position(p: Vec3) -> Vec3 {
    Vec3::new(p.x, -p.z, p.y)
}

/// How far apart two rotations are: the distance of their quaternions, either sign (half the
/// angle between them, for small ones).
fn apart(a: Quat, b: Quat) -> f32 {
    (a - b).length().min((a + b).length())
}

/// `C`: MuJoCo's frame turned to rebond's, −90° about X.
fn turn() -> Quat {
    Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2)
}

/// A body's name, mass (kg) and MuJoCo world position (m).
type Body = (&'static str, f32, [f32; 3]);

// Each body's mass (kg) and world position (m, `data.xpos` after `mj_forward`), from MuJoCo
// 4.0.1, printed by this script run in tests/data/mjcf:
//
//   import mujoco, sys
//   for f in sys.argv[1:]:
//       m = mujoco.MjModel.from_xml_path(f); d = mujoco.MjData(m); mujoco.mj_forward(m, d)
//       for i in range(1, m.nbody):
//           name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_BODY, i) or f"body{i}"
//           print(name, f"{m.body_mass[i]:.7g}", [float(f"{v:.7g}") for v in d.xpos[i]])
const ANT: &[Body] = &[
    ("torso", 0.3272492, [0.0, 0.0, 0.75]),
    ("front_left_leg", 0.03915775, [0.0, 0.0, 0.75]),
    ("aux_1", 0.03915775, [0.2, 0.2, 0.75]),
    ("body4", 0.0675922, [0.4, 0.4, 0.75]),
    ("front_right_leg", 0.03915775, [0.0, 0.0, 0.75]),
    ("aux_2", 0.03915775, [-0.2, 0.2, 0.75]),
    ("body7", 0.0675922, [-0.4, 0.4, 0.75]),
    ("back_leg", 0.03915775, [0.0, 0.0, 0.75]),
    ("aux_3", 0.03915775, [-0.2, -0.2, 0.75]),
    ("body10", 0.0675922, [-0.4, -0.4, 0.75]),
    ("right_back_leg", 0.03915775, [0.0, 0.0, 0.75]),
    ("aux_4", 0.03915775, [0.2, -0.2, 0.75]),
    ("body13", 0.0675922, [0.4, -0.4, 0.75]),
];
const HALF_CHEETAH: &[Body] = &[
    ("torso", 6.250209, [0.0, 0.0, 0.7]),
    ("bthigh", 1.543515, [-0.5, 0.0, 0.7]),
    ("bshin", 1.587448, [-0.34, 0.0, 0.45]),
    ("bfoot", 1.095397, [-0.62, 0.0, 0.31]),
    ("fthigh", 1.438075, [0.5, 0.0, 0.7]),
    ("fshin", 1.200837, [0.36, 0.0, 0.46]),
    ("ffoot", 0.8845188, [0.49, 0.0, 0.28]),
];
const HOPPER: &[Body] = &[
    ("torso", 3.665191, [0.0, 0.0, 1.25]),
    ("thigh", 4.057891, [0.0, 0.0, 1.05]),
    ("leg", 2.781357, [0.0, 0.0, 0.35]),
    ("foot", 5.315575, [0.13, 0.0, 0.0]),
];
const WALKER2D_V5: &[Body] = &[
    ("torso", 3.665191, [0.0, 0.0, 1.25]),
    ("thigh", 4.057891, [0.0, 0.0, 1.05]),
    ("leg", 2.781357, [0.0, 0.0, 0.35]),
    ("foot", 3.166725, [0.2, 0.0, 0.0]),
    ("thigh_left", 4.057891, [0.0, 0.0, 1.05]),
    ("leg_left", 2.781357, [0.0, 0.0, 0.35]),
    ("foot_left", 3.166725, [0.2, 0.0, 0.0]),
];
const HUMANOID: &[Body] = &[
    ("torso", 8.907462, [0.0, 0.0, 1.4]),
    ("lwaist", 2.261947, [-0.01, 0.0, 1.14]),
    ("pelvis", 6.616194, [-0.009340003, 0.0, 0.9750013]),
    ("right_thigh", 4.751751, [-0.009020006, -0.1, 0.9350026]),
    ("right_shin", 2.755696, [-0.005796045, -0.09, 0.5320155]),
    ("right_foot", 1.767146, [-0.002196088, -0.09, 0.0820299]),
    ("left_thigh", 4.751751, [-0.009020006, 0.1, 0.9350026]),
    ("left_shin", 2.755696, [-0.005796045, 0.09, 0.5320155]),
    ("left_foot", 1.767146, [-0.002196088, 0.09, 0.0820299]),
    ("right_upper_arm", 1.66108, [0.0, -0.17, 1.46]),
    ("right_lower_arm", 1.22954, [0.18, -0.35, 1.28]),
    ("left_upper_arm", 1.66108, [0.0, 0.17, 1.46]),
    ("left_lower_arm", 1.22954, [0.18, 0.35, 1.28]),
];
const REACHER: &[Body] = &[
    ("body0", 0.03560472, [0.0, 0.0, 0.01]),
    ("body1", 0.03560472, [0.1, 0.0, 0.01]),
    ("fingertip", 0.00418879, [0.21, 0.0, 0.01]),
    ("target", 0.003053628, [0.1, -0.1, 0.01]),
];
const INVERTED_PENDULUM: &[Body] = &[
    ("cart", 10.47198, [0.0, 0.0, 0.0]),
    ("pole", 5.018592, [0.0, 0.0, 0.0]),
];
const INVERTED_DOUBLE_PENDULUM: &[Body] = &[
    ("cart", 10.47198, [0.0, 0.0, 0.0]),
    ("pole", 4.198739, [0.0, 0.0, 0.0]),
    ("pole2", 4.198739, [0.0, 0.0, 0.6]),
];

const MODELS: &[(&str, &[Body])] = &[
    ("ant", ANT),
    ("half_cheetah", HALF_CHEETAH),
    ("hopper", HOPPER),
    ("walker2d_v5", WALKER2D_V5),
    ("humanoid", HUMANOID),
    ("reacher", REACHER),
    ("inverted_pendulum", INVERTED_PENDULUM),
    ("inverted_double_pendulum", INVERTED_DOUBLE_PENDULUM),
];

fn gymnasium(name: &str) -> Scene {
    let path = data().join(format!("{name}.xml"));
    Scene::from_file(&path).unwrap_or_else(|error| panic!("{name}: {error}"))
}

#[test]
fn gymnasium_models_have_mujocos_masses_and_poses() {
    for (name, bodies) in MODELS {
        let scene = gymnasium(name);
        for (body, mass, position) in *bodies {
            let handle = scene
                .body_handle(body)
                .unwrap_or_else(|| panic!("{name}: no body {body}"));
            let state = scene.world().body(handle).unwrap();
            // Both from the same solids' formulas, rebond's in f32 and MuJoCo's printed to 7
            // digits: within 2e-6 relative (a few f32 roundings).
            let relative = (state.mass() - mass).abs() / mass;
            assert!(
                relative < 2e-6,
                "{name}/{body}: mass {} vs {mass}",
                state.mass()
            );
            // Positions are sums of the file's offsets turned by C, exact to f32 rounding.
            let error = (mujoco_position(state.position()) - Vec3::from_array(*position)).length();
            assert!(
                error < 1e-6,
                "{name}/{body}: at {} vs {position:?}",
                state.position()
            );
        }
    }
}

#[test]
fn gymnasium_models_step_five_seconds_with_zero_controls() {
    for (name, _) in MODELS {
        let mut scene = gymnasium(name);
        let controls = vec![0.0; scene.actuators().len()];
        scene.set_controls(&controls).unwrap();
        let steps = (5.0 / scene.timestep().seconds).round() as usize;
        let mut farthest = 0.0_f32;
        let mut fastest = 0.0_f32;
        for _ in 0..steps {
            scene.step().unwrap();
            for (_, body) in scene.bodies() {
                farthest = farthest.max(body.position().length());
                fastest = fastest.max(body.linear_velocity().length());
            }
        }
        println!("{name}: {steps} steps, farthest {farthest} m, fastest {fastest} m/s");
        // Unpowered, every model falls or swings in place: nothing leaves a few metres of the
        // origin, nothing outruns a fall from 2 m (6.3 m/s) by much.
        assert!(
            farthest.is_finite() && farthest < 5.0,
            "{name}: {farthest} m"
        );
        assert!(
            fastest.is_finite() && fastest < 10.0,
            "{name}: {fastest} m/s"
        );
    }
}

#[test]
fn ant_brings_its_ankles_into_range_and_rests_on_them() {
    // Gymnasium's Ant starts its ankles at 0, outside their 30° to 70° range (`[-70°, -30°]` for
    // ankles 2 and 3), with an armature of 1 kg·m² on legs of 0.07 kg. The limits push them in
    // with their rotors; standing on them the legs spread until the ankles rest on the 30° end
    // (a leg flatter than about 39° cannot hold its foot with friction 1), the torso's centre
    // then at `0.566 sin 30° + 0.08 = 0.363` m (the leg's length and radius; the ankle at the
    // torso's height). From 1 s to 3 s, sleeping off: every ankle within 0.01 rad of its range
    // (measured 5e-6 rad; 0.27 rad while the limits pushed the legs without their rotors), and
    // the torso within 5 mm of 0.363 m at the end (measured 0.3627 m). MuJoCo's
    // soft limit throws the ankles across to 73° instead, from where its feet creep down to
    // 30° by 15 s (`docs/mjcf.md`).
    let mut scene = gymnasium("ant");
    let mut settings = *scene.world().settings();
    settings.sleep_speed = 0.0;
    scene.world_mut().set_settings(settings).unwrap();
    let controls = vec![0.0; scene.actuators().len()];
    scene.set_controls(&controls).unwrap();
    let ankles = [
        ("ankle_1", 1.0),
        ("ankle_2", -1.0),
        ("ankle_3", -1.0),
        ("ankle_4", 1.0),
    ]
    .map(|(name, sign)| (scene.joint_handle(name).unwrap(), sign));
    let (low, high) = (30_f32.to_radians(), 70_f32.to_radians());
    let mut worst = 0.0_f32;
    for step in 0..300 {
        scene.step().unwrap();
        if step >= 100 {
            for (joint, sign) in ankles {
                let angle = sign * scene.world().joint_position(joint).unwrap();
                worst = worst.max(low - angle).max(angle - high);
            }
        }
    }
    assert!(worst < 0.01, "an ankle {worst} rad outside its range");
    let torso = scene.body_handle("torso").unwrap();
    let height = scene.world().body(torso).unwrap().center_of_mass().y;
    let expected = 0.566 * 0.5 + 0.08;
    assert!((height - expected).abs() < 0.005, "torso at {height} m");
}

#[test]
fn gymnasium_actuators_and_tendons_are_read() {
    let scene = gymnasium("ant");
    assert_eq!(scene.actuators().len(), 8);
    let first = &scene.actuators()[0];
    assert_eq!(first.joint, scene.joint_handle("hip_4").unwrap());
    assert_eq!(first.gear, 150.0);
    assert_eq!(first.ctrl_range, Some([-1.0, 1.0]));
    // The free root is no joint; each hinge is one, under its MJCF name.
    assert!(scene.joint_handle("root").is_none());
    assert!(scene.joint_handle("ankle_3").is_some());
    let humanoid = gymnasium("humanoid");
    assert_eq!(humanoid.actuators().len(), 17);
    // The humanoid's hips have three hinges: two light links between the pelvis and the thigh.
    assert!(humanoid.body_handle("right_thigh/right_hip_x").is_some());
    assert!(humanoid.body_handle("right_thigh/right_hip_z").is_some());
    assert!(humanoid.body_handle("right_thigh/right_hip_y").is_none());
    let json = rebond::scene::mjcf_to_json(
        &std::fs::read(data().join("humanoid.xml")).unwrap(),
        &data(),
    )
    .unwrap();
    let json: serde_json::Value = serde_json::from_str(&json).unwrap();
    let couplings = json["couplings"].as_array().unwrap();
    assert_eq!(couplings.len(), 2);
    assert_eq!(couplings[0]["name"], "left_hipknee");
    assert_eq!(couplings[0]["joints"][0]["joint"], "left_hip_y");
    assert_eq!(couplings[0]["joints"][0]["coefficient"], -1.0);
    // MuJoCo never lets a body touch its parent: the thigh and the pelvis, three hinges and two
    // links apart, do not collide; the torso, a child of the world, is free to.
    let world = humanoid.world();
    let body = |name: &str| humanoid.body_handle(name).unwrap();
    assert!(world.is_pair_ignored(body("right_thigh"), body("pelvis")));
    assert!(world.is_pair_ignored(body("lwaist"), body("torso")));
    assert!(!world.is_pair_ignored(body("right_thigh"), body("left_thigh")));
}

/// The mass of a sphere of radius `r` at MuJoCo's default density, 1000 kg/m³.
fn sphere_mass(r: f32) -> f32 {
    4.0 / 3.0 * std::f32::consts::PI * r * r * r * 1000.0
}

#[test]
fn default_classes_nest_and_childclass_applies_to_descendants() {
    let scene = model(
        r#"<mujoco>
          <default>
            <geom size="0.1"/>
            <default class="big">
              <geom size="0.2"/>
              <default class="dense"><geom density="2000"/></default>
            </default>
          </default>
          <worldbody>
            <body name="plain" pos="0 0 1"><freejoint/><geom/></body>
            <body name="classed" pos="1 0 1"><freejoint/><geom class="big"/></body>
            <body name="nested" pos="2 0 1"><freejoint/><geom class="dense"/></body>
            <body name="parent" pos="3 0 1" childclass="big"><freejoint/>
              <geom/>
              <body name="child"><joint type="hinge"/><geom size="0.3"/></body>
            </body>
          </worldbody>
        </mujoco>"#,
    )
    .unwrap();
    let mass = |name: &str| {
        let handle = scene.body_handle(name).unwrap();
        scene.world().body(handle).unwrap().mass()
    };
    let close = |a: f32, b: f32| (a - b).abs() < 1e-6 * b;
    assert!(close(mass("plain"), sphere_mass(0.1)));
    assert!(close(mass("classed"), sphere_mass(0.2)));
    // `dense` inherits `big`'s size and doubles the density.
    assert!(close(mass("nested"), 2.0 * sphere_mass(0.2)));
    assert!(close(mass("parent"), sphere_mass(0.2)));
    // The child's own size wins over its class's.
    assert!(close(mass("child"), sphere_mass(0.3)));
    let error = refused(
        r#"<mujoco><worldbody><body><freejoint/><geom class="nope" size="1"/></body></worldbody></mujoco>"#,
    );
    assert!(
        error.starts_with("mujoco/worldbody/body/geom@class:"),
        "{error}"
    );
}

#[test]
fn every_orientation_form_gives_the_same_turn() {
    // A quarter turn about Z, written six ways (degrees by default, radians when told).
    let forms = [
        r#"quat="0.70710678 0 0 0.70710678""#,
        r#"axisangle="0 0 1 90""#,
        r#"euler="0 0 90""#,
        r#"xyaxes="0 1 0 -1 0 0""#,
    ];
    let expected = turn() * Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
    for form in forms {
        let xml = format!(
            r#"<mujoco><worldbody><body name="b" {form}><freejoint/><geom size="0.1"/></body>
               </worldbody></mujoco>"#
        );
        let scene = model(&xml).unwrap();
        let rotation = scene
            .world()
            .body(scene.body_handle("b").unwrap())
            .unwrap()
            .rotation();
        // f32 rounding of the same rotation: within 2e-6 (4e-6 rad).
        assert!(apart(rotation, expected) < 2e-6, "{form}: {rotation}");
    }
    let radians = r#"<mujoco><compiler angle="radian" eulerseq="ZYX"/><worldbody>
        <body name="b" euler="1.5707963 0 0"><freejoint/><geom size="0.1"/></body>
        </worldbody></mujoco>"#;
    let scene = model(radians).unwrap();
    let rotation = scene
        .world()
        .body(scene.body_handle("b").unwrap())
        .unwrap()
        .rotation();
    assert!(apart(rotation, expected) < 2e-6, "radians: {rotation}");
    // zaxis: the shortest turn taking Z to X, a quarter turn about Y.
    let scene = model(
        r#"<mujoco><worldbody><body name="b" zaxis="1 0 0"><freejoint/><geom size="0.1"/></body>
           </worldbody></mujoco>"#,
    )
    .unwrap();
    let rotation = scene
        .world()
        .body(scene.body_handle("b").unwrap())
        .unwrap()
        .rotation();
    let expected = turn() * Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
    assert!(apart(rotation, expected) < 2e-6, "zaxis: {rotation}");
    // Nested bodies compose: a child 1 m along its parent's X, the parent turned 90° about Z,
    // stands 1 m along MuJoCo's Y: rebond's −Z.
    let scene = model(
        r#"<mujoco><worldbody><body name="a" euler="0 0 90"><freejoint/><geom size="0.1"/>
             <body name="b" pos="1 0 0"><joint/><geom size="0.1"/></body></body>
           </worldbody></mujoco>"#,
    )
    .unwrap();
    let position = scene
        .world()
        .body(scene.body_handle("b").unwrap())
        .unwrap()
        .position();
    assert!(
        (position - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6,
        "{position}"
    );
}

#[test]
fn a_hinge_pendulum_swings_at_its_small_swing_period() {
    // 1 kg at 1 m below a hinge about Y, let go 0.05 rad from the vertical; the inertia about
    // the mass itself, 1e-6 kg·m², adds 1e-6 to m L² = 1.
    let scene = model(
        r#"<mujoco><compiler angle="radian"/><option timestep="0.001"/><worldbody>
             <body name="bob" euler="0 0.05 0" pos="0 0 2">
               <joint name="hinge" type="hinge" axis="0 1 0"/>
               <inertial pos="0 0 -1" mass="1" diaginertia="1e-6 1e-6 1e-6"/>
               <geom type="sphere" size="0.01" contype="0" conaffinity="0" pos="0 0 -1"/>
             </body></worldbody></mujoco>"#,
    );
    let mut scene = scene.unwrap();
    let hinge = scene.joint_handle("hinge").unwrap();
    let dt = scene.timestep().seconds;
    // The angle swings between 0 and ∓0.1 rad about ∓0.05 (the sign of the first move says
    // which): upward crossings of the middle, by linear interpolation between steps.
    scene.step().unwrap();
    let middle = 0.05_f32.copysign(scene.world().joint_position(hinge).unwrap());
    let mut crossings = Vec::new();
    let mut previous = scene.world().joint_position(hinge).unwrap() - middle;
    for step in 2..=10_000 {
        scene.step().unwrap();
        let now = scene.world().joint_position(hinge).unwrap() - middle;
        if previous < 0.0 && now >= 0.0 {
            let fraction = f64::from(-previous / (now - previous));
            crossings.push((step as f64 - 1.0 + fraction) * dt);
        }
        previous = now;
    }
    let periods = crossings.len() - 1;
    let period = (crossings[periods] - crossings[0]) / periods as f64;
    // T = 2π √(L / g) (1 + θ₀² / 16) = 2.006 s · 1.00016 at θ₀ = 0.05 rad.
    let expected = std::f64::consts::TAU * (1.0_f64 / 9.81).sqrt() * (1.0 + 0.05 * 0.05 / 16.0);
    println!("period {period} s over {periods} swings, expected {expected} s");
    // Measured 4e-7 off: the semi-implicit step's period error at ω dt = 0.003 is of order
    // (ω dt)² / 24 ≈ 4e-7, and the crossings' interpolation adds less; 1e-5 leaves room for f32.
    assert!(
        (period / expected - 1.0).abs() < 1e-5,
        "period {period} s, expected {expected} s"
    );
}

#[test]
fn bad_files_are_refused_with_their_path() {
    let cases = [
        (
            r#"<mujoco><worldbody><body name="torso"><freejoint/><geom size="1"/><geom size="1" foo="1"/></body></worldbody></mujoco>"#,
            "mujoco/worldbody/body[name=torso]/geom[2]@foo:",
        ),
        (
            r#"<mujoco><worldbody><body name="torso"><wheel/></body></worldbody></mujoco>"#,
            "mujoco/worldbody/body[name=torso]/wheel:",
        ),
        (
            r#"<mujoco><worldbody><body name="b" childclass="missing"><freejoint/><geom size="1"/></body></worldbody></mujoco>"#,
            "mujoco/worldbody/body[name=b]@childclass:",
        ),
        (
            r#"<mujoco><worldbody><body name="b"><joint name="j" axis="0 0 0"/><geom size="1"/></body></worldbody></mujoco>"#,
            "mujoco/worldbody/body[name=b]/joint[name=j]@axis:",
        ),
        (
            r#"<mujoco><worldbody><body name="b"><freejoint/><geom size="1" mass="-2"/></body></worldbody></mujoco>"#,
            "mujoco/worldbody/body[name=b]/geom@mass:",
        ),
        (
            r#"<mujoco><worldbody><body name="b"><freejoint/><inertial pos="0 0 0" mass="-1" diaginertia="1 1 1"/></body></worldbody></mujoco>"#,
            "mujoco/worldbody/body[name=b]/inertial@mass:",
        ),
        (
            r#"<mujoco><worldbody><body name="b"><joint name="j"/><geom size="1"/></body></worldbody>
               <actuator><motor joint="nothing"/></actuator></mujoco>"#,
            "mujoco/actuator/motor@joint:",
        ),
        (
            r#"<mujoco><compiler coordinate="global"/></mujoco>"#,
            "mujoco/compiler@coordinate:",
        ),
        (
            r#"<mujoco><worldbody><body name="b"><joint/></body></worldbody></mujoco>"#,
            "mujoco/worldbody/body[name=b]:",
        ),
        (
            r#"<mujoco><asset><mesh name="m" file="missing.stl"/></asset></mujoco>"#,
            "mujoco/asset/mesh[name=m]@file: cannot load mesh file",
        ),
        (
            // A joint with no body to belong to.
            r#"<mujoco><worldbody><joint name="j"/></worldbody></mujoco>"#,
            "mujoco/worldbody/joint[name=j]:",
        ),
        (
            r#"<mujoco><worldbody><body name="b"><freejoint/><geom type="hfield" size="1"/></body></worldbody></mujoco>"#,
            "mujoco/worldbody/body[name=b]/geom@type:",
        ),
        (r#"<mujoco><worldbody>"#, "invalid XML"),
    ];
    for (xml, start) in cases {
        let error = refused(xml);
        assert!(error.starts_with(start), "expected {start}…, got {error}");
    }
}

/// The 12 triangles of the cube from −0.5 to 0.5, as corner triples.
fn cube_triangles() -> Vec<[[f32; 3]; 3]> {
    let corner =
        |k: usize| [k & 1, (k >> 1) & 1, (k >> 2) & 1].map(|bit| if bit == 1 { 0.5 } else { -0.5 });
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    faces
        .iter()
        .flat_map(|f| [[f[0], f[1], f[2]], [f[0], f[2], f[3]]])
        .map(|t| t.map(corner))
        .collect()
}

#[test]
fn meshes_are_hulls_on_moving_bodies_and_trimeshes_on_static_ones() {
    let folder = std::env::temp_dir().join(format!("rebond_mjcf_meshes_{}", std::process::id()));
    std::fs::create_dir_all(folder.join("meshes")).unwrap();
    let triangles = cube_triangles();
    let mut ascii = String::from("solid cube\n");
    let mut binary = vec![0_u8; 80];
    binary.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
    let mut obj = String::new();
    for (index, triangle) in triangles.iter().enumerate() {
        ascii.push_str("facet normal 0 0 0\nouter loop\n");
        binary.extend_from_slice(&[0; 12]);
        for corner in triangle {
            ascii.push_str(&format!(
                "vertex {} {} {}\n",
                corner[0], corner[1], corner[2]
            ));
            obj.push_str(&format!("v {} {} {}\n", corner[0], corner[1], corner[2]));
            for value in corner {
                binary.extend_from_slice(&value.to_le_bytes());
            }
        }
        ascii.push_str("endloop\nendfacet\n");
        binary.extend_from_slice(&[0; 2]);
        let first = 3 * index + 1;
        obj.push_str(&format!("f {} {} {}\n", first, first + 1, first + 2));
    }
    ascii.push_str("endsolid cube\n");
    std::fs::write(folder.join("meshes/ascii.stl"), ascii).unwrap();
    std::fs::write(folder.join("meshes/binary.stl"), binary).unwrap();
    std::fs::write(folder.join("meshes/cube.obj"), obj).unwrap();
    let xml = r#"<mujoco><compiler meshdir="meshes"/>
        <asset><mesh file="ascii.stl" scale="2 2 2"/><mesh name="b" file="binary.stl"/>
          <mesh file="cube.obj" scale="1 1 3"/></asset>
        <worldbody>
          <geom name="ground" type="mesh" mesh="ascii" pos="0 0 -1"/>
          <body name="one" pos="0 0 2"><freejoint/><geom type="mesh" mesh="b"/></body>
          <body name="two" pos="3 0 2"><freejoint/><geom type="mesh" mesh="cube"/></body>
        </worldbody></mujoco>"#;
    let scene = Scene::from_mjcf(xml.as_bytes(), &folder).unwrap();
    let mass = |name: &str| {
        let handle = scene.body_handle(name).unwrap();
        scene.world().body(handle).unwrap().mass()
    };
    // A unit cube's hull at 1000 kg/m³, and the OBJ cube stretched ×3: exact hull volumes.
    assert!((mass("one") - 1000.0).abs() < 1e-2, "{}", mass("one"));
    assert!((mass("two") - 3000.0).abs() < 3e-2, "{}", mass("two"));
    let ground = scene.body_handle("ground").unwrap();
    let ground = scene.world().body(ground).unwrap();
    assert_eq!(ground.body_type(), rebond::BodyType::Static);
    // The 2 m cube's top face, turned to Y-up, stands at 1 − 1 = 0.
    assert!(
        (ground.aabb().max.y - 0.0).abs() < 1e-6,
        "{:?}",
        ground.aabb()
    );
    std::fs::remove_dir_all(&folder).unwrap();
}
