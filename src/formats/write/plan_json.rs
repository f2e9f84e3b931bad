//! A JSON layout for big plans: an object that holds other objects is
//! indented one key per line as `to_string_pretty` does; an object that
//! holds none (a node, a feature, a placement) is written on one line
//! (`{"node": 0, "crossing": "B00", "station_mm": 0.0}`), and arrays of
//! numbers, strings and arrays stay on one line (`"outline": [[0.0, 0.0],
//! [3000.0, 0.0], …]`). A kit's records are most of plan.json: one key per
//! line made it half indentation, one number per line three times larger,
//! and neither easier to read.
//!
//! An array learns that it holds objects only when the first one begins,
//! so the separator before each element is held back until then; an object
//! learns that it holds another only when that one begins, so it is kept
//! on one line in a buffer until then, and laid out key per line if so.

use crate::plan::Plan;
use serde_json::ser::{CharEscape, CompactFormatter, Formatter};
use std::io::{self, Write};

/// One open array or object.
#[derive(Debug, Clone, Copy)]
enum Frame {
    /// An array: whether it holds objects (laid out one per line), and the
    /// separator owed before the next element (`Some(first)`).
    Array { objects: bool, owed: Option<bool> },
    /// An object: whether it has keys.
    Object { keys: bool },
}

/// The innermost open object while it holds no object: its text so far,
/// on one line, without its braces.
#[derive(Debug, Default)]
struct Line {
    /// Where it sits in the stack (the stack's length once it is pushed).
    depth: usize,
    /// `"key": value, "key": value…`
    text: Vec<u8>,
    /// Where each key starts in `text`.
    keys: Vec<usize>,
}

/// The formatter (see the module doc).
#[derive(Debug, Default)]
pub struct PlanFormatter {
    stack: Vec<Frame>,
    line: Option<Line>,
    /// The buffers of the last leaf object written, for the next one (a
    /// big plan has millions).
    spare: Line,
    /// A number's text on its way to the writer.
    number: Vec<u8>,
}

/// What is about to be written into an array.
#[derive(PartialEq)]
enum Next {
    Object,
    Other,
}

/// Where output goes: the one-line buffer of the open leaf object, if any,
/// else the writer.
enum Out<'a, W: ?Sized> {
    Line(&'a mut Vec<u8>),
    Writer(&'a mut W),
}

impl<W: ?Sized + Write> Write for Out<'_, W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Out::Line(l) => l.write(buf),
            Out::Writer(w) => w.write(buf),
        }
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        match self {
            Out::Line(l) => l.write_all(buf),
            Out::Writer(w) => w.write_all(buf),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match self {
            Out::Line(_) => Ok(()),
            Out::Writer(w) => w.flush(),
        }
    }
}

macro_rules! out {
    ($self:ident, $w:ident) => {
        &mut match $self.line.as_mut() {
            Some(l) => Out::Line(&mut l.text),
            None => Out::Writer($w),
        }
    };
}

fn indent<W: ?Sized + Write>(w: &mut W, depth: usize) -> io::Result<()> {
    for _ in 0..depth {
        w.write_all(b"  ")?;
    }
    Ok(())
}

impl PlanFormatter {
    /// Pay the separator an array owes before its next element.
    fn pay<W: ?Sized + Write>(&mut self, w: &mut W, next: Next) -> io::Result<()> {
        let depth = self.stack.len();
        if let Some(Frame::Array { objects, owed }) = self.stack.last_mut() {
            if let Some(first) = owed.take() {
                if next == Next::Object {
                    *objects = true;
                }
                let objects = *objects;
                let out = out!(self, w);
                if objects {
                    out.write_all(if first { b"\n" } else { b",\n" })?;
                    return indent(out, depth);
                }
                if !first {
                    out.write_all(b", ")?;
                }
            }
        }
        Ok(())
    }

    /// The leaf object being buffered holds an object after all: write it
    /// key per line so far (its last key's value is still open).
    fn unfold<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        let Some(line) = self.line.take() else {
            return Ok(());
        };
        w.write_all(b"{")?;
        for (k, &start) in line.keys.iter().enumerate() {
            // Keys after the first follow a `, ` in the one-line text.
            let end = line.keys.get(k + 1).map_or(line.text.len(), |&e| e - 2);
            w.write_all(if k == 0 { b"\n" } else { b",\n" })?;
            indent(w, line.depth)?;
            w.write_all(&line.text[start..end])?;
        }
        self.spare = line;
        Ok(())
    }
}

