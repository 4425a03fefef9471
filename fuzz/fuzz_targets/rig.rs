//! Fuzz target `rig`: see [`sweepffd_fuzz::rig`]; an error is fine, a panic or abort is a finding.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = sweepffd_fuzz::rig(data);
});
