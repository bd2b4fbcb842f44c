//! Wavefront MTL material libraries: `newmtl` and the colour, highlight, transparency,
//! index, `illum`, `map_Kd` and relief (`map_Bump`, `bump`, `norm`) statements, as written, each problem named by its line (the
//! mapping to prism's materials is meshes.rs's).

use super::line_error::LineError;
use super::obj_number::numbers;
use super::obj_text::{rest_of, statements, without_byte_order_mark};
use std::collections::HashMap;

/// A material as an MTL file gives it: the statements prism maps, as written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MtlMaterial {
    /// Its `newmtl` name.
    pub name: String,
    /// The line of its `newmtl`.
    pub line: usize,
    /// `Kd`, `Ka`, `Ks`, `Ke`: diffuse, ambient, specular and emitted colours.
    pub kd: Option<[f32; 3]>,
    /// See `kd`.
    pub ka: Option<[f32; 3]>,
    /// See `kd`.
    pub ks: Option<[f32; 3]>,
    /// See `kd`.
    pub ke: Option<[f32; 3]>,
    /// `Ns`: the highlight's exponent.
    pub ns: Option<f32>,
    /// `d` (opacity) or `Tr` (transparency, its complement), as transparency.
    pub transparency: Option<f32>,
    /// `Ni`: the index of refraction.
    pub ni: Option<f32>,
    /// `illum`: the illumination model (3–7 ask for ray-traced reflection; 4, 6, 7 and 9
    /// for refraction).
    pub illum: Option<u32>,
    /// `map_Kd`: the diffuse colour's image, relative to the MTL file.
    pub map_kd: Option<String>,
    /// `map_Bump` or `bump`: a height map (or, as Blender writes them, a normal map), and
    /// its `-bm` multiplier (1 without one).
    pub bump: Option<(String, f32)>,
    /// `norm`: a tangent-space normal map, and its `-bm` multiplier.
    pub norm: Option<(String, f32)>,
    /// The line of each statement, by keyword, for messages about its value.
    pub lines: HashMap<&'static str, usize>,
}

