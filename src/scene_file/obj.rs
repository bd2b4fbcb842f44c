//! Wavefront OBJ meshes: the statements a renderer needs (`v`, `vt`, `vn`, `f`, `usemtl`,
//! `mtllib`), each problem named by its line, and the line reading MTL files share
//! (mtl.rs). Statements for other programs (`o`, `g`, `s`, lines, curves) are passed over,
//! as other readers do. Written here rather than taken from a crate so that a malformed
//! line is reported by its number.

use crate::geometry::{Mesh, MeshError};
use crate::limits;
use glam::{Vec2, Vec3};
use std::collections::HashMap;

/// A problem at a line of an OBJ or MTL file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineError {
    /// The line, counted from 1.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// The triangles of an OBJ file that use one material, as a mesh.
#[derive(Clone, Debug)]
pub struct ObjPart {
    /// The `usemtl` name in force, if any.
    pub material: Option<String>,
    /// The line of that `usemtl` (or of the part's first face), for messages.
    pub line: usize,
    /// The part's triangles (polygons split into fans), with their corners' normals and
    /// texture coordinates where every corner has them.
    pub mesh: Mesh,
}

/// What an OBJ file holds.
#[derive(Clone, Debug)]
pub struct ObjFile {
    /// One part per material, in the order the file first uses each.
    pub parts: Vec<ObjPart>,
    /// The material libraries it names (`mtllib`), with the line of each.
    pub libraries: Vec<(String, usize)>,
}

/// One corner of a face: indices into the file's positions, texture coordinates, normals.
type Corner = [u32; 3];
/// A corner's index where it has none (no texture coordinate, no normal).
const NONE: u32 = u32::MAX;

/// The faces that use one material, as they are read.
struct PartBuilder {
    material: Option<String>,
    line: usize,
    /// Triangles by corners.
    triangles: Vec<[Corner; 3]>,
}

/// Text below this size is read in one piece; larger text in pieces read in parallel, each
/// at least this large (smaller pieces would cost more to hand out than to read).
const PARALLEL_PIECE_BYTES: usize = 1 << 20;

/// Reads OBJ text. At most `max_triangles` triangles are accepted (a polygon of n corners
/// makes n − 2); `smooth` asks for vertex normals where the file has none.
///
/// Large text is cut at line ends into pieces whose numbers are read in parallel; the
/// pieces are then joined in order, resolving face corners against the counts defined so
/// far and reporting the first problem in the file's order, as a reading from start to end
/// would.
pub fn parse_obj(text: &str, max_triangles: usize, smooth: bool) -> Result<ObjFile, LineError> {
    use rayon::prelude::*;
    let text = without_byte_order_mark(text);
    let chunks = cut_at_lines(text);
    let counts = refuse_oversized_faces(&chunks, max_triangles)?;
    let pieces: Vec<Piece> = chunks
        .into_par_iter()
        .zip(counts)
        .map(|(chunk, count)| read_piece(chunk, &count))
        .collect();
    let mut positions: Vec<Vec3> =
        Vec::with_capacity(pieces.iter().map(|p| p.positions.len()).sum());
    let mut uvs: Vec<Vec2> = Vec::new();
    let mut normals: Vec<Vec3> = Vec::new();
    let mut parts: Vec<PartBuilder> = Vec::new();
    let mut current: Option<usize> = None;
    let mut libraries = Vec::new();
    let mut triangle_count = 0usize;
    let mut corners: Vec<Corner> = Vec::new();
    let mut lines_before = 0;
    for piece in pieces {
        let before = [positions.len(), uvs.len(), normals.len()];
        let mut first_corner = 0;
        for statement in &piece.statements {
            match *statement {
                Statement::Face { line, end, counts } => {
                    let line = lines_before + line;
                    let fail = |message: String| LineError { line, message };
                    let so_far: [usize; 3] =
                        std::array::from_fn(|k| before[k] + counts[k] as usize);
                    corners.clear();
                    for raw in &piece.corners[first_corner..end as usize] {
                        corners.push(resolve(raw, so_far, line)?);
                    }
                    first_corner = end as usize;
                    triangle_count += corners.len() - 2;
                    if triangle_count > max_triangles {
                        return Err(fail(format!(
                            "the mesh has more than the {max_triangles} triangles a scene may hold"
                        )));
                    }
                    let part = *current.get_or_insert_with(|| {
                        parts.push(PartBuilder {
                            material: None,
                            line,
                            triangles: Vec::new(),
                        });
                        parts.len() - 1
                    });
                    for i in 1..corners.len() - 1 {
                        parts[part]
                            .triangles
                            .push([corners[0], corners[i], corners[i + 1]]);
                    }
                }
                Statement::UseMtl { line, name } => {
                    let line = lines_before + line;
                    current = Some(
                        match parts
                            .iter()
                            .position(|p| p.material.as_deref() == Some(name))
                        {
                            Some(i) => i,
                            None => {
                                parts.push(PartBuilder {
                                    material: Some(name.to_string()),
                                    line,
                                    triangles: Vec::new(),
                                });
                                parts.len() - 1
                            }
                        },
                    );
                }
                Statement::MtlLib { line, name } => {
                    for library in library_names(name) {
                        libraries.push((library.to_string(), lines_before + line));
                    }
                }
            }
        }
        if let Some(e) = piece.error {
            return Err(LineError {
                line: lines_before + e.line,
                message: e.message,
            });
        }
        positions.extend_from_slice(&piece.positions);
        uvs.extend_from_slice(&piece.uvs);
        normals.extend_from_slice(&piece.normals);
        lines_before += piece.lines;
    }
    let parts: Vec<ObjPart> = parts
        .into_iter()
        .filter(|p| !p.triangles.is_empty())
        .map(|p| build_part(p, &positions, &uvs, &normals, smooth))
        .collect::<Result<_, _>>()?;
    if parts.is_empty() {
        return Err(LineError {
            line: text.lines().count().max(1),
            message: "the file has no faces (`f` lines): there is nothing to draw".into(),
        });
    }
    Ok(ObjFile { parts, libraries })
}

