//! Wavefront OBJ meshes: the statements a renderer needs (`v`, `vt`, `vn`, `f`, `usemtl`,
//! `mtllib`), each problem named by its line: read in pieces (obj_text.rs), joined
//! (obj_join.rs) and made into one mesh per material here. Statements for other programs (`o`, `g`, `s`, lines, curves) are passed over,
//! as other readers do. Written here rather than taken from a crate so that a malformed
//! line is reported by its number.

pub use super::line_error::LineError;
use super::obj_join::{Outline, PartBuilder};
use super::obj_text::{
    Piece, cut_at_lines, read_piece, refuse_oversized_faces, without_byte_order_mark,
};
use super::obj_vertices::Vertices;
use crate::geometry::{Mesh, MeshError};
use glam::{Vec2, Vec3};

/// The triangles of an OBJ file that use one material, as a mesh.
#[derive(Clone, Debug, PartialEq)]
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
#[derive(Clone, Debug, PartialEq)]
pub struct ObjFile {
    /// One part per material, in the order the file first uses each.
    pub parts: Vec<ObjPart>,
    /// The material libraries it names (`mtllib`), with the line of each.
    pub libraries: Vec<(String, usize)>,
}

/// Reads OBJ text. At most `max_triangles` triangles are accepted (a polygon of n corners
/// makes n − 2); `smooth` asks for vertex normals where the file has none.
///
/// Large text is cut at line ends into pieces read in parallel: a first pass counts what
/// each piece defines, so that each resolves its faces' corners against what the file
/// defined before them as it reads them. The pieces are then joined, also in parallel,
/// reporting the first problem in the file's order, as a reading from start to end would.
pub fn parse_obj(text: &str, max_triangles: usize, smooth: bool) -> Result<ObjFile, LineError> {
    let text = without_byte_order_mark(text);
    parse_pieces(text, cut_at_lines(text), max_triangles, smooth)
}