/// Reads MTL text.
pub fn parse_mtl(text: &str) -> Result<Vec<MtlMaterial>, LineError> {
    let text = without_byte_order_mark(text);
    let mut out: Vec<MtlMaterial> = Vec::new();
    for (line, content, keyword, words) in statements(text) {
        let fail = |message: String| LineError { line, message };
        if keyword == "newmtl" {
            let name = rest_of(content, keyword);
            if name.is_empty() {
                return Err(fail("`newmtl` needs a material name".into()));
            }
            out.push(MtlMaterial {
                name: name.to_string(),
                line,
                ..Default::default()
            });
            continue;
        }
        const KNOWN: [&str; 13] = [
            "Kd", "Ka", "Ks", "Ke", "Ns", "d", "Tr", "Ni", "illum", "map_Kd", "map_Bump", "bump",
            "norm",
        ];
        let Some(&known) = KNOWN.iter().find(|&&k| k == keyword) else {
            continue; // other maps, Tf, sharpness: nothing prism draws
        };
        let Some(m) = out.last_mut() else {
            return Err(fail(format!("`{keyword}` comes before any `newmtl`")));
        };
        m.lines.insert(known, line);
        let color = |words| -> Result<[f32; 3], LineError> {
            let n = numbers::<3>(words, keyword, line)?;
            match n.len {
                1 => Ok([n.values[0]; 3]),
                3 => Ok(n.values),
                k => Err(LineError {
                    line,
                    message: format!("`{keyword}` needs r g b, got {k} numbers"),
                }),
            }
        };
        let one = |words| -> Result<f32, LineError> {
            let n = numbers::<1>(words, keyword, line)?;
            if n.len == 1 {
                Ok(n.values[0])
            } else {
                Err(LineError {
                    line,
                    message: format!("`{keyword}` needs one number"),
                })
            }
        };
        match known {
            "Kd" => m.kd = Some(color(words)?),
            "Ka" => m.ka = Some(color(words)?),
            "Ks" => m.ks = Some(color(words)?),
            "Ke" => m.ke = Some(color(words)?),
            "Ns" => m.ns = Some(one(words)?),
            "d" | "Tr" => {
                // Checked as written: `d -5` is out of range as -5, not as a transparency of 6.
                let v = one(words)?;
                if !(0.0..=1.0).contains(&v) {
                    let what = if known == "d" {
                        "dissolve (opacity)"
                    } else {
                        "transparency"
                    };
                    return Err(fail(format!(
                        "`{keyword}` ({what}) must be 0 to 1, got {v}"
                    )));
                }
                m.transparency = Some(if known == "d" { 1.0 - v } else { v });
            }
            "Ni" => m.ni = Some(one(words)?),
            "illum" => {
                let v = one(words)?;
                if !((0.0..=10.0).contains(&v) && v.fract() == 0.0) {
                    return Err(fail(format!(
                        "`illum` must be a whole number 0 to 10, got {v}"
                    )));
                }
                m.illum = Some(v as u32);
            }
            "map_Kd" => {
                // Options (-s, -o, …) come before the file name, which is last.
                let name = words.last().unwrap_or("");
                if name.is_empty() {
                    return Err(fail("`map_Kd` needs an image file name".into()));
                }
                m.map_kd = Some(name.to_string());
            }
            "map_Bump" | "bump" | "norm" => {
                let words: Vec<&str> = words.collect();
                let Some((name, options)) = words.split_last() else {
                    return Err(fail(format!("`{keyword}` needs an image file name")));
                };
                let multiplier = match options.iter().position(|&w| w == "-bm") {
                    None => 1.0,
                    Some(i) => match options.get(i + 1).map(|w| w.parse::<f32>()) {
                        Some(Ok(bm)) if bm.is_finite() => bm,
                        _ => {
                            return Err(fail(format!(
                                "`{keyword}`'s `-bm` needs a number before the file name"
                            )));
                        }
                    },
                };
                let map = Some((name.to_string(), multiplier));
                if known == "norm" {
                    m.norm = map;
                } else {
                    m.bump = map;
                }
            }
            _ => unreachable!(),
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dissolve_is_checked_as_written() {
        let e = parse_mtl("newmtl a\nd -5\n").unwrap_err();
        assert_eq!(e.line, 2);
        assert!(e.message.contains("got -5"), "{}", e.message);
        let e = parse_mtl("newmtl a\nTr 1.5\n").unwrap_err();
        assert!(e.message.contains("got 1.5"), "{}", e.message);
        assert_eq!(
            parse_mtl("newmtl a\nd 0.25\n").unwrap()[0].transparency,
            Some(0.75)
        );
    }

    #[test]
    fn mtl_statements_are_read() {
        let mtl = "newmtl glass\nKd 0.1 0.2 0.3\nKs 1\nNs 200\nd 0.25\nNi 1.5\nillum 7\n\
                   newmtl tex\nmap_Kd -s 2 2 1 grain.jpg\nmap_Bump -bm 0.5 relief.png\n\
                   newmtl n\nnorm -clamp on tangent.png\n";
        let m = parse_mtl(mtl).unwrap();
        assert_eq!(m.len(), 3);
        assert_eq!(m[0].kd, Some([0.1, 0.2, 0.3]));
        assert_eq!(m[0].ks, Some([1.0; 3]));
        assert_eq!(m[0].transparency, Some(0.75));
        assert_eq!((m[0].ni, m[0].illum), (Some(1.5), Some(7)));
        assert_eq!(m[0].lines["Ni"], 6);
        // Options come before the file name: the last word is the name.
        assert_eq!(m[1].map_kd.as_deref(), Some("grain.jpg"));
        assert_eq!(m[1].bump, Some(("relief.png".to_string(), 0.5)));
        assert_eq!(m[2].norm, Some(("tangent.png".to_string(), 1.0)));
        for (text, line) in [
            ("Kd 1 1 1\n", 1),
            ("newmtl a\nKd 1 1\n", 2),
            ("newmtl a\nillum 2.5\n", 2),
            ("newmtl a\nbump\n", 2),
            ("newmtl a\n\nmap_Bump -bm x h.png\n", 3),
        ] {
            assert_eq!(parse_mtl(text).unwrap_err().line, line, "{text:?}");
        }
    }
}