/// `text` cut after line ends into pieces of about equal size (one piece when it is small).
fn cut_at_lines(text: &str) -> Vec<&str> {
    let threads = rayon::current_num_threads().max(1);
    let count = (text.len() / PARALLEL_PIECE_BYTES).clamp(1, 4 * threads);
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

/// What the faces of a piece of text make, counted before anything is built.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct FaceCount {
    /// The triangles its faces make (n − 2 for a face of n corners).
    triangles: usize,
    /// Its lines.
    lines: usize,
    /// The first face with more than `MAX_FACE_CORNERS` corners: its line and corners.
    widest: Option<(usize, usize)>,
    /// The line of the face that takes the count past the budget it was given.
    over_at: Option<usize>,
}

/// Counts the faces of `text` (lines from 1) without reading their numbers, stopping at a
/// face too wide or at the one that takes the triangles past `budget`. Bytes, not
/// statements: it runs over the whole file before the reading does.
fn count_faces(text: &str, budget: usize) -> FaceCount {
    let bytes = text.as_bytes();
    let blank = |b: u8| b == b' ' || b == b'\t' || b == b'\r';
    let mut count = FaceCount::default();
    let mut i = 0;
    while i < bytes.len() {
        count.lines += 1;
        while i < bytes.len() && blank(bytes[i]) {
            i += 1;
        }
        if bytes[i..].starts_with(b"f") && bytes.get(i + 1).is_some_and(|&b| blank(b)) {
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

/// Refuses, before any table is built, a file whose faces make more than `max_triangles`
/// triangles or one with more than `MAX_FACE_CORNERS` corners (its fan of triangles all
/// meet at one corner, where a ray would test every one).
fn refuse_oversized_faces(
    chunks: &[&str],
    max_triangles: usize,
) -> Result<Vec<FaceCount>, LineError> {
    use rayon::prelude::*;
    let counts: Vec<FaceCount> = chunks
        .par_iter()
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
            return Err(LineError {
                line: lines_before + at.unwrap_or(1),
                message: format!(
                    "the mesh has more than the {max_triangles} triangles a scene may hold"
                ),
            });
        }
        triangles += count.triangles;
        lines_before += count.lines;
    }
    Ok(counts)
}

/// A face corner as written: vertex, texture coordinate and normal indices (1-based, or
/// negative to count back), `ABSENT` where the corner has none.
type RawCorner = [i64; 3];
const ABSENT: i64 = i64::MIN;

/// The statements of a piece that depend on what came before it, in order; lines are
/// counted from the piece's start.
enum Statement<'a> {
    /// A face, whose corners end at `end` in the piece's corner list, read when the piece
    /// had defined `counts` positions, texture coordinates and normals.
    Face {
        line: usize,
        end: u32,
        counts: [u32; 3],
    },
    UseMtl {
        line: usize,
        name: &'a str,
    },
    MtlLib {
        line: usize,
        name: &'a str,
    },
}

