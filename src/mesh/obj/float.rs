//! Decimal text to f64, bit for bit as `str::parse::<f64>` reads it, but without its UTF-8
//! check and its general machinery for the short numbers most coordinates are.
//!
//! [`parse`] reads a word of the form `[+-]digits[.digits][(e|E)[+-]digits]` (or with the
//! digits before or after the point left out) of at most 19 significant digits `w` and a
//! decimal exponent `q` (value `w · 10^q`) the way `core` does, to the same correctly rounded
//! f64:
//!
//! - `w ≤ 2⁵³` and `q` in −22…22: Clinger's fast path, `w` as an exact f64 times or divided by
//!   an exact power of ten, which IEEE 754 rounds correctly;
//! - otherwise, `q` in −27…27: the Eisel–Lemire algorithm (Lemire, "Number parsing at a
//!   gigabyte per second", 2021, §5–§9), `w` times a 128-bit approximation of 5^q, rounded to
//!   nearest, ties to even, with `core`'s constants, in the range where the approximation
//!   never needs the slow path; where it would ([`lemire`] gives `None`), `str::parse`.
//!
//! Every other word (more digits, a larger exponent, `inf`, `nan`, or not a number at all)
//! goes to `str::parse`. `tests` compares both on edge cases and on random words and values.

/// The powers of ten that f64 holds exactly: 10⁰ … 10²².
const POWERS: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// `word` as `str::parse::<f64>` reads it (`None` where it fails, or for invalid UTF-8).
pub(crate) fn parse(word: &[u8]) -> Option<f64> {
    match fast(word) {
        Some(value) => Some(value),
        None => std::str::from_utf8(word).ok()?.parse().ok(),
    }
}

/// Clinger's fast path for `word`, or `None` when it does not apply (the word may still be a
/// number).
fn fast(word: &[u8]) -> Option<f64> {
    let (negative, mut at) = match word.first()? {
        b'-' => (true, 1),
        b'+' => (false, 1),
        _ => (false, 0),
    };
    let mut significand: u64 = 0;
    let mut digits = 0; // significant digits read (leading zeros left out)
    let start = at;
    at = read_digits(word, at, &mut significand, &mut digits)?;
    let mut any = at > start;
    let mut exponent: i32 = 0;
    if word.get(at) == Some(&b'.') {
        let start = at + 1;
        at = read_digits(word, start, &mut significand, &mut digits)?;
        // Each digit after the point, leading zeros included, lowers the exponent; a count
        // past 2³⁰ is held there (no f64 is that small, and the exponent's sum cannot wrap).
        exponent = -((at - start).min(1 << 30) as i32);
        any |= at > start;
    }
    if !any {
        return None;
    }
    if let Some(b'e' | b'E') = word.get(at) {
        at += 1;
        let negative = match word.get(at) {
            Some(b'-') => {
                at += 1;
                true
            }
            Some(b'+') => {
                at += 1;
                false
            }
            _ => false,
        };
        let start = at;
        let mut written: i32 = 0;
        while let Some(&b) = word.get(at).filter(|b| b.is_ascii_digit()) {
            written = written * 10 + i32::from(b - b'0');
            if written > 1000 {
                return None;
            }
            at += 1;
        }
        if at == start {
            return None;
        }
        exponent += if negative { -written } else { written };
    }
    if at != word.len() {
        return None;
    }
    let magnitude = if significand == 0 {
        0.0
    } else if significand <= 1 << 53 && (-22..=22).contains(&exponent) {
        let exact = significand as f64;
        if exponent < 0 { exact / POWERS[(-exponent) as usize] } else { exact * POWERS[exponent as usize] }
    } else {
        lemire(exponent, significand)?
    };
    Some(if negative { -magnitude } else { magnitude })
}

