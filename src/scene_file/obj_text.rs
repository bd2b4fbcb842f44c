//! OBJ text read line by line: the cut into pieces read in parallel, a first pass that
//! counts what each piece defines, the statements of each piece with its numbers and its
//! faces' corners, resolved against what the text before them defines, and the line
//! reading MTL files share (mtl.rs). Which material a piece's faces use depends on the
//! pieces before it; obj_join.rs joins them.

use super::line_error::LineError;
use super::obj_corner::{Corner, RawCorner, raw_corner, resolve};
use super::obj_number::numbers;
use crate::limits;
use glam::{Vec2, Vec3};

/// Text below this size is read in one piece; larger text in pieces read in parallel, each
/// at least this large (smaller pieces would cost more to hand out than to read).
pub(super) const PARALLEL_PIECE_BYTES: usize = 1 << 20;

/// How many pieces per thread large text is cut into at most. Lines of faces take longer
/// to read than lines of vertices, and a file holds them in long runs, so pieces of equal
/// size are not equal work: many pieces, each handed out alone, keep every thread busy to
/// the end.
const PIECES_PER_THREAD: usize = 16;

/// `text` cut after line ends into pieces of about equal size (one piece when it is small).
pub(super) fn cut_at_lines(text: &str) -> Vec<&str> {
    let threads = rayon::current_num_threads().max(1);
    let count = (text.len() / PARALLEL_PIECE_BYTES).clamp(1, PIECES_PER_THREAD * threads);
    let mut pieces = Vec::with_capacity(count);
    let mut rest = text;
    for k in (1..count).rev() {
        let target = rest.len() / (k + 1);
        match rest.as_bytes()[target..].iter().position(|&b| b == b'\n') {
            Some(at) => {
                let (piece, tail) = rest.split_at(target + at + 1);
                pieces.push(piece);
                rest = tail;
            }
            None => break,
        }
    }
    pieces.push(rest);
    pieces
}

/// What a piece of text defines and what its faces make, counted before anything is
/// read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct FaceCount {
    /// The triangles its faces make (n − 2 for a face of n corners).
    triangles: usize,
    /// Its faces.
    faces: usize,
    /// Its `v`, `vt` and `vn` statements: exactly the positions, texture coordinates and
    /// normals it defines when every one of them is well formed (when one is not, the
    /// piece ends in a problem there, and nothing after it is used).
    pub(super) defined: [usize; 3],
    /// Whether the text is plain (`is_plain`).
    plain: bool,
    /// Its lines.
    lines: usize,
    /// The first face with more than `MAX_FACE_CORNERS` corners: its line and corners.
    widest: Option<(usize, usize)>,
    /// The line of the face that takes the count past the budget it was given.
    over_at: Option<usize>,
}

/// Counts the faces of `text` (lines from 1) without reading their numbers, stopping at a
/// face too wide or at the one that takes the triangles past `budget`, and its
/// definitions. Bytes, not statements: it runs over the whole file before the reading
/// does. In plain text a line's keyword is found as `PlainWords` finds it, so the
/// definitions counted are those the reading finds; other text is counted the general way.
fn count_faces(text: &str, budget: usize) -> FaceCount {
    let bytes = text.as_bytes();
    let blank = |b: u8| b == b' ' || b == b'\t' || b == b'\r';
    let class = |i: usize| {
        bytes
            .get(i)
            .map_or(ByteClass::End, |&b| BYTE_CLASS[b as usize])
    };
    let mut count = FaceCount {
        plain: is_plain(text),
        ..FaceCount::default()
    };
    if !count.plain {
        for (_, _, keyword, _) in statements(text) {
            if let Some(k) = ["v", "vt", "vn"].iter().position(|&d| d == keyword) {
                count.defined[k] += 1;
            }
        }
    }
    let mut i = 0;
    while i < bytes.len() {
        count.lines += 1;
        while i < bytes.len() && blank(bytes[i]) {
            i += 1;
        }
        if count.plain && bytes.get(i) == Some(&b'v') {
            let kind = match bytes.get(i + 1) {
                Some(b't') => 1,
                Some(b'n') => 2,
                _ => 0,
            };
            let keyword_end = if kind == 0 { i + 1 } else { i + 2 };
            if class(keyword_end) != ByteClass::Word {
                count.defined[kind] += 1;
            }
        } else if bytes[i..].starts_with(b"f") && bytes.get(i + 1).is_some_and(|&b| blank(b)) {
            let mut corners = 0;
            let mut in_word = false;
            i += 1;
            while i < bytes.len() && bytes[i] != b'\n' && bytes[i] != b'#' {
                let word = !blank(bytes[i]);
                corners += (word && !in_word) as usize;
                in_word = word;
                i += 1;
            }
            if corners > limits::MAX_FACE_CORNERS {
                count.widest = Some((count.lines, corners));
                return count;
            }
            count.faces += 1;
            count.triangles += corners.saturating_sub(2);
            if count.triangles > budget {
                count.over_at = Some(count.lines);
                return count;
            }
        }
        i = match bytes[i..].iter().position(|&b| b == b'\n') {
            Some(n) => i + n + 1,
            None => bytes.len(),
        };
    }
    count
}

