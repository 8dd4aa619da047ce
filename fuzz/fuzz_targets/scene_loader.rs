//! Any bytes as a scene file: loading never panics, and a scene that loads steps without
//! panicking and without NaN or infinity entering a body.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rebond::scene::Scene;

fuzz_target!(|data: &[u8]| {
    let Ok(mut scene) = Scene::from_json(data) else {
        return;
    };
    for _ in 0..3 {
        if scene.step().is_err() {
            return;
        }
        for (name, body) in scene.bodies() {
            let finite = body.position().is_finite()
                && body.rotation().is_finite()
                && body.linear_velocity().is_finite()
                && body.angular_velocity().is_finite();
            assert!(finite, "body {name} is not finite");
        }
    }
});
