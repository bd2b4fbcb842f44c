//! A lexical pass over scene text before it is parsed: the brackets and braces, outside
//! strings and comments. It finds an array longer than any field takes before the parser
//! spends memory on it (a parsed number costs a hundred times its text), and a bracket that
//! is never closed, which the parser reports only where it gives up, often lines later.

/// What the pass found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BracketScan {
    /// The byte offset of the first `[` whose array has more than the allowed elements.
    pub overlong: Option<usize>,
    /// The byte offset of the outermost `[` or `{` still open at the end of the text.
    pub unclosed: Option<usize>,
}

/// Scans `source` for an array of more than `max_elements` elements (stopping there) and
/// for a bracket left open.
pub fn scan_brackets(source: &str, max_elements: usize) -> BracketScan {
    let bytes = source.as_bytes();
    // Open brackets: (offset, is an array, commas seen at its own level).
    let mut open: Vec<(usize, bool, usize)> = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'#' => {
                i = line_end(bytes, i);
                continue;
            }
            b'"' | b'\'' => {
                i = string_end(bytes, i);
                continue;
            }
            b'[' => open.push((i, true, 0)),
            b'{' => open.push((i, false, 0)),
            b']' | b'}' => {
                open.pop();
            }
            b',' => {
                if let Some((at, true, commas)) = open.last_mut() {
                    *commas += 1;
                    // n commas separate n + 1 elements (or n and a trailing comma).
                    if *commas >= max_elements {
                        return BracketScan {
                            overlong: Some(*at),
                            unclosed: None,
                        };
                    }
                }
            }
            _ => {}
        }
        i += 1;
    }
    BracketScan {
        overlong: None,
        unclosed: open.first().map(|&(at, _, _)| at),
    }
}

/// The offset of the newline ending the line that `i` is on (or the end).
fn line_end(bytes: &[u8], i: usize) -> usize {
    bytes[i..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |n| i + n)
}

/// The offset just past the string that opens at `i` (a quote): basic or literal, on one
/// line or, tripled, over many; a basic string's backslash escapes the next byte. One left
/// open ends at its line's end (one line) or the text's (many), as the parser will report.
fn string_end(bytes: &[u8], i: usize) -> usize {
    let quote = bytes[i];
    let basic = quote == b'"';
    let tripled = bytes[i..].starts_with(&[quote; 3]);
    let mut j = i + if tripled { 3 } else { 1 };
    while j < bytes.len() {
        match bytes[j] {
            b'\\' if basic => j += 1,
            b'\n' if !tripled => return j,
            b if b == quote => {
                if !tripled {
                    return j + 1;
                }
                if bytes[j..].starts_with(&[quote; 3]) {
                    // A closing triple may have one or two more quotes before it ("""").
                    let mut end = j + 3;
                    while end < bytes.len() && bytes[end] == quote && end < j + 5 {
                        end += 1;
                    }
                    return end;
                }
            }
            _ => {}
        }
        j += 1;
    }
    bytes.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_are_counted_outside_strings_and_comments() {
        let text = "a = [1, 2, 3]\nb = \"[,,,,\" # [,,,,\nc = '[,,,,'\nd = \"\"\"\n[,,,,\n\"\"\"\n\
                    e = [{ x = 1, y = 2, z = 3 }, 4]\n[[t]]\nf = [\"a\\\",,,,\"]\n";
        assert_eq!(scan_brackets(text, 3), BracketScan::default());
        let at = scan_brackets(text, 2).overlong.unwrap();
        assert_eq!(&text[at..at + 3], "[1,");
        // Commas inside an inline table are the table's, not the array's.
        assert_eq!(
            scan_brackets("e = [{ x = 1, y = 2, z = 3 }]", 1),
            BracketScan::default()
        );
    }

    #[test]
    fn a_bracket_left_open_is_found_where_it_opens() {
        let text =
            "[camera]\neye = [0, 0, 5]\n\n[[lights]]\nposition = [1, 1, 1\n\n[render]\nw = 1\n";
        let at = scan_brackets(text, 100).unclosed.unwrap();
        assert_eq!(&text[at..at + 2], "[1");
        let table = "a = { x = [1, 2]\nb = 3\n";
        assert_eq!(scan_brackets(table, 100).unclosed, Some(4));
        assert_eq!(scan_brackets("a = [1,\n2,\n]\n", 100).unclosed, None);
    }
}