/// The refusal of the face at `line`, which takes the triangles past `max_triangles`.
pub(super) fn too_many_triangles(line: usize, max_triangles: usize) -> LineError {
    LineError {
        line,
        message: format!("the mesh has more than the {max_triangles} triangles a scene may hold"),
    }
}

/// Refuses, before any table is built, a file whose faces make more than `max_triangles`
/// triangles or one with more than `MAX_FACE_CORNERS` corners (its fan of triangles all
/// meet at one corner, where a ray would test every one).
pub(super) fn refuse_oversized_faces(
    chunks: &[&str],
    max_triangles: usize,
) -> Result<Vec<FaceCount>, LineError> {
    use rayon::prelude::*;
    let counts: Vec<FaceCount> = chunks
        .par_iter()
        .with_max_len(1) // each piece handed out alone (`PIECES_PER_THREAD`)
        .map(|chunk| count_faces(chunk, usize::MAX))
        .collect();
    let (mut lines_before, mut triangles) = (0, 0usize);
    for (chunk, count) in chunks.iter().zip(&counts) {
        if let Some((line, corners)) = count.widest {
            return Err(LineError {
                line: lines_before + line,
                message: format!(
                    "a face of {corners} corners: at most {} (a fan of triangles that all \
                     meet at its first corner)",
                    limits::MAX_FACE_CORNERS
                ),
            });
        }
        if triangles + count.triangles > max_triangles {
            let at = count_faces(chunk, max_triangles - triangles).over_at;
            return Err(too_many_triangles(
                lines_before + at.unwrap_or(1),
                max_triangles,
            ));
        }
        triangles += count.triangles;
        lines_before += count.lines;
    }
    Ok(counts)
}

/// A face of a piece: where its corners end in the piece's corner list, and its line
/// (counted from the piece's start; a mesh file is far shorter than 2^32 lines).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Face {
    pub(super) end: u32,
    pub(super) line: u32,
}

/// The statements of a piece that choose a material or name material libraries, in
/// order; lines are counted from the piece's start.
#[derive(Debug, PartialEq)]
pub(super) enum Statement<'a> {
    /// The material of the piece's faces from face `faces` on.
    UseMtl {
        line: usize,
        name: &'a str,
        faces: usize,
    },
    MtlLib {
        line: usize,
        name: &'a str,
    },
}

/// What one piece of OBJ text defines and its faces, read on its own once the counts of
/// what the text before it defines are known.
pub(super) struct Piece<'a> {
    pub(super) positions: Vec<Vec3>,
    pub(super) uvs: Vec<Vec2>,
    pub(super) normals: Vec<Vec3>,
    /// Every face's corners, resolved against what the file defined before the face.
    pub(super) corners: Vec<Corner>,
    pub(super) faces: Vec<Face>,
    pub(super) statements: Vec<Statement<'a>>,
    /// The positions, texture coordinates and normals the text before the piece defines.
    defined_before: [usize; 3],
    /// The corners of the face being read, as written.
    face: Vec<RawCorner>,
    /// The first problem, which ends the piece (its line counted in the piece).
    pub(super) error: Option<LineError>,
    /// How many lines the piece holds.
    pub(super) lines: usize,
}

