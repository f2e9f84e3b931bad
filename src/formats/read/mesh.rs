//! Mesh files into a [`TriMesh`]: OBJ, PLY and STL, chosen by the extension
//! (any case). Coordinates are taken as mm; polygons are fan-triangulated
//! (v0, vi, vi+1), which keeps their orientation.
//!
//! * OBJ (read here, line by line): `v x y z [w]` (extra values such as
//!   vertex colours are ignored) and `f` with `a`, `a/t`, `a//n` or `a/t/n`
//!   corners, indices from 1 or negative (relative to the vertices read so
//!   far); lines ending in `\` continue on the next. Everything else (`vn`,
//!   `vt`, `g`, `o`, `s`, `usemtl`, `mtllib`, `l`, comments) is ignored.
//!   Errors name the line.
//! * PLY (ascii, binary little and big endian, through `ply-rs-bw`): the
//!   `vertex` element's `x`, `y`, `z` (any numeric type) and the `face`
//!   element's `vertex_indices` or `vertex_index` list (any integer type).
//!   Errors name the element (`vertex 4`, `face 12`) or the header line.
//! * STL (ascii and binary, through `stl_io`): triangles without shared
//!   vertices; corners with exactly equal coordinates (the file's f32 values
//!   widened to f64, −0 equal to +0) are welded into one vertex, numbered in
//!   the order they are first seen, so the mesh is connected and the result
//!   deterministic. Errors name the triangle.
//!
//! Non-finite coordinates are refused here, where the file position is
//! known; the mesh's topology is checked by [`crate::design::mesh::topology`].

use super::obj::{vertex, vertex_index};
use crate::error::{Error, Location, Result};
use crate::geom::mesh::TriMesh;
use glam::DVec3;
use std::collections::HashMap;
use std::path::Path;

/// The largest mesh file read, bytes (1 GiB).
pub const MAX_MESH_FILE_BYTES: u64 = 1 << 30;

/// Most triangles a mesh may have (after fan triangulation): tracing on a
/// mesh of a million triangles takes about half a minute and 3 GB. Counted
/// while an OBJ is read, from the header of a PLY or a binary STL before
/// its body is read.
pub const MAX_MESH_TRIANGLES: usize = 1_000_000;

/// The refusal of a mesh of `count` triangles (or vertices, `what`).
fn too_large(path: &Path, at: Location, count: usize, what: &str) -> Error {
    Error::input(
        path,
        at,
        format!(
            "{count} {what} is more than lamella traces on: a mesh may have at most {MAX_MESH_TRIANGLES} triangles (a million take about half a minute and 3 GB)"
        ),
    )
}

/// Read a mesh file (`.obj`, `.ply` or `.stl`, any case); coordinates in mm.
pub fn read_mesh(path: &Path) -> Result<TriMesh> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if !matches!(ext.as_str(), "obj" | "ply" | "stl") {
        return Err(Error::input(
            path,
            Location::File,
            format!("unknown mesh format '.{ext}' (use .obj, .ply or .stl)"),
        ));
    }
    let bytes = super::read_limited(path, MAX_MESH_FILE_BYTES, "a mesh file")?;
    let mesh = match ext.as_str() {
        "obj" => {
            let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes);
            let text = std::str::from_utf8(bytes).map_err(|e| {
                Error::input(
                    path,
                    Location::File,
                    format!("not UTF-8 text (byte {})", e.valid_up_to()),
                )
            })?;
            parse_obj(text, path)
        }
        "ply" => parse_ply(&bytes, path),
        _ => parse_stl(&bytes, path),
    }?;
    if mesh.triangles.len() > MAX_MESH_TRIANGLES {
        return Err(too_large(
            path,
            Location::File,
            mesh.triangles.len(),
            "triangles",
        ));
    }
    Ok(mesh)
}

