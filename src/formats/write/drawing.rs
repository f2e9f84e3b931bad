//! Sheet drawings: every placed part of a nest in sheet coordinates, sorted
//! by operation. Plain data in (a [`Plan`] with `parts` and `sheets`), plain
//! data out ([`SheetDrawing`]); the DXF and SVG writers only format it.
//!
//! The drawing is made from plan.json's own (rounded) numbers, so a reader
//! can hold every cutting file to plan.json exactly: a part's outline, holes
//! and engraving are turned by the placement's quarter turn about the part
//! origin (exact: coordinates are swapped and negated, no cosines), then
//! moved by its translation. The engraving's strokes are its texts and marks
//! set in plan.json's `engraving_font`, and once placed on the sheet are
//! rounded to [`ENGRAVE_DECIMALS`] decimals (1 µm, far below any engraving
//! tool's resolution; the cuts keep every decimal of plan.json).
//!
//! Per part: inner contours (the round holes, its `hole` features, as
//! circles in feature order, then the other inner contours as closed
//! polylines), the outer contour, the engraving (open polylines). The
//! parts of a sheet are in travel order ([`travel_order`]: rows along the
//! sheet's length, alternating direction), and the files write a sheet in
//! cutting order ([`cut_order`]): all engraving, then all inner contours,
//! then all outlines, so a part is marked before anything is cut and cut
//! free only once its inner contours are done. Consecutive points closer
//! than [`MERGE_MM`] are merged so no segment has zero length; cut
//! contours are fitted by lines and arcs within the drawer's tolerance
//! ([`super::arcs`]). With kerf compensation, outer contours are offset
//! out and inner contours in by half the kerf of the sheet's (or part's)
//! stock group ([`Kerf`]; cavalier_contours, round joins: convex corners
//! become arcs, written as bulges).

use crate::error::{Error, Result};
use crate::plan::{
    Plan, PlanEngraving, PlanFeatureKind, PlanFont, PlanGlyph, PlanPart, PlanPlacement, PlanSheet,
};
use cavalier_contours::polyline::{PlineCreation, PlineSource, PlineSourceMut, Polyline};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// Points of a contour closer than this are one point, mm.
pub const MERGE_MM: f64 = 1e-6;

/// Decimals of the engraving's sheet coordinates (1 µm).
pub const ENGRAVE_DECIMALS: i32 = 3;

/// `x` mm on the engraving grid, in its units (µm).
pub fn engrave_units(x: f64) -> i64 {
    crate::formats::text::round_to_i64(x * 10f64.powi(ENGRAVE_DECIMALS))
}

/// A point of the engraving grid (units) in mm: the double nearest the
/// decimal, so writers print it exactly.
pub fn engrave_mm(units: i64) -> f64 {
    units as f64 / 10f64.powi(ENGRAVE_DECIMALS)
}

/// The operation a shape belongs to: a DXF layer, an SVG group.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Layer {
    /// The stock sheet's outline: reference only, not cut (written only
    /// when asked, on a non-plotting layer).
    Sheet,
    /// Holes and other inner contours: cut first.
    CutInner,
    /// Part outlines: cut last, once the part's inner contours are done.
    CutOuter,
    /// Single-stroke labels and marks: engraved, not cut through.
    Engrave,
}

impl Layer {
    /// Every layer, in cutting order after the reference layer `SHEET`:
    /// engraving, inner contours, outlines.
    pub const ALL: [Layer; 4] = [
        Layer::Sheet,
        Layer::Engrave,
        Layer::CutInner,
        Layer::CutOuter,
    ];

    /// The DXF layer name and SVG group id.
    pub fn name(self) -> &'static str {
        match self {
            Layer::Sheet => "SHEET",
            Layer::CutInner => "CUT-INNER",
            Layer::CutOuter => "CUT-OUTER",
            Layer::Engrave => "ENGRAVE",
        }
    }

    /// AutoCAD colour index: red outer cuts, green inner cuts, blue
    /// engraving, grey sheet (the colours laser software maps to operations).
    pub fn aci(self) -> u8 {
        match self {
            Layer::Sheet => 8,
            Layer::CutInner => 3,
            Layer::CutOuter => 1,
            Layer::Engrave => 5,
        }
    }

    /// The same colour as SVG writes it.
    pub fn rgb(self) -> &'static str {
        match self {
            Layer::Sheet => "#808080",
            Layer::CutInner => "#00ff00",
            Layer::CutOuter => "#ff0000",
            Layer::Engrave => "#0000ff",
        }
    }
}

