//! OBJ polylines: `v` vertices and `l` elements; the current object (`o`) or
//! group (`g`) name is the curve id and its prefix (A, B, edge) the family.

use crate::error::{Error, Location, Result};
use crate::network::{Family, RawCurve, RawNetwork, Unit};
use glam::DVec3;
use std::path::Path;

/// The x, y and z of a `v` element from the words after its tag (`line`:
/// where it starts, for errors); `refuse_non_finite`: a coordinate that
/// is infinite or not a number is an error too.
pub(crate) fn vertex<'a>(
    words: &mut impl Iterator<Item = &'a str>,
    path: &Path,
    line: usize,
    refuse_non_finite: bool,
) -> Result<DVec3> {
    let mut xyz = [0.0f64; 3];
    for (k, slot) in xyz.iter_mut().enumerate() {
        let w = words
            .next()
            .ok_or_else(|| Error::input(path, Location::Line(line), "vertex needs x, y and z"))?;
        let x = w.parse::<f64>().map_err(|_| {
            Error::input(
                path,
                Location::Line(line),
                format!("vertex coordinate {} '{w}' is not a number", k + 1),
            )
        })?;
        if refuse_non_finite && !x.is_finite() {
            return Err(Error::input(
                path,
                Location::Line(line),
                format!("vertex coordinate {} '{w}' is not finite", k + 1),
            ));
        }
        *slot = x;
    }
    Ok(DVec3::from_array(xyz))
}

/// The vertex index of one word of an `f` or `l` element (`7`, `7/2`,
/// `7//3`, `-1`), as written: 1-based or, below 0, counted back.
pub(crate) fn vertex_index(w: &str, path: &Path, line: usize) -> Result<i64> {
    let v = w.split('/').next().unwrap_or(w);
    v.parse().map_err(|_| {
        Error::input(
            path,
            Location::Line(line),
            format!("vertex index '{w}' is not an integer"),
        )
    })
}

/// Parse OBJ text. OBJ carries no unit: the caller says which (`unit`).
pub fn parse(text: &str, unit: Unit, path: &Path) -> Result<RawNetwork> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.trim().is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut name: Option<(String, usize)> = None;
    // Vertices and polylines since the current name: an object with vertices
    // but no polyline is what a file cut short leaves behind.
    let (mut vertices_since_name, mut lines_since_name) = (0usize, 0usize);
    // (id, line of its name, line of its first polyline, vertex indices)
    let mut pieces: Vec<(String, usize, usize, Vec<usize>)> = Vec::new();
    let unfinished = |name: &Option<(String, usize)>, v: usize, l: usize| -> Result<()> {
        match name {
            Some((id, at)) if v > 0 && l == 0 => Err(Error::input(
                path,
                Location::Line(*at),
                format!(
                    "object '{id}' has {v} vertices but no polyline (`l` element): is the file cut short?"
                ),
            )),
            _ => Ok(()),
        }
    };
    for (i, line) in text.lines().enumerate() {
        let line_no = i + 1;
        let line = line.split('#').next().unwrap_or("").trim();
        let mut words = line.split_whitespace();
        let Some(tag) = words.next() else { continue };
        match tag {
            "v" => {
                vertices.push(vertex(&mut words, path, line_no, false)?);
                vertices_since_name += 1;
            }
            "o" | "g" => {
                let n = words.collect::<Vec<_>>().join(" ");
                if n.is_empty() {
                    return Err(Error::input(
                        path,
                        Location::Line(line_no),
                        "object/group without a name",
                    ));
                }
                unfinished(&name, vertices_since_name, lines_since_name)?;
                name = Some((n, line_no));
                (vertices_since_name, lines_since_name) = (0, 0);
            }
            "l" => {
                let (id, name_line) = name.clone().ok_or_else(|| {
                    Error::input(
                        path,
                        Location::Line(line_no),
                        "polyline before any object or group name (the name is the curve id)",
                    )
                })?;
                lines_since_name += 1;
                let mut idx = Vec::new();
                for w in words {
                    let k = vertex_index(w, path, line_no)?;
                    let n = vertices.len() as i64;
                    let resolved = if k > 0 {
                        k - 1
                    } else if k < 0 {
                        n + k
                    } else {
                        -1
                    };
                    if resolved < 0 || resolved >= n {
                        return Err(Error::input(
                            path,
                            Location::Line(line_no),
                            format!("vertex index {k} out of range (1..={n})"),
                        ));
                    }
                    idx.push(resolved as usize);
                }
                if idx.len() < 2 {
                    return Err(Error::input(
                        path,
                        Location::Line(line_no),
                        format!(
                            "polyline with {} vertex index(es); a polyline needs at least 2",
                            idx.len()
                        ),
                    ));
                }
                // Continue the object's last piece when this one chains on.
                if let Some((pid, _, _, last)) = pieces.last_mut() {
                    if *pid == id && last.last() == idx.first() {
                        last.extend_from_slice(&idx[1..]);
                        continue;
                    }
                }
                // One curve per name: a second polyline of the same object, or
                // an object named like an earlier one, is refused.
                if let Some((_, first_name, first_l, _)) = pieces.iter().find(|p| p.0 == id) {
                    let what = if *first_name == name_line {
                        format!(
                            "object '{id}' (line {name_line}) has a second polyline that does not continue its first (line {first_l}); give each curve its own object"
                        )
                    } else {
                        format!(
                            "object '{id}' (line {name_line}) has the same name as the object at line {first_name}; curve ids must be unique"
                        )
                    };
                    return Err(Error::input(path, Location::Line(line_no), what));
                }
                pieces.push((id, name_line, line_no, idx));
            }
            _ => {}
        }
    }
    unfinished(&name, vertices_since_name, lines_since_name)?;
    if pieces.is_empty() {
        return Err(Error::input(
            path,
            Location::File,
            "no polylines (`l` elements) found",
        ));
    }
    let mut curves = Vec::with_capacity(pieces.len());
    for (id, line_no, _, idx) in pieces {
        let family = Family::from_prefix(&id).ok_or_else(|| {
            Error::input(
                path,
                Location::Line(line_no),
                format!("object '{id}': name must start with A, B or edge to give the family"),
            )
        })?;
        curves.push(RawCurve {
            points: idx.iter().map(|&i| vertices[i]).collect(),
            id,
            family,
            normals: None,
        });
    }
    Ok(RawNetwork {
        name: crate::formats::read::default_name(path),
        unit,
        tolerance: None,
        precision: None,
        curves,
    })
}
