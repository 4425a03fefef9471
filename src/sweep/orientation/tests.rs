use super::*;

fn piece() -> OrientationPiece {
    let a = DQuat::from_rotation_x(0.3) * DQuat::from_rotation_y(-0.7);
    let b = DQuat::from_rotation_z(2.1) * DQuat::from_rotation_x(1.2);
    OrientationPiece::new(a, -b)
}

/// Keys turning about changing axes, at uneven knots.
fn keys() -> (Vec<f64>, Vec<DQuat>) {
    let knots = vec![0.0, 0.1, 0.35, 0.4, 0.7, 1.0];
    let rotations = (0..knots.len())
        .map(|i| {
            let t = i as f64;
            let q = DQuat::from_rotation_x(0.4 * t) * DQuat::from_rotation_y(0.3 * t * t - 0.5) * DQuat::from_rotation_z(0.9 * t);
            if i % 2 == 1 { -q } else { q }
        })
        .collect();
    (knots, rotations)
}

fn pieces(interpolation: RotationInterpolation, knots: &[f64], rotations: &[DQuat]) -> Vec<OrientationPiece> {
    let mut pieces = Vec::new();
    for_each_piece(interpolation, knots, |i| rotations[i], |k, piece| {
        assert_eq!(k, pieces.len());
        pieces.push(piece);
    });
    pieces
}

/// ω = 2·vec(q′·q*)/|q|² per unit t, on interval k of `knots` at local parameter s.
fn angular_velocity(piece: &OrientationPiece, h: f64, s: f64) -> DVec3 {
    let q = piece.unnormalized(s);
    2.0 * (piece.derivative(s) * q.conjugate()).xyz() / (q.length_squared() * h)
}

#[test]
fn ends_are_sign_aligned() {
    let p = piece();
    assert!(p.start.dot(p.end) >= 0.0);
    let (knots, rotations) = keys();
    for p in pieces(RotationInterpolation::Cubic, &knots, &rotations) {
        assert!(p.start.dot(p.end) >= 0.0);
    }
}

#[test]
fn normal_bilinear_of_a_unit_quaternion_is_its_z_axis() {
    let q = piece().start;
    assert!((normal_bilinear(q, q) - q * DVec3::Z).length() < 1e-15);
}

#[test]
fn normal_numerator_matches_the_normalized_normal() {
    let (knots, rotations) = keys();
    let cubic = pieces(RotationInterpolation::Cubic, &knots, &rotations);
    for p in std::iter::once(piece()).chain(cubic) {
        let n = p.normal_numerator();
        if !p.cubic {
            assert!(n[3..].iter().all(|c| *c == DVec3::ZERO), "a linear piece's numerator is quadratic");
        }
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            let q = p.unnormalized(s);
            let expected = p.value(s) * DVec3::Z;
            let numerator = n.iter().rev().fold(DVec3::ZERO, |acc, c| acc * s + *c);
            assert!((numerator / q.length_squared() - expected).length() < 1e-14, "s = {s}");
        }
    }
}

#[test]
fn both_interpolations_pass_through_the_keys() {
    let (knots, rotations) = keys();
    for interpolation in [RotationInterpolation::Linear, RotationInterpolation::Cubic] {
        for (k, p) in pieces(interpolation, &knots, &rotations).iter().enumerate() {
            for (s, key) in [(0.0, rotations[k]), (1.0, rotations[k + 1])] {
                let turn = p.value(s) * key.conjugate();
                assert!(turn.w.abs() > 1.0 - 1e-14, "{interpolation:?} interval {k}, s = {s}");
            }
        }
    }
}

#[test]
fn derivative_matches_finite_differences() {
    let (knots, rotations) = keys();
    for p in pieces(RotationInterpolation::Cubic, &knots, &rotations).iter().chain([&piece()]) {
        for s in [0.0, 0.3, 0.77, 1.0] {
            let step = 1e-6;
            let difference = (p.unnormalized(s + step) - p.unnormalized(s - step)) / (2.0 * step);
            assert!((difference - p.derivative(s)).length() < 1e-8, "s = {s}");
        }
    }
}