/// `parse_obj` of `text` cut into `chunks` (consecutive, whole lines).
fn parse_pieces(
    text: &str,
    chunks: Vec<&str>,
    max_triangles: usize,
    smooth: bool,
) -> Result<ObjFile, LineError> {
    use rayon::prelude::*;
    let counts = refuse_oversized_faces(&chunks, max_triangles)?;
    // What the text before each piece defines, so that each resolves its own corners.
    let defined_before: Vec<[usize; 3]> = counts
        .iter()
        .scan([0; 3], |sum, count| {
            let before = *sum;
            *sum = std::array::from_fn(|k| sum[k] + count.defined[k]);
            Some(before)
        })
        .collect();
    let pieces: Vec<Piece> = chunks
        .into_par_iter()
        .with_max_len(1) // each piece handed out alone (`PIECES_PER_THREAD`)
        .zip(counts)
        .zip(defined_before)
        .map(|((chunk, count), before)| read_piece(chunk, &count, before))
        .collect();
    let outline = Outline::of(&pieces);
    let mut parts = outline.fill(&pieces, max_triangles)?;
    let count = |list: fn(&Piece) -> usize| pieces.iter().map(list).sum();
    let mut positions: Vec<Vec3> = Vec::with_capacity(count(|p| p.positions.len()));
    let mut uvs: Vec<Vec2> = Vec::with_capacity(count(|p| p.uvs.len()));
    let mut normals: Vec<Vec3> = Vec::with_capacity(count(|p| p.normals.len()));
    for piece in &pieces {
        positions.extend_from_slice(&piece.positions);
        uvs.extend_from_slice(&piece.uvs);
        normals.extend_from_slice(&piece.normals);
    }
    parts.retain(|p| !p.triangles.is_empty());
    let libraries = outline.libraries;
    let parts: Vec<ObjPart> = parts
        .into_iter()
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

/// The mesh of one part: each distinct corner (position, texture coordinate, normal)
/// becomes one vertex, so shared corners stay shared.
fn build_part(
    part: PartBuilder,
    positions: &[Vec3],
    uvs: &[Vec2],
    normals: &[Vec3],
    smooth: bool,
) -> Result<ObjPart, LineError> {
    let Vertices {
        positions: p_out,
        uvs: uv_out,
        normals: n_out,
        triangles,
    } = Vertices::of(&part.triangles, positions, uvs, normals);
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
    use crate::scene_file::obj_text::{PARALLEL_PIECE_BYTES, library_names};

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

    /// Text cut into pieces anywhere between lines reads as it does in one piece: the same
    /// parts, meshes and libraries, and the same first problem, wherever the problems lie
    /// among the pieces (a corner out of range, a malformed line, the triangle budget).
    #[test]
    fn every_cut_into_pieces_reads_as_one_piece() {
        let mut lines = vec!["mtllib a.mtl".to_string()];
        for k in 0..6 {
            lines.push(format!("v {k} 0 0"));
            lines.push(format!("v {k} 1 0"));
            lines.push(format!("vt {} 0.5", k as f32 / 8.0));
            lines.push(format!("vn 0 0 {}", k + 1));
        }
        // Unnamed faces first, then two materials in turn, one of them used again later.
        lines.push("f 1/1/1 3/2/2 2/1/1".into());
        lines.push("usemtl red".into());
        lines.push("f 3 5 4 6".into());
        lines.push("# a comment".into());
        lines.push("usemtl blue".into());
        lines.push("f -1 -2 -3".into());
        lines.push("mtllib b.mtl c.mtl".into());
        lines.push("usemtl red".into());
        lines.push("f 7//1 9//2 8//3 10//4 12//5".into());
        lines.push("v 9 9 9".into());
        lines.push("f -1 1 2".into());
        let text = lines.join("\n") + "\n";
        // Every way to cut the text into up to three pieces at line ends.
        let ends: Vec<usize> = text.match_indices('\n').map(|(i, _)| i + 1).collect();
        let cuts = |text: &str| -> Vec<Vec<usize>> {
            let ends: Vec<usize> = text.match_indices('\n').map(|(i, _)| i + 1).collect();
            let mut all = vec![vec![]];
            for (k, &a) in ends.iter().enumerate() {
                all.push(vec![a]);
                for &b in &ends[k + 1..] {
                    all.push(vec![a, b]);
                }
            }
            all
        };
        fn pieces<'t>(text: &'t str, cut: &[usize]) -> Vec<&'t str> {
            let mut bounds = vec![0];
            bounds.extend(cut.iter().filter(|&&c| c < text.len()));
            bounds.push(text.len());
            bounds.windows(2).map(|w| &text[w[0]..w[1]]).collect()
        }
        assert!(ends.len() > 30);
        // The text whole, a corner out of range before a malformed line, a malformed line
        // alone, and budgets that the faces meet and exceed: (text, budget, reads).
        let with = |line: usize, what: &str| {
            let mut l = lines.clone();
            l.insert(line, what.to_string());
            l.join("\n") + "\n"
        };
        let variants = [
            (text.clone(), usize::MAX, true),
            (with(28, "f 1 2 99"), usize::MAX, false),
            (
                with(28, "f 1 2 99").replace("f -1 1 2", "vn 1 x 0"),
                usize::MAX,
                false,
            ),
            (text.replace("f -1 1 2", "vt"), usize::MAX, false),
            // A piece that is not plain text counts its definitions the general way (an
            // ideographic space is trimmed, so this is a vertex the last face uses).
            (text.replace("v 9 9 9", "\u{3000}v 9 9 9"), usize::MAX, true),
            (with(26, "usemtl"), usize::MAX, false),
            (text.clone(), 8, true),
            (text.clone(), 7, false),
        ];
        for (text, budget, reads) in variants {
            let whole = parse_pieces(&text, vec![&text], budget, false);
            assert_eq!(whole.is_ok(), reads, "{whole:?}");
            for cut in cuts(&text) {
                let got = parse_pieces(&text, pieces(&text, &cut), budget, false);
                assert_eq!(got, whole, "cut at {cut:?}");
            }
        }
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