impl Piece<'_> {
    /// Where face `k`'s corners start in `corners`.
    pub(super) fn corners_before(&self, k: usize) -> usize {
        k.checked_sub(1).map_or(0, |k| self.faces[k].end as usize)
    }
}

/// Reads one piece, whose faces `count` counted: its numbers, its faces' corners as
/// written, and its other statements. The lists are sized from the count (a face of n
/// corners makes n − 2 triangles, so its corners are at most three per triangle, and a line
/// that is not a face may be a vertex): grown by doubling instead, they would be copied and
/// their fresh pages touched again and again.
pub(super) fn read_piece<'a>(
    text: &'a str,
    count: &FaceCount,
    defined_before: [usize; 3],
) -> Piece<'a> {
    let mut piece = Piece {
        positions: Vec::with_capacity(count.defined[0]),
        uvs: Vec::with_capacity(count.defined[1]),
        normals: Vec::with_capacity(count.defined[2]),
        corners: Vec::with_capacity(3 * count.triangles),
        faces: Vec::with_capacity(count.faces),
        statements: Vec::new(),
        defined_before,
        face: Vec::new(),
        error: None,
        lines: text.bytes().filter(|&b| b == b'\n').count(),
    };
    let read = if count.plain {
        read_plain(text, &mut piece)
    } else {
        read_general(text, &mut piece)
    };
    piece.error = read.err();
    piece
}

/// Reads `text` statement by statement, the general way.
fn read_general<'a>(text: &'a str, piece: &mut Piece<'a>) -> Result<(), LineError> {
    for (line, content, keyword, words) in statements(text) {
        read_statement(piece, line, content, keyword, words)?;
    }
    Ok(())
}

/// Whether `text` is printable ASCII, spaces, tabs and line ends only, as nearly every OBJ
/// file is. In such text the only white space is a space, a tab or a carriage return, so
/// the words `statements` finds are the runs of other bytes before a `#`, and
/// `read_plain` finds them in one pass over the bytes instead of the several that splitting
/// off the comment, trimming and splitting into words take.
fn is_plain(text: &str) -> bool {
    let plain =
        |b: u8| b.wrapping_sub(b' ') <= b'~' - b' ' || b == b'\t' || b == b'\r' || b == b'\n';
    // Blocks without an early exit inside, which the compiler turns into SIMD.
    text.as_bytes()
        .chunks(4096)
        .all(|block| block.iter().fold(true, |all, &b| all & plain(b)))
}

/// What a byte of plain text is to `PlainWords`.
#[derive(Clone, Copy, PartialEq, Eq)]
enum ByteClass {
    /// Part of a word.
    Word,
    /// Between words: a space, a tab or a carriage return.
    Blank,
    /// The end of a line's statement: a line feed or a comment's `#`.
    End,
}

const BYTE_CLASS: [ByteClass; 256] = {
    let mut class = [ByteClass::Word; 256];
    class[b' ' as usize] = ByteClass::Blank;
    class[b'\t' as usize] = ByteClass::Blank;
    class[b'\r' as usize] = ByteClass::Blank;
    class[b'\n' as usize] = ByteClass::End;
    class[b'#' as usize] = ByteClass::End;
    class
};

/// The words of one line of plain text (`is_plain`) from byte `at`: what
/// `split_ascii_whitespace` gives on the line's text before any `#`. It stops at the end of
/// the line's statement, where `at` is then left.
struct PlainWords<'a> {
    text: &'a str,
    at: usize,
}

impl<'a> Iterator for PlainWords<'a> {
    type Item = &'a str;

    #[inline(always)]
    fn next(&mut self) -> Option<&'a str> {
        let bytes = self.text.as_bytes();
        let class = |i: usize| {
            bytes
                .get(i)
                .map_or(ByteClass::End, |&b| BYTE_CLASS[b as usize])
        };
        let mut i = self.at;
        while class(i) == ByteClass::Blank {
            i += 1;
        }
        let start = i;
        while class(i) == ByteClass::Word {
            i += 1;
        }
        self.at = i;
        // Plain text is ASCII: every byte is a character boundary.
        (i > start).then(|| &self.text[start..i])
    }
}