macro_rules! scalar {
    ($($name:ident: $t:ty),*) => {$(
        fn $name<W: ?Sized + Write>(&mut self, w: &mut W, v: $t) -> io::Result<()> {
            self.pay(w, Next::Other)?;
            CompactFormatter.$name(out!(self, w), v)
        }
    )*};
}

impl Formatter for PlanFormatter {
    fn write_null<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.pay(w, Next::Other)?;
        out!(self, w).write_all(b"null")
    }

    scalar!(write_bool: bool, write_i8: i8, write_i16: i16, write_i32: i32, write_i64: i64,
        write_u8: u8, write_u16: u16, write_u32: u32, write_u64: u64, write_f32: f32,
        write_number_str: &str);

    /// A number on the micrometre grid (all of plan.json's lengths are
    /// rounded to it) by integer arithmetic, with the digits serde_json's
    /// shortest round trip gives (test `grid_numbers_are_written_as_serde_json_writes_them`);
    /// any other as serde_json writes it. Formatting floats was a fifth of
    /// writing a big plan.
    fn write_f64<W: ?Sized + Write>(&mut self, w: &mut W, v: f64) -> io::Result<()> {
        self.pay(w, Next::Other)?;
        let Some(micro) = on_micro_grid(v) else {
            return CompactFormatter.write_f64(out!(self, w), v);
        };
        match self.line.as_mut() {
            Some(l) => crate::formats::text::push_scaled(&mut l.text, v < 0.0, micro, 6, true),
            None => {
                self.number.clear();
                crate::formats::text::push_scaled(&mut self.number, v < 0.0, micro, 6, true);
                w.write_all(&self.number)?;
            }
        }
        Ok(())
    }

    fn begin_string<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.pay(w, Next::Other)?;
        out!(self, w).write_all(b"\"")
    }

    fn end_string<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        out!(self, w).write_all(b"\"")
    }

    fn write_string_fragment<W: ?Sized + Write>(
        &mut self,
        w: &mut W,
        fragment: &str,
    ) -> io::Result<()> {
        out!(self, w).write_all(fragment.as_bytes())
    }

    fn write_char_escape<W: ?Sized + Write>(
        &mut self,
        w: &mut W,
        escape: CharEscape,
    ) -> io::Result<()> {
        CompactFormatter.write_char_escape(out!(self, w), escape)
    }

    fn write_byte_array<W: ?Sized + Write>(&mut self, w: &mut W, value: &[u8]) -> io::Result<()> {
        self.begin_array(w)?;
        for (i, b) in value.iter().enumerate() {
            self.begin_array_value(w, i == 0)?;
            self.write_u8(w, *b)?;
            self.end_array_value(w)?;
        }
        self.end_array(w)
    }

    fn write_raw_fragment<W: ?Sized + Write>(
        &mut self,
        w: &mut W,
        fragment: &str,
    ) -> io::Result<()> {
        self.pay(w, Next::Other)?;
        out!(self, w).write_all(fragment.as_bytes())
    }

    fn begin_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.pay(w, Next::Other)?;
        self.stack.push(Frame::Array {
            objects: false,
            owed: None,
        });
        out!(self, w).write_all(b"[")
    }

    fn end_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        let frame = self.stack.pop();
        let depth = self.stack.len();
        let out = out!(self, w);
        if let Some(Frame::Array { objects: true, .. }) = frame {
            out.write_all(b"\n")?;
            indent(out, depth)?;
        }
        out.write_all(b"]")
    }

    fn begin_array_value<W: ?Sized + Write>(&mut self, _w: &mut W, first: bool) -> io::Result<()> {
        if let Some(Frame::Array { owed, .. }) = self.stack.last_mut() {
            *owed = Some(first);
        }
        Ok(())
    }

    fn end_array_value<W: ?Sized + Write>(&mut self, _w: &mut W) -> io::Result<()> {
        Ok(())
    }

    fn begin_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        // The object being buffered holds this one: it is not a leaf.
        self.unfold(w)?;
        self.pay(w, Next::Object)?;
        self.stack.push(Frame::Object { keys: false });
        let mut line = std::mem::take(&mut self.spare);
        line.depth = self.stack.len();
        line.text.clear();
        line.keys.clear();
        self.line = Some(line);
        Ok(())
    }

    fn end_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        let frame = self.stack.pop();
        if let Some(line) = self.line.take() {
            // A leaf: on one line.
            w.write_all(b"{")?;
            w.write_all(&line.text)?;
            self.spare = line;
            return w.write_all(b"}");
        }
        if let Some(Frame::Object { keys: true }) = frame {
            w.write_all(b"\n")?;
            indent(w, self.stack.len())?;
        }
        w.write_all(b"}")
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if let Some(Frame::Object { keys }) = self.stack.last_mut() {
            *keys = true;
        }
        if let Some(line) = self.line.as_mut() {
            if !first {
                line.text.extend_from_slice(b", ");
            }
            line.keys.push(line.text.len());
            return Ok(());
        }
        w.write_all(if first { b"\n" } else { b",\n" })?;
        indent(w, self.stack.len())
    }

    fn end_object_key<W: ?Sized + Write>(&mut self, _w: &mut W) -> io::Result<()> {
        Ok(())
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        out!(self, w).write_all(b": ")
    }

    fn end_object_value<W: ?Sized + Write>(&mut self, _w: &mut W) -> io::Result<()> {
        Ok(())
    }
}

