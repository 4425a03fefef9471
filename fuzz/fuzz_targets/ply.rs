//! Fuzz target `ply`: see [`sweepffd_fuzz::ply`]; an error is fine, a panic or abort is a finding.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = sweepffd_fuzz::ply(data);
});
