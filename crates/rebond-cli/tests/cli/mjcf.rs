//! MuJoCo MJCF models (`.xml`) run like scene files.

use crate::common::{assert_one_error_line, rebond, TestDir};

/// A pendulum on a hinge above a floor, with a motor.
const PENDULUM: &str = r#"<mujoco model="pendulum">
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="bob" pos="0 0 2" euler="0 30 0">
      <joint name="hinge" type="hinge" axis="0 1 0" damping="0.1"/>
      <geom type="capsule" fromto="0 0 0 0 0 -1" size="0.05"/>
    </body>
  </worldbody>
  <actuator><motor joint="hinge" gear="2" ctrlrange="-1 1"/></actuator>
</mujoco>"#;

#[test]
fn an_mjcf_model_runs_and_records_its_bodies() {
    let dir = TestDir::new("mjcf_runs");
    let model = dir.write("pendulum.xml", PENDULUM);
    let record = dir.path("pendulum.jsonl");
    let outcome = rebond([
        "run".as_ref(),
        model.as_os_str(),
        "--steps".as_ref(),
        "10".as_ref(),
        "--record".as_ref(),
        record.as_os_str(),
    ]);
    assert_eq!(outcome.status, 0, "stderr: {}", outcome.stderr);
    let record = std::fs::read_to_string(record).expect("the record");
    let last: serde_json::Value =
        serde_json::from_str(record.lines().last().expect("a line")).expect("JSON");
    // The floor (a static body named after its geom) and the bob, in rebond's Y-up frame: the
    // bob's origin stays on the hinge, 2 m up.
    assert_eq!(last["step"], 10);
    assert_eq!(last["bodies"][0]["name"], "floor");
    assert_eq!(last["bodies"][1]["name"], "bob");
    let height = last["bodies"][1]["position"][1].as_f64().expect("a height");
    assert!(
        (height - 2.0).abs() < 1e-3,
        "the bob's origin at {height} m"
    );
}

#[test]
fn a_bad_mjcf_model_is_one_error_line_naming_the_element() {
    let dir = TestDir::new("mjcf_bad");
    let model = dir.write("bad.xml", &PENDULUM.replace("damping=", "dampng="));
    let outcome = rebond(["run".as_ref(), model.as_os_str()]);
    let line = assert_one_error_line(&outcome, 2, &model);
    assert!(
        line.contains("mujoco/worldbody/body[name=bob]/joint[name=hinge]@dampng"),
        "{line}"
    );
}