/// What one piece of OBJ text defines, read on its own.
struct Piece<'a> {
    positions: Vec<Vec3>,
    uvs: Vec<Vec2>,
    normals: Vec<Vec3>,
    corners: Vec<RawCorner>,
    statements: Vec<Statement<'a>>,
    /// The first problem, which ends the piece (its line counted in the piece).
    error: Option<LineError>,
    /// How many lines the piece holds.
    lines: usize,
}

/// Reads one piece, whose faces `count` counted: its numbers, its faces' corners as
/// written, and its other statements. The lists are sized from the count (a face of n
/// corners makes n − 2 triangles, so its corners are at most three per triangle, and a line
/// that is not a face may be a vertex): grown by doubling instead, they would be copied and
/// their fresh pages touched again and again.
fn read_piece<'a>(text: &'a str, count: &FaceCount) -> Piece<'a> {
    let mut piece = Piece {
        positions: Vec::with_capacity(count.lines.saturating_sub(count.triangles.min(count.lines))),
        uvs: Vec::new(),
        normals: Vec::new(),
        corners: Vec::with_capacity(3 * count.triangles),
        statements: Vec::with_capacity(count.triangles),
        error: None,
        lines: text.bytes().filter(|&b| b == b'\n').count(),
    };
    for (line, content, keyword, words) in statements(text) {
        if let Err(e) = read_statement(&mut piece, line, content, keyword, words) {
            piece.error = Some(e);
            break;
        }
    }
    piece
}

fn read_statement<'a>(
    piece: &mut Piece<'a>,
    line: usize,
    content: &'a str,
    keyword: &str,
    words: std::str::SplitAsciiWhitespace<'_>,
) -> Result<(), LineError> {
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
            let start = piece.corners.len();
            for word in words {
                piece.corners.push(raw_corner(word, line)?);
            }
            let count = piece.corners.len() - start;
            if count < 3 {
                return Err(fail(format!(
                    "a face needs at least three corners, got {count}"
                )));
            }
            piece.statements.push(Statement::Face {
                line,
                end: piece.corners.len() as u32,
                counts: [
                    piece.positions.len() as u32,
                    piece.uvs.len() as u32,
                    piece.normals.len() as u32,
                ],
            });
        }
        "usemtl" => {
            let name = rest_of(content, keyword);
            if name.is_empty() {
                return Err(fail("`usemtl` needs a material name".into()));
            }
            piece.statements.push(Statement::UseMtl { line, name });
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

/// `text` without the UTF-8 byte-order mark some editors put first, which would otherwise
/// hide the first line's keyword (and shift every index after it).
pub(super) fn without_byte_order_mark(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// The libraries one `mtllib` line names: OBJ allows several, separated by spaces, but
/// exporters also write one name with spaces in it; the words are taken as several names
/// only when each of them is an `.mtl` file name.
fn library_names(rest: &str) -> Vec<&str> {
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
        let content = raw.split('#').next().unwrap_or("").trim();
        let mut words = content.split_ascii_whitespace();
        let keyword = words.next()?;
        Some((index + 1, content, keyword, words))
    })
}

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
        let v: f32 = word.parse().map_err(|_| LineError {
            line,
            message: format!(
                "`{keyword}`: {} is not a number",
                crate::messages::quoted(word)
            ),
        })?;
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