/// Parse OBJ text (see the module documentation); `path` names the file in errors.
pub fn parse_obj(text: &str, path: &Path) -> Result<TriMesh> {
    if text.trim().is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    let at = |line: usize| Location::Line(line);
    let mut positions: Vec<DVec3> = Vec::new();
    // Faces as (line, resolved 0-based indices or the raw positive index):
    // positive indices are checked against the final vertex count, so a file
    // that lists its vertices after its faces is still read.
    let mut faces: Vec<(usize, Vec<i64>)> = Vec::new();
    let mut face_triangles = 0usize;
    let mut logical = String::new();
    let mut first_line = 0usize;
    let lines: Vec<&str> = text.lines().collect();
    for (i, raw) in lines.iter().enumerate() {
        let line_no = i + 1;
        let content = raw.split('#').next().unwrap_or("");
        if logical.is_empty() {
            first_line = line_no;
        }
        // A trailing backslash continues the element on the next line.
        if let Some(head) = content.trim_end().strip_suffix('\\') {
            if i + 1 < lines.len() {
                logical.push_str(head);
                logical.push(' ');
                continue;
            }
        }
        logical.push_str(content);
        let line = std::mem::take(&mut logical);
        let mut words = line.split_whitespace();
        let Some(tag) = words.next() else { continue };
        match tag {
            "v" => {
                positions.push(vertex(&mut words, path, first_line, true)?);
            }
            "f" => {
                let n = positions.len() as i64;
                let mut idx = Vec::new();
                for w in words {
                    let k = vertex_index(w, path, first_line)?;
                    let resolved = match k {
                        0 => {
                            return Err(Error::input(
                                path,
                                at(first_line),
                                "vertex index 0: OBJ indices count from 1 (or back from -1)",
                            ))
                        }
                        k if k < 0 => {
                            if n + k < 0 {
                                return Err(Error::input(
                                    path,
                                    at(first_line),
                                    format!(
                                        "relative vertex index {k} reaches before the first vertex ({n} read so far)"
                                    ),
                                ));
                            }
                            n + k
                        }
                        k => k - 1,
                    };
                    idx.push(resolved);
                }
                if idx.len() < 3 {
                    return Err(Error::input(
                        path,
                        at(first_line),
                        format!(
                            "face with {} vertex index(es); a face needs at least 3",
                            idx.len()
                        ),
                    ));
                }
                face_triangles += idx.len() - 2;
                if face_triangles > MAX_MESH_TRIANGLES {
                    return Err(too_large(
                        path,
                        at(first_line),
                        face_triangles,
                        "triangles in the faces up to here",
                    ));
                }
                faces.push((first_line, idx));
            }
            _ => {}
        }
    }
    if faces.is_empty() {
        return Err(Error::input(
            path,
            Location::File,
            "no faces (`f` elements) found: lamella reads surface meshes",
        ));
    }
    let n = positions.len();
    let mut triangles = Vec::new();
    for (line_no, idx) in faces {
        let mut face = Vec::with_capacity(idx.len());
        for k in idx {
            if k >= n as i64 || k > u32::MAX as i64 {
                return Err(Error::input(
                    path,
                    at(line_no),
                    format!("vertex index {} out of range (1..={n})", k + 1),
                ));
            }
            face.push(k as u32);
        }
        fan(&face, &mut triangles);
    }
    Ok(TriMesh {
        positions_mm: positions,
        triangles,
    })
}

/// Fan-triangulate a polygon (v0, vi, vi+1), appending to `out`.
fn fan(face: &[u32], out: &mut Vec<[u32; 3]>) {
    for i in 1..face.len() - 1 {
        out.push([face[0], face[i], face[i + 1]]);
    }
}

