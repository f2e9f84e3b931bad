//! A guard for the writers: JSON has no NaN or infinity (serde_json writes
//! them as `null`, indistinguishable from "no value"), so before an output is
//! written every number in it must be finite. [`first_non_finite`] walks any
//! `Serialize` value and names the first field that is not.

use serde::ser::{self, Serialize};
use std::fmt;

/// The dotted path (`strips[3].length_mm`) of the first NaN or infinite
/// number in `value`, if any.
pub fn first_non_finite<T: Serialize + ?Sized>(value: &T) -> Option<String> {
    let mut w = Walker {
        path: Vec::new(),
        found: None,
    };
    let _ = value.serialize(&mut w);
    w.found
}

enum Seg {
    Field(&'static str),
    Index(usize),
    Key(String),
}

struct Walker {
    path: Vec<Seg>,
    found: Option<String>,
}

/// Stops the walk once a non-finite number is found.
#[derive(Debug)]
struct Found;

impl fmt::Display for Found {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("non-finite number")
    }
}
impl std::error::Error for Found {}
impl ser::Error for Found {
    fn custom<T: fmt::Display>(_: T) -> Self {
        Found
    }
}

impl Walker {
    fn number(&mut self, x: f64) -> Result<(), Found> {
        if x.is_finite() {
            return Ok(());
        }
        let mut s = String::new();
        for seg in &self.path {
            match seg {
                Seg::Field(f) => {
                    if !s.is_empty() {
                        s.push('.');
                    }
                    s.push_str(f);
                }
                Seg::Index(i) => s.push_str(&format!("[{i}]")),
                Seg::Key(k) => s.push_str(&format!("[{k:?}]")),
            }
        }
        self.found = Some(if s.is_empty() { "value".into() } else { s });
        Err(Found)
    }
    fn within<T: Serialize + ?Sized>(&mut self, seg: Seg, v: &T) -> Result<(), Found> {
        self.path.push(seg);
        let r = v.serialize(&mut *self);
        self.path.pop();
        r
    }
}

/// A compound (sequence, map, struct) being walked: counts its elements.
struct Compound<'a> {
    w: &'a mut Walker,
    index: usize,
    key: Option<String>,
}

/// Renders a map key for the path.
struct KeyText(Option<String>);

macro_rules! ok_scalars {
    ($($name:ident: $t:ty),*) => {
        $(fn $name(self, _: $t) -> Result<(), Found> { Ok(()) })*
    };
}

/// The methods both serializers share: no value, an optional one and a
/// newtype are looked through; a unit is nothing to check.
macro_rules! see_through {
    () => {
        fn serialize_none(self) -> Result<(), Found> {
            Ok(())
        }
        fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> Result<(), Found> {
            v.serialize(self)
        }
        fn serialize_unit(self) -> Result<(), Found> {
            Ok(())
        }
        fn serialize_newtype_struct<T: Serialize + ?Sized>(
            self,
            _: &'static str,
            v: &T,
        ) -> Result<(), Found> {
            v.serialize(self)
        }
    };
}

/// The compound values (sequences, tuples, maps, structs, variants) of a
/// serializer, each opened by `$open` (called with the serializer).
macro_rules! compounds {
    ($open:expr) => {
        fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, Found> {
            ($open)(self)
        }
        fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, Found> {
            ($open)(self)
        }
        fn serialize_tuple_struct(
            self,
            _: &'static str,
            _: usize,
        ) -> Result<Self::SerializeTupleStruct, Found> {
            ($open)(self)
        }
        fn serialize_tuple_variant(
            self,
            _: &'static str,
            _: u32,
            _: &'static str,
            _: usize,
        ) -> Result<Self::SerializeTupleVariant, Found> {
            ($open)(self)
        }
        fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, Found> {
            ($open)(self)
        }
        fn serialize_struct(
            self,
            _: &'static str,
            _: usize,
        ) -> Result<Self::SerializeStruct, Found> {
            ($open)(self)
        }
        fn serialize_struct_variant(
            self,
            _: &'static str,
            _: u32,
            _: &'static str,
            _: usize,
        ) -> Result<Self::SerializeStructVariant, Found> {
            ($open)(self)
        }
    };
}

impl<'a> ser::Serializer for &'a mut Walker {
    type Ok = ();
    type Error = Found;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = Compound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    ok_scalars!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32,
        serialize_i64: i64, serialize_u8: u8, serialize_u16: u16, serialize_u32: u32,
        serialize_u64: u64, serialize_char: char, serialize_str: &str, serialize_bytes: &[u8],
        serialize_unit_struct: &'static str);

