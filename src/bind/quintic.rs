//! Every root of a quintic on [0, 1], certified by Bernstein sign variations.
//!
//! On one knot interval the binding function f(t) = ⟨v − C(t), N(t)⟩ equals g(s)/|q(s)|² with g
//! a polynomial of degree 5 in the local parameter s (C is cubic, the unnormalized normal is
//! quadratic) and |q(s)|² > 0, so f and g have the same roots. In the Bernstein basis on an
//! interval, the number of real roots inside is at most the number of sign variations of the
//! coefficients and has its parity (Descartes' rule of signs for the Bernstein basis). So an
//! interval with no variation has no root, one with one variation has exactly one, and only
//! intervals with more are subdivided (de Casteljau at the midpoint). Unlike sampling at a
//! fixed step, this cannot miss two roots that are close together however sharply the sweep
//! bends.

/// Power-basis coefficients `[a0, …, a5]` of `g(s) = Σ a_i·s^i`.
pub type Quintic = [f64; 6];

/// Binomial ratios `C(i, j) / C(5, j)` for the power → Bernstein conversion.
const POWER_TO_BERNSTEIN: [[f64; 6]; 6] = [
    [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0, 1.0 / 5.0, 0.0, 0.0, 0.0, 0.0],
    [1.0, 2.0 / 5.0, 1.0 / 10.0, 0.0, 0.0, 0.0],
    [1.0, 3.0 / 5.0, 3.0 / 10.0, 1.0 / 10.0, 0.0, 0.0],
    [1.0, 4.0 / 5.0, 6.0 / 10.0, 4.0 / 10.0, 1.0 / 5.0, 0.0],
    [1.0, 1.0, 1.0, 1.0, 1.0, 1.0],
];

/// Subdivision stops at intervals of width 2^−40; an interval that still has several sign
/// variations there holds a (near-)double root, reported at its midpoint.
const MAX_DEPTH: u32 = 40;

/// Root refinement stops when the bracket or the Newton step is below this width in s.
const S_TOLERANCE: f64 = 1e-13;

/// g(s) by Horner's rule.
pub fn eval(g: &Quintic, s: f64) -> f64 {
    g.iter().rev().fold(0.0, |acc, &a| acc * s + a)
}

/// g(s) and g′(s) by Horner's rule.
fn eval_with_derivative(g: &Quintic, s: f64) -> (f64, f64) {
    let (mut value, mut derivative) = (0.0, 0.0);
    for &a in g.iter().rev() {
        derivative = derivative * s + value;
        value = value * s + a;
    }
    (value, derivative)
}

/// Bernstein coefficients of g on [0, 1].
fn bernstein(g: &Quintic) -> [f64; 6] {
    std::array::from_fn(|i| (0..=i).map(|j| POWER_TO_BERNSTEIN[i][j] * g[j]).sum())
}

/// Sign variations of a coefficient sequence, counting 0 as positive.
fn sign_variations(b: &[f64; 6]) -> u32 {
    b.windows(2).filter(|w| (w[0] >= 0.0) != (w[1] >= 0.0)).count() as u32
}

/// The Bernstein coefficients of the left and right halves (de Casteljau at ½).
fn split(b: &[f64; 6]) -> ([f64; 6], [f64; 6]) {
    let mut work = *b;
    let mut left = [0.0; 6];
    let mut right = [0.0; 6];
    for level in 0..6 {
        left[level] = work[0];
        right[5 - level] = work[5 - level];
        for i in 0..5 - level {
            work[i] = 0.5 * (work[i] + work[i + 1]);
        }
    }
    (left, right)
}

/// Calls `found` with every root of `g` in [0, 1], in increasing order (a root on the boundary
/// of two subintervals may be reported twice).
pub fn for_each_root(g: &Quintic, found: &mut impl FnMut(f64)) {
    if g[0] == 0.0 {
        found(0.0);
    }
    isolate(g, &bernstein(g), 0.0, 1.0, 0, found);
    if eval(g, 1.0) == 0.0 {
        found(1.0);
    }
}

