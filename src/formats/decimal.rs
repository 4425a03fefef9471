//! Shortest round-trip decimal text of f64 and f32, byte for byte as std prints it with `{}`
//! ([`push_display`]) and `{:e}` ([`push_lower_exp`]), but several times faster: the digits
//! come from `zmij` (Schubfach / yy), the layout is std's.
//!
//! Both produce the shortest digit string that reads back to the same float, the one nearest
//! the exact value when several are as short; they differ only in layout (`zmij` prints
//! `1.0`, `1e+16`, std `1` and `10000000000000000`). So a number is printed by `zmij`, read
//! back into its significant digits and decimal exponent ([`Digits`]), and laid out again the
//! way `core::fmt` does (`flt2dec::digits_to_dec_str` and `digits_to_exp_str` with no minimum
//! precision). Most values skip that: where `zmij` already writes std's layout but for a `.0`
//! or a `+`, and the value cannot be a halfway case, its text is copied with those dropped.
//! `tests` compares the two on edge cases, halfway cases and millions of random bit patterns.
//!
//! Only finite values are printed here: every writer checks its coordinates first.

/// A float whose shortest round-trip digits `zmij` prints.
pub(crate) trait Shortest: Copy {
    /// The value's text from `zmij` (any layout), finite values only.
    fn zmij(self, buffer: &mut zmij::Buffer) -> &str;
    /// The magnitude as `m · 2^e` with `m` odd (`m` = 0 for ±0).
    fn odd_significand(self) -> (u64, i32);
}

impl Shortest for f64 {
    fn zmij(self, buffer: &mut zmij::Buffer) -> &str {
        buffer.format_finite(self)
    }

    fn odd_significand(self) -> (u64, i32) {
        let bits = self.to_bits();
        let (fraction, biased) = (bits & ((1 << 52) - 1), ((bits >> 52) & 0x7ff) as i32);
        let (m, e) = if biased == 0 { (fraction, -1074) } else { (fraction | 1 << 52, biased - 1075) };
        odd(m, e)
    }
}

impl Shortest for f32 {
    fn zmij(self, buffer: &mut zmij::Buffer) -> &str {
        buffer.format_finite(self)
    }

    fn odd_significand(self) -> (u64, i32) {
        let bits = self.to_bits();
        let (fraction, biased) = (u64::from(bits & ((1 << 23) - 1)), ((bits >> 23) & 0xff) as i32);
        let (m, e) = if biased == 0 { (fraction, -149) } else { (fraction | 1 << 23, biased - 150) };
        odd(m, e)
    }
}

/// Whether `value` may lie exactly halfway between two shortest candidates `d` and `d + 1` at
/// `10^k` ([`halfway`]), a cheap test that lets almost every coordinate skip the exact one: it
/// needs `e = k − 1` and either `5^k ≤ m < 2^53` (so `k ≤ 22`) or `5^−k ≤ 2d + 1 < 2·10^17`
/// (so `k ≥ −24`).
fn may_be_halfway(value: impl Shortest) -> bool {
    let (m, e) = value.odd_significand();
    m != 0 && (-26..=22).contains(&e)
}

/// `m · 2^e` with the factors of two of `m` moved into `e`.
fn odd(m: u64, e: i32) -> (u64, i32) {
    if m == 0 {
        return (0, 0);
    }
    let zeros = m.trailing_zeros();
    (m >> zeros, e + zeros as i32)
}

/// Whether `m · 2^e` (`m` odd) is exactly `(d + ½) · 10^k`: halfway between the digits `d` and
/// `d + 1` at `10^k`. As `2(d + ½) = 2d + 1` is odd, that needs `e + 1 = k` and
/// `m = (2d + 1) · 5^k` (for `k ≥ 0`) or `m · 5^−k = 2d + 1` (for `k < 0`).
fn halfway(m: u64, e: i32, d: u64, k: i32) -> bool {
    if m == 0 || e + 1 != k {
        return false;
    }
    let five = |n: u32| 5u128.checked_pow(n);
    let odd = 2 * u128::from(d) + 1;
    match k {
        0.. => five(k as u32).and_then(|p| odd.checked_mul(p)) == Some(u128::from(m)),
        _ => five(k.unsigned_abs()).and_then(|p| u128::from(m).checked_mul(p)) == Some(odd),
    }
}

