//! The `world_calls` fuzz target's sequences of library calls (`fuzz/calls.rs`) from random
//! bytes: a short run of what the fuzzer explores at length, and every crash it found. No call
//! panics, NaN or infinity never enters a body, and a saved world restores to step bit for bit.

#[path = "../../../fuzz/calls.rs"]
mod calls;

use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn any_sequence_of_calls_keeps_every_body_finite(
        data in proptest::collection::vec(any::<u8>(), 0..4096)
    ) {
        calls::run_bytes(&data);
    }
}

#[test]
fn every_crash_the_fuzzer_found_now_runs_through() {
    // `fuzz/README.md` says what each was and what fixed it.
    let folder = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fuzz/regressions/world_calls"
    );
    let mut replayed = 0;
    for entry in std::fs::read_dir(folder).unwrap() {
        calls::run_bytes(&std::fs::read(entry.unwrap().path()).unwrap());
        replayed += 1;
    }
    assert_eq!(replayed, 4);
}