/// |v| in micrometres, when `v` is the double nearest a whole number of
/// them, from 0.001 to below 10⁹ (where serde_json writes no exponent), or
/// +0. Within that range two such numbers are never the same double, so
/// the decimal with at most six places is the shortest that reads back.
fn on_micro_grid(v: f64) -> Option<u64> {
    if v == 0.0 {
        return v.is_sign_positive().then_some(0);
    }
    let a = v.abs();
    if !(1e-3..1e9).contains(&a) {
        return None;
    }
    let micro = crate::formats::text::round_to_i64(a * 1e6) as u64;
    (micro as f64 / 1e6 == a).then_some(micro)
}

/// Serialise `value` in this layout into `w`, with a final newline.
pub fn write<T: serde::Serialize + ?Sized, W: Write + ?Sized>(
    value: &T,
    w: &mut W,
) -> io::Result<()> {
    let mut ser = serde_json::Serializer::with_formatter(&mut *w, PlanFormatter::default());
    value.serialize(&mut ser).map_err(io::Error::other)?;
    w.write_all(b"\n")
}

/// The dotted path of a NaN or infinite number in `plan`, if any
/// ([`super::finite::first_non_finite`]): the first outside its parts,
/// else the first in them (walked in parallel).
pub fn first_non_finite(plan: &mut Plan) -> Option<String> {
    use rayon::prelude::*;
    let parts = plan.parts.take();
    let rest = super::finite::first_non_finite(plan);
    plan.parts = parts;
    rest.or_else(|| {
        plan.parts.as_deref().and_then(|parts| {
            parts.par_iter().enumerate().find_map_first(|(i, p)| {
                super::finite::first_non_finite(p).map(|f| format!("parts[{i}].{f}"))
            })
        })
    })
}

/// Serialise a plan (pretty JSON, trailing newline).
pub fn to_json(plan: &Plan) -> String {
    let mut out = Vec::new();
    if let Err(e) = write_json(plan, &mut out) {
        return format!("{{\"error\":\"{e}\"}}\n");
    }
    String::from_utf8(out).unwrap_or_default()
}

