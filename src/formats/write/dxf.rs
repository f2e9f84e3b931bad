//! A sheet drawing as DXF for laser and waterjet software: R2000 (AC1015),
//! millimetres (`$INSUNITS` = 4, `$MEASUREMENT` = 1), one layer per
//! operation with its colour, closed LWPOLYLINEs per contour with arcs as
//! bulges, round holes as CIRCLEs, engraving as open LWPOLYLINEs, no blocks
//! referenced and no splines.
//!
//! The document is complete as AutoCAD and ODA-based importers expect it,
//! written here by hand: a HEADER with `$HANDSEED` past the last handle and
//! `$EXTMIN`/`$EXTMAX` the drawing's real extents; CLASSES for the objects
//! R2000 needs; TABLES whose heads and records carry handles and owners and
//! whose heads count their records (VPORT `*Active`; LTYPE `ByBlock`,
//! `ByLayer`, `Continuous`; LAYER `0` and the operations'; STYLE, VIEW,
//! UCS, APPID `ACAD`, DIMSTYLE, BLOCK_RECORD `*Model_Space` and
//! `*Paper_Space`); BLOCKS with both spaces' BLOCK/ENDBLK; ENTITIES, each
//! with its handle and `*Model_Space` as owner; OBJECTS with the root
//! dictionary, `ACAD_GROUP`, `ACAD_LAYOUT` (both layouts) and
//! `ACAD_PLOTSTYLENAME`. Every handle is fixed, so the same sheet gives
//! the same bytes.
//!
//! The entities come in cutting order ([`super::drawing::cut_order`]):
//! the engraving, then the inner contours, then the outlines. The
//! sheet's outline is written only when asked, on the non-plotting
//! reference layer `SHEET`. Coordinates have up to 6 decimals (trailing
//! zeros dropped), bulges 9.

use super::drawing::{cut_order, strokes, Layer, Shape, SheetDrawing, SheetFileOptions, Vertex};

/// Decimals of coordinates and radii.
const COORD_DECIMALS: u32 = 6;

/// Decimals of bulges.
const BULGE_DECIMALS: u32 = 9;

/// Fixed handles of the document's structure (entities follow from
/// [`FIRST_ENTITY`]).
mod h {
    pub const VPORT_TABLE: u64 = 0x1;
    pub const LTYPE_TABLE: u64 = 0x2;
    pub const LAYER_TABLE: u64 = 0x3;
    pub const STYLE_TABLE: u64 = 0x4;
    pub const VIEW_TABLE: u64 = 0x5;
    pub const UCS_TABLE: u64 = 0x6;
    pub const APPID_TABLE: u64 = 0x7;
    pub const DIMSTYLE_TABLE: u64 = 0x8;
    pub const BLOCK_RECORD_TABLE: u64 = 0x9;
    pub const ROOT_DICT: u64 = 0xA;
    pub const GROUP_DICT: u64 = 0xB;
    pub const LAYOUT_DICT: u64 = 0xC;
    pub const PLOTSTYLE_DICT: u64 = 0xD;
    pub const PLOTSTYLE_NORMAL: u64 = 0xE;
    pub const VPORT_ACTIVE: u64 = 0x10;
    pub const LTYPE_BYBLOCK: u64 = 0x11;
    pub const LTYPE_BYLAYER: u64 = 0x12;
    pub const LTYPE_CONTINUOUS: u64 = 0x13;
    /// Layer `0`; the operations' layers follow in [`super::LAYERS`] order.
    pub const LAYER_0: u64 = 0x14;
    pub const STYLE_STANDARD: u64 = 0x1A;
    pub const APPID_ACAD: u64 = 0x1B;
    pub const DIMSTYLE_STANDARD: u64 = 0x1C;
    pub const MODEL_RECORD: u64 = 0x1D;
    pub const PAPER_RECORD: u64 = 0x1E;
    pub const MODEL_BLOCK: u64 = 0x1F;
    pub const MODEL_ENDBLK: u64 = 0x20;
    pub const PAPER_BLOCK: u64 = 0x21;
    pub const PAPER_ENDBLK: u64 = 0x22;
    pub const MODEL_LAYOUT: u64 = 0x23;
    pub const PAPER_LAYOUT: u64 = 0x24;
    /// The first entity's handle.
    pub const FIRST_ENTITY: u64 = 0x30;
}