/// The shortest round-trip digits of a finite value: `negative`, the significant digits
/// `digits[..len]` (no leading or trailing zero; empty for ±0) and the exponent `exp` with
/// value = 0.d₁d₂…dₙ × 10^exp.
struct Digits {
    negative: bool,
    digits: [u8; 24],
    len: usize,
    exp: i32,
}

impl Digits {
    /// The digits of `value` from `text`, its output from `zmij`.
    fn of(value: impl Shortest, text: &[u8]) -> Digits {
        let (negative, text) = match text.split_first() {
            Some((b'-', rest)) => (true, rest),
            _ => (false, text),
        };
        let (mantissa, exponent) = match text.iter().position(|&b| b == b'e' || b == b'E') {
            Some(e) => (&text[..e], parse_exponent(&text[e + 1..])),
            None => (text, 0),
        };
        let mut digits = Digits { negative, digits: [0; 24], len: 0, exp: 0 };
        // Digits before the point so far, leading zeros dropped.
        let mut point = None;
        let mut integer_digits = 0i32;
        let mut leading_zeros_after_point = 0i32;
        for &b in mantissa {
            if b == b'.' {
                point = Some(());
                continue;
            }
            let d = b - b'0';
            if digits.len == 0 && d == 0 {
                if point.is_some() {
                    leading_zeros_after_point += 1;
                }
                continue;
            }
            if point.is_none() {
                integer_digits += 1;
            }
            if digits.len < digits.digits.len() {
                digits.digits[digits.len] = b;
                digits.len += 1;
            }
        }
        while digits.len > 0 && digits.digits[digits.len - 1] == b'0' {
            digits.len -= 1;
        }
        digits.exp = exponent + if integer_digits > 0 { integer_digits } else { -leading_zeros_after_point };
        digits.round_ties_up(value);
        digits
    }

    /// Where the value lies exactly halfway between two shortest candidates, `zmij` keeps the
    /// even one and `core::fmt` the one of larger magnitude (its Dragon4 fallback rounds a
    /// remainder of exactly one half up): take that one. The last digit is then even, so adding
    /// one never carries. Both candidates read back to the value.
    fn round_ties_up(&mut self, value: impl Shortest) {
        let Some(&last) = self.significant().last() else { return };
        if !(last - b'0').is_multiple_of(2) {
            return;
        }
        let d = self.significant().iter().fold(0u64, |d, &b| d * 10 + u64::from(b - b'0'));
        let (m, e) = value.odd_significand();
        if halfway(m, e, d, self.exp - self.len as i32) {
            self.digits[self.len - 1] += 1;
        }
    }

    fn significant(&self) -> &[u8] {
        &self.digits[..self.len]
    }
}

/// The exponent after `e`: an optional sign and decimal digits.
fn parse_exponent(text: &[u8]) -> i32 {
    let (sign, digits) = match text.split_first() {
        Some((b'-', rest)) => (-1, rest),
        Some((b'+', rest)) => (1, rest),
        _ => (1, text),
    };
    sign * digits.iter().fold(0i32, |n, &b| n * 10 + i32::from(b - b'0'))
}