/// Reads the ASCII digits of `word` from `at` on into `significand` (ten times it plus the
/// digit, for each), counting its significant digits (leading zeros left out) in `digits`;
/// the offset past the digits, or `None` past 19 significant digits. Once a significant digit
/// is read, eight digits at a time where there are eight ([`eight_digits`]).
fn read_digits(word: &[u8], mut at: usize, significand: &mut u64, digits: &mut u32) -> Option<usize> {
    loop {
        if *significand != 0
            && *digits + 8 <= 19
            && let Some(eight) = word.get(at..at + 8).and_then(eight_digits)
        {
            *significand = *significand * 100_000_000 + eight;
            *digits += 8;
            at += 8;
            continue;
        }
        let Some(&b) = word.get(at).filter(|b| b.is_ascii_digit()) else { return Some(at) };
        let d = u64::from(b - b'0');
        if *significand != 0 || d != 0 {
            *digits += 1;
            if *digits > 19 {
                return None;
            }
        }
        *significand = *significand * 10 + d;
        at += 1;
    }
}

/// The value of eight bytes that are all ASCII digits, read as one word (the first byte the
/// most significant digit), or `None` if any is not a digit; by the SWAR method of Lemire's
/// `fast_float` (its `parse_eight_digits_unrolled`): the digit pairs, then the quadruples,
/// then the whole, each by one multiplication of the word.
fn eight_digits(bytes: &[u8]) -> Option<u64> {
    let v = u64::from_le_bytes(bytes.try_into().ok()?);
    // Each byte is a digit when its high nibble is 3, and still is once 6 is added (a byte of
    // 0xfa or more, whose sum carries into the next byte, fails the first test already).
    let high = 0xf0f0_f0f0_f0f0_f0f0;
    if (v & high) | ((v.wrapping_add(0x0606_0606_0606_0606) & high) >> 4) != 0x3333_3333_3333_3333 {
        return None;
    }
    let v = v - 0x3030_3030_3030_3030;
    let pairs = v.wrapping_mul(10).wrapping_add(v >> 8);
    let low = (pairs & 0x0000_00ff_0000_00ff).wrapping_mul(100 + (1_000_000 << 32));
    let high = ((pairs >> 16) & 0x0000_00ff_0000_00ff).wrapping_mul(1 + (10_000 << 32));
    Some(u64::from((low.wrapping_add(high) >> 32) as u32))
}

/// The smallest and largest decimal exponents of [`FIVES`].
const Q_MIN: i32 = -27;
const Q_MAX: i32 = 27;

/// 5^q for q in `Q_MIN..=Q_MAX` as 128 bits with the top one set, `(high, low)` words: exact
/// (shifted) for q ≥ 0; for q < 0, ⌊2^(z+127) / 5^−q⌋ + 1 where 2^(z−1) < 5^−q < 2^z. These
/// are the entries of `core`'s table (and of the paper's) for these exponents.
const FIVES: [(u64, u64); (Q_MAX - Q_MIN + 1) as usize] = {
    let mut table = [(0u64, 0u64); (Q_MAX - Q_MIN + 1) as usize];
    let mut q = Q_MIN;
    while q <= Q_MAX {
        let value: u128 = if q >= 0 {
            let five = 5u128.pow(q as u32);
            five << five.leading_zeros()
        } else {
            let five = 5u128.pow((-q) as u32);
            let z = 128 - (five - 1).leading_zeros();
            // ⌊2^b / five⌋ by long division, b = z + 127; the quotient fits in 128 bits.
            let b = z + 127;
            let (mut quotient, mut remainder) = (0u128, 0u128);
            let mut bit = b as i32;
            while bit >= 0 {
                remainder = remainder * 2 + if bit == b as i32 { 1 } else { 0 };
                quotient <<= 1;
                if remainder >= five {
                    remainder -= five;
                    quotient |= 1;
                }
                bit -= 1;
            }
            quotient + 1
        };
        table[(q - Q_MIN) as usize] = ((value >> 64) as u64, value as u64);
        q += 1;
    }
    table
};