/// The operations' layers in the LAYER table, after `0`.
const LAYERS: [Layer; 4] = [
    Layer::Sheet,
    Layer::Engrave,
    Layer::CutInner,
    Layer::CutOuter,
];

/// The DXF text of one sheet.
pub fn to_dxf(sheet: &SheetDrawing, opts: SheetFileOptions) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    write_dxf(sheet, opts, &mut out)?;
    Ok(out)
}

/// The DXF text of one sheet into `out` (cleared first; a buffer used
/// again for the next sheet keeps its memory).
pub fn write_dxf(
    sheet: &SheetDrawing,
    opts: SheetFileOptions,
    out: &mut Vec<u8>,
) -> Result<(), String> {
    let outline = sheet.outline();
    let sheet_shape = opts.sheet_outline.then_some(&outline);
    let shapes = || sheet_shape.into_iter().chain(cut_order(sheet));
    // The handles the entities take, about the bytes they need, and the
    // extents.
    let mut ext = Extents::default();
    let (count, bytes) = shapes().fold((0u64, 0usize), |(n, b), sh| {
        ext.shape(sh);
        match sh {
            Shape::Polyline { vertices, .. } => (n + 1, b + 100 + 32 * vertices.len()),
            Shape::Circle { .. } => (n + 1, b + 130),
            Shape::Strokes {
                points_um, ends, ..
            } => (
                n + ends.len() as u64,
                b + 100 * ends.len() + 32 * points_um.len(),
            ),
        }
    });
    out.clear();
    out.reserve(12_000 + bytes);
    let (lo, hi) = ext.corners();
    header(
        out,
        h::FIRST_ENTITY + count,
        lo,
        hi,
        [sheet.length_mm, sheet.width_mm],
        sheet
            .stock_note
            .as_deref()
            .map(|n| format!("{} {n}", sheet.id)),
    );
    structure(out, lo, hi);
    section(out, "ENTITIES");
    let mut handle = h::FIRST_ENTITY;
    for shape in shapes() {
        entity(out, shape, &mut handle);
    }
    endsec(out);
    objects(out);
    out.extend_from_slice(b"  0\nEOF\n");
    Ok(())
}

/// The drawing's extents: the bounding box of every entity (arcs by their
/// extreme points), or the origin when there is none.
#[derive(Debug, Clone, Copy)]
struct Extents {
    lo: [f64; 2],
    hi: [f64; 2],
}

impl Default for Extents {
    fn default() -> Self {
        Extents {
            lo: [f64::INFINITY; 2],
            hi: [f64::NEG_INFINITY; 2],
        }
    }
}

impl Extents {
    fn point(&mut self, p: [f64; 2]) {
        self.lo = [self.lo[0].min(p[0]), self.lo[1].min(p[1])];
        self.hi = [self.hi[0].max(p[0]), self.hi[1].max(p[1])];
    }

    fn shape(&mut self, sh: &Shape) {
        match sh {
            Shape::Circle {
                center_mm: [x, y],
                radius_mm: r,
                ..
            } => {
                self.point([x - r, y - r]);
                self.point([x + r, y + r]);
            }
            Shape::Polyline {
                vertices, closed, ..
            } => {
                let n = vertices.len();
                for (i, a) in vertices.iter().enumerate() {
                    self.point([a.x_mm, a.y_mm]);
                    if a.bulge != 0.0 && (*closed || i + 1 < n) {
                        let b = vertices[(i + 1) % n];
                        self.arc_extremes(*a, b);
                    }
                }
            }
            Shape::Strokes { points_um, .. } => {
                for &[x, y] in points_um {
                    self.point([x as f64 * 1e-3, y as f64 * 1e-3]);
                }
            }
        }
    }

    /// The axis-extreme points of the arc from `a` to `b` (`a`'s bulge).
    fn arc_extremes(&mut self, a: Vertex, b: Vertex) {
        let Some(arc) = super::arcs::BulgeArc::of(a, b) else {
            return;
        };
        for k in 0..4 {
            let phi = k as f64 * std::f64::consts::FRAC_PI_2;
            if arc.contains_angle(phi) {
                self.point([
                    arc.center[0] + arc.radius * phi.cos(),
                    arc.center[1] + arc.radius * phi.sin(),
                ]);
            }
        }
    }

