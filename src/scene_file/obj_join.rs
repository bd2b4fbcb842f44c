//! The pieces of an OBJ file joined: their faces, whose corners the reading resolved,
//! gathered into one part per material, the pieces in parallel once one ordered pass over
//! their material statements has found where each starts.

use super::line_error::LineError;
use super::obj_corner::Corner;
use super::obj_text::{Piece, Statement, library_names, too_many_triangles};

/// The faces that use one material, as they are read.
pub(super) struct PartBuilder {
    pub(super) material: Option<String>,
    pub(super) line: usize,
    /// Triangles by corners.
    pub(super) triangles: Vec<[Corner; 3]>,
}

/// What the pieces make together, found in one pass over their material statements in
/// order (a run of faces between two counts its triangles from where its corners start
/// and end): where each piece starts, the parts in the order the file first uses them and
/// how many triangles each piece adds to each, so that the pieces can then write their
/// triangles in parallel.
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

/// What the text before a piece made, and the part its faces join first.
#[derive(Clone, Copy)]
struct PieceStart {
    lines: usize,
    triangles: usize,
    part: Option<usize>,
}

/// A piece's faces `from .. to` (indices into its faces), which use one material.
struct Run {
    from: usize,
    to: usize,
}

impl Run {
    /// The triangles the run's faces make: n − 2 for a face of n corners.
    fn triangles(&self, piece: &Piece) -> usize {
        piece.corners_before(self.to) - piece.corners_before(self.from) - 2 * (self.to - self.from)
    }
}

/// What a piece holds, in order: runs of faces and the statements between them.
enum Step<'s, 'a> {
    Run(Run),
    Statement(&'s Statement<'a>),
}

/// A piece's statements in order, with the non-empty runs of faces between them.
fn walk<'s, 'a>(piece: &'s Piece<'a>, mut on: impl FnMut(Step<'s, 'a>)) {
    let mut from = 0;
    for statement in &piece.statements {
        if let Statement::UseMtl { faces, .. } = *statement {
            if faces > from {
                on(Step::Run(Run { from, to: faces }));
            }
            from = faces;
        }
        on(Step::Statement(statement));
    }
    if piece.faces.len() > from {
        on(Step::Run(Run {
            from,
            to: piece.faces.len(),
        }));
    }
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
            lines: 0,
            triangles: 0,
            part: None,
        };
        for piece in pieces {
            outline.starts.push(start);
            let mut made = vec![0; outline.parts.len()];
            walk(piece, |step| match step {
                Step::Run(run) => {
                    let part = *start.part.get_or_insert_with(|| {
                        let line = start.lines + piece.faces[run.from].line as usize;
                        outline.parts.push((None, line));
                        outline.unnamed = Some(outline.parts.len() - 1);
                        outline.parts.len() - 1
                    });
                    let triangles = run.triangles(piece);
                    made.resize(outline.parts.len(), 0);
                    made[part] += triangles;
                    start.triangles += triangles;
                }
                Step::Statement(&Statement::UseMtl { line, name, .. }) => {
                    let known = outline.parts.iter().position(|p| p.0 == Some(name));
                    start.part = Some(known.unwrap_or_else(|| {
                        outline.parts.push((Some(name), start.lines + line));
                        outline.parts.len() - 1
                    }));
                }
                Step::Statement(&Statement::MtlLib { line, name }) => {
                    for library in library_names(name) {
                        outline
                            .libraries
                            .push((library.to_string(), start.lines + line));
                    }
                }
            });
            outline.made.push(made);
            if piece.error.is_some() {
                break;
            }
            start.lines += piece.lines;
        }
        for made in &mut outline.made {
            made.resize(outline.parts.len(), 0);
        }
        outline
    }

    /// The parts, with every piece's triangles written in parallel into its own stretch of
    /// each part; the first problem in the file's order, if any.
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

    /// Writes one piece's triangles (polygons as fans) into its stretches of the parts.
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
        let mut over = None;
        walk(piece, |step| match step {
            Step::Run(run) => {
                if over.is_some() {
                    return;
                }
                // The outline made the unnamed part at the first face before any `usemtl`.
                let part = *current.get_or_insert_with(|| {
                    self.unnamed
                        .expect("the outline made the part of unnamed faces")
                });
                for k in run.from..run.to {
                    let corners =
                        &piece.corners[piece.corners_before(k)..piece.corners_before(k + 1)];
                    triangles += corners.len() - 2;
                    if triangles > max_triangles {
                        let line = start.lines + piece.faces[k].line as usize;
                        over = Some(too_many_triangles(line, max_triangles));
                        return;
                    }
                    for i in 1..corners.len() - 1 {
                        stretch[part][written[part]] = [corners[0], corners[i], corners[i + 1]];
                        written[part] += 1;
                    }
                }
            }
            Step::Statement(&Statement::UseMtl { name, .. }) => {
                current = self.parts.iter().position(|p| p.0 == Some(name));
            }
            Step::Statement(Statement::MtlLib { .. }) => {}
        });
        match (over, &piece.error) {
            (Some(e), _) => Err(e),
            (None, Some(e)) => Err(LineError {
                line: start.lines + e.line,
                message: e.message.clone(),
            }),
            (None, None) => Ok(()),
        }
    }
}