/// `w · 10^q` (w ≠ 0, at most 19 digits) correctly rounded to f64 by Eisel–Lemire, as `core`'s
/// `dec2flt::lemire::compute_float`; `None` where `q` is outside [`FIVES`] or the result would
/// not be a normal f64.
fn lemire(q: i32, w: u64) -> Option<f64> {
    const SIG_BITS: i32 = 52;
    if !(Q_MIN..=Q_MAX).contains(&q) || w == 0 {
        return None;
    }
    let zeros = w.leading_zeros() as i32;
    let w = w << zeros;
    // w × 5^q to 128 bits: one product suffices unless the bits below the 55 kept are all ones.
    let (high5, low5) = FIVES[(q - Q_MIN) as usize];
    let product = u128::from(w) * u128::from(high5);
    let (mut lo, mut hi) = (product as u64, (product >> 64) as u64);
    let mask = u64::MAX >> (SIG_BITS + 3);
    if hi & mask == mask {
        let second = ((u128::from(w) * u128::from(low5)) >> 64) as u64;
        lo = lo.wrapping_add(second);
        if second > lo {
            hi += 1;
        }
    }
    // `lo` all ones cannot mislead the rounding for q in −27…55 (the paper's §8–9).
    let upper = (hi >> 63) as i32;
    let mut mantissa = hi >> (upper + 64 - SIG_BITS - 3);
    let mut power2 = ((q.wrapping_mul(152_170 + 65_536) >> 16) + 63) + upper - zeros + 1023;
    if power2 <= 0 {
        return None;
    }
    // Exactly halfway (possible only where 5^q fits in 64 bits): round to even.
    if lo <= 1 && (-4..=23).contains(&q) && mantissa & 3 == 1 && (mantissa << (upper + 64 - SIG_BITS - 3)) == hi {
        mantissa &= !1;
    }
    mantissa += mantissa & 1;
    mantissa >>= 1;
    if mantissa >= 2 << SIG_BITS {
        mantissa = 1 << SIG_BITS;
        power2 += 1;
    }
    mantissa &= !(1 << SIG_BITS);
    if power2 >= 0x7ff {
        return None;
    }
    Some(f64::from_bits(mantissa | (power2 as u64) << SIG_BITS))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks that [`parse`] and `str::parse` agree on `word`, bits and failures alike.
    fn check(word: &[u8]) {
        let expected = std::str::from_utf8(word).ok().and_then(|s| s.parse::<f64>().ok());
        let got = parse(word);
        assert_eq!(
            got.map(f64::to_bits),
            expected.map(f64::to_bits),
            "{:?}: {got:?}, str::parse {expected:?}",
            String::from_utf8_lossy(word)
        );
    }

    #[test]
    fn eight_digits_read_every_digit_word_and_refuse_every_other_byte() {
        let mut state = 3_u64;
        for round in 0..20_000 {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            let value = (state >> 20) % 100_000_000;
            let word = format!("{value:08}");
            assert_eq!(eight_digits(word.as_bytes()), Some(value), "{word}");
            // Any byte other than a digit, at any place, is refused.
            let mut bytes = word.into_bytes();
            bytes[round % 8] = [b'/', b':', b' ', b'.', b'e', 0, 0x80, 0xfa, 0xff, b'0' + 0x80][round % 10];
            assert_eq!(eight_digits(&bytes), None, "{bytes:?}");
        }
        for byte in (0..=255u8).filter(|b| !b.is_ascii_digit()) {
            for place in 0..8 {
                let mut bytes = *b"99999999";
                bytes[place] = byte;
                assert_eq!(eight_digits(&bytes), None, "{bytes:?}");
            }
        }
        assert_eq!(eight_digits(b"00000000"), Some(0));
        assert_eq!(eight_digits(b"99999999"), Some(99_999_999));
        assert_eq!(eight_digits(b"1234567"), None);
    }

    #[test]
    fn long_runs_of_digits_read_as_str_parse_reads_them() {
        for word in [
            &b"0.050528833333333335"[..],
            b"-0.06668822222222225",
            b"1234567890123456789",
            b"12345678901234567890",
            b"1234567890.123456789",
            b"1234567890.1234567891",
            b"0.00000000000000000000000000000000001234567812345678",
            b"00000000000000000000000012345678.12345678e-3",
            b"9999999999999999999",
            b"99999999.99999999999",
            b"0.12345678",
            b"12345678.",
            b".12345678",
        ] {
            check(word);
        }
    }

    #[test]
    fn powers_of_five_are_cores_table_entries() {
        let entry = |q: i32| FIVES[(q - Q_MIN) as usize];
        assert_eq!(entry(0), (0x8000_0000_0000_0000, 0));
        assert_eq!(entry(1), (0xa000_0000_0000_0000, 0));
        assert_eq!(entry(-1), (0xcccc_cccc_cccc_cccc, 0xcccc_cccc_cccc_cccd));
        assert_eq!(entry(-2), (0xa3d7_0a3d_70a3_d70a, 0x3d70_a3d7_0a3d_70a4));
        assert_eq!(entry(27), (0xcecb_8f27_f420_0f3a, 0));
    }

    #[test]
    fn edge_cases_read_as_str_parse_reads_them() {
        let words: &[&[u8]] = &[
            b"0",
            b"-0",
            b"+0",
            b"0.0",
            b"-0.0",
            b"00",
            b"-00.000",
            b"1",
            b"-1",
            b"+1",
            b"1.",
            b"-1.",
            b".5",
            b"-.5",
            b"+.5",
            b".",
            b"-",
            b"+",
            b"",
            b"-.",
            b"e5",
            b"1e",
            b"1e+",
            b"1e-",
            b"1e5",
            b"1E5",
            b"1e+5",
            b"1e-5",
            b"-1.5e-3",
            b".e1",
            b"1.e1",
            b"1.5e",
            b"0e999",
            b"-0e-999",
            b"1e22",
            b"1e23",
            b"1e-22",
            b"1e-23",
            b"9007199254740992",
            b"9007199254740993",
            b"9007199254740991e-22",
            b"9007199254740993e-22",
            b"123456789012345678",
            b"1234567890123456789",
            b"12345678901234567890",
            b"0.1234567890123456789",
            b"0.00000000000000000000000000001",
            b"1e308",
            b"1e309",
            b"-1e309",
            b"1e-324",
            b"2.2250738585072014e-308",
            b"4.9e-324",
            b"inf",
            b"-inf",
            b"Infinity",
            b"nan",
            b"NaN",
            b"-nan",
            b"1..2",
            b"1.2.3",
            b"--1",
            b"+-1",
            b"1 ",
            b" 1",
            b"1\r",
            b"1#",
            b"0x10",
            b"1_000",
            b"\xff",
            b"1\xff",
            b"\xd9\xa3",
            b"1e1000",
            b"1e0001",
            b"0.1",
            b"0.2",
            b"0.3",
            b"-0.03783",
            b"0.128887",
            b"0.004475",
            b"1e-7",
            b"6.1e-17",
            b"123456.789e-3",
        ];
        for word in words {
            check(word);
        }
    }

    #[test]
    fn shortest_digits_of_random_doubles_read_back_exactly() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for i in 0..300_000 {
            let bits = next();
            // Random bit patterns, and values of mesh-like magnitudes with few or many digits.
            let value = match i % 3 {
                0 => f64::from_bits(bits),
                1 => (bits >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0,
                _ => ((bits >> 40) as f64 - 8_388_608.0) / 10f64.powi((bits % 9) as i32),
            };
            if !value.is_finite() {
                continue;
            }
            for text in [format!("{value}"), format!("{value:e}"), format!("{value:.3}"), format!("{value:.20}")] {
                check(text.as_bytes());
                assert_eq!(parse(text.as_bytes()).map(f64::to_bits), text.parse::<f64>().ok().map(f64::to_bits));
            }
        }
    }

    #[test]
    fn random_words_of_number_characters_read_as_str_parse_reads_them() {
        let alphabet = b"0123456789.-+eE";
        let mut state = 12345_u64;
        for _ in 0..300_000 {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            let len = (state >> 60) as usize + 1;
            let mut word = Vec::with_capacity(len);
            let mut s = state;
            for _ in 0..len {
                s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                // Mostly digits, so that many words are numbers.
                let pick = (s >> 33) as usize % (alphabet.len() + 10);
                word.push(if pick < alphabet.len() { alphabet[pick] } else { b'0' + (pick % 10) as u8 });
            }
            check(&word);
        }
    }
}