/// Appends `value` as `format!("{value}")` writes it: shortest round-trip digits, never an
/// exponent (`1e300` is a 1 and 300 zeros, `1e-7` is `0.0000001`), `-` before a negative
/// value and before −0, no fraction for an integer (`1`, `-0`).
pub(crate) fn push_display(out: &mut Vec<u8>, value: impl Shortest) {
    let mut buffer = zmij::Buffer::new();
    let text = value.zmij(&mut buffer).as_bytes();
    if !may_be_halfway(value) && !text.contains(&b'e') {
        // `zmij`'s fixed layout is std's, but for the `.0` it writes after an integer.
        out.extend_from_slice(text.strip_suffix(b".0").unwrap_or(text));
        return;
    }
    let d = Digits::of(value, text);
    if d.negative {
        out.push(b'-');
    }
    let digits = d.significant();
    if digits.is_empty() {
        out.push(b'0');
        return;
    }
    if d.exp <= 0 {
        out.extend_from_slice(b"0.");
        out.resize(out.len() + (-d.exp) as usize, b'0');
        out.extend_from_slice(digits);
    } else if (d.exp as usize) < digits.len() {
        let (integer, fraction) = digits.split_at(d.exp as usize);
        out.extend_from_slice(integer);
        out.push(b'.');
        out.extend_from_slice(fraction);
    } else {
        out.extend_from_slice(digits);
        out.resize(out.len() + d.exp as usize - digits.len(), b'0');
    }
}

