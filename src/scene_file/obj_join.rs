//! The pieces of an OBJ file joined: each face's corners resolved against what the file
//! defined before it, and its triangles gathered into one part per material, the pieces
//! in parallel once one ordered pass has found where each starts.

use super::obj_text::{
    ABSENT, LineError, Piece, RawCorner, Statement, library_names, too_many_triangles,
};

/// One corner of a face: indices into the file's positions, texture coordinates, normals.
pub(super) type Corner = [u32; 3];
/// A corner's index where it has none (no texture coordinate, no normal).
pub(super) const NONE: u32 = u32::MAX;

/// The faces that use one material, as they are read.
pub(super) struct PartBuilder {
    pub(super) material: Option<String>,
    pub(super) line: usize,
    /// Triangles by corners.
    pub(super) triangles: Vec<[Corner; 3]>,
}

/// What the pieces make together, found in one pass over their statements in order
/// before any corner is resolved: where each piece starts, the parts in the order the
/// file first uses them and how many triangles each piece adds to each, so that the
/// pieces can then resolve their corners and write their triangles in parallel.
pub(super) struct Outline<'a> {
    /// Where each piece starts, for the pieces up to and including the first that ends in
    /// a problem (the rest are never reached).
    starts: Vec<PieceStart>,
    /// Each part's material and the line that starts it.
    parts: Vec<(Option<&'a str>, usize)>,
    /// The part of faces before any `usemtl`, if there are such faces.
    unnamed: Option<usize>,
    /// `made[piece][part]`: the triangles the piece adds to the part.
    made: Vec<Vec<usize>>,
    pub(super) libraries: Vec<(String, usize)>,
}

/// What the text before a piece defined and made, and the part its faces join first.
#[derive(Clone, Copy)]
struct PieceStart {
    /// Positions, texture coordinates and normals.
    defined: [usize; 3],
    lines: usize,
    triangles: usize,
    part: Option<usize>,
}

impl<'a> Outline<'a> {
    pub(super) fn of(pieces: &[Piece<'a>]) -> Outline<'a> {
        let mut outline = Outline {
            starts: Vec::with_capacity(pieces.len()),
            parts: Vec::new(),
            unnamed: None,
            made: Vec::with_capacity(pieces.len()),
            libraries: Vec::new(),
        };
        let mut start = PieceStart {
            defined: [0; 3],
            lines: 0,
            triangles: 0,
            part: None,
        };
        for piece in pieces {
            outline.starts.push(start);
            let mut made = vec![0; outline.parts.len()];
            let mut first_corner = 0;
            for statement in &piece.statements {
                match *statement {
                    Statement::Face { line, end, .. } => {
                        let triangles = end as usize - first_corner - 2;
                        first_corner = end as usize;
                        let part = *start.part.get_or_insert_with(|| {
                            outline.parts.push((None, start.lines + line));
                            outline.unnamed = Some(outline.parts.len() - 1);
                            outline.parts.len() - 1
                        });
                        made.resize(outline.parts.len(), 0);
                        made[part] += triangles;
                        start.triangles += triangles;
                    }
                    Statement::UseMtl { line, name } => {
                        let known = outline.parts.iter().position(|p| p.0 == Some(name));
                        start.part = Some(known.unwrap_or_else(|| {
                            outline.parts.push((Some(name), start.lines + line));
                            outline.parts.len() - 1
                        }));
                    }
                    Statement::MtlLib { line, name } => {
                        for library in library_names(name) {
                            outline
                                .libraries
                                .push((library.to_string(), start.lines + line));
                        }
                    }
                }
            }
            outline.made.push(made);
            if piece.error.is_some() {
                break;
            }
            start.defined[0] += piece.positions.len();
            start.defined[1] += piece.uvs.len();
            start.defined[2] += piece.normals.len();
            start.lines += piece.lines;
        }
        for made in &mut outline.made {
            made.resize(outline.parts.len(), 0);
        }
        outline
    }

    /// The parts, with every piece's triangles resolved and written in parallel into its
    /// own stretch of each part; the first problem in the file's order, if any.
    pub(super) fn fill(
        &self,
        pieces: &[Piece<'a>],
        max_triangles: usize,
    ) -> Result<Vec<PartBuilder>, LineError> {
        use rayon::prelude::*;
        let mut parts: Vec<PartBuilder> = self
            .parts
            .iter()
            .enumerate()
            .map(|(part, &(material, line))| PartBuilder {
                material: material.map(str::to_string),
                line,
                triangles: vec![[[0; 3]; 3]; self.made.iter().map(|m| m[part]).sum()],
            })
            .collect();
        // Each piece's stretch of each part, in order.
        let mut stretches: Vec<Vec<&mut [[Corner; 3]]>> = (0..self.starts.len())
            .map(|_| Vec::with_capacity(parts.len()))
            .collect();
        for (part, builder) in parts.iter_mut().enumerate() {
            let mut rest = &mut builder.triangles[..];
            for (piece, stretch) in stretches.iter_mut().enumerate() {
                let (mine, after) = rest.split_at_mut(self.made[piece][part]);
                stretch.push(mine);
                rest = after;
            }
        }
        let results: Vec<Result<(), LineError>> = pieces[..self.starts.len()]
            .par_iter()
            .zip(&self.starts)
            .zip(stretches)
            .map(|((piece, start), stretch)| self.fill_piece(piece, start, stretch, max_triangles))
            .collect();
        results.into_iter().collect::<Result<(), _>>()?;
        Ok(parts)
    }

    /// Resolves one piece's face corners against what was defined before each face and
    /// writes its triangles (polygons as fans) into its stretches of the parts.
    fn fill_piece(
        &self,
        piece: &Piece,
        start: &PieceStart,
        mut stretch: Vec<&mut [[Corner; 3]]>,
        max_triangles: usize,
    ) -> Result<(), LineError> {
        let mut written = vec![0; stretch.len()];
        let mut current = start.part;
        let mut triangles = start.triangles;
        let mut corners: Vec<Corner> = Vec::new();
        let mut first_corner = 0;
        for statement in &piece.statements {
            match *statement {
                Statement::Face { line, end, counts } => {
                    let line = start.lines + line;
                    let so_far: [usize; 3] =
                        std::array::from_fn(|k| start.defined[k] + counts[k] as usize);
                    corners.clear();
                    for raw in &piece.corners[first_corner..end as usize] {
                        corners.push(resolve(raw, so_far, line)?);
                    }
                    first_corner = end as usize;
                    triangles += corners.len() - 2;
                    if triangles > max_triangles {
                        return Err(too_many_triangles(line, max_triangles));
                    }
                    // The outline made the unnamed part at the first face before any
                    // `usemtl`.
                    let part = *current.get_or_insert_with(|| {
                        self.unnamed
                            .expect("the outline made the part of unnamed faces")
                    });
                    for i in 1..corners.len() - 1 {
                        stretch[part][written[part]] = [corners[0], corners[i], corners[i + 1]];
                        written[part] += 1;
                    }
                }
                Statement::UseMtl { name, .. } => {
                    current = self.parts.iter().position(|p| p.0 == Some(name));
                }
                Statement::MtlLib { .. } => {}
            }
        }
        match &piece.error {
            Some(e) => Err(LineError {
                line: start.lines + e.line,
                message: e.message.clone(),
            }),
            None => Ok(()),
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
