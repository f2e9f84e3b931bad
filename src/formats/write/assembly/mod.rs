//! `DIR/assembly.pdf`: the assembly sheets a workshop builds the grid from
//! (docs/fabrication.md "Assembly sheets"). Plain data in (the plan
//! with its parts and sheets, the takeoff, the curves' points), PDF bytes
//! out; vector drawings on landscape A3 or A4, every page titled with the
//! project, its section, its scale and "page i of N".
//!
//! Sections, in order (each starts on a new page):
//! * **cover**: project, network, profile, counts, the elastic verdict,
//!   takeoff totals, the legend of the engraved marks, contents;
//! * **overview**: plan and two elevations of the erected grid at one
//!   scale, strips coloured by utilisation (colour bar), labelled at both
//!   ends, nodes dotted, edge strips in black;
//!   then the node plan ([`nodeplan`]): every node's id in plan, tiled
//!   over pages at a standard scale where one page would not keep them
//!   legible;
//! * **assembly order**: which strips go down first and in which order
//!   the rest follow (interlocking: family A slots up, then B slotted in;
//!   two-level: lower level, studs, upper level; edge strips last);
//! * **joint sections** ([`joints`]): one section per kind of joint with
//!   its stack and dimensions;
//! * **strip sheets** ([`strips`]): every lamella flat at a stated scale,
//!   broken across rows, a new page for every strip;
//! * **schedules** ([`tables`]): nodes, the setting-out table (every
//!   node's position and normal), shear blocks, parts, stock and hardware;
//! * **sheets as nested** ([`nested`]): one stock sheet per page;
//! * **elastic check**: A and B strips by utilisation, governing first;
//! * **structure** ([`structure`], when built with a loads file): supports,
//!   loads and the verdict, the deformed shape, utilisation by colour, the
//!   first buckling mode, the reactions.
//!
//! Only the built-in Helvetica is used (no font embedded): text is
//! WinAnsi, mapped by [`canvas::winansi`]. The file around the pages is
//! written by [`pdf`]. The bytes are deterministic: the dates are fixed at
//! the epoch and the trailer's `/ID` is derived from the document's content.

pub mod canvas;
pub mod joints;
pub mod nested;
pub mod nodeplan;
pub mod overview;
pub mod pdf;
pub mod strips;
pub mod structure;
pub mod tables;

use crate::error::{Error, Result};
use crate::plan::Plan;
use canvas::{Align, Canvas, BLACK, GREY};
use rayon::prelude::*;
use std::path::Path;

/// Paper size (always landscape).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Paper {
    /// 420 × 297 mm.
    #[default]
    A3,
    /// 297 × 210 mm.
    A4,
}

impl Paper {
    /// Width and height, landscape, mm.
    pub fn size_mm(self) -> (f64, f64) {
        match self {
            Paper::A3 => (420.0, 297.0),
            Paper::A4 => (297.0, 210.0),
        }
    }

    /// `A3` or `A4`.
    pub fn name(self) -> &'static str {
        match self {
            Paper::A3 => "A3",
            Paper::A4 => "A4",
        }
    }

    /// `a3` or `a4` (either case).
    pub fn parse(s: &str) -> Option<Paper> {
        match s.to_ascii_lowercase().as_str() {
            "a3" => Some(Paper::A3),
            "a4" => Some(Paper::A4),
            _ => None,
        }
    }
}

/// What the assembly sheets are drawn from.
#[derive(Debug, Clone, Copy)]
pub struct AssemblyInput<'a> {
    /// The plan with its parts and sheets (`lamella build`'s plan.json).
    pub plan: &'a Plan,
    /// Paper size.
    pub paper: Paper,
    /// Names the plan in errors.
    pub plan_path: &'a Path,
}

/// Page margin, mm.
pub const MARGIN_MM: f64 = 10.0;
/// Height of the title block at the foot of every page, mm.
pub const TITLE_BLOCK_MM: f64 = 10.0;
/// Height of the section heading at the top of every page, mm.
pub const HEADING_MM: f64 = 8.0;

