//! The numbers of an OBJ or MTL statement: the common spelling (`-0.125`, `3`) read by a
//! fast path that gives exactly what `str::parse` gives, everything else by `str::parse`.

use super::line_error::LineError;

/// Up to N numbers from `words`, all finite; more than N is an error.
pub(super) struct Numbers<const N: usize> {
    pub(super) values: [f32; N],
    pub(super) len: usize,
}

pub(super) fn numbers<'a, const N: usize>(
    words: impl Iterator<Item = &'a str>,
    keyword: &str,
    line: usize,
) -> Result<Numbers<N>, LineError> {
    let mut out = Numbers {
        values: [0.0; N],
        len: 0,
    };
    for word in words {
        if out.len == N {
            return Err(LineError {
                line,
                message: format!("`{keyword}` takes at most {N} numbers"),
            });
        }
        let v = match plain_decimal(word.as_bytes()) {
            Some(v) => v,
            None => word.parse().map_err(|_| LineError {
                line,
                message: format!(
                    "`{keyword}`: {} is not a number",
                    crate::messages::quoted(word)
                ),
            })?,
        };
        if !v.is_finite() {
            return Err(LineError {
                line,
                message: format!("`{keyword}`: {word} is not a finite number"),
            });
        }
        out.values[out.len] = v;
        out.len += 1;
    }
    Ok(out)
}

/// Powers of ten that f32 holds exactly (5^9 < 2^24).
const POWERS_OF_TEN: [f32; 10] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9];

/// The value of a word in the common spelling of a number: an optional sign, then at most
/// nine digits with at most one point among them (`-1.25`, `+3`, `.5`, `2.`), whose digits
/// make an integer below 2^24. That integer and the power of ten that places the point are
/// both exact in f32, so their one quotient is rounded once, correctly, as `str::parse`
/// rounds (Clinger's fast path). None for any other word, which `str::parse` then reads or
/// refuses: a file of millions of coordinates would otherwise run the general parser
/// millions of times.
#[inline]
fn plain_decimal(word: &[u8]) -> Option<f32> {
    let (negative, rest) = match word {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, word),
    };
    let (mut digits, mut after_point, mut point) = (0u32, 0usize, false);
    let mut seen = 0usize;
    for &b in rest {
        match b {
            b'0'..=b'9' => {
                digits = digits * 10 + u32::from(b - b'0');
                seen += 1;
                after_point += point as usize;
                if seen > 9 {
                    return None;
                }
            }
            b'.' if !point => point = true,
            _ => return None,
        }
    }
    if seen == 0 || digits >= 1 << 24 {
        return None;
    }
    let value = digits as f32 / POWERS_OF_TEN[after_point];
    Some(if negative { -value } else { value })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xorshift::XorShift32;

    /// Where the fast path gives a value it is `str::parse`'s bit for bit, and it declines
    /// every word outside its spelling: on hand-picked words, on 200,000 made-up ones of
    /// digits, points, signs, exponents and stray bytes, and on 400,000 numbers of eight
    /// significant digits, where a second rounding would part from the first.
    #[test]
    fn plain_decimals_read_as_str_parse_reads_them() {
        let agree = |word: &str| {
            if let Some(v) = plain_decimal(word.as_bytes()) {
                let parsed: f32 = word.parse().unwrap_or_else(|_| panic!("{word:?} parses"));
                assert_eq!(v.to_bits(), parsed.to_bits(), "{word:?}");
            }
        };
        let taken = [
            "0",
            "-0",
            "+0",
            "1",
            "-1.25",
            "+3",
            ".5",
            "-.5",
            "2.",
            "0.1",
            "16777215",
            "1.6777215",
            "0.00000001",
            "12345678",
            "00000.1",
        ];
        for word in taken {
            assert!(plain_decimal(word.as_bytes()).is_some(), "{word:?}");
            agree(word);
        }
        assert_eq!(
            plain_decimal(b"-0").map(f32::to_bits),
            Some((-0.0f32).to_bits())
        );
        let declined = [
            "",
            "-",
            "+",
            ".",
            "-.",
            "1e5",
            "1E5",
            "1.2.3",
            "--1",
            "+-1",
            "nan",
            "inf",
            "16777216",
            "123456789",
            "0.000000001",
            "1,5",
            " 1",
            "1 ",
            "0x10",
            "½",
        ];
        for word in declined {
            assert!(plain_decimal(word.as_bytes()).is_none(), "{word:?}");
        }
        let mut rng = XorShift32::new(0x5eed_f10a);
        let alphabet = b"0123456789012345678901234567890123456789..-+eE x";
        for _ in 0..200_000 {
            let len = 1 + rng.next_u32() as usize % 11;
            let word: String = (0..len)
                .map(|_| alphabet[rng.next_u32() as usize % alphabet.len()] as char)
                .collect();
            agree(&word);
        }
        // Eight significant digits with the point anywhere: the integers from 10^7 up to
        // 2^24, where f32's spacing is widest relative to the digits.
        for _ in 0..200_000 {
            let digits = 10_000_000 + rng.next_u32() % 6_777_216;
            let text = digits.to_string();
            let at = rng.next_u32() as usize % (text.len() + 1);
            agree(&format!("{}.{}", &text[..at], &text[at..]));
            agree(&format!("-{}.{}", &text[..at], &text[at..]));
        }
    }
}