    fn corners(&self) -> ([f64; 2], [f64; 2]) {
        if self.lo[0] > self.hi[0] {
            ([0.0; 2], [0.0; 2])
        } else {
            (self.lo, self.hi)
        }
    }
}

/// A group code and its value line.
fn g(s: &mut Vec<u8>, code: u16, value: &str) {
    let c = code.to_string();
    for _ in c.len()..3 {
        s.push(b' ');
    }
    s.extend_from_slice(c.as_bytes());
    s.push(b'\n');
    s.extend_from_slice(value.as_bytes());
    s.push(b'\n');
}

/// A group code and a handle (upper-case hexadecimal).
fn gh(s: &mut Vec<u8>, code: u16, handle: u64) {
    g(s, code, &format!("{handle:X}"));
}

/// A group code and a number (up to [`COORD_DECIMALS`], at least one).
fn gf(s: &mut Vec<u8>, code: u16, x: f64) {
    let mut t = String::new();
    crate::formats::text::push_decimal_str(&mut t, x, COORD_DECIMALS, true);
    g(s, code, &t);
}

/// A point's group codes (`code`, `code + 10`, `code + 20`).
fn gp(s: &mut Vec<u8>, code: u16, p: [f64; 2], z: bool) {
    gf(s, code, p[0]);
    gf(s, code + 10, p[1]);
    if z {
        gf(s, code + 20, 0.0);
    }
}

fn section(s: &mut Vec<u8>, name: &str) {
    g(s, 0, "SECTION");
    g(s, 2, name);
}

fn endsec(s: &mut Vec<u8>) {
    g(s, 0, "ENDSEC");
}

fn var(s: &mut Vec<u8>, name: &str) {
    g(s, 9, name);
}

/// The HEADER section; `note` (a nested sheet's id, material and
/// thickness) as `$PROJECTNAME`, ASCII with anything else as DXF's
/// `\U+XXXX`.
fn header(
    s: &mut Vec<u8>,
    seed: u64,
    lo: [f64; 2],
    hi: [f64; 2],
    sheet_mm: [f64; 2],
    note: Option<String>,
) {
    section(s, "HEADER");
    var(s, "$ACADVER");
    g(s, 1, "AC1015");
    var(s, "$ACADMAINTVER");
    g(s, 70, "6");
    var(s, "$DWGCODEPAGE");
    g(s, 3, "ANSI_1252");
    var(s, "$INSBASE");
    gp(s, 10, [0.0, 0.0], true);
    var(s, "$EXTMIN");
    gp(s, 10, lo, true);
    var(s, "$EXTMAX");
    gp(s, 10, hi, true);
    var(s, "$LIMMIN");
    gp(s, 10, [0.0, 0.0], false);
    var(s, "$LIMMAX");
    gp(s, 10, sheet_mm, false);
    var(s, "$CLAYER");
    g(s, 8, "0");
    var(s, "$CELTYPE");
    g(s, 6, "ByLayer");
    var(s, "$TEXTSTYLE");
    g(s, 7, "Standard");
    var(s, "$DIMSTYLE");
    g(s, 2, "Standard");
    var(s, "$LUNITS");
    g(s, 70, "2");
    var(s, "$LUPREC");
    g(s, 70, "4");
    var(s, "$HANDSEED");
    gh(s, 5, seed);
    var(s, "$INSUNITS");
    g(s, 70, "4");
    var(s, "$MEASUREMENT");
    g(s, 70, "1");
    if let Some(note) = note {
        let mut text = String::with_capacity(note.len());
        for c in note.chars() {
            if c.is_ascii() && !c.is_ascii_control() {
                text.push(c);
            } else {
                text += &format!("\\U+{:04X}", c as u32);
            }
        }
        var(s, "$PROJECTNAME");
        g(s, 1, &text);
    }
    endsec(s);
}