/// What follows the keyword on a line (a name may hold spaces).
pub(super) fn rest_of<'a>(content: &'a str, keyword: &str) -> &'a str {
    content[keyword.len()..].trim()
}

/// One face corner as written, `v`, `v/vt`, `v//vn` or `v/vt/vn`: its indices, not yet
/// checked against what is defined.
fn raw_corner(word: &str, line: usize) -> Result<RawCorner, LineError> {
    match plain_corner(word.as_bytes()) {
        Some(corner) => Ok(corner),
        None => general_corner(word, line),
    }
}

/// `raw_corner` by the general parser, for every spelling and every refusal.
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
fn resolve(raw: &RawCorner, counts: [usize; 3], line: usize) -> Result<Corner, LineError> {
    let written = || match raw {
        [v, ABSENT, ABSENT] => format!("{v}"),
        [v, t, ABSENT] => format!("{v}/{t}"),
        [v, ABSENT, n] => format!("{v}//{n}"),
        [v, t, n] => format!("{v}/{t}/{n}"),
    };
    let what = ["vertex", "texture coordinate", "normal"];
    let mut out = [NONE; 3];
    for k in 0..3 {
        let i = raw[k];
        if i == ABSENT {
            continue;
        }
        let count = counts[k];
        let resolved = if i > 0 { i - 1 } else { count as i64 + i };
        if i == 0 || resolved < 0 || resolved >= count as i64 {
            return Err(LineError {
                line,
                message: format!(
                    "face corner {}: {} index {i} is out of range ({count} defined so far)",
                    crate::messages::quoted(&written()),
                    what[k]
                ),
            });
        }
        out[k] = resolved as u32;
    }
    Ok(out)
}

