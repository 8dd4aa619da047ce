//! Any bytes as a saved state: restoring never panics, and a state that restores steps.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rebond::scene::Scene;
use rebond::World;

fuzz_target!(|data: &[u8]| {
    if let Ok((mut scene, _)) = Scene::load_state(data) {
        let _ = scene.step();
    }
    if let Ok(mut world) = World::load_state(data) {
        let _ = world.step(1.0 / 60.0);
    }
});