/// CLASSES, TABLES and BLOCKS.
fn structure(s: &mut Vec<u8>, lo: [f64; 2], hi: [f64; 2]) {
    section(s, "CLASSES");
    for (name, cpp) in [
        ("ACDBDICTIONARYWDFLT", "AcDbDictionaryWithDefault"),
        ("ACDBPLACEHOLDER", "AcDbPlaceHolder"),
        ("LAYOUT", "AcDbLayout"),
    ] {
        g(s, 0, "CLASS");
        g(s, 1, name);
        g(s, 2, cpp);
        g(s, 3, "ObjectDBX Classes");
        g(s, 90, "0");
        g(s, 280, "0");
        g(s, 281, "0");
    }
    endsec(s);

    section(s, "TABLES");
    // VPORT: the active view shows the extents.
    table(s, "VPORT", h::VPORT_TABLE, 1);
    record(
        s,
        "VPORT",
        h::VPORT_ACTIVE,
        h::VPORT_TABLE,
        "AcDbViewportTableRecord",
    );
    g(s, 2, "*Active");
    g(s, 70, "0");
    gp(s, 10, [0.0, 0.0], false);
    gp(s, 11, [1.0, 1.0], false);
    gp(s, 12, [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])], false);
    gp(s, 13, [0.0, 0.0], false);
    gp(s, 14, [1.0, 1.0], false);
    gp(s, 15, [1.0, 1.0], false);
    gf(s, 16, 0.0);
    gf(s, 26, 0.0);
    gf(s, 36, 1.0);
    gf(s, 17, 0.0);
    gf(s, 27, 0.0);
    gf(s, 37, 0.0);
    let (w, ht) = ((hi[0] - lo[0]).max(1.0), (hi[1] - lo[1]).max(1.0));
    gf(s, 40, 1.1 * ht.max(w / 1.5));
    gf(s, 41, 1.5);
    gf(s, 42, 50.0);
    gf(s, 43, 0.0);
    gf(s, 44, 0.0);
    gf(s, 50, 0.0);
    gf(s, 51, 0.0);
    for (code, v) in [
        (71, "0"),
        (72, "100"),
        (73, "1"),
        (74, "3"),
        (75, "0"),
        (76, "0"),
        (77, "0"),
        (78, "0"),
    ] {
        g(s, code, v);
    }
    endtab(s);

    table(s, "LTYPE", h::LTYPE_TABLE, 3);
    for (name, handle) in [
        ("ByBlock", h::LTYPE_BYBLOCK),
        ("ByLayer", h::LTYPE_BYLAYER),
        ("Continuous", h::LTYPE_CONTINUOUS),
    ] {
        record(
            s,
            "LTYPE",
            handle,
            h::LTYPE_TABLE,
            "AcDbLinetypeTableRecord",
        );
        g(s, 2, name);
        g(s, 70, "0");
        g(
            s,
            3,
            if name == "Continuous" {
                "Solid line"
            } else {
                ""
            },
        );
        g(s, 72, "65");
        g(s, 73, "0");
        gf(s, 40, 0.0);
    }
    endtab(s);

    table(s, "LAYER", h::LAYER_TABLE, 1 + LAYERS.len());
    let layer = |s: &mut Vec<u8>, handle: u64, name: &str, aci: u8, plotted: bool| {
        record(s, "LAYER", handle, h::LAYER_TABLE, "AcDbLayerTableRecord");
        g(s, 2, name);
        g(s, 70, "0");
        g(s, 62, &aci.to_string());
        g(s, 6, "Continuous");
        if !plotted {
            g(s, 290, "0");
        }
        g(s, 370, "-3");
        gh(s, 390, h::PLOTSTYLE_NORMAL);
    };
    layer(s, h::LAYER_0, "0", 7, true);
    for (i, l) in LAYERS.iter().enumerate() {
        layer(
            s,
            h::LAYER_0 + 1 + i as u64,
            l.name(),
            l.aci(),
            *l != Layer::Sheet,
        );
    }
    endtab(s);

    table(s, "STYLE", h::STYLE_TABLE, 1);
    record(
        s,
        "STYLE",
        h::STYLE_STANDARD,
        h::STYLE_TABLE,
        "AcDbTextStyleTableRecord",
    );
    g(s, 2, "Standard");
    g(s, 70, "0");
    gf(s, 40, 0.0);
    gf(s, 41, 1.0);
    gf(s, 50, 0.0);
    g(s, 71, "0");
    gf(s, 42, 2.5);
    g(s, 3, "txt");
    g(s, 4, "");
    endtab(s);

    table(s, "VIEW", h::VIEW_TABLE, 0);
    endtab(s);
    table(s, "UCS", h::UCS_TABLE, 0);
    endtab(s);

    table(s, "APPID", h::APPID_TABLE, 1);
    record(
        s,
        "APPID",
        h::APPID_ACAD,
        h::APPID_TABLE,
        "AcDbRegAppTableRecord",
    );
    g(s, 2, "ACAD");
    g(s, 70, "0");
    endtab(s);

    table(s, "DIMSTYLE", h::DIMSTYLE_TABLE, 1);
    g(s, 100, "AcDbDimStyleTable");
    g(s, 0, "DIMSTYLE");
    gh(s, 105, h::DIMSTYLE_STANDARD);
    gh(s, 330, h::DIMSTYLE_TABLE);
    g(s, 100, "AcDbSymbolTableRecord");
    g(s, 100, "AcDbDimStyleTableRecord");
    g(s, 2, "Standard");
    g(s, 70, "0");
    endtab(s);

    table(s, "BLOCK_RECORD", h::BLOCK_RECORD_TABLE, 2);
    for (name, handle, layout) in [
        ("*Model_Space", h::MODEL_RECORD, h::MODEL_LAYOUT),
        ("*Paper_Space", h::PAPER_RECORD, h::PAPER_LAYOUT),
    ] {
        record(
            s,
            "BLOCK_RECORD",
            handle,
            h::BLOCK_RECORD_TABLE,
            "AcDbBlockTableRecord",
        );
        g(s, 2, name);
        gh(s, 340, layout);
    }
    endtab(s);
    endsec(s);

    section(s, "BLOCKS");
    for (name, record, begin, end, paper) in [
        (
            "*Model_Space",
            h::MODEL_RECORD,
            h::MODEL_BLOCK,
            h::MODEL_ENDBLK,
            false,
        ),
        (
            "*Paper_Space",
            h::PAPER_RECORD,
            h::PAPER_BLOCK,
            h::PAPER_ENDBLK,
            true,
        ),
    ] {
        g(s, 0, "BLOCK");
        gh(s, 5, begin);
        gh(s, 330, record);
        g(s, 100, "AcDbEntity");
        if paper {
            g(s, 67, "1");
        }
        g(s, 8, "0");
        g(s, 100, "AcDbBlockBegin");
        g(s, 2, name);
        g(s, 70, "0");
        gp(s, 10, [0.0, 0.0], true);
        g(s, 3, name);
        g(s, 1, "");
        g(s, 0, "ENDBLK");
        gh(s, 5, end);
        gh(s, 330, record);
        g(s, 100, "AcDbEntity");
        if paper {
            g(s, 67, "1");
        }
        g(s, 8, "0");
        g(s, 100, "AcDbBlockEnd");
    }
    endsec(s);
}