/// Stream the plan as JSON into `w` (the layout of [`to_json`]).
pub fn write_json<W: std::io::Write + ?Sized>(plan: &Plan, w: &mut W) -> std::io::Result<()> {
    write(plan, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout(v: &serde_json::Value) -> String {
        let mut out = Vec::new();
        write(v, &mut out).expect("write");
        let text = String::from_utf8(out).expect("utf8");
        // The same value reads back.
        let back: serde_json::Value = serde_json::from_str(&text).expect("json");
        assert_eq!(&back, v);
        text
    }

    #[test]
    fn leaf_objects_and_number_arrays_stay_on_one_line() {
        let v = serde_json::json!({
            "schema": "x",
            "parts": [
                {"id": "A", "outline": [[0.0, 0.0], [1.5, 0.0]], "holes": [], "features": [
                    {"kind": "hole", "at": [1.0, 2.0], "use": null},
                    {"kind": "slot", "at": [3.0, 4.0], "use": "a \"quoted\" \\ name"}
                ], "z": 1},
                {"id": "B"}
            ],
            "empty": {},
            "names": ["a", "b"],
            "nested": {"inner": {"k": 1}, "after": [1, 2]}
        });
        let want = r#"{
  "empty": {},
  "names": ["a", "b"],
  "nested": {
    "after": [1, 2],
    "inner": {"k": 1}
  },
  "parts": [
    {
      "features": [
        {"at": [1.0, 2.0], "kind": "hole", "use": null},
        {"at": [3.0, 4.0], "kind": "slot", "use": "a \"quoted\" \\ name"}
      ],
      "holes": [],
      "id": "A",
      "outline": [[0.0, 0.0], [1.5, 0.0]],
      "z": 1
    },
    {"id": "B"}
  ],
  "schema": "x"
}
"#;
        assert_eq!(layout(&v), want);
    }

    /// Against serde_json's own float formatting: a sweep of the µm grid,
    /// its ends, integers, halves and values off the grid.
    #[test]
    fn grid_numbers_are_written_as_serde_json_writes_them() {
        let mut values: Vec<f64> = Vec::new();
        for k in -200_000i64..200_000 {
            values.push(k as f64 / 1000.0);
            values.push(k as f64 * 0.001 + 0.000_001 * (k % 997) as f64);
            values.push(k as f64 * 1_234.567_891);
        }
        values.extend([
            0.0,
            -0.0,
            1e-3,
            -1e-3,
            0.000_999_999,
            1e-6,
            1e-7,
            0.1,
            0.2,
            0.3,
            1.0 / 3.0,
            2.5,
            3.0,
            1e8,
            123_456_789.123_456,
            999_999_999.999_999,
            1e9,
            1e9 + 0.5,
            4_503_599_627.370_496,
            1e15,
            1e16,
            -1e21,
            f64::MIN_POSITIVE,
            f64::MAX,
        ]);
        for &v in &values {
            let mut ours = Vec::new();
            write(&v, &mut ours).expect("write");
            let theirs = serde_json::to_string(&v).expect("json") + "\n";
            assert_eq!(String::from_utf8(ours).expect("utf8"), theirs, "{v:e}");
        }
    }

    #[test]
    fn an_object_of_objects_in_an_array_of_arrays() {
        let v = serde_json::json!([[{"a": {"b": []}}], [1, [2, {"c": 3}]]]);
        let want = r#"[[
    {
      "a": {"b": []}
    }
  ], [1, [2,
      {"c": 3}
    ]]]
"#;
        assert_eq!(layout(&v), want);
    }
}

#[cfg(test)]
mod plan_tests {
    use super::*;
    use crate::plan::{Plan, PlanPart, SCHEMA};

    fn part(id: &str, length_mm: f64) -> PlanPart {
        PlanPart {
            id: id.into(),
            kind: "washer".into(),
            group: "washer-3".into(),
            material: "S235".into(),
            thickness_mm: 3.0,
            strip: None,
            lamella: None,
            count: 1,
            length_mm,
            height_mm: 10.0,
            station_start_mm: None,
            outline: vec![[0.0, 0.0], [length_mm, 0.0], [0.0, 10.0]],
            holes: vec![],
            engraving: vec![],
            features: vec![],
        }
    }

    /// The parts are walked in parallel, the rest as a whole walk would.
    #[test]
    fn non_finite_numbers_named_in_the_parts_and_outside() {
        let mut plan: Plan = serde_json::from_value(serde_json::json!({
            "schema": SCHEMA, "generator": "t", "units": "mm",
            "network": {"name": "n", "source": "n.yaml", "file_units": "mm", "tolerance_mm": 0.5},
            "summary": {"curves": 0, "nodes": 0, "total_length_mm": 0.0,
                "shortest_node_to_node_mm": null, "longest_node_to_node_mm": null,
                "max_normal_curvature_per_m": 0.0, "min_angle_deg": null, "max_angle_deg": null},
            "strips": [], "nodes": [], "warnings": []
        }))
        .expect("plan");
        plan.parts = Some((0..50).map(|i| part(&format!("P{i}"), 10.0)).collect());
        assert_eq!(first_non_finite(&mut plan), None);
        let parts = plan.parts.as_mut().expect("parts");
        parts[40].outline[2][1] = f64::INFINITY;
        parts[7].length_mm = f64::NAN;
        assert_eq!(
            first_non_finite(&mut plan).as_deref(),
            Some("parts[7].length_mm")
        );
        plan.network.tolerance_mm = f64::NAN;
        assert_eq!(
            first_non_finite(&mut plan).as_deref(),
            Some("network.tolerance_mm")
        );
        assert_eq!(plan.parts.as_ref().map(Vec::len), Some(50));
    }
}
