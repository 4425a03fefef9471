//! What the autorig tests print about the parts they find.

use sweepffd::fit::autorig::Autorig;
use sweepffd::mesh::Mesh;

/// Prints each part of `rigged`, found on `mesh` (named `name`): vertices, tip, keys, fit
/// quality at its own vertices and at those it was fitted to, and time.
pub fn print_parts(name: &str, mesh: &Mesh, rigged: &Autorig) {
    for part in &rigged.parts {
        let q = part.quality;
        eprintln!(
            "{name} {}: {} vertices, tip {:.3}, {} keys, RMS |d| {:.2}% ({:.2}% over the {} it was fitted to), max {:.1}%, {:.3} s",
            part.name,
            part.vertices.len(),
            mesh.positions[part.tip as usize],
            part.fit.keys.len(),
            100.0 * q.rms_d,
            100.0 * part.fit.quality.rms_d,
            part.fit.quality.vertices,
            100.0 * q.max_d,
            part.seconds
        );
    }
}
