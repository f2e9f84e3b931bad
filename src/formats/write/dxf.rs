//! A sheet drawing as DXF for laser and waterjet software: R2000 (the
//! oldest version ezdxf and AutoCAD LT both read from the dxf crate),
//! millimetres (`$INSUNITS` = 4, `$MEASUREMENT` = 1), one layer per
//! operation with its colour (the `SHEET` layer not plotted), closed
//! LWPOLYLINEs per contour with arcs as bulges, round holes as CIRCLEs,
//! engraving as open LWPOLYLINEs, no blocks or splines.
//!
//! The document's structure (header, classes, tables with the layers,
//! blocks, objects) comes from the dxf crate, made once per process with
//! fixed dates and GUIDs so the same sheet gives the same bytes. The
//! entities are streamed into its ENTITIES section here, in the same group
//! codes the crate writes, with handles after the structure's and
//! `$HANDSEED` past the last: the crate builds every group code in memory
//! and prints each number through exact 12-decimal formatting, which made
//! it four times slower than the rest of a big build together.
//! Coordinates have 6 decimals (1 nm), bulges 10.

use super::drawing::{strokes, Layer, Shape, SheetDrawing, Vertex};
use dxf::enums::{AcadVersion, DrawingUnits, Units};
use dxf::tables::Layer as DxfLayer;
use dxf::{Color, Drawing};
use std::sync::OnceLock;

/// Decimals of coordinates and radii.
const COORD_DECIMALS: u32 = 6;

/// Decimals of bulges.
const BULGE_DECIMALS: u32 = 9;

/// The document around the entities, split where they go.
struct Skeleton {
    /// Up to the `$HANDSEED` value.
    before_seed: String,
    /// From after the `$HANDSEED` value to the ENTITIES section's first entity.
    before_entities: String,
    /// From the ENTITIES section's end to the end of the file.
    after_entities: String,
    /// The first handle free for entities.
    first_handle: u64,
}

fn skeleton() -> Result<&'static Skeleton, String> {
    static SKELETON: OnceLock<Result<Skeleton, String>> = OnceLock::new();
    SKELETON
        .get_or_init(make_skeleton)
        .as_ref()
        .map_err(Clone::clone)
}

fn make_skeleton() -> Result<Skeleton, String> {
    let mut d = Drawing::new();
    let h = &mut d.header;
    h.version = AcadVersion::R2000;
    h.default_drawing_units = Units::Millimeters;
    h.drawing_units = DrawingUnits::Metric;
    // Fixed, so equal sheets give equal bytes (the defaults are "now" and
    // random GUIDs). DXF counts local dates from 1900-01-01 local time, so
    // that date is the one that reads the same in every time zone.
    let epoch = chrono::NaiveDate::from_ymd_opt(1900, 1, 1)
        .and_then(|d| d.and_hms_opt(0, 0, 0))
        .ok_or("bad fixed date")?;
    let local = epoch
        .and_local_timezone(chrono::Local)
        .earliest()
        .ok_or("no local time for the fixed date")?;
    let utc = epoch.and_utc();
    h.creation_date = local;
    h.update_date = local;
    h.creation_date_universal = utc;
    h.update_date_universal = utc;
    h.fingerprint_guid = uuid::Uuid::nil();
    h.version_guid = uuid::Uuid::nil();
    for layer in Layer::ALL {
        d.add_layer(DxfLayer {
            name: layer.name().to_string(),
            color: Color::from_index(layer.aci()),
            is_layer_plotted: layer != Layer::Sheet,
            ..Default::default()
        });
    }
    let mut bytes = Vec::new();
    d.save(&mut bytes).map_err(|e| e.to_string())?;
    let text = String::from_utf8(bytes).map_err(|e| e.to_string())?;
    // The crate ends lines with CRLF; the file gets LF throughout (a
    // tenth smaller, read alike by every DXF reader).
    let text = text.replace("\r\n", "\n");
    let seed_key = "$HANDSEED\n  5\n";
    let seed_at = text.find(seed_key).ok_or("no $HANDSEED")? + seed_key.len();
    let seed_end = seed_at + text[seed_at..].find('\n').ok_or("no $HANDSEED value")?;
    let first_handle =
        u64::from_str_radix(text[seed_at..seed_end].trim(), 16).map_err(|e| e.to_string())?;
    let marker = "\nENTITIES\n";
    let ent_at = text.find(marker).ok_or("no ENTITIES section")? + marker.len();
    if !text[ent_at..].starts_with("  0\nENDSEC\n") {
        return Err("the ENTITIES section is not empty".into());
    }
    Ok(Skeleton {
        before_seed: text[..seed_at].to_string(),
        before_entities: text[seed_end..ent_at].to_string(),
        after_entities: text[ent_at..].to_string(),
        first_handle,
    })
}

/// The DXF text of one sheet.
pub fn to_dxf(sheet: &SheetDrawing) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    write_dxf(sheet, &mut out)?;
    Ok(out)
}

