//! Decimal text to f64, bit for bit as `str::parse::<f64>` reads it, without its UTF-8 check:
//! `fast-float2`'s port of Lemire's fast_float (Clinger's fast path, the Eisel–Lemire algorithm
//! of "Number parsing at a gigabyte per second", 2021, and a big-decimal fallback), which
//! accepts and rejects exactly the words `str::parse` does (`+`, `.5`, `5.`, `inf`, `nan` in any
//! case; not hex, `_`, `1e` or surrounding spaces). `tests` compares both on edge cases and on
//! random words and values.

/// `word` as `str::parse::<f64>` reads it (`None` where it fails, or for invalid UTF-8).
pub(crate) fn parse(word: &[u8]) -> Option<f64> {
    fast_float2::parse(word).ok()
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
