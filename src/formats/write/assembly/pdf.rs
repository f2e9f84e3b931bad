//! The PDF file around the pages' content streams: header, page tree, the
//! two built-in fonts, per-page resources, the catalog, the document
//! information, the cross-reference table and the trailer (PDF 1.3, one
//! object per number, generation 0, no object streams).
//!
//! The layout is fixed, for `n` pages:
//!
//! | object             | what                                                  |
//! |--------------------|-------------------------------------------------------|
//! | 1                  | the page tree (`/Kids` 8 … 7 + n)                     |
//! | 2, 3               | Helvetica, Helvetica-Bold (Type1, WinAnsiEncoding)    |
//! | 4                  | the font resources (`/F5`, `/F6`)                     |
//! | 5, 6, 7            | empty XObject, ExtGState and Shading resources        |
//! | 8 + i              | page i (0-based)                                      |
//! | 8 + n + 2i         | page i's resources                                    |
//! | 9 + n + 2i         | page i's drawing (FlateDecode)                        |
//! | 8 + 3n             | the catalog                                           |
//! | 9 + 3n             | the document information                              |
//! | 10 + 3n + i        | page i's heading and title block (FlateDecode)        |
//!
//! Objects are written in number order, each streamed into the output as
//! it comes; only their offsets are kept for the cross-reference table.

use super::canvas::{HELVETICA_BOLD_RES, HELVETICA_RES};
use std::io::{self, Write};

/// The first page's object number.
const FIRST_PAGE: usize = 8;

/// What the document information and the trailer say.
#[derive(Debug, Clone, Copy)]
pub struct DocInfo<'a> {
    /// The title (written as UTF-16BE with a byte order mark).
    pub title: &'a str,
    /// The creator and producer (UTF-16BE as the title).
    pub creator: &'a str,
    /// The trailer's `/ID` (both entries), as bytes written in hex.
    pub id: &'a [u8],
}

/// One page: its drawing and its heading, each a zlib-compressed content
/// stream.
#[derive(Debug)]
pub struct PageStreams {
    /// The drawing (the page's first content stream).
    pub body_deflated: Vec<u8>,
    /// The heading and title block (its second).
    pub heading_deflated: Vec<u8>,
}

/// A writer that counts the bytes it has passed on.
struct Counting<'w> {
    inner: &'w mut dyn Write,
    written: u64,
}

impl Counting<'_> {
    fn put(&mut self, bytes: &[u8]) -> io::Result<()> {
        self.written += bytes.len() as u64;
        self.inner.write_all(bytes)
    }
}

/// A page size in points as written in the page boxes: millimetres to
/// points in single precision (72 / 25.4 rounded to 2.834646), printed in
/// the shortest form that reads back to the same `f32`.
pub fn mm_to_pt_text(mm: f64) -> String {
    format!("{}", mm as f32 * 2.834_646_f32)
}

/// `bytes` as an upper-case hex string object (`<…>`).
fn hex_string(out: &mut String, bytes: &[u8]) {
    use std::fmt::Write as _;
    out.push('<');
    for b in bytes {
        // Writing into a String cannot fail.
        let _ = write!(out, "{b:02X}");
    }
    out.push('>');
}

/// A text string: UTF-16BE with a byte order mark, in hex; `()` when empty.
fn text_string(out: &mut String, text: &str) {
    if text.is_empty() {
        out.push_str("()");
        return;
    }
    let mut bytes = vec![0xFE, 0xFF];
    for unit in text.encode_utf16() {
        bytes.extend_from_slice(&unit.to_be_bytes());
    }
    hex_string(out, &bytes);
}