/// Reads plain text (`is_plain`): the statements that carry numbers and faces from the
/// words `PlainWords` finds, every other line the general way, and the same problems
/// reported in the same words, as both end in `read_statement`.
fn read_plain<'a>(text: &'a str, piece: &mut Piece<'a>) -> Result<(), LineError> {
    let bytes = text.as_bytes();
    let line_end = |from: usize| {
        bytes[from..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |n| from + n)
    };
    let (mut at, mut line) = (0, 0);
    while at < bytes.len() {
        line += 1;
        let mut words = PlainWords { text, at };
        let stopped = match words.next() {
            None => words.at,
            Some(keyword @ ("v" | "vt" | "vn" | "f")) => {
                read_data(piece, line, keyword, &mut words)?;
                words.at
            }
            Some(_) => {
                let end = line_end(at);
                if let Some((content, keyword, words)) = statement_of(&text[at..end]) {
                    read_statement(piece, line, content, keyword, words)?;
                }
                end
            }
        };
        at = match bytes.get(stopped) {
            Some(b'\n') => stopped + 1,
            _ => line_end(stopped) + 1,
        };
    }
    Ok(())
}

fn read_statement<'a>(
    piece: &mut Piece<'a>,
    line: usize,
    content: &'a str,
    keyword: &str,
    words: impl Iterator<Item = &'a str>,
) -> Result<(), LineError> {
    if read_data(piece, line, keyword, words)? {
        return Ok(());
    }
    let fail = |message: String| LineError { line, message };
    match keyword {
        "usemtl" => {
            let name = rest_of(content, keyword);
            if name.is_empty() {
                return Err(fail("`usemtl` needs a material name".into()));
            }
            let faces = piece.faces.len();
            piece
                .statements
                .push(Statement::UseMtl { line, name, faces });
        }
        "mtllib" => {
            let name = rest_of(content, keyword);
            if name.is_empty() {
                return Err(fail("`mtllib` needs a file name".into()));
            }
            piece.statements.push(Statement::MtlLib { line, name });
        }
        _ => {} // o, g, s, l, p, curves and surfaces: not for a ray tracer of meshes
    }
    Ok(())
}

/// Reads a statement that carries numbers (`v`, `vt`, `vn`) or a face (`f`) from the words
/// after its keyword; false for any other keyword.
#[inline(always)]
fn read_data<'a>(
    piece: &mut Piece<'a>,
    line: usize,
    keyword: &str,
    words: impl Iterator<Item = &'a str>,
) -> Result<bool, LineError> {
    let fail = |message: String| LineError { line, message };
    match keyword {
        "v" => {
            // x y z, an optional w, or (a common extension) a colour r g b.
            let n = numbers::<6>(words, "v", line)?;
            match n.len {
                3 | 6 => {}
                4 => {
                    if n.values[3] == 0.0 {
                        return Err(fail("`v` has a weight w of 0".into()));
                    }
                }
                k => {
                    return Err(fail(format!(
                        "`v` needs x y z (and an optional w), got {k} number{}",
                        if k == 1 { "" } else { "s" }
                    )));
                }
            }
            let w = if n.len == 4 { n.values[3] } else { 1.0 };
            let position = Vec3::new(n.values[0], n.values[1], n.values[2]) / w;
            let far = position.abs().max_element();
            // NaN fails the comparison: refused too.
            let within = far as f64 <= crate::limits::MAX_MESH_COORDINATE;
            if !within {
                return Err(fail(format!(
                    "`v` lies {} from the mesh's origin along an axis: at most {:e}",
                    crate::messages::number(far),
                    crate::limits::MAX_MESH_COORDINATE
                )));
            }
            piece.positions.push(position);
        }
        "vt" => {
            let n = numbers::<3>(words, "vt", line)?;
            if n.len == 0 {
                return Err(fail("`vt` needs u (and optional v, w)".into()));
            }
            // OBJ's v runs up the picture, prism's down it (as image rows do).
            let v = if n.len > 1 { n.values[1] } else { 0.0 };
            piece.uvs.push(Vec2::new(n.values[0], 1.0 - v));
        }
        "vn" => {
            let n = numbers::<3>(words, "vn", line)?;
            if n.len != 3 {
                return Err(fail(format!("`vn` needs x y z, got {} numbers", n.len)));
            }
            piece.normals.push(Vec3::from_slice(&n.values));
        }
        "f" => {
            let so_far = [
                piece.defined_before[0] + piece.positions.len(),
                piece.defined_before[1] + piece.uvs.len(),
                piece.defined_before[2] + piece.normals.len(),
            ];
            // Every corner is read before any is resolved: a malformed corner, or too few,
            // is the face's problem before an index out of range is.
            piece.face.clear();
            for word in words {
                piece.face.push(raw_corner(word, line)?);
            }
            let count = piece.face.len();
            if count < 3 {
                return Err(fail(format!(
                    "a face needs at least three corners, got {count}"
                )));
            }
            for raw in &piece.face {
                piece.corners.push(resolve(raw, so_far, line)?);
            }
            piece.faces.push(Face {
                end: piece.corners.len() as u32,
                line: line as u32,
            });
        }
        _ => return Ok(false),
    }
    Ok(true)
}

