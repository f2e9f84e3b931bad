//! OBJ polylines: `v` vertices and `l` elements; the current object (`o`) or
//! group (`g`) name is the curve id and its prefix (A, B, edge) the family.

use crate::error::{Error, Location, Result};
use crate::network::{Family, RawCurve, RawNetwork, Unit};
use glam::DVec3;
use std::path::Path;

/// Parse OBJ text. OBJ carries no unit: the caller says which (`unit`).
pub fn parse(text: &str, unit: Unit, path: &Path) -> Result<RawNetwork> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.trim().is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut name: Option<(String, usize)> = None;
    // (id, line of its name, vertex indices)
    let mut pieces: Vec<(String, usize, Vec<usize>)> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line_no = i + 1;
        let line = line.split('#').next().unwrap_or("").trim();
        let mut words = line.split_whitespace();
        let Some(tag) = words.next() else { continue };
        match tag {
            "v" => {
                let mut xyz = [0.0f64; 3];
                for (k, slot) in xyz.iter_mut().enumerate() {
                    let w = words.next().ok_or_else(|| {
                        Error::input(path, Location::Line(line_no), "vertex needs x, y and z")
                    })?;
                    *slot = w.parse::<f64>().map_err(|_| {
                        Error::input(
                            path,
                            Location::Line(line_no),
                            format!("vertex coordinate {} '{w}' is not a number", k + 1),
                        )
                    })?;
                }
                vertices.push(DVec3::from_array(xyz));
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
                name = Some((n, line_no));
            }
            "l" => {
                let (id, _) = name.clone().ok_or_else(|| {
                    Error::input(
                        path,
                        Location::Line(line_no),
                        "polyline before any object or group name (the name is the curve id)",
                    )
                })?;
                let mut idx = Vec::new();
                for w in words {
                    let v = w.split('/').next().unwrap_or(w);
                    let k: i64 = v.parse().map_err(|_| {
                        Error::input(
                            path,
                            Location::Line(line_no),
                            format!("vertex index '{w}' is not an integer"),
                        )
                    })?;
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
                match pieces.last_mut() {
                    Some((pid, _, last)) if *pid == id && last.last() == idx.first() => {
                        last.extend_from_slice(&idx[1..]);
                    }
                    _ => pieces.push((id, line_no, idx)),
                }
            }
            _ => {}
        }
    }
    if pieces.is_empty() {
        return Err(Error::input(
            path,
            Location::File,
            "no polylines (`l` elements) found",
        ));
    }
    // An object with several disjoint pieces gets ids `name.1`, `name.2`, ...
    let mut curves = Vec::with_capacity(pieces.len());
    for (k, (id, line_no, idx)) in pieces.iter().enumerate() {
        let count = pieces.iter().filter(|p| p.0 == *id).count();
        let curve_id = if count > 1 {
            let nth = pieces[..=k].iter().filter(|p| p.0 == *id).count();
            format!("{id}.{nth}")
        } else {
            id.clone()
        };
        let family = Family::from_prefix(id).ok_or_else(|| {
            Error::input(
                path,
                Location::Line(*line_no),
                format!("object '{id}': name must start with A, B or edge to give the family"),
            )
        })?;
        curves.push(RawCurve {
            id: curve_id,
            family,
            points: idx.iter().map(|&i| vertices[i]).collect(),
            normals: None,
        });
    }
    Ok(RawNetwork {
        name: crate::io::default_name(path),
        unit,
        tolerance: None,
        curves,
    })
}