/// The `element NAME COUNT` lines of a PLY header (read as text up to
/// `end_header`, within its first 64 KiB), so that a count is checked before
/// the body is read; malformed lines are left to the PLY reader.
fn ply_header_counts(bytes: &[u8]) -> Vec<(String, usize)> {
    let head = &bytes[..bytes.len().min(64 << 10)];
    let text = String::from_utf8_lossy(head);
    text.lines()
        .take_while(|l| l.trim() != "end_header")
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            if w.next()? != "element" {
                return None;
            }
            let name = w.next()?.to_string();
            // A count beyond usize is beyond the limit too.
            let count = w.next()?.parse::<u128>().ok()?;
            Some((name, usize::try_from(count).unwrap_or(usize::MAX)))
        })
        .collect()
}

/// Parse PLY bytes (ascii or binary); `path` names the file in errors.
pub fn parse_ply(bytes: &[u8], path: &Path) -> Result<TriMesh> {
    use ply_rs_bw::parser::Parser;
    use ply_rs_bw::ply::{DefaultElement, Property};
    if bytes.is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    for (name, count) in ply_header_counts(bytes) {
        if (name == "vertex" || name == "face") && count > MAX_MESH_TRIANGLES {
            return Err(too_large(
                path,
                Location::File,
                count,
                &format!("`{name}` elements in the header"),
            ));
        }
    }
    let parser = Parser::<DefaultElement>::new();
    let mut source = bytes;
    let ply = parser.read_ply(&mut source).map_err(|e| {
        let at = e.line().map(Location::Line).unwrap_or(Location::File);
        // The crate's message repeats the line ("Line 5: …") and spans lines.
        let msg = e.to_string();
        let msg = match (e.line(), msg.split_once(": ")) {
            (Some(_), Some((head, rest))) if head.starts_with("Line ") => rest.to_string(),
            _ => msg,
        };
        Error::input(path, at, format!("not a readable PLY file: {msg}"))
    })?;
    let elem = |name: &str| -> Result<&Vec<DefaultElement>> {
        ply.payload.get(name).ok_or_else(|| {
            Error::input(
                path,
                Location::File,
                format!("no `{name}` element in the header"),
            )
        })
    };
    let vertices = elem("vertex")?;
    let faces = elem("face")?;
    let scalar = |p: &Property| -> Option<f64> {
        Some(match *p {
            Property::Char(v) => v as f64,
            Property::UChar(v) => v as f64,
            Property::Short(v) => v as f64,
            Property::UShort(v) => v as f64,
            Property::Int(v) => v as f64,
            Property::UInt(v) => v as f64,
            Property::Float(v) => v as f64,
            Property::Double(v) => v,
            _ => return None,
        })
    };
    let mut positions = Vec::with_capacity(vertices.len());
    for (i, v) in vertices.iter().enumerate() {
        let at = || Location::Element(format!("vertex {i}"));
        let mut xyz = [0.0; 3];
        for (slot, name) in xyz.iter_mut().zip(["x", "y", "z"]) {
            let p = v
                .get(name)
                .ok_or_else(|| Error::input(path, at(), format!("no `{name}` property")))?;
            let x = scalar(p).ok_or_else(|| {
                Error::input(path, at(), format!("`{name}` is a list, not a number"))
            })?;
            if !x.is_finite() {
                return Err(Error::input(path, at(), format!("`{name}` is not finite")));
            }
            *slot = x;
        }
        positions.push(DVec3::from_array(xyz));
    }
    let n = positions.len();
    let mut triangles = Vec::new();
    let mut face = Vec::new();
    for (i, f) in faces.iter().enumerate() {
        let at = || Location::Element(format!("face {i}"));
        let list = f
            .get("vertex_indices")
            .or_else(|| f.get("vertex_index"))
            .ok_or_else(|| {
                Error::input(
                    path,
                    at(),
                    "no `vertex_indices` (or `vertex_index`) property",
                )
            })?;
        let idx: Vec<i64> = match list {
            Property::ListChar(l) => l.iter().map(|&k| k as i64).collect(),
            Property::ListUChar(l) => l.iter().map(|&k| k as i64).collect(),
            Property::ListShort(l) => l.iter().map(|&k| k as i64).collect(),
            Property::ListUShort(l) => l.iter().map(|&k| k as i64).collect(),
            Property::ListInt(l) => l.iter().map(|&k| k as i64).collect(),
            Property::ListUInt(l) => l.iter().map(|&k| k as i64).collect(),
            _ => {
                return Err(Error::input(
                    path,
                    at(),
                    "the vertex index property is not a list of integers",
                ))
            }
        };
        if idx.len() < 3 {
            return Err(Error::input(
                path,
                at(),
                format!(
                    "face with {} vertex index(es); a face needs at least 3",
                    idx.len()
                ),
            ));
        }
        face.clear();
        for k in idx {
            if k < 0 || k >= n as i64 {
                return Err(Error::input(
                    path,
                    at(),
                    format!("vertex index {k} out of range (0..={})", n as i64 - 1),
                ));
            }
            face.push(k as u32);
        }
        fan(&face, &mut triangles);
    }
    if triangles.is_empty() {
        return Err(Error::input(path, Location::File, "no faces found"));
    }
    Ok(TriMesh {
        positions_mm: positions,
        triangles,
    })
}

