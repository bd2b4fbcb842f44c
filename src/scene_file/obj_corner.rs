//! A face corner of an OBJ file: its indices as written (`v`, `v/vt`, `v//vn`,
//! `v/vt/vn`, each 1-based or negative to count back), read by a fast path for the common
//! spelling and the general parser for the rest, and resolved against what the file
//! defined before the face.

use super::line_error::LineError;

/// A face corner as written: vertex, texture coordinate and normal indices (1-based, or
/// negative to count back), `ABSENT` where the corner has none.
pub(super) type RawCorner = [i64; 3];
pub(super) const ABSENT: i64 = i64::MIN;

/// One corner of a face: indices into the file's positions, texture coordinates, normals.
pub(super) type Corner = [u32; 3];
/// A corner's index where it has none (no texture coordinate, no normal).
pub(super) const NONE: u32 = u32::MAX;

/// One face corner as written, `v`, `v/vt`, `v//vn` or `v/vt/vn`: its indices, not yet
/// checked against what is defined.
#[inline(always)] // as `resolve`
pub(super) fn raw_corner(word: &str, line: usize) -> Result<RawCorner, LineError> {
    match plain_corner(word.as_bytes()) {
        Some(corner) => Ok(corner),
        None => general_corner(word, line),
    }
}

/// `raw_corner` by the general parser, for every spelling and every refusal.
#[inline(never)]
fn general_corner(word: &str, line: usize) -> Result<RawCorner, LineError> {
    let fail = |message: String| LineError { line, message };
    let mut fields = word.split('/');
    let mut index = |what: &str, required: bool| -> Result<i64, LineError> {
        let Some(text) = fields.next().filter(|t| !t.is_empty() || required) else {
            return Ok(ABSENT);
        };
        text.parse().map_err(|_| {
            fail(format!(
                "face corner {}: {} is not a {what} index",
                crate::messages::quoted(word),
                crate::messages::quoted(text)
            ))
        })
    };
    let v = index("vertex", true)?;
    let vt = index("texture coordinate", false)?;
    let vn = index("normal", false)?;
    if fields.next().is_some() {
        return Err(fail(format!(
            "face corner {} has more than three indices",
            crate::messages::quoted(word)
        )));
    }
    Ok([v, vt, vn])
}

/// The common spelling of a corner, up to three fields of digits with an optional minus
/// sign (an empty field after the first: none), read without the general parser, which a
/// million-triangle file would run millions of times. None for anything else and for a
/// number out of range, which `raw_corner` then reads, or refuses, the general way.
#[inline]
fn plain_corner(word: &[u8]) -> Option<RawCorner> {
    let mut corner = [ABSENT; 3];
    let mut field = 0;
    let mut i = 0;
    loop {
        let negative = word.get(i) == Some(&b'-');
        i += negative as usize;
        let digits = i;
        let mut value: i64 = 0;
        while let Some(&b) = word.get(i).filter(|b| b.is_ascii_digit()) {
            value = value.checked_mul(10)?.checked_add(i64::from(b - b'0'))?;
            i += 1;
        }
        if i > digits {
            corner[field] = if negative { -value } else { value };
        } else if negative || field == 0 {
            return None;
        }
        match word.get(i) {
            None => return Some(corner),
            Some(b'/') if field < 2 => {
                field += 1;
                i += 1;
            }
            Some(_) => return None,
        }
    }
}

/// A corner's indices resolved (1-based, or negative: counted back from the last element
/// defined so far) against the counts of positions, texture coordinates and normals so far.
// Inlined: a million-triangle file resolves millions of corners, and the answer is best
// kept in registers rather than passed back through memory.
#[inline(always)]
pub(super) fn resolve(
    raw: &RawCorner,
    counts: [usize; 3],
    line: usize,
) -> Result<Corner, LineError> {
    let mut out = [NONE; 3];
    for k in 0..3 {
        let i = raw[k];
        if i == ABSENT {
            continue;
        }
        let count = counts[k];
        let resolved = if i > 0 { i - 1 } else { count as i64 + i };
        if i == 0 || resolved < 0 || resolved >= count as i64 {
            return Err(out_of_range(raw, k, count, line));
        }
        out[k] = resolved as u32;
    }
    Ok(out)
}

/// The refusal of `raw`'s index `k`, which is not among the `count` defined so far.
#[cold]
#[inline(never)]
fn out_of_range(raw: &RawCorner, k: usize, count: usize, line: usize) -> LineError {
    let written = match raw {
        [v, ABSENT, ABSENT] => format!("{v}"),
        [v, t, ABSENT] => format!("{v}/{t}"),
        [v, ABSENT, n] => format!("{v}//{n}"),
        [v, t, n] => format!("{v}/{t}/{n}"),
    };
    let what = ["vertex", "texture coordinate", "normal"][k];
    LineError {
        line,
        message: format!(
            "face corner {}: {what} index {} is out of range ({count} defined so far)",
            crate::messages::quoted(&written),
            raw[k]
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fast reading of a corner answers what the general one does wherever it answers,
    /// and leaves to it everything unusual: signs, empty and extra fields, numbers out of
    /// range, stray characters.
    #[test]
    fn plain_corners_read_as_the_general_parser_reads_them() {
        let mut words: Vec<String> = [
            "1",
            "12/7",
            "3//9",
            "4/5/6",
            "-1",
            "-2/-3/-4",
            "1/",
            "1//",
            "0",
            "-0",
            "007",
            "+1",
            "",
            "/1",
            "//",
            "-",
            "1-2",
            "1/2/3/",
            "1/2/3/4",
            "1 ",
            "a",
            "1/a",
            "1/-",
            "9223372036854775807",
            "9223372036854775808",
            "-9223372036854775808",
            "-9223372036854775809",
            "99999999999999999999/1",
            "1/+2",
            "１",
        ]
        .iter()
        .map(|w| w.to_string())
        .collect();
        let mut rng = crate::xorshift::XorShift32::new(0x9e37_79b9);
        for _ in 0..20_000 {
            let len = 1 + rng.next_u32() as usize % 9;
            let word: String = (0..len)
                .map(|_| b"0123456789/-+x"[rng.next_u32() as usize % 14] as char)
                .collect();
            words.push(word);
        }
        let mut plain = 0;
        for w in &words {
            let general = general_corner(w, 1).ok();
            if let Some(fast) = plain_corner(w.as_bytes()) {
                assert_eq!(Some(fast), general, "{w:?}");
                plain += 1;
            }
            assert_eq!(raw_corner(w, 1).ok(), general, "{w:?}");
        }
        assert!(plain > 1000, "the fast reading answered only {plain} times");
    }
}