/// The drawable area of a page, mm: below the heading, above the title block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Page width, mm.
    pub page_w_mm: f64,
    /// Page height, mm.
    pub page_h_mm: f64,
    /// Left edge of the content, mm.
    pub x0_mm: f64,
    /// Right edge of the content, mm.
    pub x1_mm: f64,
    /// Bottom of the content, mm.
    pub y0_mm: f64,
    /// Top of the content, mm.
    pub y1_mm: f64,
}

impl Frame {
    /// The frame of a page of `paper`.
    pub fn of(paper: Paper) -> Frame {
        let (w, h) = paper.size_mm();
        Frame {
            page_w_mm: w,
            page_h_mm: h,
            x0_mm: MARGIN_MM,
            x1_mm: w - MARGIN_MM,
            y0_mm: MARGIN_MM + TITLE_BLOCK_MM + 2.0,
            y1_mm: h - MARGIN_MM - HEADING_MM,
        }
    }

    /// Content width, mm.
    pub fn width_mm(&self) -> f64 {
        self.x1_mm - self.x0_mm
    }

    /// Content height, mm.
    pub fn height_mm(&self) -> f64 {
        self.y1_mm - self.y0_mm
    }
}

/// One page before numbering: its section, its heading, its scale and
/// what is drawn on it.
#[derive(Debug)]
pub struct Page {
    /// The section (`Strip sheets`, …), also in the title block.
    pub section: &'static str,
    /// The heading at the top (the section and what this page holds).
    pub heading: String,
    /// The drawing scale `1:n`, or `None` (not to scale).
    pub scale: Option<u32>,
    /// The drawing.
    pub canvas: Canvas,
}

impl Page {
    /// An empty page.
    pub fn new(section: &'static str, heading: impl Into<String>, scale: Option<u32>) -> Page {
        Page {
            section,
            heading: heading.into(),
            scale,
            canvas: Canvas::new(),
        }
    }
}

/// A page drawn and compressed, waiting for its number: its drawing is
/// one content stream (FlateDecode) wrapped in `q … Q`, so the heading and
/// title block written after it as a second stream start from the default
/// graphics state. Pages are sealed as they are drawn, so a big kit's
/// drawings are never all held uncompressed at once.
#[derive(Debug)]
pub struct SealedPage {
    /// The section (`Strip sheets`, …), also in the title block.
    pub section: &'static str,
    /// The heading at the top.
    pub heading: String,
    /// The drawing scale `1:n`, or `None` (not to scale).
    pub scale: Option<u32>,
    /// The drawing's content stream, zlib-compressed.
    pub body_deflated: Vec<u8>,
}

impl Page {
    /// The page with its drawing compressed (see [`SealedPage`]).
    pub fn seal(self) -> SealedPage {
        let content = self.canvas.into_content();
        let mut wrapped = Vec::with_capacity(content.len() + 4);
        wrapped.extend_from_slice(b"q\n");
        wrapped.extend_from_slice(&content);
        wrapped.extend_from_slice(b"Q\n");
        SealedPage {
            section: self.section,
            heading: self.heading,
            scale: self.scale,
            body_deflated: deflate(&wrapped),
        }
    }
}

/// The section names, in the document's order.
pub const SECTIONS: [&str; 12] = [
    "Cover",
    "Overview",
    "Assembly order",
    "Joint sections",
    "Strip sheets",
    "Node schedule",
    "Setting out",
    "Shear blocks",
    "Parts, stock and hardware",
    "Sheets as nested",
    "Elastic check",
    structure::SECTION,
];

/// The PDF of the assembly sheets.
pub fn assembly_pdf(input: &AssemblyInput) -> Result<Vec<u8>> {
    assembly_pdf_counted(input).map(|(bytes, _)| bytes)
}

/// [`assembly_pdf`] and its page count.
pub fn assembly_pdf_counted(input: &AssemblyInput) -> Result<(Vec<u8>, usize)> {
    let frame = Frame::of(input.paper);
    let (sections, nested) = rayon::join(
        || sections(input),
        || nested::pages(input.plan, &frame, input.plan_path),
    );
    Ok(assemble(input, sections?, nested?))
}