/// The DXF text of one sheet into `out` (cleared first; a buffer used
/// again for the next sheet keeps its memory).
pub fn write_dxf(sheet: &SheetDrawing, out: &mut Vec<u8>) -> Result<(), String> {
    let sk = skeleton()?;
    let outline = sheet.outline();
    let shapes = || std::iter::once(&outline).chain(sheet.parts.iter().flat_map(|p| &p.shapes));
    // The handles the entities take, and about the bytes they need.
    let (count, bytes) = shapes().fold((0u64, 0usize), |(n, b), sh| match sh {
        Shape::Polyline { vertices, .. } => (n + 1, b + 100 + 32 * vertices.len()),
        Shape::Circle { .. } => (n + 1, b + 130),
        Shape::Strokes {
            points_um, ends, ..
        } => (
            n + ends.len() as u64,
            b + 100 * ends.len() + 32 * points_um.len(),
        ),
    });
    out.clear();
    out.reserve(
        sk.before_seed.len() + sk.before_entities.len() + bytes + sk.after_entities.len() + 16,
    );
    out.extend_from_slice(sk.before_seed.as_bytes());
    push_hex(out, sk.first_handle + count);
    out.extend_from_slice(sk.before_entities.as_bytes());
    let mut handle = sk.first_handle;
    for shape in shapes() {
        entity(out, shape, &mut handle);
    }
    out.extend_from_slice(sk.after_entities.as_bytes());
    Ok(())
}

/// One entity with its handle (a [`Shape::Strokes`]: one per stroke), in
/// the group codes the dxf crate writes (integers without its padding).
fn entity(s: &mut Vec<u8>, shape: &Shape, handle: &mut u64) {
    match shape {
        Shape::Polyline {
            layer,
            closed,
            vertices,
        } => polyline(s, *layer, *closed, vertices, handle),
        Shape::Strokes {
            layer,
            points_um,
            ends,
        } => {
            for stroke in strokes(points_um, ends) {
                header(s, *layer, false, stroke.len(), handle);
                for &[x, y] in stroke {
                    // Whole µm: the digits `push_decimal` gives their mm.
                    s.extend_from_slice(b" 10\n");
                    crate::formats::text::push_scaled(s, x < 0, x.unsigned_abs(), 3, true);
                    s.extend_from_slice(b"\n 20\n");
                    crate::formats::text::push_scaled(s, y < 0, y.unsigned_abs(), 3, true);
                    s.push(b'\n');
                }
            }
        }
        Shape::Circle {
            layer,
            center_mm,
            radius_mm,
        } => {
            s.extend_from_slice(b"  0\nCIRCLE\n  5\n");
            push_hex(s, *handle);
            s.extend_from_slice(b"\n100\nAcDbEntity\n  8\n");
            s.extend_from_slice(layer.name().as_bytes());
            s.extend_from_slice(b"\n100\nAcDbCircle\n 10\n");
            crate::formats::text::push_decimal(s, center_mm[0], COORD_DECIMALS, true);
            s.extend_from_slice(b"\n 20\n");
            crate::formats::text::push_decimal(s, center_mm[1], COORD_DECIMALS, true);
            s.extend_from_slice(b"\n 30\n0.0\n 40\n");
            crate::formats::text::push_decimal(s, *radius_mm, COORD_DECIMALS, true);
            s.push(b'\n');
            *handle += 1;
        }
    }
}

/// `n` in upper-case hexadecimal, as DXF handles are written.
fn push_hex(s: &mut Vec<u8>, n: u64) {
    const DIGITS: &[u8; 16] = b"0123456789ABCDEF";
    let mut buf = [0u8; 16];
    let mut i = buf.len();
    let mut n = n;
    loop {
        i -= 1;
        buf[i] = DIGITS[(n & 0xF) as usize];
        n >>= 4;
        if n == 0 {
            break;
        }
    }
    s.extend_from_slice(&buf[i..]);
}

/// One LWPOLYLINE with its handle.
fn polyline(s: &mut Vec<u8>, layer: Layer, closed: bool, vertices: &[Vertex], handle: &mut u64) {
    header(s, layer, closed, vertices.len(), handle);
    for v in vertices {
        s.extend_from_slice(b" 10\n");
        crate::formats::text::push_decimal(s, v.x_mm, COORD_DECIMALS, true);
        s.extend_from_slice(b"\n 20\n");
        crate::formats::text::push_decimal(s, v.y_mm, COORD_DECIMALS, true);
        s.push(b'\n');
        if v.bulge != 0.0 {
            s.extend_from_slice(b" 42\n");
            crate::formats::text::push_decimal(s, v.bulge, BULGE_DECIMALS, true);
            s.push(b'\n');
        }
    }
}

/// An LWPOLYLINE's group codes up to its vertices, taking the next handle.
fn header(s: &mut Vec<u8>, layer: Layer, closed: bool, vertices: usize, handle: &mut u64) {
    // Pieces pushed one by one: `write!`'s formatting machinery was a
    // tenth of writing the engraving's many short polylines.
    s.extend_from_slice(b"  0\nLWPOLYLINE\n  5\n");
    push_hex(s, *handle);
    s.extend_from_slice(b"\n100\nAcDbEntity\n  8\n");
    s.extend_from_slice(layer.name().as_bytes());
    s.extend_from_slice(b"\n100\nAcDbPolyline\n 90\n");
    crate::formats::text::push_scaled(s, false, vertices as u64, 0, false);
    s.extend_from_slice(if closed { b"\n 70\n1\n" } else { b"\n 70\n0\n" });
    *handle += 1;
}

#[cfg(test)]
mod hex_tests {
    use super::push_hex;

    #[test]
    fn handles_are_written_as_the_standard_upper_hex() {
        for n in [
            0u64,
            1,
            9,
            10,
            15,
            16,
            255,
            256,
            0x1A2B,
            0xFFFF_FFFF,
            u64::MAX,
        ] {
            let mut s = b"x".to_vec();
            push_hex(&mut s, n);
            assert_eq!(s, format!("x{n:X}").as_bytes(), "{n}");
        }
    }
}
