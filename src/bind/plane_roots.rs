//! Every root of the plane polynomial on [0, 1], certified by Bernstein sign variations.
//!
//! On one knot interval the binding function f(t) = ⟨v − C(t), N(t)⟩ equals g(s)/|q(s)|² with g
//! a polynomial in the local parameter s (degree 5 for the linear rotation interpolation: C is
//! cubic, the unnormalized normal quadratic; degree 9 for the cubic one, whose normal has degree
//! 6) and |q(s)|² > 0, so f and g have the same roots. In the Bernstein basis on an
//! interval, the number of real roots inside is at most the number of sign variations of the
//! coefficients and has its parity (Descartes' rule of signs for the Bernstein basis). So an
//! interval with no variation has no root, one with one variation has exactly one, and only
//! intervals with more are subdivided (de Casteljau at the midpoint). Unlike sampling at a
//! fixed step, this cannot miss two roots that are close together however sharply the sweep
//! bends.

/// Subdivision stops at intervals of width 2^−40; an interval that still has several sign
/// variations there holds a (near-)double root, reported at its midpoint.
const MAX_DEPTH: u32 = 40;

/// Root refinement stops when the bracket or the Newton step is below this width in s.
const S_TOLERANCE: f64 = 1e-13;

/// g(s) by Horner's rule; `g` holds the power coefficients a0 … a_degree.
pub fn eval(g: &[f64], s: f64) -> f64 {
    g.iter().rev().fold(0.0, |acc, &a| acc * s + a)
}

/// g(s) and g′(s) by Horner's rule.
fn eval_with_derivative<const N: usize>(g: &[f64; N], s: f64) -> (f64, f64) {
    let (mut value, mut derivative) = (0.0, 0.0);
    for &a in g.iter().rev() {
        derivative = derivative * s + value;
        value = value * s + a;
    }
    (value, derivative)
}

/// The binomial coefficient C(n, k), exact in f64 for n ≤ 9.
const fn binomial(n: usize, k: usize) -> f64 {
    let mut product = 1.0;
    let mut i = 0;
    while i < k {
        product = product * (n - i) as f64 / (i + 1) as f64;
        i += 1;
    }
    product
}

/// Polynomials of degree N − 1, as arrays of N power or Bernstein coefficients: the sizes are
/// constants, so that the loops below unroll for the quintic (N = 6) and the nonic (N = 10).
struct Degree<const N: usize>;

impl<const N: usize> Degree<N> {
    /// The ratios C(i, j) / C(N − 1, j) of the power → Bernstein conversion.
    const POWER_TO_BERNSTEIN: [[f64; N]; N] = {
        let mut table = [[0.0; N]; N];
        let mut i = 0;
        while i < N {
            let mut j = 0;
            while j <= i {
                table[i][j] = binomial(i, j) / binomial(N - 1, j);
                j += 1;
            }
            i += 1;
        }
        table
    };
}

/// Bernstein coefficients of g on [0, 1]: b_i = Σ_{j ≤ i} C(i, j) / C(n, j) · a_j.
fn bernstein<const N: usize>(g: &[f64; N]) -> [f64; N] {
    std::array::from_fn(|i| (0..=i).map(|j| Degree::<N>::POWER_TO_BERNSTEIN[i][j] * g[j]).sum())
}

/// Sign variations of a coefficient sequence, counting 0 as positive.
fn sign_variations<const N: usize>(b: &[f64; N]) -> u32 {
    b.windows(2).filter(|w| (w[0] >= 0.0) != (w[1] >= 0.0)).count() as u32
}

/// The Bernstein coefficients of the left and right halves (de Casteljau at ½).
fn split<const N: usize>(b: &[f64; N]) -> ([f64; N], [f64; N]) {
    let mut work = *b;
    let mut left = [0.0; N];
    let mut right = [0.0; N];
    for level in 0..N {
        left[level] = work[0];
        right[N - 1 - level] = work[N - 1 - level];
        for i in 0..N - 1 - level {
            work[i] = 0.5 * (work[i] + work[i + 1]);
        }
    }
    (left, right)
}

/// Calls `found` with every root in [0, 1] of `g`, the power coefficients a0 … a_n of a
/// quintic (n = 5) or a nonic (n = 9), in increasing order (a root on the boundary of two
/// subintervals may be reported twice).
pub fn for_each_root(g: &[f64], found: &mut impl FnMut(f64)) {
    match g.len() {
        6 => roots_of_degree::<6>(g.try_into().expect("six coefficients"), found),
        10 => roots_of_degree::<10>(g.try_into().expect("ten coefficients"), found),
        n => unreachable!("plane polynomials have degree 5 or 9, not {}", n - 1),
    }
}

