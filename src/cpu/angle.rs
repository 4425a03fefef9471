//! Twin of `shaders/angle.wgsl`: angles without WGSL's atan2, whose precision is left to the
//! driver.

use std::f32::consts::PI;

/// The angle of (x, y) in [−π, π], for (x, y) ≠ 0, to about 2e-7 rad on every device (WGSL's
/// atan2 may be far less accurate): octant reduction to atan(a), a ∈ [0, 1]; above tan(π/8),
/// atan(a) = π/4 + atan((a − 1)/(a + 1)); then the odd series to z¹⁵ (|z| ≤ tan(π/8)).
pub fn angle_of(x: f32, y: f32) -> f32 {
    let ax = x.abs();
    let ay = y.abs();
    let mut a = ax.min(ay) / ax.max(ay);
    let mut base = 0.0;
    if a > 0.41421356 {
        a = (a - 1.0) / (a + 1.0);
        base = 0.25 * PI;
    }
    let z2 = a * a;
    let series = a
        * (1.0
            - z2 * (1.0 / 3.0
                - z2 * (1.0 / 5.0
                    - z2 * (1.0 / 7.0
                        - z2 * (1.0 / 9.0 - z2 * (1.0 / 11.0 - z2 * (1.0 / 13.0 - z2 * (1.0 / 15.0))))))));
    let mut angle = base + series;
    if ay > ax {
        angle = 0.5 * PI - angle;
    }
    if x < 0.0 {
        angle = PI - angle;
    }
    if y < 0.0 {
        angle = -angle;
    }
    angle
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angle_of_matches_atan2_all_around_the_circle() {
        let mut worst = 0.0f64;
        for i in 0..100_000 {
            let t = i as f64 / 100_000.0 * std::f64::consts::TAU - std::f64::consts::PI;
            let (x, y) = ((3.0 * t.cos()) as f32, (3.0 * t.sin()) as f32);
            let exact = (y as f64).atan2(x as f64);
            worst = worst.max((angle_of(x, y) as f64 - exact).abs());
        }
        assert!(worst < 3e-7, "worst error {worst:e} rad");
        assert_eq!(angle_of(1.0, 0.0), 0.0);
        assert_eq!(angle_of(-1.0, 0.0), PI);
        assert_eq!(angle_of(0.0, 2.0), 0.5 * PI);
    }
}