/// Every section but the sheets as nested, drawn and sealed: `lamella
/// build` draws each stock sheet once for its cutting files and its page
/// ([`nested::page`]), and [`assemble`] puts the two together.
#[derive(Debug)]
pub struct Sections {
    overview: Vec<SealedPage>,
    order: Vec<SealedPage>,
    joints: Vec<SealedPage>,
    strips: Vec<SealedPage>,
    nodes: Vec<SealedPage>,
    setting_out: Vec<SealedPage>,
    blocks: Vec<SealedPage>,
    takeoff: SealedPage,
    check: Vec<SealedPage>,
    structure: Vec<SealedPage>,
}

impl Sections {
    /// Every section after the cover in the document's order ([`SECTIONS`]),
    /// with the sheets as nested (`nested`) before the elastic check.
    fn in_order(self, nested: Vec<SealedPage>) -> Vec<Vec<SealedPage>> {
        vec![
            self.overview,
            self.order,
            self.joints,
            self.strips,
            self.nodes,
            self.setting_out,
            self.blocks,
            vec![self.takeoff],
            nested,
            self.check,
            self.structure,
        ]
    }
}

/// The sections of the assembly sheets other than the sheets as nested.
pub fn sections(input: &AssemblyInput) -> Result<Sections> {
    sections_with(input, None)
}

/// [`sections`], with the strip sheets already drawn when `strips` is
/// given ([`strips::pages_of`]).
pub fn sections_with(
    input: &AssemblyInput,
    strip_pages: Option<Vec<SealedPage>>,
) -> Result<Sections> {
    let plan = input.plan;
    let frame = Frame::of(input.paper);
    let (Some(_), Some(_)) = (&plan.parts, &plan.sheets) else {
        return Err(Error::output(
            input.plan_path,
            "the plan has no parts or no sheets: the assembly sheets need a built kit",
        ));
    };
    let Some(takeoff) = &plan.takeoff else {
        return Err(Error::output(
            input.plan_path,
            "the plan has no takeoff: the assembly sheets need a nested kit",
        ));
    };
    let seal =
        |pages: Vec<Page>| -> Vec<SealedPage> { pages.into_par_iter().map(Page::seal).collect() };
    // The heavy sections in parallel; each is deterministic on its own.
    let ((overview, order, joints), (strips, (nodes, blocks, takeoff, check))) = rayon::join(
        || {
            let mut order = tables::order_pages(plan, &frame);
            order.extend(overview::flat_page(plan, &frame));
            let mut overview = overview::pages(input, &frame);
            overview.extend(nodeplan::pages(plan, &frame));
            (
                seal(overview),
                seal(order),
                seal(joints::pages(plan, &frame)),
            )
        },
        || {
            rayon::join(
                || strip_pages.unwrap_or_else(|| strips::pages(plan, &frame)),
                || {
                    (
                        seal(tables::node_pages(plan, &frame)),
                        seal(tables::block_pages(plan, &frame)),
                        tables::takeoff_page(takeoff, &frame).seal(),
                        seal(tables::check_pages(plan, &frame)),
                    )
                },
            )
        },
    );
    let setting_out = seal(tables::setting_out_pages(plan, &frame));
    let structure = seal(structure::pages(plan, &frame));
    Ok(Sections {
        overview,
        order,
        joints,
        strips,
        nodes,
        setting_out,
        blocks,
        takeoff,
        check,
        structure,
    })
}

/// The document: the cover (with its contents) first, then the sections
/// with the sheets as nested (`nested`, in nest order) before the elastic
/// check; every page titled. Returns the PDF's bytes and its page count.
pub fn assemble(
    input: &AssemblyInput,
    sections: Sections,
    nested: Vec<SealedPage>,
) -> (Vec<u8>, usize) {
    let mut bytes = Vec::new();
    // Writing into a Vec cannot fail.
    let count = assemble_into(input, sections, nested, &mut bytes).unwrap_or(0);
    (bytes, count)
}