    fn serialize_f32(self, v: f32) -> Result<(), Found> {
        self.number(v as f64)
    }
    fn serialize_f64(self, v: f64) -> Result<(), Found> {
        self.number(v)
    }
    see_through!();
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Result<(), Found> {
        Ok(())
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        v: &T,
    ) -> Result<(), Found> {
        self.within(Seg::Field(variant), v)
    }
    compounds!(|w| Ok(Compound {
        w,
        index: 0,
        key: None
    }));
}

impl Compound<'_> {
    fn element<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), Found> {
        let i = self.index;
        self.index += 1;
        self.w.within(Seg::Index(i), v)
    }
}

macro_rules! seq_like {
    ($($tr:ident :: $m:ident),*) => {$(
        impl ser::$tr for Compound<'_> {
            type Ok = ();
            type Error = Found;
            fn $m<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), Found> {
                self.element(v)
            }
            fn end(self) -> Result<(), Found> {
                Ok(())
            }
        }
    )*};
}
seq_like!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

impl ser::SerializeMap for Compound<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, k: &T) -> Result<(), Found> {
        let mut text = KeyText(None);
        let _ = k.serialize(&mut text);
        self.key = text.0;
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), Found> {
        match self.key.take() {
            Some(k) => self.w.within(Seg::Key(k), v),
            None => self.element(v),
        }
    }
    fn end(self) -> Result<(), Found> {
        Ok(())
    }
}

macro_rules! struct_like {
    ($($tr:ident),*) => {$(
        impl ser::$tr for Compound<'_> {
            type Ok = ();
            type Error = Found;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                name: &'static str,
                v: &T,
            ) -> Result<(), Found> {
                self.w.within(Seg::Field(name), v)
            }
            fn end(self) -> Result<(), Found> {
                Ok(())
            }
        }
    )*};
}
struct_like!(SerializeStruct, SerializeStructVariant);

/// Map keys are strings in JSON; anything else is left unnamed.
impl ser::Serializer for &mut KeyText {
    type Ok = ();
    type Error = Found;
    type SerializeSeq = ser::Impossible<(), Found>;
    type SerializeTuple = ser::Impossible<(), Found>;
    type SerializeTupleStruct = ser::Impossible<(), Found>;
    type SerializeTupleVariant = ser::Impossible<(), Found>;
    type SerializeMap = ser::Impossible<(), Found>;
    type SerializeStruct = ser::Impossible<(), Found>;
    type SerializeStructVariant = ser::Impossible<(), Found>;

    fn serialize_str(self, v: &str) -> Result<(), Found> {
        self.0 = Some(v.to_string());
        Ok(())
    }
    ok_scalars!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32,
        serialize_i64: i64, serialize_u8: u8, serialize_u16: u16, serialize_u32: u32,
        serialize_u64: u64, serialize_char: char, serialize_bytes: &[u8],
        serialize_unit_struct: &'static str, serialize_f32: f32, serialize_f64: f64);
    see_through!();
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<(), Found> {
        self.0 = Some(variant.to_string());
        Ok(())
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<(), Found> {
        Ok(())
    }
    compounds!(|_| Err(Found));
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    #[derive(serde::Serialize)]
    struct Strip {
        id: String,
        length_mm: f64,
        radius_mm: Option<f64>,
    }

    #[derive(serde::Serialize)]
    struct Plan {
        total: f64,
        strips: Vec<Strip>,
        extra: BTreeMap<String, [f64; 2]>,
    }

    #[test]
    fn names_the_first_non_finite_number() {
        let strip = |x: f64, r: Option<f64>| Strip {
            id: "A".into(),
            length_mm: x,
            radius_mm: r,
        };
        let mut plan = Plan {
            total: 1.0,
            strips: vec![strip(1.0, None), strip(2.0, Some(3.0))],
            extra: BTreeMap::new(),
        };
        assert_eq!(first_non_finite(&plan), None);
        plan.strips[1].radius_mm = Some(f64::NAN);
        assert_eq!(
            first_non_finite(&plan).as_deref(),
            Some("strips[1].radius_mm")
        );
        plan.strips[1].radius_mm = None;
        plan.extra.insert("k".into(), [0.0, f64::INFINITY]);
        assert_eq!(first_non_finite(&plan).as_deref(), Some("extra[\"k\"][1]"));
        assert_eq!(first_non_finite(&f64::NAN).as_deref(), Some("value"));
    }
}
