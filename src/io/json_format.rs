//! A JSON layout for big plans: objects indented one key per line as
//! `to_string_pretty` does, but arrays of numbers, strings and arrays on one
//! line (`"outline": [[0.0, 0.0], [3000.0, 0.0], …]`). A kit's outlines and
//! engraving are most of plan.json; one number per line made it three times
//! larger and no easier to read.
//!
//! An array learns that it holds objects only when the first one begins,
//! so the separator before each element is held back until then.

use serde_json::ser::{CompactFormatter, Formatter};
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

/// The formatter (see the module doc).
#[derive(Debug, Default)]
pub struct PlanFormatter {
    stack: Vec<Frame>,
}

/// What is about to be written into an array.
#[derive(PartialEq)]
enum Next {
    Object,
    Other,
}

impl PlanFormatter {
    fn indent<W: ?Sized + Write>(&self, w: &mut W, depth: usize) -> io::Result<()> {
        for _ in 0..depth {
            w.write_all(b"  ")?;
        }
        Ok(())
    }

    /// Pay the separator an array owes before its next element.
    fn pay<W: ?Sized + Write>(&mut self, w: &mut W, next: Next) -> io::Result<()> {
        let depth = self.stack.len();
        if let Some(Frame::Array { objects, owed }) = self.stack.last_mut() {
            if let Some(first) = owed.take() {
                if next == Next::Object {
                    *objects = true;
                }
                if *objects {
                    w.write_all(if first { b"\n" } else { b",\n" })?;
                    return self.indent(w, depth);
                }
                if !first {
                    w.write_all(b", ")?;
                }
            }
        }
        Ok(())
    }
}

macro_rules! scalar {
    ($($name:ident: $t:ty),*) => {$(
        fn $name<W: ?Sized + Write>(&mut self, w: &mut W, v: $t) -> io::Result<()> {
            self.pay(w, Next::Other)?;
            CompactFormatter.$name(w, v)
        }
    )*};
}

impl Formatter for PlanFormatter {
    fn write_null<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.pay(w, Next::Other)?;
        w.write_all(b"null")
    }

    scalar!(write_bool: bool, write_i8: i8, write_i16: i16, write_i32: i32, write_i64: i64,
        write_u8: u8, write_u16: u16, write_u32: u32, write_u64: u64, write_f32: f32,
        write_f64: f64, write_number_str: &str);

    fn begin_string<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.pay(w, Next::Other)?;
        w.write_all(b"\"")
    }

    fn begin_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.pay(w, Next::Other)?;
        self.stack.push(Frame::Array {
            objects: false,
            owed: None,
        });
        w.write_all(b"[")
    }

    fn end_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if let Some(Frame::Array { objects: true, .. }) = self.stack.pop() {
            w.write_all(b"\n")?;
            self.indent(w, self.stack.len())?;
        }
        w.write_all(b"]")
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
        self.pay(w, Next::Object)?;
        self.stack.push(Frame::Object { keys: false });
        w.write_all(b"{")
    }

    fn end_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if let Some(Frame::Object { keys: true }) = self.stack.pop() {
            w.write_all(b"\n")?;
            self.indent(w, self.stack.len())?;
        }
        w.write_all(b"}")
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if let Some(Frame::Object { keys }) = self.stack.last_mut() {
            *keys = true;
        }
        w.write_all(if first { b"\n" } else { b",\n" })?;
        self.indent(w, self.stack.len())
    }

    fn end_object_key<W: ?Sized + Write>(&mut self, _w: &mut W) -> io::Result<()> {
        Ok(())
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(b": ")
    }

    fn end_object_value<W: ?Sized + Write>(&mut self, _w: &mut W) -> io::Result<()> {
        Ok(())
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objects_indent_and_number_arrays_stay_on_one_line() {
        let v = serde_json::json!({
            "schema": "x",
            "parts": [{"id": "A", "outline": [[0.0, 0.0], [1.5, 0.0]], "holes": []}, {"id": "B"}],
            "empty": {},
            "names": ["a", "b"]
        });
        let mut out = Vec::new();
        write(&v, &mut out).expect("write");
        let text = String::from_utf8(out).expect("utf8");
        let want = r#"{
  "empty": {},
  "names": ["a", "b"],
  "parts": [
    {
      "holes": [],
      "id": "A",
      "outline": [[0.0, 0.0], [1.5, 0.0]]
    },
    {
      "id": "B"
    }
  ],
  "schema": "x"
}
"#;
        assert_eq!(text, want);
        // The same value reads back.
        let back: serde_json::Value = serde_json::from_str(&text).expect("json");
        assert_eq!(back, v);
    }
}