/// A binary STL (80-byte header, a triangle count, 50 bytes a triangle)
/// must hold exactly the triangles its header counts: a reader that trusts
/// the count traces part of a longer file, or nothing of a shorter one. A
/// file that begins `solid` and names a `facet` (or ends the solid) in its
/// first kilobyte is ascii and is left to the ascii reader.
fn check_binary_stl_length(bytes: &[u8], path: &Path) -> Result<()> {
    let head = &bytes[..bytes.len().min(1024)];
    let text = String::from_utf8_lossy(head);
    if text.trim_start().starts_with("solid")
        && (text.contains("facet") || text.contains("endsolid"))
    {
        return Ok(());
    }
    if bytes.len() < 84 {
        return Err(Error::input(
            path,
            Location::File,
            format!(
                "a binary STL needs an 84-byte header, this file has {} bytes",
                bytes.len()
            ),
        ));
    }
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let body = bytes.len() - 84;
    if body != 50 * count {
        return Err(Error::input(
            path,
            Location::File,
            format!(
                "the binary STL header counts {count} triangles ({} bytes) but {body} bytes follow it ({} triangles{}): a truncated or damaged file",
                50 * count,
                body / 50,
                if body.is_multiple_of(50) {
                    String::new()
                } else {
                    format!(" and {} bytes", body % 50)
                }
            ),
        ));
    }
    if count > MAX_MESH_TRIANGLES {
        return Err(too_large(
            path,
            Location::File,
            count,
            "triangles in the binary STL header",
        ));
    }
    Ok(())
}