/// [`assemble`], streamed into `w` (a big kit's PDF is not held twice);
/// returns the page count.
pub fn assemble_into(
    input: &AssemblyInput,
    sections: Sections,
    nested: Vec<SealedPage>,
    w: &mut dyn std::io::Write,
) -> std::io::Result<usize> {
    let frame = Frame::of(input.paper);
    let sections = sections.in_order(nested);
    // Contents: the first page of every section (the cover is page 1).
    let mut first = Vec::new();
    let mut n = 2;
    for (name, s) in SECTIONS[1..].iter().zip(&sections) {
        if !s.is_empty() {
            first.push((*name, n, s.len()));
        }
        n += s.len();
    }
    let mut pages = vec![tables::cover_page(input, &frame, &first).seal()];
    pages.extend(sections.into_iter().flatten());
    let count = pages.len();
    write_pdf(input, pages, w)?;
    Ok(count)
}

/// Title every page (heading, title block, page i of N) and write the PDF.
fn write_pdf(
    input: &AssemblyInput,
    pages: Vec<SealedPage>,
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    let plan = input.plan;
    let frame = Frame::of(input.paper);
    let total = pages.len();
    let project = plan.network.name.clone();
    let profile = plan
        .profile
        .as_ref()
        .map(|p| p.name.clone())
        .unwrap_or_default();
    let (w, h) = input.paper.size_mm();
    // Each page's drawing and then its title (heading, title block, page i
    // of N), compressed, in parallel.
    let contents: Vec<pdf::PageStreams> = pages
        .into_par_iter()
        .enumerate()
        .map(|(i, page)| {
            let mut c = Canvas::new();
            title(
                &mut c,
                &page,
                &frame,
                &project,
                &profile,
                i + 1,
                total,
                input.paper,
            );
            pdf::PageStreams {
                body_deflated: page.body_deflated,
                heading_deflated: deflate(&c.into_content()),
            }
        })
        .collect();
    let title = canvas::winansi(&format!("{project}: assembly sheets"));
    let creator = format!("lamella {}", env!("CARGO_PKG_VERSION"));
    let id = stable_id(&project, total, plan.parts.as_ref().map_or(0, Vec::len));
    let info = pdf::DocInfo {
        title: &title,
        creator: &creator,
        id: id.as_bytes(),
    };
    pdf::write_document(out, w, h, &info, contents)
}

/// zlib-compressed bytes (FlateDecode), at the fastest level: at level 6
/// the assembly sheets of the 200 × 200 benchmark (3,012 pages) took 3.7 s
/// of CPU, at level 1 1.7 s, for a file 30 % larger (22.8 MiB, not 17.5).
/// flate2's zlib-rs backend (zlib-ng's quick strategy at level 1) takes
/// half the CPU of miniz_oxide's level 1 for a file about 18 % larger
/// (the 400 × 400 kit's: 110 MiB, not 93).
fn deflate(bytes: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut e = flate2::write::ZlibEncoder::new(
        Vec::with_capacity(bytes.len() / 4),
        flate2::Compression::new(1),
    );
    // Writing into a Vec cannot fail.
    let _ = e.write_all(bytes);
    e.finish().unwrap_or_default()
}

/// A 16-byte id (FNV-1a over what the document is of).
fn stable_id(project: &str, pages: usize, parts: usize) -> String {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for b in format!("{project}/{pages}/{parts}").bytes() {
        hash ^= u64::from(b);
        hash = hash.wrapping_mul(0x0100_0000_01b3);
    }
    let mut s = String::new();
    for h in [hash, hash.rotate_left(29) ^ 0x9e37_79b9_7f4a_7c15] {
        for b in h.to_be_bytes() {
            s.push(char::from(b'0' + b % 10));
        }
    }
    s
}

