//! The `world_calls` fuzz target's sequences of library calls (`fuzz/calls.rs`) from random
//! bytes: a short run of what the fuzzer explores at length. No call panics, and NaN or infinity
//! never enters a body.

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