/// Write the document: `pages` in order, each `width_mm` × `height_mm`.
pub fn write_document(
    out: &mut dyn Write,
    width_mm: f64,
    height_mm: f64,
    info: &DocInfo,
    pages: Vec<PageStreams>,
) -> io::Result<()> {
    let n = pages.len();
    let resources = |i: usize| FIRST_PAGE + n + 2 * i;
    let catalog = FIRST_PAGE + 3 * n;
    let info_id = catalog + 1;
    let heading = |i: usize| catalog + 2 + i;
    let size = heading(n);
    let mut w = Counting {
        inner: out,
        written: 0,
    };
    let mut offsets: Vec<u64> = Vec::with_capacity(size);
    // Object `offsets.len() + 1`, a dictionary.
    let object = |w: &mut Counting, offsets: &mut Vec<u64>, dict: &str| -> io::Result<()> {
        offsets.push(w.written);
        w.put(format!("{} 0 obj\n{dict}\nendobj\n", offsets.len()).as_bytes())
    };
    // Object `offsets.len() + 1`, a FlateDecode stream.
    let stream = |w: &mut Counting, offsets: &mut Vec<u64>, data: &[u8]| -> io::Result<()> {
        offsets.push(w.written);
        w.put(
            format!(
                "{} 0 obj\n<</Filter/FlateDecode/Length {}>>stream\n",
                offsets.len(),
                data.len()
            )
            .as_bytes(),
        )?;
        w.put(data)?;
        w.put(b"\nendstream \nendobj\n")
    };

    w.put(b"%PDF-1.3\n%\xBB\xAD\xC0\xDE\n")?;
    let mut kids = String::with_capacity(12 * n);
    for i in 0..n {
        if i > 0 {
            kids.push(' ');
        }
        kids.push_str(&format!("{} 0 R", FIRST_PAGE + i));
    }
    object(
        &mut w,
        &mut offsets,
        &format!("<</Type/Pages/Count {n}/Kids[{kids}]>>"),
    )?;
    drop(kids);
    for font in ["Helvetica", "Helvetica-Bold"] {
        object(
            &mut w,
            &mut offsets,
            &format!("<</Type/Font/Subtype/Type1/BaseFont/{font}/Encoding/WinAnsiEncoding>>"),
        )?;
    }
    object(
        &mut w,
        &mut offsets,
        &format!("<</{HELVETICA_RES} 2 0 R/{HELVETICA_BOLD_RES} 3 0 R>>"),
    )?;
    for _ in 0..3 {
        object(&mut w, &mut offsets, "<<>>")?;
    }
    let (pw, ph) = (mm_to_pt_text(width_mm), mm_to_pt_text(height_mm));
    let media = format!("[0 0 {pw} {ph}]");
    for i in 0..n {
        object(
            &mut w,
            &mut offsets,
            &format!(
                "<</Type/Page/MediaBox{media}/TrimBox{media}/CropBox{media}/Parent 1 0 R\
                 /Resources {} 0 R/Contents[{} 0 R {} 0 R]/Annots[]>>",
                resources(i),
                resources(i) + 1,
                heading(i)
            ),
        )?;
    }
    let mut headings = Vec::with_capacity(n);
    for page in pages {
        object(
            &mut w,
            &mut offsets,
            "<</Font 4 0 R/XObject 5 0 R/ExtGState 6 0 R/Shading 7 0 R>>",
        )?;
        stream(&mut w, &mut offsets, &page.body_deflated)?;
        headings.push(page.heading_deflated);
    }
    object(
        &mut w,
        &mut offsets,
        "<</Type/Catalog/PageLayout/OneColumn/PageMode/UseNone/Pages 1 0 R>>",
    )?;
    let date = "(D:19700101000000+00'00')";
    let mut dict =
        format!("<</Trapped/False/CreationDate{date}/ModDate{date}/GTS_PDFXVersion()/Title");
    text_string(&mut dict, info.title);
    dict.push_str("/Author()/Creator");
    text_string(&mut dict, info.creator);
    dict.push_str("/Producer");
    text_string(&mut dict, info.creator);
    dict.push_str("/Subject()/Identifier()/Keywords()>>");
    object(&mut w, &mut offsets, &dict)?;
    for h in headings {
        stream(&mut w, &mut offsets, &h)?;
    }
    debug_assert_eq!(offsets.len() + 1, size);

    let xref_at = w.written;
    let mut xref = String::with_capacity(20 * (size + 1) + 16);
    xref.push_str(&format!("xref\n0 {size}\n0000000000 65535 f \n"));
    for at in &offsets {
        xref.push_str(&format!("{at:010} 00000 n \n"));
    }
    xref.push_str(&format!(
        "trailer\n<</Root {catalog} 0 R/Info {info_id} 0 R/ID["
    ));
    hex_string(&mut xref, info.id);
    hex_string(&mut xref, info.id);
    xref.push_str(&format!("]/Size {size}>>\nstartxref\n{xref_at}\n%%EOF"));
    w.put(xref.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_pages() -> Vec<PageStreams> {
        vec![
            PageStreams {
                body_deflated: b"BODY one".to_vec(),
                heading_deflated: b"HEAD one".to_vec(),
            },
            PageStreams {
                body_deflated: b"BODY two\nendstream".to_vec(),
                heading_deflated: b"H2".to_vec(),
            },
        ]
    }

    fn document() -> Vec<u8> {
        let mut out = Vec::new();
        let info = DocInfo {
            title: "Caf\u{e9}: assembly sheets",
            creator: "lamella 0.1.0",
            id: b"0123456789012345",
        };
        write_document(&mut out, 297.0, 210.0, &info, two_pages()).unwrap_or_default();
        out
    }

    /// The bytes printpdf 0.12 and lopdf 0.44 wrote for this document
    /// (checked against them when this writer replaced them): every
    /// assembly.pdf stays byte for byte what it was.
    #[test]
    fn bytes_as_before() {
        let rest = concat!(
            "1 0 obj\n<</Type/Pages/Count 2/Kids[8 0 R 9 0 R]>>\nendobj\n",
            "2 0 obj\n<</Type/Font/Subtype/Type1/BaseFont/Helvetica/Encoding/WinAnsiEncoding>>\nendobj\n",
            "3 0 obj\n<</Type/Font/Subtype/Type1/BaseFont/Helvetica-Bold/Encoding/WinAnsiEncoding>>\nendobj\n",
            "4 0 obj\n<</F5 2 0 R/F6 3 0 R>>\nendobj\n",
            "5 0 obj\n<<>>\nendobj\n",
            "6 0 obj\n<<>>\nendobj\n",
            "7 0 obj\n<<>>\nendobj\n",
            "8 0 obj\n<</Type/Page/MediaBox[0 0 841.88983 595.27563]/TrimBox[0 0 841.88983 595.27563]/CropBox[0 0 841.88983 595.27563]/Parent 1 0 R/Resources 10 0 R/Contents[11 0 R 16 0 R]/Annots[]>>\nendobj\n",
            "9 0 obj\n<</Type/Page/MediaBox[0 0 841.88983 595.27563]/TrimBox[0 0 841.88983 595.27563]/CropBox[0 0 841.88983 595.27563]/Parent 1 0 R/Resources 12 0 R/Contents[13 0 R 17 0 R]/Annots[]>>\nendobj\n",
            "10 0 obj\n<</Font 4 0 R/XObject 5 0 R/ExtGState 6 0 R/Shading 7 0 R>>\nendobj\n",
            "11 0 obj\n<</Filter/FlateDecode/Length 8>>stream\nBODY one\nendstream \nendobj\n",
            "12 0 obj\n<</Font 4 0 R/XObject 5 0 R/ExtGState 6 0 R/Shading 7 0 R>>\nendobj\n",
            "13 0 obj\n<</Filter/FlateDecode/Length 18>>stream\nBODY two\nendstream\nendstream \nendobj\n",
            "14 0 obj\n<</Type/Catalog/PageLayout/OneColumn/PageMode/UseNone/Pages 1 0 R>>\nendobj\n",
            "15 0 obj\n<</Trapped/False/CreationDate(D:19700101000000+00'00')/ModDate(D:19700101000000+00'00')/GTS_PDFXVersion()/Title<FEFF00430061006600E9003A00200061007300730065006D0062006C00790020007300680065006500740073>/Author()/Creator<FEFF006C0061006D0065006C006C006100200030002E0031002E0030>/Producer<FEFF006C0061006D0065006C006C006100200030002E0031002E0030>/Subject()/Identifier()/Keywords()>>\nendobj\n",
            "16 0 obj\n<</Filter/FlateDecode/Length 8>>stream\nHEAD one\nendstream \nendobj\n",
            "17 0 obj\n<</Filter/FlateDecode/Length 2>>stream\nH2\nendstream \nendobj\n",
            "xref\n0 18\n",
        );
        let expected = [b"%PDF-1.3\n%\xBB\xAD\xC0\xDE\n".as_slice(), rest.as_bytes()].concat();
        let doc = document();
        assert_eq!(
            String::from_utf8_lossy(&doc[..expected.len()]),
            String::from_utf8_lossy(&expected)
        );
        assert_eq!(&doc[..expected.len()], &expected[..]);
        let tail = String::from_utf8_lossy(&doc[expected.len()..]).into_owned();
        let trailer = tail.split("trailer\n").nth(1).unwrap_or_default();
        assert_eq!(
            trailer,
            format!(
                "<</Root 14 0 R/Info 15 0 R/ID[<{id}><{id}>]/Size 18>>\nstartxref\n{}\n%%EOF",
                expected.len() - "xref\n0 18\n".len(),
                id = "30313233343536373839303132333435"
            )
        );
    }

    /// Every cross-reference entry points at its object's `N 0 obj`, and
    /// `startxref` at the table.
    #[test]
    fn cross_references_point_at_their_objects() {
        let doc = document();
        let tail_at = doc.len() - 64;
        let tail = String::from_utf8_lossy(&doc[tail_at..]).into_owned();
        let start: usize = tail
            .rsplit("startxref\n")
            .next()
            .and_then(|t| t.strip_suffix("\n%%EOF"))
            .and_then(|t| t.parse().ok())
            .unwrap_or(usize::MAX);
        assert!(doc[start..].starts_with(b"xref\n0 18\n"));
        let table = String::from_utf8_lossy(&doc[start + "xref\n0 18\n".len()..]).into_owned();
        let entries: Vec<&str> = table.split('\n').take(18).collect();
        assert_eq!(entries[0], "0000000000 65535 f ");
        for (id, entry) in entries.iter().enumerate().skip(1) {
            assert_eq!(entry.len(), 19, "{entry:?}");
            assert!(entry.ends_with(" 00000 n "), "{entry:?}");
            let at: usize = entry[..10].parse().unwrap_or(usize::MAX);
            let head = format!("{id} 0 obj\n");
            assert!(
                doc[at..].starts_with(head.as_bytes()),
                "object {id} is not at {at}"
            );
        }
        assert!(table.split('\n').nth(18) == Some("trailer"));
    }
}
