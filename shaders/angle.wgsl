// Angles without WGSL's atan2, whose precision is left to the driver.
// Twin: src/cpu/angle.rs.

const PI: f32 = 3.141592653589793;

// The angle of (x, y) in [-pi, pi], for (x, y) != 0, to about 2e-7 rad on every device (WGSL's
// atan2 may be far less accurate): octant reduction to atan(a), a in [0, 1]; above tan(pi / 8),
// atan(a) = pi / 4 + atan((a - 1) / (a + 1)); then the odd series to z^15 (|z| <= tan(pi / 8)).
fn angle_of(x: f32, y: f32) -> f32 {
    let ax = abs(x);
    let ay = abs(y);
    var a = min(ax, ay) / max(ax, ay);
    var base = 0.0;
    if (a > 0.41421356) {
        a = (a - 1.0) / (a + 1.0);
        base = 0.25 * PI;
    }
    let z2 = a * a;
    let series = a * (1.0 - z2 * (1.0 / 3.0 - z2 * (1.0 / 5.0 - z2 * (1.0 / 7.0 - z2 * (1.0 / 9.0
        - z2 * (1.0 / 11.0 - z2 * (1.0 / 13.0 - z2 * (1.0 / 15.0))))))));
    var angle = base + series;
    if (ay > ax) {
        angle = 0.5 * PI - angle;
    }
    if (x < 0.0) {
        angle = PI - angle;
    }
    if (y < 0.0) {
        angle = -angle;
    }
    return angle;
}