/// Appends `value` as `format!("{value:e}")` writes it: `d.ddde-7`, `de16`, `0e0` (one digit
/// before the point, the point only when more digits follow, the exponent without `+`).
pub(crate) fn push_lower_exp(out: &mut Vec<u8>, value: impl Shortest) {
    let mut buffer = zmij::Buffer::new();
    let text = value.zmij(&mut buffer).as_bytes();
    if !may_be_halfway(value)
        && let Some(e) = text.iter().position(|&b| b == b'e')
    {
        // `zmij`'s exponent layout is std's, but for the `+` it writes before a positive
        // exponent.
        out.extend_from_slice(&text[..=e]);
        let exponent = &text[e + 1..];
        out.extend_from_slice(exponent.strip_prefix(b"+").unwrap_or(exponent));
        return;
    }
    let d = Digits::of(value, text);
    if d.negative {
        out.push(b'-');
    }
    let digits = d.significant();
    let Some((first, rest)) = digits.split_first() else {
        out.extend_from_slice(b"0e0");
        return;
    };
    out.push(*first);
    if !rest.is_empty() {
        out.push(b'.');
        out.extend_from_slice(rest);
    }
    out.push(b'e');
    let exp = d.exp - 1;
    if exp < 0 {
        out.push(b'-');
    }
    let mut text = [0u8; 10];
    let mut n = exp.unsigned_abs();
    let mut at = text.len();
    loop {
        at -= 1;
        text[at] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend_from_slice(&text[at..]);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn display(value: impl Shortest) -> String {
        let mut out = Vec::new();
        push_display(&mut out, value);
        String::from_utf8(out).unwrap()
    }

    fn lower_exp(value: impl Shortest) -> String {
        let mut out = Vec::new();
        push_lower_exp(&mut out, value);
        String::from_utf8(out).unwrap()
    }

    /// Checks both layouts of `value` against std's, naming the bits of a mismatch (non-finite
    /// values are not printed here).
    fn check_f64(value: f64) {
        if !value.is_finite() {
            return;
        }
        assert_eq!(display(value), format!("{value}"), "{{}} of {value:e} (bits {:#018x})", value.to_bits());
        assert_eq!(lower_exp(value), format!("{value:e}"), "{{:e}} of {value:e} (bits {:#018x})", value.to_bits());
    }

    fn check_f32(value: f32) {
        if !value.is_finite() {
            return;
        }
        assert_eq!(display(value), format!("{value}"), "{{}} of {value:e} (bits {:#010x})", value.to_bits());
        assert_eq!(lower_exp(value), format!("{value:e}"), "{{:e}} of {value:e} (bits {:#010x})", value.to_bits());
    }

    /// xorshift64: reproducible bit patterns without a dependency.
    fn bits(state: &mut u64) -> u64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        *state
    }

    #[test]
    fn zeros_integers_and_powers_of_ten_match_std() {
        for value in [0.0, -0.0, 1.0, -1.0, 2.0, 10.0, 100.0, 43210.0, 1e15, 1e16, 1e17, 1e21, 1e22, 1e23, 1e300] {
            check_f64(value);
            check_f64(-value);
        }
        for e in -330..=310 {
            let value: f64 = format!("1e{e}").parse().unwrap();
            check_f64(value);
            check_f64(value * 3.0);
        }
        for i in 0..100_000u64 {
            check_f64(i as f64);
            check_f64(i as f64 / 1000.0);
        }
    }

    #[test]
    fn subnormals_extremes_and_boundaries_match_std() {
        let specials = [
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            f64::from_bits(1),
            f64::from_bits(2),
            f64::from_bits(0x000f_ffff_ffff_ffff),
            f64::from_bits(0x0010_0000_0000_0001),
            2.2250738585072004e-308,
            5.960464477539063e-8,
            2.9802322387695312e-8,
            1.3076622631878654e65,
            9.03725590277404e159,
            6.606854224493745e-17,
            0.1,
            0.2,
            0.3,
            1.0 / 3.0,
            std::f64::consts::PI,
            123_456.789,
            5e-324,
            1e-5,
            0.999_999_999_999_999_9,
            9_007_199_254_740_993.0,
        ];
        for value in specials {
            check_f64(value);
            check_f64(-value);
            check_f64(value.next_up());
            check_f64(value.next_down());
        }
        for value in [f32::MIN_POSITIVE, f32::MAX, f32::EPSILON, f32::from_bits(1), 0.1, 1e-40, 16_777_217.0, 0.0, -0.0]
        {
            check_f32(value);
            check_f32(-value);
        }
    }

    #[test]
    fn every_power_of_two_and_its_neighbours_matches_std() {
        for e in -1074..=1023 {
            let value = 2f64.powi(e);
            for v in [value, value.next_up(), value.next_down()] {
                check_f64(v);
            }
        }
        for e in -149..=127 {
            let value = 2f32.powi(e);
            for v in [value, value.next_up(), value.next_down()] {
                check_f32(v);
            }
        }
    }

    #[test]
    fn halfway_values_round_up_as_std_does() {
        // Few significant bits: exact decimal expansions short enough that the shortest
        // digits can fall exactly halfway (2.9802322387695312e-8 is 2⁻²⁵, …3125 exactly).
        let mut state = 0x1234_5678_9abc_def1;
        for _ in 0..400_000 {
            let width = 1 + bits(&mut state) % 54;
            let m = (bits(&mut state) >> (64 - width)) | 1;
            let e = (bits(&mut state) % 160) as i32 - 100;
            let value = m as f64 * 2f64.powi(e);
            check_f64(value);
            check_f64(-value);
            check_f32(value as f32);
        }
        check_f64(2.9802322387695312e-8);
        check_f64(-1.1496366673247973e15);
        check_f64(-76.39419555664063);
    }

    #[test]
    fn random_bit_patterns_match_std() {
        let mut state = 0x2545_f491_4f6c_dd1d;
        let mut checked = 0;
        while checked < 1_000_000 {
            let value = f64::from_bits(bits(&mut state));
            if value.is_finite() {
                check_f64(value);
                checked += 1;
            }
        }
        for _ in 0..300_000 {
            let value = f32::from_bits(bits(&mut state) as u32);
            if value.is_finite() {
                check_f32(value);
            }
        }
    }

    #[test]
    fn random_mesh_like_coordinates_match_std() {
        // Values such as a deformer writes: modest magnitudes with 15–17 significant digits,
        // and short decimals such as a scanner writes, rounded to f32 and back.
        let mut state = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..500_000 {
            let unit = (bits(&mut state) >> 11) as f64 / (1u64 << 53) as f64;
            let scale = [1e-6, 1e-3, 0.1, 1.0, 10.0, 1e3, 1e6][(bits(&mut state) % 7) as usize];
            let value = (unit - 0.5) * scale;
            check_f64(value);
            check_f64(f64::from(value as f32));
            check_f32(value as f32);
            check_f64((value * 1e4).round() / 1e4);
        }
    }
}