/// A table's head: handle, no owner, how many records follow.
fn table(s: &mut Vec<u8>, name: &str, handle: u64, count: usize) {
    g(s, 0, "TABLE");
    g(s, 2, name);
    gh(s, 5, handle);
    g(s, 330, "0");
    g(s, 100, "AcDbSymbolTable");
    g(s, 70, &count.to_string());
}

fn endtab(s: &mut Vec<u8>) {
    g(s, 0, "ENDTAB");
}

/// A table record's head: its handle, its table as owner, its subclasses.
fn record(s: &mut Vec<u8>, kind: &str, handle: u64, owner: u64, subclass: &str) {
    g(s, 0, kind);
    gh(s, 5, handle);
    gh(s, 330, owner);
    g(s, 100, "AcDbSymbolTableRecord");
    g(s, 100, subclass);
}

/// The OBJECTS section: the root dictionary, its groups, layouts and plot
/// styles.
fn objects(s: &mut Vec<u8>) {
    section(s, "OBJECTS");
    let dict = |s: &mut Vec<u8>, handle: u64, owner: u64, entries: &[(&str, u64)]| {
        g(s, 0, "DICTIONARY");
        gh(s, 5, handle);
        gh(s, 330, owner);
        g(s, 100, "AcDbDictionary");
        g(s, 281, "1");
        for (name, target) in entries {
            g(s, 3, name);
            gh(s, 350, *target);
        }
    };
    dict(
        s,
        h::ROOT_DICT,
        0,
        &[
            ("ACAD_GROUP", h::GROUP_DICT),
            ("ACAD_LAYOUT", h::LAYOUT_DICT),
            ("ACAD_PLOTSTYLENAME", h::PLOTSTYLE_DICT),
        ],
    );
    dict(s, h::GROUP_DICT, h::ROOT_DICT, &[]);
    dict(
        s,
        h::LAYOUT_DICT,
        h::ROOT_DICT,
        &[("Layout1", h::PAPER_LAYOUT), ("Model", h::MODEL_LAYOUT)],
    );
    g(s, 0, "ACDBDICTIONARYWDFLT");
    gh(s, 5, h::PLOTSTYLE_DICT);
    gh(s, 330, h::ROOT_DICT);
    g(s, 100, "AcDbDictionary");
    g(s, 281, "1");
    g(s, 3, "Normal");
    gh(s, 350, h::PLOTSTYLE_NORMAL);
    g(s, 100, "AcDbDictionaryWithDefault");
    gh(s, 340, h::PLOTSTYLE_NORMAL);
    g(s, 0, "ACDBPLACEHOLDER");
    gh(s, 5, h::PLOTSTYLE_NORMAL);
    gh(s, 330, h::PLOTSTYLE_DICT);
    for (name, handle, record, tab) in [
        ("Model", h::MODEL_LAYOUT, h::MODEL_RECORD, 0),
        ("Layout1", h::PAPER_LAYOUT, h::PAPER_RECORD, 1),
    ] {
        g(s, 0, "LAYOUT");
        gh(s, 5, handle);
        gh(s, 330, h::LAYOUT_DICT);
        g(s, 100, "AcDbPlotSettings");
        g(s, 1, "");
        g(s, 4, "");
        g(s, 6, "");
        for code in [40, 41, 42, 43, 44, 45, 46, 47, 48, 49, 140, 141] {
            gf(s, code, 0.0);
        }
        gf(s, 142, 1.0);
        gf(s, 143, 1.0);
        g(s, 70, if tab == 0 { "1024" } else { "0" });
        g(s, 72, "1");
        g(s, 73, "0");
        g(s, 74, "5");
        g(s, 7, "");
        g(s, 75, "16");
        gf(s, 147, 1.0);
        gf(s, 148, 0.0);
        gf(s, 149, 0.0);
        g(s, 100, "AcDbLayout");
        g(s, 1, name);
        g(s, 70, "1");
        g(s, 71, &tab.to_string());
        gp(s, 10, [0.0, 0.0], false);
        gp(s, 11, [420.0, 297.0], false);
        gp(s, 12, [0.0, 0.0], true);
        gp(s, 14, [0.0, 0.0], true);
        gp(s, 15, [0.0, 0.0], true);
        gf(s, 146, 0.0);
        gp(s, 13, [0.0, 0.0], true);
        gf(s, 16, 1.0);
        gf(s, 26, 0.0);
        gf(s, 36, 0.0);
        gf(s, 17, 0.0);
        gf(s, 27, 1.0);
        gf(s, 37, 0.0);
        g(s, 76, "0");
        gh(s, 330, record);
    }
    endsec(s);
}