/// What a cutting file holds beyond the cuts and the engraving.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SheetFileOptions {
    /// The stock sheet's outline, on the reference layer `SHEET` (off by
    /// default: CAM software that cuts every closed contour would cut it).
    pub sheet_outline: bool,
    /// The SVG's screen labels (each part's id as text over it; off by
    /// default: laser software imports text as something to engrave).
    pub labels: bool,
}

pub use super::arcs::Vertex;

/// One contour or mark.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A polyline; closed ones do not repeat their first vertex.
    Polyline {
        /// Its operation.
        layer: Layer,
        /// Closed contour (cut) or open stroke (engraving).
        closed: bool,
        /// At least two vertices (three when closed).
        vertices: Vec<Vertex>,
    },
    /// A round hole.
    Circle {
        /// Its operation.
        layer: Layer,
        /// Centre, sheet frame, mm.
        center_mm: [f64; 2],
        /// Radius, mm.
        radius_mm: f64,
    },
    /// Open polylines of one engraving (a text or a mark), kept together
    /// (one allocation, not one per stroke): stroke k is
    /// `points_um[ends[k − 1]..ends[k]]` (from 0 for the first), at least
    /// two distinct consecutive points each, straight segments. The points
    /// are on the engraving's grid ([`ENGRAVE_DECIMALS`]) and kept as whole
    /// micrometres, so the writers format integers.
    Strokes {
        /// Its operation.
        layer: Layer,
        /// Every stroke's points, one after the other, sheet frame, µm.
        points_um: Vec<[i64; 2]>,
        /// Where each stroke ends in `points_um`.
        ends: Vec<usize>,
    },
}

impl Shape {
    /// The operation it belongs to.
    pub fn layer(&self) -> Layer {
        match self {
            Shape::Polyline { layer, .. }
            | Shape::Circle { layer, .. }
            | Shape::Strokes { layer, .. } => *layer,
        }
    }
}

/// The strokes of a [`Shape::Strokes`]: its points split at its ends.
pub fn strokes<'a, T>(vertices: &'a [T], ends: &'a [usize]) -> impl Iterator<Item = &'a [T]> {
    ends.iter().scan(0, move |start, &end| {
        let s = &vertices[*start..end];
        *start = end;
        Some(s)
    })
}

/// One placed copy of a part.
#[derive(Debug, Clone, PartialEq)]
pub struct PartOnSheet {
    /// Part id.
    pub part: String,
    /// Which copy, from 0.
    pub copy: u32,
    /// The outline's bounding box on the sheet: [min x, min y, max x, max y], mm.
    pub bbox_mm: [f64; 4],
    /// Inner contours, the outer contour, then engraving.
    pub shapes: Vec<Shape>,
}

/// One stock sheet with everything cut from it.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetDrawing {
    /// The plan's sheet id (`S01`, …).
    pub id: String,
    /// 1-based position in the nest (file names: `sheet-001`).
    pub number: usize,
    /// Along the sheet's x, mm.
    pub length_mm: f64,
    /// Along the sheet's y, mm.
    pub width_mm: f64,
    /// Placed parts, in travel order ([`travel_order`]).
    pub parts: Vec<PartOnSheet>,
    /// A nested sheet's stock group (`lamella-1.5`; empty for a part's
    /// own file): its files are named by it.
    pub group: String,
    /// A nested sheet's material and thickness, as its DXF header and SVG
    /// title state them (`S355, 1.5 mm sheet, stock group lamella-1.5`).
    pub stock_note: Option<String>,
}