fn isolate(g: &Quintic, b: &[f64; 6], lo: f64, hi: f64, depth: u32, found: &mut impl FnMut(f64)) {
    match sign_variations(b) {
        0 => {}
        1 => found(refine(g, lo, hi, b[0] >= 0.0)),
        _ if depth >= MAX_DEPTH => {
            let at_ends_differ = (b[0] >= 0.0) != (b[5] >= 0.0);
            found(if at_ends_differ { refine(g, lo, hi, b[0] >= 0.0) } else { 0.5 * (lo + hi) });
        }
        _ => {
            let (left, right) = split(b);
            let mid = 0.5 * (lo + hi);
            isolate(g, &left, lo, mid, depth + 1, found);
            isolate(g, &right, mid, hi, depth + 1, found);
        }
    }
}

/// The root of g in [lo, hi], where g(lo) and g(hi) differ in sign (0 counted as positive):
/// Newton's method kept inside the shrinking bracket, bisecting when a step would leave it.
fn refine(g: &Quintic, mut lo: f64, mut hi: f64, positive_at_lo: bool) -> f64 {
    let mut s = 0.5 * (lo + hi);
    for _ in 0..100 {
        let (value, derivative) = eval_with_derivative(g, s);
        if value == 0.0 {
            return s;
        }
        if (value >= 0.0) == positive_at_lo {
            lo = s;
        } else {
            hi = s;
        }
        let newton = s - value / derivative;
        let next = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        let step = (next - s).abs();
        s = next;
        if step <= S_TOLERANCE || hi - lo <= S_TOLERANCE {
            break;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Power coefficients of Π (s − r_i) times `scale`, padded to degree 5 with extra factors
    /// that have no root in [0, 1].
    fn from_roots(roots: &[f64], scale: f64) -> Quintic {
        let mut g = [0.0; 6];
        g[0] = scale;
        let mut degree = 0;
        let mut multiply = |c0: f64, c1: f64, g: &mut Quintic| {
            for i in (0..=degree + 1).rev() {
                let lower = if i > 0 { g[i - 1] } else { 0.0 };
                g[i] = c0 * g[i] + c1 * lower;
            }
            degree += 1;
        };
        for r in roots {
            multiply(-r, 1.0, &mut g);
        }
        for _ in roots.len()..5 {
            multiply(3.0, 1.0, &mut g); // (s + 3): root at −3
        }
        g
    }

    fn roots_of(g: &Quintic) -> Vec<f64> {
        let mut roots = Vec::new();
        for_each_root(g, &mut |s| roots.push(s));
        roots.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        roots
    }

    #[test]
    fn finds_five_separated_roots() {
        let expected = [0.05, 0.3, 0.5, 0.71, 0.98];
        let roots = roots_of(&from_roots(&expected, 2.0));
        assert_eq!(roots.len(), 5, "{roots:?}");
        for (r, e) in roots.iter().zip(expected) {
            assert!((r - e).abs() < 1e-12, "{r} vs {e}");
        }
    }

    #[test]
    fn finds_two_roots_closer_than_any_sampling_step() {
        let expected = [0.4, 0.400001];
        let roots = roots_of(&from_roots(&expected, -1.0));
        assert_eq!(roots.len(), 2, "{roots:?}");
        // Close roots are ill-conditioned: each is determined to about eps / |g′(root)|.
        assert!((roots[0] - 0.4).abs() < 1e-9 && (roots[1] - 0.400001).abs() < 1e-9, "{roots:?}");
    }

    #[test]
    fn no_root_in_the_interval_reports_none() {
        assert!(roots_of(&from_roots(&[1.5, -0.2], 1.0)).is_empty());
    }

    #[test]
    fn roots_on_the_interval_ends_are_reported() {
        let roots = roots_of(&from_roots(&[0.0, 1.0], 1.0));
        assert_eq!(roots.len(), 2, "{roots:?}");
        assert_eq!(roots[0], 0.0);
        assert!((roots[1] - 1.0).abs() < 1e-12, "{roots:?}");
    }

    #[test]
    fn double_root_is_reported_near_its_position() {
        let roots = roots_of(&from_roots(&[0.625, 0.625], 1.0));
        assert!(!roots.is_empty());
        assert!(roots.iter().all(|r| (r - 0.625).abs() < 1e-6), "{roots:?}");
    }

    #[test]
    fn bernstein_endpoints_are_the_values_at_the_ends() {
        let g = [0.3, -1.0, 2.0, 0.5, -0.25, 0.125];
        let b = bernstein(&g);
        assert_eq!(b[0], g[0]);
        assert!((b[5] - eval(&g, 1.0)).abs() < 1e-15);
    }
}
