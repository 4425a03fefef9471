//! Fuzz target `script`: see [`sweepffd_fuzz::script`]; an error is fine, a panic or abort is a finding.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = sweepffd_fuzz::script(data);
});