impl SheetDrawing {
    /// The sheet's outline (layer `SHEET`), counter-clockwise from the origin.
    pub fn outline(&self) -> Shape {
        let v = |x_mm, y_mm| Vertex {
            x_mm,
            y_mm,
            bulge: 0.0,
        };
        Shape::Polyline {
            layer: Layer::Sheet,
            closed: true,
            vertices: vec![
                v(0.0, 0.0),
                v(self.length_mm, 0.0),
                v(self.length_mm, self.width_mm),
                v(0.0, self.width_mm),
            ],
        }
    }

    /// The file stem: the stock group, then the sheet's number
    /// (`lamella-1.5-sheet-001`; `sheet-001` without a group).
    pub fn file_stem(&self) -> String {
        if self.group.is_empty() {
            format!("sheet-{:03}", self.number)
        } else {
            format!("{}-sheet-{:03}", self.group, self.number)
        }
    }
}

/// A part's file stem in `parts/`: its id, every character but ASCII
/// letters, digits, `-`, `_` and `.` as `_` (and a leading `.` too).
pub fn part_file_stem(id: &str) -> String {
    id.chars()
        .enumerate()
        .map(|(i, c)| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' || (c == '.' && i > 0) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Part-local (x, y) turned by a quarter-turn multiple counter-clockwise
/// about the origin, then moved by (tx, ty): the placement's map, exact.
pub fn place(p: [f64; 2], rotation_deg: u32, tx_mm: f64, ty_mm: f64) -> [f64; 2] {
    let [x, y] = p;
    let (rx, ry) = match rotation_deg % 360 {
        90 => (-y, x),
        180 => (-x, -y),
        270 => (y, -x),
        _ => (x, y),
    };
    [rx + tx_mm, ry + ty_mm]
}

/// Kerf compensation: the kerf each stock group is cut with (a sheet's
/// `group`, a part's `group` in plan.json), mm.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Kerf {
    /// The kerf of a sheet or part whose group is not listed (a plan
    /// without groups), mm.
    pub default_mm: f64,
    /// Each group's kerf by its name, mm.
    pub by_group_mm: BTreeMap<String, f64>,
}

impl Kerf {
    /// Half the kerf of `group`, mm: how far its contours move.
    pub fn half_mm(&self, group: &str) -> f64 {
        0.5 * self
            .by_group_mm
            .get(group)
            .copied()
            .unwrap_or(self.default_mm)
    }
}

/// Draws the sheets of a plan one at a time (a big kit's drawings need not
/// all be in memory at once).
#[derive(Debug)]
pub struct Drawer<'a> {
    sheets: &'a [PlanSheet],
    parts: &'a [PlanPart],
    by_id: HashMap<&'a str, &'a PlanPart>,
    font: Font<'a>,
    kerf: Option<Kerf>,
    arc_tolerance_mm: Option<f64>,
    plan_path: &'a Path,
}

