//! Sequences of library calls with arbitrary values (`../calls.rs`): no call panics, and NaN or
//! infinity never enters a body.
#![no_main]

#[path = "../calls.rs"]
mod calls;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| calls::run_bytes(data));