/// The heading and the title block.
#[allow(clippy::too_many_arguments)]
fn title(
    c: &mut Canvas,
    page: &SealedPage,
    frame: &Frame,
    project: &str,
    profile: &str,
    number: usize,
    total: usize,
    paper: Paper,
) {
    let (x0, x1) = (frame.x0_mm, frame.x1_mm);
    let top = frame.page_h_mm - MARGIN_MM;
    c.fill(BLACK);
    c.text([x0, top - 5.0], 12.0, true, Align::Left, 0.0, &page.heading);
    c.stroke(BLACK);
    c.width(0.3);
    c.line([x0, top - 7.0], [x1, top - 7.0]);
    let y = MARGIN_MM;
    c.width(0.3);
    c.rect(x0, y, x1 - x0, TITLE_BLOCK_MM, false, true);
    let scale = match page.scale {
        Some(n) => format!("scale 1:{n} ({})", paper.name()),
        None => format!("not to scale ({})", paper.name()),
    };
    let mid = 0.5 * (x0 + x1);
    c.text([x0 + 3.0, y + 3.5], 9.0, true, Align::Left, 0.0, project);
    let left_w = canvas::text_width_mm(&canvas::winansi(project), 9.0, true);
    c.fill(GREY);
    c.text(
        [x0 + 6.0 + left_w, y + 3.5],
        9.0,
        false,
        Align::Left,
        0.0,
        profile,
    );
    c.fill(BLACK);
    c.text(
        [mid, y + 3.5],
        9.0,
        false,
        Align::Center,
        0.0,
        &format!("{}  |  {scale}", page.section),
    );
    c.text(
        [x1 - 3.0, y + 3.5],
        9.0,
        true,
        Align::Right,
        0.0,
        &format!("page {number} of {total}"),
    );
}

/// Format a length in whole millimetres with thin grouping (`12 345`).
pub fn mm0(x: f64) -> String {
    let v = x.round() as i64;
    let (neg, mut n) = (v < 0, v.unsigned_abs());
    let mut groups = Vec::new();
    loop {
        groups.push(n % 1000);
        n /= 1000;
        if n == 0 {
            break;
        }
    }
    let mut s = String::new();
    if neg {
        s.push('-');
    }
    for (i, g) in groups.iter().rev().enumerate() {
        if i == 0 {
            s.push_str(&g.to_string());
        } else {
            s.push_str(&format!(" {g:03}"));
        }
    }
    s
}

/// `x` with `d` decimals.
pub fn fixed(x: f64, d: usize) -> String {
    let s = format!("{x:.d$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// The smallest standard scale denominator (1, 2, 2.5, 5 × 10^k, and
/// 1 upward) at or above `den`.
pub fn standard_scale(den: f64) -> u32 {
    let mut k = 1.0;
    loop {
        for m in [1.0, 2.0, 2.5, 5.0] {
            let s = m * k;
            if s >= den - 1e-9 && s.fract() == 0.0 {
                return s as u32;
            }
        }
        k *= 10.0;
        if k > 1e9 {
            return u32::MAX;
        }
    }
}

/// The colour of a utilisation: green at 0, yellow at 0.5, red at 1,
/// purple above.
pub fn utilisation_colour(u: f64) -> canvas::Rgb3 {
    if u > 1.0 {
        return [0.55, 0.0, 0.55];
    }
    let u = u.clamp(0.0, 1.0) as f32;
    if u < 0.5 {
        let t = u / 0.5;
        [0.1 + 0.8 * t, 0.6 + 0.15 * t, 0.1]
    } else {
        let t = (u - 0.5) / 0.5;
        [0.9, 0.75 * (1.0 - t), 0.1 * (1.0 - t)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_scales() {
        assert_eq!(standard_scale(1.0), 1);
        assert_eq!(standard_scale(3.0), 5);
        assert_eq!(standard_scale(11.0), 20);
        assert_eq!(standard_scale(21.0), 25);
        assert_eq!(standard_scale(26.0), 50);
        assert_eq!(standard_scale(101.0), 200);
    }

    #[test]
    fn millimetres_grouped() {
        assert_eq!(mm0(12345.4), "12 345");
        assert_eq!(mm0(-25.0), "-25");
        assert_eq!(mm0(1000.0), "1 000");
        assert_eq!(fixed(-0.0001, 2), "0.00");
    }
}