impl<'a> Drawer<'a> {
    /// A drawer for `plan`'s sheets. `kerf_compensation`: offset outer
    /// contours out and inner contours in by half of each group's kerf.
    /// `plan_path` names the plan in errors.
    pub fn new(
        plan: &'a Plan,
        kerf_compensation: Option<Kerf>,
        plan_path: &'a Path,
    ) -> Result<Drawer<'a>> {
        let (Some(parts), Some(sheets)) = (&plan.parts, &plan.sheets) else {
            return Err(Error::output(
                plan_path,
                "the plan has no parts or no sheets: run the parts and nest stages first",
            ));
        };
        Ok(Drawer {
            sheets,
            parts,
            by_id: parts.iter().map(|p| (p.id.as_str(), p)).collect(),
            font: Font::new(plan.engraving_font.as_ref()),
            kerf: kerf_compensation,
            arc_tolerance_mm: Some(super::arcs::DEFAULT_TOLERANCE_MM),
            plan_path,
        })
    }

    /// Fit cut contours by lines and arcs within `tol_mm` (the default:
    /// [`super::arcs::DEFAULT_TOLERANCE_MM`]), or keep plan.json's
    /// polygons (`None`).
    pub fn arc_tolerance(mut self, tol_mm: Option<f64>) -> Drawer<'a> {
        self.arc_tolerance_mm = tol_mm;
        self
    }

    /// How many sheets.
    pub fn len(&self) -> usize {
        self.sheets.len()
    }

    /// Whether there are no sheets.
    pub fn is_empty(&self) -> bool {
        self.sheets.is_empty()
    }

    /// The drawing of sheet `i` (0-based).
    pub fn sheet(&self, i: usize) -> Result<SheetDrawing> {
        self.draw(i, true)
    }

    /// How many distinct parts.
    pub fn part_count(&self) -> usize {
        self.parts.len()
    }

    /// Distinct part `i` (plan.json's order) alone, in its own frame at
    /// the origin, unturned, with its engraving, on a "sheet" of its
    /// extent: its per-part cutting file. Its shapes are the nested
    /// copies' exactly, moved by their placements (the fit is made in the
    /// part's frame).
    pub fn part(&self, i: usize) -> Result<SheetDrawing> {
        let part = &self.parts[i];
        let at = PlanPlacement {
            part: part.id.clone(),
            copy: 0,
            x_mm: 0.0,
            y_mm: 0.0,
            rotation_deg: 0,
        };
        let placed = part_on_sheet(
            part,
            &at,
            self.half_kerf_mm(&part.group),
            self.arc_tolerance_mm,
            &self.font,
            true,
        )
        .map_err(|what| Error::output(self.plan_path, format!("part {}: {what}", part.id)))?;
        Ok(SheetDrawing {
            id: part.id.clone(),
            number: i + 1,
            length_mm: part.length_mm,
            width_mm: part.height_mm,
            parts: vec![placed],
            group: String::new(),
            stock_note: None,
        })
    }

    /// Half the kerf a contour of `group` moves by, if compensated.
    fn half_kerf_mm(&self, group: &str) -> Option<f64> {
        self.kerf.as_ref().map(|k| k.half_mm(group))
    }

    /// The drawing of sheet `i` (0-based) without the engraving: the cuts.
    pub fn sheet_cuts(&self, i: usize) -> Result<SheetDrawing> {
        self.draw(i, false)
    }

    fn draw(&self, i: usize, engraving: bool) -> Result<SheetDrawing> {
        let s = &self.sheets[i];
        let placed = s
            .placements
            .iter()
            .map(|pl| {
                let part = self.by_id.get(pl.part.as_str()).ok_or_else(|| {
                    Error::output(
                        self.plan_path,
                        format!(
                            "sheet {}: part {} is not in the plan's parts",
                            s.id, pl.part
                        ),
                    )
                })?;
                part_on_sheet(
                    part,
                    pl,
                    self.half_kerf_mm(&s.group),
                    self.arc_tolerance_mm,
                    &self.font,
                    engraving,
                )
                .map_err(|what| {
                    Error::output(
                        self.plan_path,
                        format!("sheet {}: part {} copy {}: {what}", s.id, pl.part, pl.copy),
                    )
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let placed = travel_order(placed);
        Ok(SheetDrawing {
            id: s.id.clone(),
            number: i + 1,
            length_mm: s.length_mm,
            width_mm: s.width_mm,
            parts: placed,
            group: s.group.clone(),
            stock_note: (!s.group.is_empty()).then(|| {
                format!(
                    "{}, {} mm {}, stock group {}",
                    s.material, s.thickness_mm, s.form, s.group
                )
            }),
        })
    }
}

/// Every sheet of `plan` as a drawing (see [`Drawer::new`]).
pub fn sheet_drawings(
    plan: &Plan,
    kerf_compensation: Option<Kerf>,
    plan_path: &Path,
) -> Result<Vec<SheetDrawing>> {
    let d = Drawer::new(plan, kerf_compensation, plan_path)?;
    (0..d.len()).map(|i| d.sheet(i)).collect()
}

/// The plan's engraving font, by character.
#[derive(Debug)]
struct Font<'a> {
    letter_spacing: f64,
    glyphs: HashMap<char, &'a PlanGlyph>,
    marks: HashMap<&'a str, &'a PlanGlyph>,
}

impl<'a> Font<'a> {
    fn new(font: Option<&'a PlanFont>) -> Font<'a> {
        let Some(f) = font else {
            return Font {
                letter_spacing: 0.0,
                glyphs: HashMap::new(),
                marks: HashMap::new(),
            };
        };
        Font {
            letter_spacing: f.letter_spacing,
            glyphs: f
                .glyphs
                .iter()
                .filter_map(|(k, g)| {
                    let mut cs = k.chars();
                    match (cs.next(), cs.next()) {
                        (Some(c), None) => Some((c, g)),
                        _ => None,
                    }
                })
                .collect(),
            marks: f.marks.iter().map(|(k, g)| (k.as_str(), g)).collect(),
        }
    }

    /// Calls `stroke` with the part-frame points of every stroke of `e`
    /// (plan.json's rule: `at` + height × (x_k + gx, gy)).
    fn strokes(
        &self,
        e: &PlanEngraving,
        mut stroke: impl FnMut(&mut dyn Iterator<Item = [f64; 2]>),
    ) -> std::result::Result<(), String> {
        let ([ax, ay], h) = (e.at_mm, e.height_mm);
        match (&e.text, &e.mark) {
            (Some(text), None) => {
                let mut x = 0.0;
                for c in text.chars() {
                    let g = self.glyphs.get(&c).ok_or_else(|| {
                        format!("engraving {text:?}: the engraving font has no glyph for {c:?}")
                    })?;
                    for s in &g.strokes {
                        stroke(&mut s.iter().map(|q| [ax + (x + q[0]) * h, ay + q[1] * h]));
                    }
                    x += g.width + self.letter_spacing;
                }
                Ok(())
            }
            (None, Some(mark)) => {
                let g = self
                    .marks
                    .get(mark.as_ref())
                    .ok_or_else(|| format!("the engraving font has no mark {mark:?}"))?;
                for s in &g.strokes {
                    stroke(&mut s.iter().map(|q| [ax + q[0] * h, ay + q[1] * h]));
                }
                Ok(())
            }
            _ => Err("an engraving is neither a text nor a mark".into()),
        }
    }
}

/// One placed part's shapes; the error is what is wrong with it.
fn part_on_sheet(
    part: &PlanPart,
    pl: &PlanPlacement,
    half_kerf_mm: Option<f64>,
    tol_mm: Option<f64>,
    font: &Font,
    engraving: bool,
) -> std::result::Result<PartOnSheet, String> {
    if !matches!(pl.rotation_deg, 0 | 90 | 180 | 270) {
        return Err(format!(
            "rotation {}° is not a quarter turn",
            pl.rotation_deg
        ));
    }
    let map = |p: &[f64; 2]| place(*p, pl.rotation_deg, pl.x_mm, pl.y_mm);
    let mut shapes = Vec::with_capacity(part.features.len() + part.holes.len() + 1);
    for f in part
        .features
        .iter()
        .filter(|f| f.kind == PlanFeatureKind::Hole)
    {
        let r = 0.5 * f.width_mm;
        let radius_mm = r - half_kerf_mm.unwrap_or(0.0);
        if radius_mm <= MERGE_MM {
            return Err(format!(
                "a {:.3} mm hole closes up under kerf compensation",
                2.0 * r
            ));
        }
        shapes.push(Shape::Circle {
            layer: Layer::CutInner,
            center_mm: map(&f.center_mm),
            radius_mm,
        });
    }
    for hole in &part.holes {
        shapes.push(contour(
            Layer::CutInner,
            hole.clone(),
            &map,
            half_kerf_mm,
            tol_mm,
        )?);
    }
    let outline: Vec<[f64; 2]> = part.outline.iter().map(map).collect();
    let mut bbox_mm = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for p in &outline {
        bbox_mm = [
            bbox_mm[0].min(p[0]),
            bbox_mm[1].min(p[1]),
            bbox_mm[2].max(p[0]),
            bbox_mm[3].max(p[1]),
        ];
    }
    shapes.push(contour(
        Layer::CutOuter,
        part.outline.clone(),
        &map,
        half_kerf_mm,
        tol_mm,
    )?);
    for e in part.engraving.iter().filter(|_| engraving) {
        let mut points_um: Vec<[i64; 2]> = Vec::new();
        let mut ends: Vec<usize> = Vec::new();
        font.strokes(e, |points| {
            // Placed, on the grid, consecutive equal points merged (grid
            // points apart are 1 µm apart, far more than `MERGE_MM`); a
            // stroke left with one point is dropped.
            let start = points_um.len();
            for p in points {
                let [x, y] = map(&p);
                let q = [engrave_units(x), engrave_units(y)];
                if points_um.len() == start || points_um[points_um.len() - 1] != q {
                    points_um.push(q);
                }
            }
            if points_um.len() - start >= 2 {
                ends.push(points_um.len());
            } else {
                points_um.truncate(start);
            }
        })?;
        if !ends.is_empty() {
            shapes.push(Shape::Strokes {
                layer: Layer::Engrave,
                points_um,
                ends,
            });
        }
    }
    Ok(PartOnSheet {
        part: part.id.clone(),
        copy: pl.copy,
        bbox_mm,
        shapes,
    })
}

/// Parts in travel order: of three orders, the one whose path from box
/// middle to box middle is shortest (the first on a tie): the nest's
/// own; rows (each row the parts whose box middle lies within the box of
/// its lowest-middled part, as lamellas share a lane) from y = 0 up, each
/// along x, alternating direction, so the head snakes along the lanes;
/// and nearest next from the sheet's origin.
pub fn travel_order(parts: Vec<PartOnSheet>) -> Vec<PartOnSheet> {
    let n = parts.len();
    let mid = |p: &PartOnSheet| {
        [
            0.5 * (p.bbox_mm[0] + p.bbox_mm[2]),
            0.5 * (p.bbox_mm[1] + p.bbox_mm[3]),
        ]
    };
    let mids: Vec<[f64; 2]> = parts.iter().map(mid).collect();
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let path =
        |order: &[usize]| -> f64 { order.windows(2).map(|w| dist(mids[w[0]], mids[w[1]])).sum() };
    let tie = |a: usize, b: usize| {
        parts[a]
            .part
            .cmp(&parts[b].part)
            .then(parts[a].copy.cmp(&parts[b].copy))
    };
    // Rows along the lanes.
    let mut by_y: Vec<usize> = (0..n).collect();
    by_y.sort_by(|&a, &b| {
        mids[a][1]
            .total_cmp(&mids[b][1])
            .then(mids[a][0].total_cmp(&mids[b][0]))
            .then(tie(a, b))
    });
    let mut rows = Vec::with_capacity(n);
    let mut k = 0;
    let mut forward = true;
    while k < n {
        let top = parts[by_y[k]].bbox_mm[3];
        let mut end = k + 1;
        while end < n && mids[by_y[end]][1] <= top {
            end += 1;
        }
        let mut row = by_y[k..end].to_vec();
        row.sort_by(|&a, &b| {
            let o = mids[a][0].total_cmp(&mids[b][0]);
            if forward { o } else { o.reverse() }.then(tie(a, b))
        });
        rows.extend(row);
        forward = !forward;
        k = end;
    }
    // Nearest next, from the origin.
    let mut left: Vec<usize> = (0..n).collect();
    let mut nearest = Vec::with_capacity(n);
    let mut at = [0.0, 0.0];
    while !left.is_empty() {
        let (i, _) = left
            .iter()
            .enumerate()
            .min_by(|x, y| {
                dist(at, mids[*x.1])
                    .total_cmp(&dist(at, mids[*y.1]))
                    .then(tie(*x.1, *y.1))
            })
            .unwrap_or((0, &0));
        let p = left.swap_remove(i);
        at = mids[p];
        nearest.push(p);
    }
    let nest: Vec<usize> = (0..n).collect();
    let mut best = nest;
    for order in [rows, nearest] {
        if path(&order) < path(&best) {
            best = order;
        }
    }
    let mut slots: Vec<Option<PartOnSheet>> = parts.into_iter().map(Some).collect();
    best.into_iter().filter_map(|i| slots[i].take()).collect()
}

/// A sheet's shapes in cutting order: every part's engraving, then every
/// part's inner contours, then every part's outline, parts in travel order
/// each time (the sheet's outline is not among them).
pub fn cut_order(sheet: &SheetDrawing) -> impl Iterator<Item = &Shape> {
    [Layer::Engrave, Layer::CutInner, Layer::CutOuter]
        .into_iter()
        .flat_map(move |layer| {
            sheet
                .parts
                .iter()
                .flat_map(move |p| p.shapes.iter().filter(move |s| s.layer() == layer))
        })
}

/// Whether the vector (dx, dy) is at most `r_mm` long: compared squared
/// (`hypot` is a slow library call, and sheet coordinates are far from
/// overflowing a square). Differs from `hypot(dx, dy) <= r` only within an
/// ulp of `r`, never reached on plan.json's 0.1 µm grid against 1 µm.
pub(crate) fn within(dx: f64, dy: f64, r_mm: f64) -> bool {
    dx * dx + dy * dy <= r_mm * r_mm
}

/// A closed cut contour (part frame, placed by `map`), offset outward (outline, counter-clockwise) or
/// inward into its hole (holes, clockwise) by half the kerf when asked: both
/// are to the right of the direction of travel.
fn contour(
    layer: Layer,
    points: Vec<[f64; 2]>,
    map: &dyn Fn(&[f64; 2]) -> [f64; 2],
    half_kerf_mm: Option<f64>,
    tol_mm: Option<f64>,
) -> std::result::Result<Shape, String> {
    let points = merged(points, true);
    if points.len() < 3 {
        return Err(format!(
            "a {} contour has fewer than three distinct points",
            layer.name()
        ));
    }
    // Fitted in the part's frame, then placed (a quarter turn keeps every
    // bulge): every copy, and the part's own file, gets the same fit.
    let fitted: Vec<Vertex> = match tol_mm {
        Some(tol) if tol > 0.0 => super::arcs::fit_closed(&points, tol),
        _ => straight(&points),
    }
    .into_iter()
    .map(|v| {
        let [x_mm, y_mm] = map(&[v.x_mm, v.y_mm]);
        Vertex {
            x_mm,
            y_mm,
            bulge: v.bulge,
        }
    })
    .collect();
    // Fitted contours keep no segment under the fit's shortest.
    let shortest_mm = match tol_mm {
        Some(tol) if tol > 0.0 => super::arcs::MIN_SEGMENT_MM,
        _ => MERGE_MM,
    };
    let vertices = match half_kerf_mm {
        None | Some(0.0) => fitted,
        Some(d) => offset_right(&fitted, d, shortest_mm).ok_or_else(|| {
            format!(
                "its {} contour does not survive kerf compensation by {:.3} mm",
                layer.name(),
                d
            )
        })?,
    };
    Ok(Shape::Polyline {
        layer,
        closed: true,
        vertices,
    })
}

/// Straight-segment vertices.
fn straight(points: &[[f64; 2]]) -> Vec<Vertex> {
    points
        .iter()
        .map(|p| Vertex {
            x_mm: p[0],
            y_mm: p[1],
            bulge: 0.0,
        })
        .collect()
}

/// Drop points within [`MERGE_MM`] of the previous one (and, when closed,
/// a last point on the first).
fn merged(points: Vec<[f64; 2]>, closed: bool) -> Vec<[f64; 2]> {
    let close = |a: [f64; 2], b: [f64; 2]| within(a[0] - b[0], a[1] - b[1], MERGE_MM);
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(points.len());
    for p in points {
        if out.last().is_none_or(|&q| !close(p, q)) {
            out.push(p);
        }
    }
    while closed && out.len() > 1 && close(out[0], out[out.len() - 1]) {
        out.pop();
    }
    out
}

/// The closed polyline offset by `d_mm` to the right of its direction
/// (round joins), or `None` when it vanishes or splits.
fn offset_right(points: &[Vertex], d_mm: f64, shortest_mm: f64) -> Option<Vec<Vertex>> {
    let mut pl: Polyline<f64> = Polyline::with_capacity(points.len(), true);
    for p in points {
        pl.add(p.x_mm, p.y_mm, p.bulge);
    }
    let mut out = pl.parallel_offset(-d_mm);
    if out.len() != 1 {
        return None;
    }
    let off = out.pop()?;
    let mut v: Vec<Vertex> = off
        .iter_vertexes()
        .map(|q| Vertex {
            x_mm: q.x,
            y_mm: q.y,
            bulge: q.bulge,
        })
        .collect();
    // A vertex on the next one (within `shortest_mm`) starts a segment too
    // short to cut: drop it (the segment into it keeps its bulge and now
    // ends on the next vertex, moved by less than `shortest_mm`).
    let close = |a: &Vertex, b: &Vertex| within(a.x_mm - b.x_mm, a.y_mm - b.y_mm, shortest_mm);
    let mut i = 0;
    while v.len() > 2 && i < v.len() {
        let j = (i + 1) % v.len();
        if close(&v[i], &v[j]) {
            v.remove(i);
        } else {
            i += 1;
        }
    }
    (v.len() >= 2).then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_turns_are_exact() {
        assert_eq!(place([3.0, 1.0], 0, 10.0, 20.0), [13.0, 21.0]);
        assert_eq!(place([3.0, 1.0], 90, 10.0, 20.0), [9.0, 23.0]);
        assert_eq!(place([3.0, 1.0], 180, 10.0, 20.0), [7.0, 19.0]);
        assert_eq!(place([3.0, 1.0], 270, 10.0, 20.0), [11.0, 17.0]);
    }

    #[test]
    fn merging_removes_zero_length_segments() {
        let p = merged(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]],
            true,
        );
        assert_eq!(p, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]);
    }

    /// Offsetting a 100 × 20 rectangle out by 1 mm: straight sides 1 mm
    /// out and four quarter-circle corners of radius 1 (bulge tan(π/8)),
    /// area 100·20 + 2·(100 + 20)·1 + π·1².
    #[test]
    fn outer_offset_rounds_convex_corners() {
        let rect = [[0.0, 0.0], [100.0, 0.0], [100.0, 20.0], [0.0, 20.0]];
        let v = offset_right(&straight(&rect), 1.0, MERGE_MM).expect("offset");
        assert_eq!(v.len(), 8);
        let quarter = (std::f64::consts::PI / 8.0).tan();
        let arcs = v
            .iter()
            .filter(|q| (q.bulge - quarter).abs() < 1e-9)
            .count();
        assert_eq!(arcs, 4);
        let area = bulge_area(&v);
        let expected = 2000.0 + 240.0 + std::f64::consts::PI;
        assert!((area - expected).abs() < 1e-9, "{area} vs {expected}");
        // A clockwise hole shrinks: its area (negative) loses the ring.
        let hole: Vec<[f64; 2]> = rect.iter().rev().copied().collect();
        let h = offset_right(&straight(&hole), 1.0, MERGE_MM).expect("offset");
        assert!((bulge_area(&h) + 98.0 * 18.0).abs() < 1e-9);
    }

    /// Signed area of a polyline with bulges: the polygon of its vertices
    /// plus each arc's circular segment.
    fn bulge_area(v: &[Vertex]) -> f64 {
        let n = v.len();
        (0..n)
            .map(|i| {
                let (a, b) = (v[i], v[(i + 1) % n]);
                let chord = (b.x_mm - a.x_mm).hypot(b.y_mm - a.y_mm);
                let theta = 4.0 * a.bulge.atan();
                let seg = if a.bulge == 0.0 {
                    0.0
                } else {
                    let r = chord / (2.0 * (0.5 * theta).sin().abs());
                    0.5 * r * r * (theta.abs() - theta.abs().sin()) * theta.signum()
                };
                0.5 * (a.x_mm * b.y_mm - b.x_mm * a.y_mm) + seg
            })
            .sum()
    }
}