/// The owner group of every entity: `*Model_Space`'s block record.
const OWNER: &[u8] = b"\n330\n1D\n100\nAcDbEntity\n  8\n";

/// One entity with its handle (a [`Shape::Strokes`]: one per stroke).
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
                polyline_head(s, *layer, false, stroke.len(), handle);
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
            s.extend_from_slice(OWNER);
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
    polyline_head(s, layer, closed, vertices.len(), handle);
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
fn polyline_head(s: &mut Vec<u8>, layer: Layer, closed: bool, vertices: usize, handle: &mut u64) {
    // Pieces pushed one by one: `write!`'s formatting machinery was a
    // tenth of writing the engraving's many short polylines.
    s.extend_from_slice(b"  0\nLWPOLYLINE\n  5\n");
    push_hex(s, *handle);
    s.extend_from_slice(OWNER);
    s.extend_from_slice(layer.name().as_bytes());
    s.extend_from_slice(b"\n100\nAcDbPolyline\n 90\n");
    crate::formats::text::push_scaled(s, false, vertices as u64, 0, false);
    s.extend_from_slice(if closed { b"\n 70\n1\n" } else { b"\n 70\n0\n" });
    *handle += 1;
}

#[cfg(test)]
mod tests {
    use super::*;

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

    /// An empty sheet's document: every handle (groups 5 and 105) unique
    /// and below `$HANDSEED`, every owner (330) and pointer (340, 350,
    /// 390) one of them or 0, every table head's count its records'.
    #[test]
    fn handles_owners_and_counts_hold_together() {
        let sheet = SheetDrawing {
            id: "S01".into(),
            number: 1,
            length_mm: 100.0,
            width_mm: 50.0,
            parts: Vec::new(),
            group: String::new(),
            stock_note: None,
        };
        let opts = SheetFileOptions {
            sheet_outline: true,
            labels: false,
        };
        let text = String::from_utf8(to_dxf(&sheet, opts).expect("dxf")).expect("ascii");
        let lines: Vec<&str> = text.lines().collect();
        let pairs: Vec<(u16, &str)> = lines
            .chunks(2)
            .map(|c| (c[0].trim().parse().expect("code"), c[1]))
            .collect();
        let hex = |v: &str| u64::from_str_radix(v, 16).expect("hex");
        let mut handles = std::collections::BTreeSet::new();
        for (k, (c, v)) in pairs.iter().enumerate() {
            // (The seed's own value is a group 5 too.)
            if (*c == 5 || *c == 105) && pairs[k - 1] != (9, "$HANDSEED") {
                assert!(handles.insert(hex(v)), "handle {v} twice");
            }
        }
        let seed = pairs
            .windows(2)
            .find(|w| w[0] == (9, "$HANDSEED"))
            .map(|w| hex(w[1].1))
            .expect("seed");
        assert!(handles.iter().all(|h| *h < seed));
        for (c, v) in &pairs {
            if matches!(c, 330 | 340 | 350 | 390) && *v != "0" {
                assert!(handles.contains(&hex(v)), "{c} -> {v} points nowhere");
            }
        }
        // Each table's count against the records up to its ENDTAB.
        let mut i = 0;
        let mut tables = 0;
        while i < pairs.len() {
            if pairs[i] == (0, "TABLE") {
                let name = pairs[i + 1].1;
                let count: usize = pairs[i + 1..]
                    .iter()
                    .find(|p| p.0 == 70)
                    .map(|p| p.1.parse().expect("count"))
                    .expect("count");
                let end = i + pairs[i..]
                    .iter()
                    .position(|p| *p == (0, "ENDTAB"))
                    .expect("end");
                let records = pairs[i + 1..end]
                    .iter()
                    .filter(|p| **p == (0, name))
                    .count();
                assert_eq!(records, count, "{name}");
                tables += 1;
                i = end;
            }
            i += 1;
        }
        assert_eq!(tables, 9);
        // The sheet outline, owned by the model space.
        assert!(text.contains("LWPOLYLINE\n  5\n30\n330\n1D\n100\nAcDbEntity\n  8\nSHEET\n"));
        assert!(text.ends_with("  0\nEOF\n"));
    }

    /// A half circle of radius 5 from (0, 0) to (10, 0), counter-clockwise
    /// (bulge 1): below the chord, so the extents reach y = −5.
    #[test]
    fn extents_hold_the_arcs() {
        let v = |x_mm, bulge| Vertex {
            x_mm,
            y_mm: 0.0,
            bulge,
        };
        let mut e = Extents::default();
        e.shape(&Shape::Polyline {
            layer: Layer::CutOuter,
            closed: true,
            vertices: vec![v(0.0, 1.0), v(10.0, 0.0)],
        });
        let (lo, hi) = e.corners();
        assert!((lo[1] + 5.0).abs() < 1e-12, "{lo:?}");
        assert_eq!(lo[0], 0.0);
        assert!(hi[0] == 10.0 && hi[1].abs() < 1e-12, "{hi:?}");
    }
}