/// The cubic interpolation's angular velocity is continuous at every interior key; the linear
/// one's jumps there (the check fails on it).
#[test]
fn cubic_rotation_is_c1_across_the_keys_and_linear_is_not() {
    let (knots, rotations) = keys();
    let jumps = |interpolation| {
        let pieces = pieces(interpolation, &knots, &rotations);
        (1..pieces.len())
            .map(|k| {
                let left = angular_velocity(&pieces[k - 1], knots[k] - knots[k - 1], 1.0);
                let right = angular_velocity(&pieces[k], knots[k + 1] - knots[k], 0.0);
                (left - right).length() / left.length().max(right.length())
            })
            .fold(0.0, f64::max)
    };
    let (cubic, linear) = (jumps(RotationInterpolation::Cubic), jumps(RotationInterpolation::Linear));
    assert!(cubic < 1e-12, "cubic: ω jumps by {cubic} (relative)");
    assert!(linear > 0.1, "linear: ω jumps by {linear} (relative)");
}

#[test]
fn two_keys_give_the_linear_interpolation() {
    let knots = [0.0, 1.0];
    let rotations = [piece().start, piece().end];
    let cubic = pieces(RotationInterpolation::Cubic, &knots, &rotations)[0];
    let linear = pieces(RotationInterpolation::Linear, &knots, &rotations)[0];
    for i in 0..=8 {
        let s = i as f64 / 8.0;
        assert!((cubic.unnormalized(s) - linear.unnormalized(s)).length() < 1e-15, "s = {s}");
    }
}

/// Hostile keys (nearly opposite rotations, repeated keys, knots a thousand times closer on one
/// side): the cubic never comes near a zero quaternion.
#[test]
fn cubic_norm_stays_above_its_bound() {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut random = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut smallest = f64::INFINITY;
    for trial in 0..400 {
        let n = 2 + trial % 7;
        let mut knots: Vec<f64> = vec![0.0];
        for _ in 0..n {
            let step = if random() < 0.3 { 1e-3 * random() + 1e-6 } else { random() + 0.01 };
            knots.push(knots.last().unwrap() + step);
        }
        let rotations: Vec<DQuat> = (0..=n)
            .map(|i| {
                if i > 0 && random() < 0.1 {
                    return DQuat::IDENTITY;
                }
                let axis = DVec3::new(random() - 0.5, random() - 0.5, random() - 0.5).normalize_or(DVec3::X);
                DQuat::from_axis_angle(axis, std::f64::consts::TAU * random())
            })
            .collect();
        for p in pieces(RotationInterpolation::Cubic, &knots, &rotations) {
            for i in 0..=64 {
                smallest = smallest.min(p.unnormalized(i as f64 / 64.0).length());
            }
        }
    }
    assert!(smallest >= 0.28, "|q(s)| down to {smallest}");
}

/// A key turned between still stretches (the pose of one `move_key`): the cubic turns only
/// across the turned interval, never backwards before it or past the turn after it.
#[test]
fn cubic_never_turns_back_beside_still_keys() {
    let knots = [0.0, 0.2, 0.4, 0.6, 0.8, 1.0];
    let (still, turned) = (DQuat::IDENTITY, DQuat::from_rotation_x(1.0));
    let rotations = [still, still, still, turned, turned, turned];
    let pieces = pieces(RotationInterpolation::Cubic, &knots, &rotations);
    let mut previous = 0.0;
    for (k, p) in pieces.iter().enumerate() {
        for i in 0..=32 {
            let angle = p.value(i as f64 / 32.0).angle_between(still);
            assert!(angle >= previous - 1e-15 && angle <= 1.0 + 1e-15, "interval {k}: {angle} after {previous}");
            if k != 2 {
                assert!((angle - if k < 2 { 0.0 } else { 1.0 }).abs() < 1e-15, "interval {k} turns: {angle}");
            }
            previous = angle;
        }
    }
}