/// The mesh of one part: each distinct corner (position, texture coordinate, normal)
/// becomes one vertex, so shared corners stay shared.
fn build_part(
    part: PartBuilder,
    positions: &[Vec3],
    uvs: &[Vec2],
    normals: &[Vec3],
    smooth: bool,
) -> Result<ObjPart, LineError> {
    let all_uv = part.triangles.iter().flatten().all(|c| c[1] != NONE);
    let all_normals = part.triangles.iter().flatten().all(|c| c[2] != NONE);
    let key = |c: &Corner| -> Corner {
        [
            c[0],
            if all_uv { c[1] } else { NONE },
            if all_normals { c[2] } else { NONE },
        ]
    };
    // Most positions make one vertex: the first corner at each position is found by a
    // table indexed by position, and only corners that differ from it there (a seam of
    // texture coordinates or normals) by a hash map.
    let mut first_at: Vec<u32> = vec![u32::MAX; positions.len()];
    let mut keys: Vec<Corner> = Vec::new();
    let mut others: HashMap<Corner, u32> = HashMap::new();
    let (mut p_out, mut uv_out, mut n_out) = (Vec::new(), Vec::new(), Vec::new());
    let mut triangles = Vec::with_capacity(part.triangles.len());
    for tri in &part.triangles {
        triangles.push(tri.map(|c| {
            let k = key(&c);
            let first = first_at[k[0] as usize];
            if first != u32::MAX && keys[first as usize] == k {
                return first;
            }
            let mut add = || {
                p_out.push(positions[k[0] as usize]);
                if k[1] != NONE {
                    uv_out.push(uvs[k[1] as usize]);
                }
                if k[2] != NONE {
                    n_out.push(normals[k[2] as usize]);
                }
                keys.push(k);
                (p_out.len() - 1) as u32
            };
            if first == u32::MAX {
                let v = add();
                first_at[k[0] as usize] = v;
                v
            } else {
                *others.entry(k).or_insert_with(add)
            }
        }));
    }
    let mesh = Mesh::new(p_out, n_out, uv_out, triangles).map_err(|e| LineError {
        line: part.line,
        message: match e {
            MeshError::NoTriangles => format!(
                "every face {} has no area",
                match &part.material {
                    Some(m) => format!("with material {}", crate::messages::quoted(m)),
                    None => "here".into(),
                }
            ),
            other => other.to_string(),
        },
    })?;
    let mesh = if smooth {
        mesh.smooth()
    } else {
        mesh.faceted()
    };
    Ok(ObjPart {
        material: part.material,
        line: part.line,
        mesh,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_file::mtl::parse_mtl;

    #[test]
    fn faces_are_triangulated_and_corners_shared() {
        let obj = "# a square and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n\
                   f 1 2 3 4\nf -4 5 -3\n";
        let file = parse_obj(obj, 100, false).unwrap();
        assert_eq!(file.parts.len(), 1);
        let mesh = &file.parts[0].mesh;
        assert_eq!(mesh.triangle_count(), 3);
        assert_eq!(mesh.vertex_count(), 5);
        assert!(!mesh.is_smooth());
        assert!(parse_obj(obj, 100, true).unwrap().parts[0].mesh.is_smooth());
    }

    #[test]
    fn materials_split_parts_and_uvs_normals_are_kept() {
        let obj = "mtllib a b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n\
                   usemtl red\nf 1/1/1 2/2/1 3/3/1\nusemtl blue\nf 1//1 3//1 2//1\nusemtl red\nf 3 2 1\n";
        let file = parse_obj(obj, 100, true).unwrap();
        assert_eq!(file.libraries, vec![("a b.mtl".to_string(), 1)]);
        let names: Vec<_> = file
            .parts
            .iter()
            .map(|p| p.material.clone().unwrap())
            .collect();
        assert_eq!(names, ["red", "blue"]);
        assert_eq!(file.parts[0].line, 9);
        // Red: one face with uvs, one without, so the part has none.
        assert_eq!(file.parts[0].mesh.triangle_count(), 2);
        assert!(!file.parts[0].mesh.has_uvs());
        assert!(file.parts[1].mesh.is_smooth());
    }

    /// Text large enough to be read in parallel pieces reads as it would in one: corners
    /// counted back across pieces resolve, materials switch where they should, and a
    /// problem far down the file is named by its own line.
    #[test]
    fn large_files_read_in_pieces_as_in_one() {
        let rows = 400;
        let mut text = String::from("mtllib m.mtl\n");
        let mut lines = 1;
        for r in 0..rows {
            for c in 0..rows {
                text.push_str(&format!("v {c} {r} 0.5\n"));
                lines += 1;
            }
            if r > 0 {
                text.push_str(if r % 2 == 0 {
                    "usemtl even\n"
                } else {
                    "usemtl odd\n"
                });
                lines += 1;
                // The previous row by absolute indices, this row counted back.
                for c in 0..rows - 1 {
                    let below = (r - 1) * rows + c + 1;
                    let back = rows - c;
                    text.push_str(&format!("f {below} {} -{} -{back}\n", below + 1, back - 1));
                    lines += 1;
                }
            }
        }
        assert!(
            text.len() > 4 * PARALLEL_PIECE_BYTES,
            "{} bytes",
            text.len()
        );
        assert!(cut_at_lines(&text).len() > 1);
        let file = parse_obj(&text, usize::MAX, false).unwrap();
        assert_eq!(file.libraries, vec![("m.mtl".to_string(), 1)]);
        let names: Vec<_> = file.parts.iter().map(|p| p.material.clone()).collect();
        assert_eq!(names, vec![Some("odd".into()), Some("even".into())]);
        let triangles: usize = file.parts.iter().map(|p| p.mesh.triangle_count()).sum();
        assert_eq!(triangles, 2 * (rows - 1) * (rows - 1));
        // Every triangle spans one grid cell: its corners one apart in x or y.
        for part in &file.parts {
            let p = part.mesh.positions();
            for t in part.mesh.triangles() {
                let [a, b, c] = t.map(|i| glam::Vec3::from(p[i as usize]));
                let span = a.max(b).max(c) - a.min(b).min(c);
                assert_eq!((span.x, span.y, span.z), (1.0, 1.0, 0.0), "{a} {b} {c}");
            }
        }
        // A corner out of range on the last line is reported there.
        let bad = format!("{text}f 1 2 {}\n", rows * rows + 1);
        let e = parse_obj(&bad, usize::MAX, false).unwrap_err();
        assert_eq!(e.line, lines + 1);
        assert!(e.message.contains("out of range"), "{}", e.message);
    }

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
        let mut state = 0x9e37_79b9u32;
        for _ in 0..20_000 {
            let len = 1 + state as usize % 9;
            let word: String = (0..len)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 17;
                    state ^= state << 5;
                    b"0123456789/-+x"[state as usize % 14] as char
                })
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

    #[test]
    fn malformed_lines_are_named() {
        let cases = [
            ("v 0 0\n", 1, "`v` needs x y z"),
            ("v 0 0 0\nv 1 x 0\n", 2, "\"x\" is not a number"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
                4,
                "at least three corners",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
                4,
                "vertex index 4 is out of range",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",
                4,
                "vertex index 0 is out of range",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2 2 3\n",
                4,
                "texture coordinate index 2",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3\n",
                6,
                "more than three",
            ),
            ("v 0 0 0\nv 1 0 inf\n", 2, "not a finite number"),
            ("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", 4, "no area"),
            ("v 0 0 0\n", 1, "no faces"),
            ("v 0 0 0 0\n", 1, "weight w of 0"),
        ];
        for (text, line, words) in cases {
            let e = parse_obj(text, 100, true).unwrap_err();
            assert_eq!(e.line, line, "{text:?}: {e:?}");
            assert!(e.message.contains(words), "{text:?}: {}", e.message);
        }
        let big = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\nf 1 2 3\n";
        let e = parse_obj(big, 2, true).unwrap_err();
        assert_eq!(e.line, 6);
    }

    /// Too many triangles, or a face too wide, are refused from a count of the faces
    /// before any number is read or table built: before a bad number further on is met,
    /// and at the line that crosses the limit, even across the pieces read in parallel.
    #[test]
    fn oversized_faces_are_refused_before_reading() {
        let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        for _ in 0..400_000 {
            text += "f 1 2 3\n";
        }
        text += "v nonsense\n";
        let e = parse_obj(&text, 350_000, true).unwrap_err();
        assert_eq!(e.line, 3 + 350_001, "{e:?}");
        assert!(
            e.message.contains("more than the 350000 triangles"),
            "{e:?}"
        );
        let e = parse_obj(&text, 1 << 20, true).unwrap_err();
        assert!(e.message.contains("not a finite number") || e.message.contains("nonsense"));

        let corners: Vec<String> = (0..5000).map(|k| format!("{}", k % 3 + 1)).collect();
        let wide = format!(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\n# a comment\nf {}\n",
            corners.join(" ")
        );
        let e = parse_obj(&wide, 1 << 20, true).unwrap_err();
        assert_eq!(e.line, 5);
        assert!(e.message.contains("5000 corners: at most 4096"), "{e:?}");
        // Commented corners do not count; a keyword starting with f is not a face.
        let ok = format!(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 # {}\nfo 1\n",
            corners.join(" ")
        );
        assert_eq!(count_faces(&ok, usize::MAX).triangles, 1);
    }

    #[test]
    fn a_byte_order_mark_hides_nothing() {
        let obj = "\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n";
        let file = parse_obj(obj, 10, false).unwrap();
        let plain = parse_obj(&obj[3..], 10, false).unwrap();
        assert_eq!(format!("{:?}", file.parts), format!("{:?}", plain.parts));
        // Without the mark's removal, `f 1 2 3` would name vertices (1,0,0), (0,1,0), (5,5,5).
        let mtl = parse_mtl("\u{feff}newmtl a\nKd 1 0 0\n").unwrap();
        assert_eq!(mtl[0].name, "a");
    }

    #[test]
    fn mtllib_names_several_libraries_or_one_with_spaces() {
        assert_eq!(library_names("a.mtl b.MTL"), vec!["a.mtl", "b.MTL"]);
        assert_eq!(library_names("my file.mtl"), vec!["my file.mtl"]);
        assert_eq!(library_names("one.mtl"), vec!["one.mtl"]);
        let file = parse_obj(
            "mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            10,
            false,
        )
        .unwrap();
        assert_eq!(
            file.libraries,
            vec![("a.mtl".to_string(), 1), ("b.mtl".to_string(), 1)]
        );
    }
}