/// Parse STL bytes (ascii or binary), welding equal corners; `path` names
/// the file in errors.
pub fn parse_stl(bytes: &[u8], path: &Path) -> Result<TriMesh> {
    if bytes.is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    check_binary_stl_length(bytes, path)?;
    let mut cursor = std::io::Cursor::new(bytes);
    let reader = stl_io::create_stl_reader(&mut cursor).map_err(|e| {
        Error::input(
            path,
            Location::File,
            format!("not a readable STL file: {e}"),
        )
    })?;
    let mut positions: Vec<DVec3> = Vec::new();
    let mut index_of: HashMap<[u64; 3], u32> = HashMap::new();
    let mut triangles = Vec::new();
    for (i, t) in reader.enumerate() {
        let at = || Location::Element(format!("triangle {i}"));
        let t = t.map_err(|e| Error::input(path, at(), format!("cannot be read: {e}")))?;
        let mut tri = [0u32; 3];
        for (slot, v) in tri.iter_mut().zip(t.vertices.iter()) {
            // Widen, and make −0 equal to +0 (adding +0.0 does exactly that).
            let p = [v[0] as f64 + 0.0, v[1] as f64 + 0.0, v[2] as f64 + 0.0];
            if p.iter().any(|x| !x.is_finite()) {
                return Err(Error::input(
                    path,
                    at(),
                    "a corner's coordinate is not finite",
                ));
            }
            let key = p.map(f64::to_bits);
            let next = positions.len() as u32;
            *slot = *index_of.entry(key).or_insert_with(|| {
                positions.push(DVec3::from_array(p));
                next
            });
        }
        triangles.push(tri);
        if triangles.len() > MAX_MESH_TRIANGLES {
            return Err(too_large(path, at(), triangles.len(), "triangles"));
        }
    }
    if triangles.is_empty() {
        return Err(Error::input(path, Location::File, "no triangles found"));
    }
    Ok(TriMesh {
        positions_mm: positions,
        triangles,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("lamella-mesh-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let p = dir.join(name);
        std::fs::write(&p, bytes).expect("write");
        p
    }

    fn err(r: Result<TriMesh>) -> String {
        match r {
            Ok(m) => panic!("expected an error, got {m:?}"),
            Err(e) => e.to_string(),
        }
    }

    /// The unit square in z = 0 as two counter-clockwise triangles.
    fn square() -> TriMesh {
        TriMesh {
            positions_mm: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn obj_two_triangles_with_texture_and_normal_indices() {
        let text = "# square\nmtllib x.mtl\no sq\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\n\
                    vn 0 0 1\nvt 0 0\ns off\nusemtl m\nf 1/1/1 2/1/1 3//1\nf 1/1 3 4\nl 1 2\n";
        let m = parse_obj(text, Path::new("sq.obj")).expect("reads");
        assert_eq!(m, square());
    }

    #[test]
    fn obj_quad_is_fan_triangulated_and_negative_indices_resolve() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n";
        let m = parse_obj(text, Path::new("q.obj")).expect("reads");
        assert_eq!(m, square());
        // A pentagon: 3 triangles sharing corner 0; relative indices count
        // from the vertices read so far, not from the end of the file.
        let text = "v 0 0 0\nv 1 0 0\nv 2 1 0\nf 1 2 3\nv 1 2 0\nv 0 1 0\nf -5 -4 -3 -2 -1\n";
        let m = parse_obj(text, Path::new("p.obj")).expect("reads");
        assert_eq!(
            m.triangles,
            vec![[0, 1, 2], [0, 1, 2], [0, 2, 3], [0, 3, 4]]
        );
    }

    #[test]
    fn obj_continuation_lines_and_crlf() {
        let text = "v 0 0 0\r\nv 1 0 \\\r\n 0\r\nv 1 1 0\r\nv 0 1 0\r\nf 1 2 \\\n3\nf 1 3 4\r\n";
        let m = parse_obj(text, Path::new("c.obj")).expect("reads");
        assert_eq!(m, square());
    }

    #[test]
    fn obj_errors_name_the_line() {
        let p = Path::new("bad.obj");
        let e = err(parse_obj("v 0 0 0\nv 1 0 0\nv 1 x 0\nf 1 2 3\n", p));
        assert_eq!(
            e,
            "bad.obj: line 3: vertex coordinate 2 'x' is not a number"
        );
        let e = err(parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\n\nf 1 2 4\n", p));
        assert_eq!(e, "bad.obj: line 5: vertex index 4 out of range (1..=3)");
        let e = err(parse_obj("v 0 0 0\nv 1 0 0\nf 1 -3 2\n", p));
        assert!(
            e.starts_with("bad.obj: line 3: relative vertex index -3"),
            "{e}"
        );
        let e = err(parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2\n", p));
        assert_eq!(
            e,
            "bad.obj: line 4: face with 2 vertex index(es); a face needs at least 3"
        );
        let e = err(parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 0 2\n", p));
        assert!(e.starts_with("bad.obj: line 4: vertex index 0"), "{e}");
        let e = err(parse_obj("v 0 0 nan\n", p));
        assert_eq!(
            e,
            "bad.obj: line 1: vertex coordinate 3 'nan' is not finite"
        );
        let e = err(parse_obj("v 0 0 0\nv 1 0 0\nl 1 2\n", p));
        assert_eq!(
            e,
            "bad.obj: no faces (`f` elements) found: lamella reads surface meshes"
        );
        let e = err(parse_obj("  \n", p));
        assert_eq!(e, "bad.obj: the file is empty");
    }

    /// A PLY header for `nv` vertices of `vt` coordinates and `nf` faces
    /// with `lt` counts and `it` indices.
    fn ply_header(format: &str, nv: usize, vt: &str, nf: usize, lt: &str, it: &str) -> String {
        format!(
            "ply\nformat {format} 1.0\ncomment made by hand\nelement vertex {nv}\n\
             property {vt} x\nproperty {vt} y\nproperty {vt} z\nproperty uchar red\n\
             element face {nf}\nproperty list {lt} {it} vertex_indices\nend_header\n"
        )
    }

    #[test]
    fn ply_ascii_quad_and_triangle() {
        let text = ply_header("ascii", 4, "float", 1, "uchar", "int")
            + "0 0 0 255\n1 0 0 0\n1 1 0 0\n0 1 0 0\n4 0 1 2 3\n";
        let m = parse_ply(text.as_bytes(), Path::new("q.ply")).expect("reads");
        assert_eq!(m, square());
        // `vertex_index` and unsigned short indices, double coordinates.
        let text = text
            .replace("vertex_indices", "vertex_index")
            .replace("uchar int", "uchar ushort")
            .replace("property float", "property double");
        let m = parse_ply(text.as_bytes(), Path::new("q.ply")).expect("reads");
        assert_eq!(m, square());
    }

    /// The square as binary PLY (little or big endian), float or double.
    fn ply_binary(big: bool, double: bool) -> Vec<u8> {
        let format = if big {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let vt = if double { "double" } else { "float" };
        let mut b = ply_header(format, 4, vt, 2, "uchar", "uint").into_bytes();
        for p in square().positions_mm {
            for x in p.to_array() {
                if double {
                    b.extend(if big {
                        x.to_be_bytes()
                    } else {
                        x.to_le_bytes()
                    });
                } else {
                    let x = x as f32;
                    b.extend(if big {
                        x.to_be_bytes()
                    } else {
                        x.to_le_bytes()
                    });
                }
            }
            b.push(7); // red
        }
        for t in square().triangles {
            b.push(3);
            for k in t {
                b.extend(if big {
                    k.to_be_bytes()
                } else {
                    k.to_le_bytes()
                });
            }
        }
        b
    }

    #[test]
    fn ply_binary_both_endians() {
        for big in [false, true] {
            for double in [false, true] {
                let m = parse_ply(&ply_binary(big, double), Path::new("b.ply")).expect("reads");
                assert_eq!(m, square(), "big {big} double {double}");
            }
        }
    }

    #[test]
    fn ply_errors_name_the_element() {
        let p = Path::new("bad.ply");
        let text = ply_header("ascii", 3, "float", 2, "uchar", "int")
            + "0 0 0 1\n1 0 0 1\n1 1 0 1\n3 0 1 2\n3 0 2 3\n";
        let e = err(parse_ply(text.as_bytes(), p));
        assert_eq!(e, "bad.ply: face 1: vertex index 3 out of range (0..=2)");
        let text = ply_header("ascii", 3, "float", 1, "uchar", "int")
            + "0 0 0 1\n1 0 0 1\n1 1 0 1\n2 0 1\n";
        let e = err(parse_ply(text.as_bytes(), p));
        assert_eq!(
            e,
            "bad.ply: face 0: face with 2 vertex index(es); a face needs at least 3"
        );
        let text = ply_header("ascii", 3, "float", 1, "uchar", "int")
            + "0 0 0 1\n1 0 0 1\n1 1 0 1\n3 0 -1 2\n";
        let e = err(parse_ply(text.as_bytes(), p));
        assert_eq!(e, "bad.ply: face 0: vertex index -1 out of range (0..=2)");
        let text =
            ply_header("ascii", 3, "float", 1, "uchar", "int") + "0 0 0 1\n1 0 0 1\n1 1 0 1\n";
        let e = err(parse_ply(text.as_bytes(), p));
        assert!(
            e.starts_with("bad.ply: line 15: not a readable PLY file"),
            "{e}"
        );
        assert!(!e.contains('\n'), "{e}");
        let text = ply_header("ascii", 0, "float", 0, "uchar", "int");
        let e = err(parse_ply(text.as_bytes(), p));
        assert_eq!(e, "bad.ply: no faces found");
        let e = err(parse_ply(b"solid x\n", p));
        assert!(
            e.starts_with("bad.ply: line 1: not a readable PLY file"),
            "{e}"
        );
    }

    fn stl_ascii(mesh: &TriMesh) -> String {
        let mut s = String::from("solid sq\n");
        for t in &mesh.triangles {
            s += "facet normal 0 0 1\nouter loop\n";
            for &k in t {
                let p = mesh.positions_mm[k as usize];
                s += &format!("vertex {} {} {}\n", p.x, p.y, p.z);
            }
            s += "endloop\nendfacet\n";
        }
        s + "endsolid sq\n"
    }

    fn stl_binary(mesh: &TriMesh) -> Vec<u8> {
        let mut b = vec![0u8; 80];
        b.extend((mesh.triangles.len() as u32).to_le_bytes());
        for t in &mesh.triangles {
            for x in [0.0f32, 0.0, 1.0] {
                b.extend(x.to_le_bytes());
            }
            for &k in t {
                for x in mesh.positions_mm[k as usize].to_array() {
                    b.extend((x as f32).to_le_bytes());
                }
            }
            b.extend([0u8, 0]);
        }
        b
    }

    #[test]
    fn stl_ascii_and_binary_are_welded() {
        let mut sq = square();
        // −0 and +0 are one vertex.
        let text = stl_ascii(&sq).replacen("vertex 0 0 0", "vertex -0 0 -0", 1);
        let m = parse_stl(text.as_bytes(), Path::new("s.stl")).expect("reads");
        assert_eq!(m, square());
        let m = parse_stl(&stl_binary(&sq), Path::new("s.stl")).expect("reads");
        assert_eq!(m, square());
        // Welding is by first appearance.
        sq.triangles = vec![[2, 3, 0], [0, 1, 2]];
        let m = parse_stl(&stl_binary(&sq), Path::new("s.stl")).expect("reads");
        assert_eq!(m.triangles, vec![[0, 1, 2], [2, 3, 0]]);
        assert_eq!(m.positions_mm[0], DVec3::new(1.0, 1.0, 0.0));
    }

    /// A binary STL whose header counts fewer or more triangles than it
    /// holds is refused, naming both counts (it was read from the first
    /// `count` triangles, or found no anticlastic region in one).
    #[test]
    fn binary_stl_counts_must_match_the_file() {
        let p = Path::new("count.stl");
        let mut b = stl_binary(&square());
        assert_eq!(b.len(), 84 + 50 * 2);
        b[80..84].copy_from_slice(&1u32.to_le_bytes());
        assert_eq!(
            err(parse_stl(&b, p)),
            "count.stl: the binary STL header counts 1 triangles (50 bytes) but 100 bytes follow it (2 triangles): a truncated or damaged file"
        );
        b[80..84].copy_from_slice(&3u32.to_le_bytes());
        assert!(err(parse_stl(&b, p)).contains("counts 3 triangles"));
        b[80..84].copy_from_slice(&2u32.to_le_bytes());
        b.extend([0u8; 7]);
        assert!(err(parse_stl(&b, p)).contains("(2 triangles and 7 bytes)"));
        b.truncate(84 + 100);
        assert_eq!(parse_stl(&b, p).expect("reads"), square());
        assert!(err(parse_stl(&b[..40], p)).contains("84-byte header"));
    }

    #[test]
    fn stl_errors() {
        let p = Path::new("bad.stl");
        let e = err(parse_stl(b"solid x\nendsolid x\n", p));
        assert_eq!(e, "bad.stl: no triangles found");
        let mut b = stl_binary(&square());
        b.truncate(b.len() - 20);
        let e = err(parse_stl(&b, p));
        assert!(e.starts_with("bad.stl: "), "{e}");
        let mut sq = square();
        sq.positions_mm[1].x = f64::NAN;
        let e = err(parse_stl(&stl_binary(&sq), p));
        assert_eq!(
            e,
            "bad.stl: triangle 0: a corner's coordinate is not finite"
        );
    }

    /// One mesh written as OBJ, PLY and STL reads back as the same TriMesh
    /// (coordinates exact in f32, so equal after widening).
    #[test]
    fn the_three_formats_agree() {
        let mut mesh = TriMesh::default();
        for j in 0..4 {
            for i in 0..5 {
                let (x, y) = (i as f64 * 12.5, j as f64 * 10.25);
                mesh.positions_mm
                    .push(DVec3::new(x, y, 0.001 * (x * y).round()));
            }
        }
        for j in 0..3u32 {
            for i in 0..4u32 {
                let a = j * 5 + i;
                mesh.triangles.push([a, a + 1, a + 6]);
                mesh.triangles.push([a, a + 6, a + 5]);
            }
        }
        let mut obj = String::new();
        for p in &mesh.positions_mm {
            obj += &format!("v {} {} {}\n", p.x, p.y, p.z);
        }
        for t in &mesh.triangles {
            obj += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
        }
        let mut ply = ply_header(
            "ascii",
            mesh.positions_mm.len(),
            "float",
            mesh.triangles.len(),
            "uchar",
            "int",
        );
        for p in &mesh.positions_mm {
            ply += &format!("{} {} {} 0\n", p.x as f32, p.y as f32, p.z as f32);
        }
        for t in &mesh.triangles {
            ply += &format!("3 {} {} {}\n", t[0], t[1], t[2]);
        }
        let from_obj = read_mesh(&tmp("m.OBJ", obj.as_bytes())).expect("obj");
        let from_ply = read_mesh(&tmp("m.Ply", ply.as_bytes())).expect("ply");
        let from_stl = read_mesh(&tmp("m.stl", &stl_binary(&mesh))).expect("stl");
        let from_ascii_stl = read_mesh(&tmp("m2.STL", stl_ascii(&mesh).as_bytes())).expect("stl");
        let f32_mesh = TriMesh {
            positions_mm: mesh
                .positions_mm
                .iter()
                .map(|p| p.as_vec3().as_dvec3())
                .collect(),
            triangles: mesh.triangles.clone(),
        };
        assert_eq!(from_obj, mesh);
        assert_eq!(from_ply, f32_mesh);
        // STL numbers the welded vertices by first appearance: the same mesh
        // up to that numbering (same corners, same vertex count).
        let corners = |m: &TriMesh| -> Vec<[DVec3; 3]> {
            m.triangles
                .iter()
                .map(|t| t.map(|k| m.positions_mm[k as usize]))
                .collect()
        };
        for stl in [&from_stl, &from_ascii_stl] {
            assert_eq!(stl.positions_mm.len(), mesh.positions_mm.len());
            assert_eq!(corners(stl), corners(&f32_mesh));
        }
        // f32 is within 1e-7 relative of the f64 input.
        for (a, b) in f32_mesh.positions_mm.iter().zip(&mesh.positions_mm) {
            assert!((*a - *b).length() <= 1e-7 * b.length().max(1.0));
        }
        let e = read_mesh(&tmp("m.off", b"OFF\n")).map(|_| ()).unwrap_err();
        assert!(e
            .to_string()
            .ends_with("unknown mesh format '.off' (use .obj, .ply or .stl)"));
    }
}