/// `text` without the UTF-8 byte-order mark some editors put first, which would otherwise
/// hide the first line's keyword (and shift every index after it).
pub(super) fn without_byte_order_mark(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// The libraries one `mtllib` line names: OBJ allows several, separated by spaces, but
/// exporters also write one name with spaces in it; the words are taken as several names
/// only when each of them is an `.mtl` file name.
pub(super) fn library_names(rest: &str) -> Vec<&str> {
    let words: Vec<&str> = rest.split_ascii_whitespace().collect();
    let is_mtl = |w: &&str| {
        w.len() > 4
            && w.is_char_boundary(w.len() - 4)
            && w[w.len() - 4..].eq_ignore_ascii_case(".mtl")
    };
    if words.len() > 1 && words.iter().all(is_mtl) {
        words
    } else {
        vec![rest]
    }
}

/// The statements of OBJ or MTL text: each non-blank line's number (from 1), its text
/// without the comment, its keyword, and the words after the keyword.
pub(super) fn statements(
    text: &str,
) -> impl Iterator<Item = (usize, &str, &str, std::str::SplitAsciiWhitespace<'_>)> {
    text.lines().enumerate().filter_map(|(index, raw)| {
        let (content, keyword, words) = statement_of(raw)?;
        Some((index + 1, content, keyword, words))
    })
}

/// The statement of one line: its text without the comment, its keyword, and the words
/// after the keyword; None for a blank line or a comment.
fn statement_of(raw: &str) -> Option<(&str, &str, std::str::SplitAsciiWhitespace<'_>)> {
    let content = raw.split('#').next().unwrap_or("").trim();
    let mut words = content.split_ascii_whitespace();
    let keyword = words.next()?;
    Some((content, keyword, words))
}

/// What follows the keyword on a line (a name may hold spaces).
pub(super) fn rest_of<'a>(content: &'a str, keyword: &str) -> &'a str {
    content[keyword.len()..].trim()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Plain text read word by word (`read_plain`) reads as the general way reads it: the
    /// same numbers, corners and statements, and the same first problem at the same line,
    /// on texts made of lines that are right, wrong, commented, spaced and ended in every
    /// way plain text allows.
    #[test]
    fn plain_text_reads_as_the_general_way_reads_it() {
        let lines = [
            "v 1 2 3",
            "v\t1.5  -2e3\t3 ",
            "v 1 2 3 # c",
            "v 1 2 3#c",
            "v 0.5 0.25 1 1 0 0",
            "v 1 2",
            "v 1 2 3 4",
            "v 1 2 3 0",
            "v 1 2 3 4 5 6 7",
            "v 1e40 0 0",
            "v nan 0 0",
            "v 1 2 x",
            "vt 0.5",
            "vt 0.25 0.75",
            "vt",
            "vt 1 2 3 4",
            "vn 0 0 1",
            "vn 0 1",
            "f 1 2 3",
            "f 1/1 2/2 3/3",
            "f 1//1 2//2 3//3 # x",
            "f 1/1/1 2/2/2 3/3/3 4/4/4",
            "f 1 2",
            "f 1 2 3 4",
            "f a b c",
            "f 1 2 3\r",
            "  f\t-1 -2 -3  ",
            "f 1 2 3#4",
            "f 99 1 2",
            "usemtl red",
            "usemtl  two words ",
            "usemtl",
            "usemtl # none",
            "mtllib a.mtl b.mtl",
            "mtllib",
            "# comment",
            "",
            "   ",
            "\r",
            "\t# tab then comment",
            "g group",
            "s 1",
            "o thing",
            "vx 1 2 3",
            "fo 1 2 3",
            "v#",
            "f#1 2 3",
            "#v 1 2 3",
            "v 1 2 3\r",
        ];
        let new_piece = || Piece {
            positions: Vec::new(),
            uvs: Vec::new(),
            normals: Vec::new(),
            corners: Vec::new(),
            faces: Vec::new(),
            statements: Vec::new(),
            defined_before: [50, 50, 50],
            face: Vec::new(),
            error: None,
            lines: 0,
        };
        let mut rng = crate::xorshift::XorShift32::new(0x2545_f491);
        let mut errors = 0;
        for _ in 0..20_000 {
            let count = 1 + rng.next_u32() as usize % 12;
            let end = if rng.next_u32().is_multiple_of(2) {
                "\n"
            } else {
                "\r\n"
            };
            let mut text: String = (0..count)
                .map(|_| lines[rng.next_u32() as usize % lines.len()])
                .collect::<Vec<_>>()
                .join(end);
            if rng.next_u32().is_multiple_of(2) {
                text.push_str(end);
            }
            assert!(is_plain(&text));
            let (mut plain, mut general) = (new_piece(), new_piece());
            let plain_read = read_plain(&text, &mut plain);
            let general_read = read_general(&text, &mut general);
            assert_eq!(plain_read, general_read, "{text:?}");
            errors += plain_read.is_err() as usize;
            assert_eq!(plain.positions, general.positions, "{text:?}");
            assert_eq!(plain.uvs, general.uvs, "{text:?}");
            assert_eq!(plain.normals, general.normals, "{text:?}");
            assert_eq!(plain.corners, general.corners, "{text:?}");
            assert_eq!(plain.faces, general.faces, "{text:?}");
            assert_eq!(plain.statements, general.statements, "{text:?}");
        }
        // Both kinds of text were met often.
        assert!(
            (2_000..18_000).contains(&errors),
            "{errors} of 20,000 texts failed"
        );
    }

    /// Text with any byte outside printable ASCII, tab and line ends is read the general
    /// way, which knows Unicode's spaces.
    #[test]
    fn text_with_other_bytes_is_not_plain() {
        assert!(is_plain("v 1 2 3\r\n\tf 1 2 3 # ~\n"));
        for odd in ["\u{a0}", "\u{3000}", "\x0c", "\x0b", "\0", "\x7f", "é"] {
            let text = format!("v 1 2 3\nv 1 2 3{odd}\n");
            assert!(!is_plain(&text), "{odd:?}");
        }
        // A no-break space ends a number the general way (it is trimmed), as it must.
        let text = "v 1 2 3\u{a0}\n";
        let piece = read_piece(text, &count_faces(text, usize::MAX), [0; 3]);
        assert_eq!(piece.error, None);
        assert_eq!(piece.positions, vec![Vec3::new(1.0, 2.0, 3.0)]);
    }

    /// Commented corners do not count; a keyword starting with f is not a face.
    #[test]
    fn faces_are_counted_by_their_corners_before_any_comment() {
        let corners: Vec<String> = (0..5000).map(|k| format!("{}", k % 3 + 1)).collect();
        let ok = format!(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 # {}\nfo 1\n",
            corners.join(" ")
        );
        assert_eq!(count_faces(&ok, usize::MAX).triangles, 1);
    }
}