fn roots_of_degree<const N: usize>(g: &[f64; N], found: &mut impl FnMut(f64)) {
    if g[0] == 0.0 {
        found(0.0);
    }
    isolate(g, &bernstein(g), 0.0, 1.0, 0, found);
    if eval(g, 1.0) == 0.0 {
        found(1.0);
    }
}

fn isolate<const N: usize>(g: &[f64; N], b: &[f64; N], lo: f64, hi: f64, depth: u32, found: &mut impl FnMut(f64)) {
    match sign_variations(b) {
        0 => {}
        1 => found(refine(g, lo, hi, b[0] >= 0.0)),
        _ if depth >= MAX_DEPTH => {
            let at_ends_differ = (b[0] >= 0.0) != (b[N - 1] >= 0.0);
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
fn refine<const N: usize>(g: &[f64; N], mut lo: f64, mut hi: f64, positive_at_lo: bool) -> f64 {
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

    /// Power coefficients of Π (s − r_i) times `scale`, padded to `DEGREE` with extra factors
    /// that have no root in [0, 1].
    fn from_roots<const DEGREE: usize>(roots: &[f64], scale: f64) -> Vec<f64> {
        let mut g = vec![0.0; DEGREE + 1];
        g[0] = scale;
        let mut degree = 0;
        let mut multiply = |c0: f64, c1: f64, g: &mut Vec<f64>| {
            for i in (0..=degree + 1).rev() {
                let lower = if i > 0 { g[i - 1] } else { 0.0 };
                g[i] = c0 * g[i] + c1 * lower;
            }
            degree += 1;
        };
        for r in roots {
            multiply(-r, 1.0, &mut g);
        }
        for _ in roots.len()..DEGREE {
            multiply(3.0, 1.0, &mut g); // (s + 3): root at −3
        }
        g
    }

    fn roots_of(g: &[f64]) -> Vec<f64> {
        let mut roots = Vec::new();
        for_each_root(g, &mut |s| roots.push(s));
        roots.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        roots
    }

    #[test]
    fn finds_five_separated_roots() {
        let expected = [0.05, 0.3, 0.5, 0.71, 0.98];
        let roots = roots_of(&from_roots::<5>(&expected, 2.0));
        assert_eq!(roots.len(), 5, "{roots:?}");
        for (r, e) in roots.iter().zip(expected) {
            assert!((r - e).abs() < 1e-12, "{r} vs {e}");
        }
    }

    #[test]
    fn finds_two_roots_closer_than_any_sampling_step() {
        let expected = [0.4, 0.400001];
        let roots = roots_of(&from_roots::<5>(&expected, -1.0));
        assert_eq!(roots.len(), 2, "{roots:?}");
        // Close roots are ill-conditioned: each is determined to about eps / |g′(root)|.
        assert!((roots[0] - 0.4).abs() < 1e-9 && (roots[1] - 0.400001).abs() < 1e-9, "{roots:?}");
    }

    #[test]
    fn no_root_in_the_interval_reports_none() {
        assert!(roots_of(&from_roots::<5>(&[1.5, -0.2], 1.0)).is_empty());
    }

    #[test]
    fn roots_on_the_interval_ends_are_reported() {
        let roots = roots_of(&from_roots::<5>(&[0.0, 1.0], 1.0));
        assert_eq!(roots.len(), 2, "{roots:?}");
        assert_eq!(roots[0], 0.0);
        assert!((roots[1] - 1.0).abs() < 1e-12, "{roots:?}");
    }

    #[test]
    fn double_root_is_reported_near_its_position() {
        let roots = roots_of(&from_roots::<5>(&[0.625, 0.625], 1.0));
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

    #[test]
    fn finds_nine_separated_roots_of_a_nonic() {
        let expected = [0.02, 0.1, 0.25, 0.3, 0.5, 0.62, 0.71, 0.9, 0.99];
        let roots = roots_of(&from_roots::<9>(&expected, -0.5));
        assert_eq!(roots.len(), 9, "{roots:?}");
        for (r, e) in roots.iter().zip(expected) {
            assert!((r - e).abs() < 1e-10, "{r} vs {e}");
        }
    }

    #[test]
    fn finds_close_roots_of_a_nonic_with_roots_outside() {
        let expected = [0.3, 0.300001, 0.8];
        let roots = roots_of(&from_roots::<9>(&expected, 3.0));
        assert_eq!(roots.len(), 3, "{roots:?}");
        for (r, e) in roots.iter().zip(expected) {
            assert!((r - e).abs() < 1e-9, "{r} vs {e}");
        }
    }

    #[test]
    fn the_nonic_conversion_keeps_the_end_values() {
        let g: [f64; 10] = from_roots::<9>(&[0.2, 0.7], 1.5).try_into().unwrap();
        let b = bernstein(&g);
        assert_eq!(b[0], g[0]);
        let size: f64 = g.iter().map(|a| a.abs()).sum();
        assert!((b[9] - eval(&g, 1.0)).abs() < 1e-14 * size);
    }
}
