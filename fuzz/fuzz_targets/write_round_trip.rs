//! Fuzz target `write_round_trip`: see [`sweepffd_fuzz::write_round_trip`]; an error is fine, a panic or abort is a finding.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = sweepffd_fuzz::write_round_trip(data);
});
