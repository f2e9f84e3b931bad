//! Parts by their true outlines: the sheet-elimination pass
//! ([`eliminate`]) after the lane, skyline and edge-band nests, the
//! true-shape distance `check_nest` uses, and [`grown_outline`] (a part's
//! outline grown by half the gap, which the sparrow instance exports too).
//!
//! For each sheet holding no lamella, fewest-filled first, every one of its
//! parts is moved into the free space of the other sheets by its outline:
//! in an allowed rotation, inside the margins, its outline grown by half the
//! gap (kerf + spacing) plus [`SAFETY_MM`] clear of every placed part's
//! outline grown as much. Where all of a sheet's parts find a place, the
//! sheet is dropped. Collisions are tested by jagua-rs's collision-detection
//! engine (one `CDEngine` per target sheet, the placed parts as hazards; f32),
//! then confirmed in f64 by [`polygon_distance`](plane::polygon_distance) against the neighbours, so the
//! clearance holds exactly. Candidate positions: a bottom-left scan of a
//! grid over the usable area (step a quarter of the part's smaller side, at
//! most [`GRID_POINTS`] points), the first free point refined towards the
//! lower-left by halving steps. Deterministic (no threads, fixed orders) and
//! bounded ([`MAX_ATTEMPTS`] sheets tried, [`MAX_TARGETS`] target sheets).

use super::model::{bounds, placed_bbox, rotate, Placement, SheetNest};
use crate::fabricate::part::{FeatureKind, SlotEdge};
use crate::fabricate::part::{Part, PartKind};
use crate::fabricate::Kit;
use crate::geom::plane;
use jagua_rs::collision_detection::hazards::filter::NoFilter;
use jagua_rs::collision_detection::hazards::{Hazard, HazardEntity};
use jagua_rs::collision_detection::{CDEConfig, CDEngine};
use jagua_rs::geometry::fail_fast::{SPSurrogate, SPSurrogateConfig};
use jagua_rs::geometry::geo_enums::GeoPosition;
use jagua_rs::geometry::geo_traits::{Transformable, TransformableFrom};
use jagua_rs::geometry::primitives::{Point as JPoint, Rect, SPolygon};
use jagua_rs::geometry::Transformation;
use kurbo::Point;
use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::rc::Rc;
use std::sync::Arc;

/// Extra growth of every outline beyond half the gap, mm: absorbs the f32
/// arithmetic of the collision engine.
pub const SAFETY_MM: f64 = 0.02;
/// The engine's polygons: grown this much more, then simplified to within
/// it (Douglas–Peucker), so they still hold the outline grown by the gap and
/// have few edges; the f64 check decides exactly, mm.
pub const SIMPLIFY_MM: f64 = 0.05;
/// Grid points of the candidate scan at most, per part and rotation.
pub const GRID_POINTS: f64 = 6000.0;
/// Sheets whose elimination is tried at most.
pub const MAX_ATTEMPTS: usize = 6;
/// Target sheets (most free area first) a part may move to at most.
pub const MAX_TARGETS: usize = 8;
/// Outline vertices tested against the lamellas' boxes before the engine.
const PROBES: usize = 16;
/// Collision queries of one pass at most (a deterministic bound on its time).
pub const MAX_QUERIES: u64 = 1_000_000;

/// What induces a hazard on a sheet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Haz {
    Exterior,
    Part(usize),
}

impl HazardEntity for Haz {
    fn scope(&self) -> GeoPosition {
        match self {
            Haz::Exterior => GeoPosition::Exterior,
            Haz::Part(_) => GeoPosition::Interior,
        }
    }

    fn is_dynamic(&self) -> bool {
        matches!(self, Haz::Part(_))
    }
}

/// A placed part's outline in sheet coordinates.
pub fn placed_outline(p: &Part, pl: &Placement) -> Vec<Point> {
    p.outline_part_mm
        .iter()
        .map(|&q| {
            let r = rotate(q, pl.rotation_deg);
            Point::new(r.x + pl.x_mm, r.y + pl.y_mm)
        })
        .collect()
}

fn jpoly(v: &[Point]) -> Option<SPolygon> {
    let pts: Vec<JPoint> = v.iter().map(|q| JPoint(q.x as f32, q.y as f32)).collect();
    SPolygon::new(pts).ok()
}

/// The polygon of a box, counter-clockwise.
fn box_poly(b: (f64, f64, f64, f64)) -> Vec<Point> {
    vec![
        Point::new(b.0, b.1),
        Point::new(b.2, b.1),
        Point::new(b.2, b.3),
        Point::new(b.0, b.3),
    ]
}

/// A part's grown outline as a jagua-rs polygon, in its own frame; where the
/// grown outline is not a simple polygon, its bounding box. A lamella as a
/// hazard (`hazard`): its grown bounding box (its slots are too narrow to
/// take a part, and four edges query faster than hundreds).
fn grown_poly(p: &Part, d: f64, hazard: bool) -> Option<SPolygon> {
    let g = plane::simplify_closed(&grown_outline(p, d + SIMPLIFY_MM), SIMPLIFY_MM);
    if hazard && p.kind == PartKind::Lamella {
        return jpoly(&box_poly(bounds(&g)));
    }
    jpoly(&g).or_else(|| jpoly(&box_poly(bounds(&g))))
}

/// A box (x0, y0, x1, y1), mm.
type BBox = (f64, f64, f64, f64);
/// jagua-rs polygons made once (`None`: none could be made).
type PolyCache<K> = RefCell<HashMap<K, Option<Arc<SPolygon>>>>;

/// One target sheet: its collision engine and the true outlines on it.
struct Board {
    engine: CDEngine<Haz>,
    /// True outlines (sheet frame) and their boxes.
    placed: Vec<(Vec<Point>, BBox)>,
    /// The boxes of the lamellas on it (hazards as their grown boxes): a
    /// part with an outline vertex inside one collides.
    boxes: Vec<BBox>,
    /// Usable area less the parts' net area, mm².
    free: f64,
}

/// What both outline passes work in.
#[derive(Clone, Copy)]
pub struct Setting<'a> {
    /// The parts.
    pub kit: &'a Kit,
    /// Every part's net area by index (`fabricate::net_area_mm2`), mm².
    pub areas_mm2: &'a [f64],
    /// Edge margin all round a sheet, mm.
    pub margin_mm: f64,
    /// Kerf + part spacing between parts, mm.
    pub gap_mm: f64,
    /// The allowed rotations, degrees.
    pub rotations_deg: &'a [u32],
}

/// The pass's settings.
struct Pass<'a> {
    kit: &'a Kit,
    margin: f64,
    gap: f64,
    rotations: &'a [u32],
    /// Net area of each part, mm².
    areas: Vec<f64>,
    /// Collision queries made so far.
    queries: Cell<u64>,
    /// Collision queries allowed.
    limit: u64,
    /// Grown hazard polygons by (part, rotation), in the part's frame.
    hazards: PolyCache<(usize, u32)>,
    /// Grown polygons by (part, as a hazard), in the part's frame (those
    /// of moving parts with fail-fast poles).
    bases: PolyCache<(usize, bool)>,
    /// Whether a part's grown polygon has fail-fast poles.
    surrogates: RefCell<HashMap<usize, Option<()>>>,
    /// Each part's shapes in its allowed rotations.
    shapes: RefCell<HashMap<usize, Option<Rc<Vec<Shape>>>>>,
}

impl<'a> Pass<'a> {
    /// A pass in `setting` with empty caches, allowed `limit` collision
    /// queries.
    fn new(setting: Setting<'a>, limit: u64) -> Self {
        Pass {
            kit: setting.kit,
            margin: setting.margin_mm,
            gap: setting.gap_mm,
            rotations: setting.rotations_deg,
            areas: setting.areas_mm2.to_vec(),
            queries: Cell::new(0),
            limit,
            hazards: RefCell::new(HashMap::new()),
            shapes: RefCell::new(HashMap::new()),
            bases: RefCell::new(HashMap::new()),
            surrogates: RefCell::new(HashMap::new()),
        }
    }

    fn exhausted(&self) -> bool {
        self.queries.get() >= self.limit
    }

    fn board(&self, s: &SheetNest) -> Option<Board> {
        let g = self.gap;
        let pad = g + 10.0;
        let outer = jpoly(&box_poly((-pad, -pad, s.length_mm + pad, s.width_mm + pad)))?;
        let rect = Rect::try_new(
            -pad as f32,
            -pad as f32,
            (s.length_mm + pad) as f32,
            (s.width_mm + pad) as f32,
        )
        .ok()?;
        let config = CDEConfig {
            quadtree_depth: 6,
            cd_threshold: 16,
            item_surrogate_config: SPSurrogateConfig::none(),
        };
        let mut engine = CDEngine::new(
            rect.inflate_to_square(),
            vec![Hazard::new(Haz::Exterior, Arc::new(outer))],
            config,
        );
        let mut placed = Vec::with_capacity(s.placements.len());
        let mut boxes = Vec::new();
        let mut area = 0.0;
        for pl in &s.placements {
            let p = &self.kit.parts[pl.part];
            self.register(&mut engine, placed.len(), p, pl)?;
            let o = placed_outline(p, pl);
            let b = bounds(&o);
            if p.kind == PartKind::Lamella {
                boxes.push(b);
            }
            placed.push((o, b));
            area += self.areas[pl.part];
        }
        let m = self.margin;
        let free = (s.length_mm - 2.0 * m) * (s.width_mm - 2.0 * m) - area;
        Some(Board {
            engine,
            placed,
            boxes,
            free,
        })
    }

    fn register(
        &self,
        engine: &mut CDEngine<Haz>,
        k: usize,
        p: &Part,
        pl: &Placement,
    ) -> Option<()> {
        let shape = self
            .hazards
            .borrow_mut()
            .entry((pl.part, pl.rotation_deg))
            .or_insert_with(|| self.turned(pl.part, p, pl.rotation_deg, true).map(Arc::new))
            .clone()?;
        let t = Transformation::from_translation((pl.x_mm as f32, pl.y_mm as f32));
        engine.register_hazard(Hazard::new(
            Haz::Part(k),
            Arc::new(shape.transform_clone(&t)),
        ));
        Some(())
    }

    /// Where part `p` turned by `rot` can go on `b` with its outline's box
    /// lower-left corner at (x, y): free by the engine, then by [`polygon_distance`](plane::polygon_distance).
    fn free_at(&self, b: &Board, shape: &Shape, x: f64, y: f64) -> bool {
        if self.exhausted() {
            return false;
        }
        self.queries.set(self.queries.get() + 1);
        let (tx, ty) = (x - shape.bbox.0, y - shape.bbox.1);
        // A probe vertex inside a lamella's box: the engine would say so.
        if shape.probes.iter().any(|q| {
            let (px, py) = (q.x + tx, q.y + ty);
            b.boxes
                .iter()
                .any(|bb| bb.0 <= px && px <= bb.2 && bb.1 <= py && py <= bb.3)
        }) {
            return false;
        }
        let t = Transformation::from_translation((tx as f32, ty as f32));
        if let Some(sur) = shape.surrogate.as_ref() {
            if b.engine.detect_surrogate_collision(sur, &t, &NoFilter) {
                return false;
            }
        }
        let mut moved = shape.scratch.borrow_mut();
        moved.transform_from(&shape.grown, &t);
        if b.engine.detect_poly_collision(&moved, &NoFilter) {
            return false;
        }
        drop(moved);
        self.confirm(b, shape, x, y)
    }

    /// Whether part `shape` at (x, y) (as in [`Pass::free_at`]) is at least
    /// the gap from every part on `b`, in f64: by boxes, else by
    /// [`polygon_distance`](plane::polygon_distance).
    fn confirm(&self, b: &Board, shape: &Shape, x: f64, y: f64) -> bool {
        let (tx, ty) = (x - shape.bbox.0, y - shape.bbox.1);
        let g = self.gap;
        let (w, h) = (shape.bbox.2 - shape.bbox.0, shape.bbox.3 - shape.bbox.1);
        let moved: Vec<Point> = shape
            .outline
            .iter()
            .map(|q| Point::new(q.x + tx, q.y + ty))
            .collect();
        b.placed.iter().all(|(o, ob)| {
            ob.2 + g <= x || x + w + g <= ob.0 || ob.3 + g <= y || y + h + g <= ob.1 || {
                plane::polygon_distance(&moved, o, g) >= g + 1e-6
            }
        })
    }

    /// The bottom-left free place of a part on `b` (the lowest x, then the
    /// lowest y): (x, y, rotation index).
    fn find(&self, b: &Board, shapes: &[Shape], s: &SheetNest) -> Option<(f64, f64, usize)> {
        let m = self.margin;
        let (lu, wu) = (s.length_mm - 2.0 * m, s.width_mm - 2.0 * m);
        let mut best: Option<(f64, f64, usize)> = None;
        for (r, shape) in shapes.iter().enumerate() {
            let (w, h) = (shape.bbox.2 - shape.bbox.0, shape.bbox.3 - shape.bbox.1);
            if w > lu + 1e-9 || h > wu + 1e-9 {
                continue;
            }
            let (x_max, y_max) = (m + lu - w, m + wu - h);
            let step = (0.25 * w.min(h))
                .max((lu * wu / GRID_POINTS).sqrt())
                .max(1.0);
            let nx = ((x_max - m) / step).floor() as usize + 1;
            let ny = ((y_max - m) / step).floor() as usize + 1;
            let at = |i: usize, n: usize, hi: f64| {
                if i == n {
                    hi
                } else {
                    (m + i as f64 * step).min(hi)
                }
            };
            let mut found = None;
            'scan: for i in 0..=nx {
                let x = at(i, nx, x_max);
                if best.is_some_and(|bb| x > bb.0 + 1e-9) {
                    break;
                }
                for j in 0..=ny {
                    let y = at(j, ny, y_max);
                    if self.free_at(b, shape, x, y) {
                        found = Some((x, y));
                        break 'scan;
                    }
                }
            }
            let Some((mut x, mut y)) = found else {
                continue;
            };
            // Towards the lower left by halving steps.
            for _ in 0..2 {
                let mut d = step;
                while d > 0.05 {
                    if y - d >= m - 1e-9 && self.free_at(b, shape, x, (y - d).max(m)) {
                        y = (y - d).max(m);
                    } else {
                        d *= 0.5;
                    }
                }
                let mut d = step;
                while d > 0.05 {
                    if x - d >= m - 1e-9 && self.free_at(b, shape, (x - d).max(m), y) {
                        x = (x - d).max(m);
                    } else {
                        d *= 0.5;
                    }
                }
            }
            if best.is_none_or(|bb| x < bb.0 - 1e-9 || (x <= bb.0 + 1e-9 && y < bb.1 - 1e-9)) {
                best = Some((x, y, r));
            }
        }
        best
    }

    /// The shapes of part `i` in each allowed rotation.
    /// Part `i`'s grown polygon (as a hazard: a lamella's box) turned by
    /// `rot`: made once in the part's frame (jagua-rs's polygons are costly
    /// to make), then turned by the engine's own transformation.
    fn turned(&self, i: usize, p: &Part, rot: u32, hazard: bool) -> Option<SPolygon> {
        let base = self
            .bases
            .borrow_mut()
            .entry((i, hazard))
            .or_insert_with(|| {
                let mut g = grown_poly(p, 0.5 * self.gap + SAFETY_MM, hazard)?;
                if !hazard && p.kind != PartKind::EdgeStrip {
                    let sur = SPSurrogateConfig {
                        n_pole_limits: [(8, 0.0), (4, 0.6), (2, 0.9)],
                        ff_pole_area_ratio: 0.6,
                        n_ff_piers: 0,
                    };
                    let ok = g.generate_surrogate(sur).is_ok();
                    self.surrogates.borrow_mut().insert(i, ok.then_some(()));
                }
                Some(Arc::new(g))
            })
            .clone()?;
        if rot.is_multiple_of(360) {
            return Some((*base).clone());
        }
        let angle = (f64::from(rot % 360)).to_radians() as f32;
        Some(base.transform_clone(&Transformation::from_rotation(angle)))
    }

    fn shapes_of(&self, i: usize) -> Option<Vec<Shape>> {
        let p = &self.kit.parts[i];
        self.rotations
            .iter()
            .map(|&rot| {
                let outline: Vec<Point> =
                    p.outline_part_mm.iter().map(|&q| rotate(q, rot)).collect();
                let grown = self.turned(i, p, rot, false)?;
                let surrogate = self
                    .surrogates
                    .borrow()
                    .get(&i)
                    .cloned()
                    .flatten()
                    .map(|_| grown.surrogate().clone());
                let step = outline.len().div_ceil(PROBES).max(1);
                let probes = outline.iter().step_by(step).copied().collect();
                Some(Shape {
                    probes,
                    surrogate,
                    rot,
                    bbox: bounds(&outline),
                    scratch: RefCell::new(grown.clone()),
                    grown,
                    outline,
                })
            })
            .collect()
    }
}

/// A part turned by one rotation, in its own frame.
struct Shape {
    rot: u32,
    outline: Vec<Point>,
    bbox: (f64, f64, f64, f64),
    /// A few of the outline's vertices, for a quick test against lamellas.
    probes: Vec<Point>,
    /// The outline grown by half the gap and [`SAFETY_MM`], for the engine.
    grown: SPolygon,
    /// Fail-fast poles of `grown`, if they could be made.
    surrogate: Option<SPSurrogate>,
    /// Room for `grown` moved to a candidate place.
    scratch: RefCell<SPolygon>,
}

/// The sheet-elimination pass: sheets of non-lamella parts, fewest-filled
/// first, emptied into the free space of the others by true outline where
/// every part finds a place; returns how many sheets were dropped.
pub fn eliminate(setting: Setting, sheets: &mut Vec<SheetNest>) -> usize {
    let kit = setting.kit;
    let pass = Pass::new(setting, MAX_QUERIES);
    let only_small = |s: &SheetNest| {
        s.placements
            .iter()
            .all(|pl| kit.parts[pl.part].kind != PartKind::Lamella)
    };
    if sheets.len() < 2 || !sheets.iter().any(only_small) {
        return 0;
    }
    let area = |s: &SheetNest| -> f64 { s.placements.iter().map(|pl| pass.areas[pl.part]).sum() };
    // Boards are built when a sheet is first a target.
    let mut boards: Vec<Option<Board>> = sheets.iter().map(|_| None).collect();
    let mut tried = vec![false; sheets.len()];
    let mut dropped = 0;
    let mut attempts = 0;
    while attempts < MAX_ATTEMPTS && sheets.len() > 1 && !pass.exhausted() {
        // The fewest-filled sheet not tried yet, ties by index.
        let Some(k) = (0..sheets.len())
            .filter(|&k| !tried[k] && only_small(&sheets[k]))
            .map(|k| (area(&sheets[k]), k))
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
            .map(|(_, k)| k)
        else {
            break;
        };
        attempts += 1;
        tried[k] = true;
        if let Some(moves) = try_empty(&pass, sheets, &mut boards, k) {
            for (t, pl) in moves {
                sheets[t].placements.push(pl);
            }
            sheets.remove(k);
            boards.remove(k);
            tried.remove(k);
            dropped += 1;
        }
    }
    dropped
}

/// Places for every part of sheet `k` on the other sheets' boards (which
/// then hold them): (sheet, placement); `None` (the boards as they were)
/// where some part finds none.
fn try_empty(
    pass: &Pass,
    sheets: &[SheetNest],
    boards: &mut [Option<Board>],
    k: usize,
) -> Option<Vec<(usize, Placement)>> {
    let kit = pass.kit;
    let need: f64 = sheets[k]
        .placements
        .iter()
        .map(|pl| pass.areas[pl.part])
        .sum();
    // Most free area first, ties by index.
    let m = pass.margin;
    let free = |t: usize| -> f64 {
        boards[t].as_ref().map_or_else(
            || {
                let s = &sheets[t];
                (s.length_mm - 2.0 * m) * (s.width_mm - 2.0 * m)
                    - s.placements
                        .iter()
                        .map(|pl| pass.areas[pl.part])
                        .sum::<f64>()
            },
            |b| b.free,
        )
    };
    let mut targets: Vec<usize> = (0..sheets.len()).filter(|&t| t != k).collect();
    let frees: Vec<f64> = (0..sheets.len()).map(free).collect();
    targets.sort_by(|&a, &b| frees[b].total_cmp(&frees[a]).then(a.cmp(&b)));
    targets.truncate(MAX_TARGETS);
    if targets.iter().map(|&t| frees[t]).sum::<f64>() < need {
        return None;
    }
    for &t in &targets {
        if boards[t].is_none() {
            boards[t] = pass.board(&sheets[t]);
        }
    }
    targets.retain(|&t| boards[t].is_some());
    let saved: Vec<_> = targets
        .iter()
        .filter_map(|&t| boards[t].as_ref())
        .map(|b| (b.engine.save(), b.placed.len(), b.free))
        .collect();
    // Largest box first, ties by index.
    let mut order: Vec<Placement> = sheets[k].placements.clone();
    order.sort_by(|a, b| {
        let ar = |pl: &Placement| {
            let bb = placed_bbox(&kit.parts[pl.part], pl);
            (bb.2 - bb.0) * (bb.3 - bb.1)
        };
        ar(b)
            .total_cmp(&ar(a))
            .then(a.part.cmp(&b.part))
            .then(a.copy.cmp(&b.copy))
    });
    let mut moves = Vec::with_capacity(order.len());
    let mut ok = true;
    'parts: for pl in order {
        let cached = pass
            .shapes
            .borrow_mut()
            .entry(pl.part)
            .or_insert_with(|| pass.shapes_of(pl.part).map(Rc::new))
            .clone();
        let Some(shapes) = cached else {
            ok = false;
            break;
        };
        let p = &kit.parts[pl.part];
        let area = pass.areas[pl.part];
        for &t in &targets {
            let Some(b) = boards[t].as_mut() else {
                continue;
            };
            if b.free < area {
                continue;
            }
            let Some((x, y, r)) = pass.find(b, &shapes, &sheets[t]) else {
                continue;
            };
            let sh = &shapes[r];
            let new = Placement {
                part: pl.part,
                copy: pl.copy,
                x_mm: x - sh.bbox.0,
                y_mm: y - sh.bbox.1,
                rotation_deg: sh.rot,
            };
            let n = b.placed.len();
            if pass.register(&mut b.engine, n, p, &new).is_none() {
                continue;
            }
            let o = placed_outline(p, &new);
            let bb = bounds(&o);
            b.placed.push((o, bb));
            b.free -= area;
            moves.push((t, new));
            continue 'parts;
        }
        ok = false;
        break;
    }
    if ok {
        return Some(moves);
    }
    for (&t, (snap, n, free)) in targets.iter().zip(saved) {
        if let Some(b) = boards[t].as_mut() {
            b.engine.restore(&snap);
            b.placed.truncate(n);
            b.free = free;
        }
    }
    None
}

/// The outline of a part grown by `d` mm: exact for lamellas (a rectangle
/// with notches, each notch narrowed by 2d and made d shallower, dropped when
/// it closes), a miter offset for every other part (whose corners are right
/// angles or smooth).
pub fn grown_outline(p: &Part, d: f64) -> Vec<Point> {
    if p.kind == PartKind::Lamella {
        let (len, h) = (p.length_mm, p.height_mm);
        let mut out = vec![Point::new(-d, -d)];
        let notches = |edge: SlotEdge| -> Vec<(f64, f64, f64)> {
            p.features
                .iter()
                .filter(|f| f.kind == FeatureKind::Slot && f.edge == Some(edge))
                .map(|f| {
                    (
                        f.center_part_mm.x - 0.5 * f.width_mm + d,
                        f.center_part_mm.x + 0.5 * f.width_mm - d,
                        f.depth_mm - d,
                    )
                })
                .filter(|&(a, b, depth)| b > a && depth > 0.0)
                .collect()
        };
        for (a, b, depth) in notches(SlotEdge::Bottom) {
            out.extend([
                Point::new(a, -d),
                Point::new(a, depth),
                Point::new(b, depth),
                Point::new(b, -d),
            ]);
        }
        out.push(Point::new(len + d, -d));
        out.push(Point::new(len + d, h + d));
        for (a, b, depth) in notches(SlotEdge::Top).into_iter().rev() {
            out.extend([
                Point::new(b, h + d),
                Point::new(b, h - depth),
                Point::new(a, h - depth),
                Point::new(a, h + d),
            ]);
        }
        out.push(Point::new(-d, h + d));
        return out;
    }
    plane::miter_offset(&p.outline_part_mm, d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fabricate::part::Feature;
    use crate::geom::plane::signed_area_mm2;

    fn part(kind: PartKind, outline: Vec<Point>, features: Vec<Feature>) -> Part {
        Part {
            id: "P".into(),
            kind,
            strip: None,
            lamella: None,
            count: 1,
            length_mm: 100.0,
            height_mm: 50.0,
            station_start_mm: None,
            outline_part_mm: outline,
            holes_part_mm: Vec::new(),
            engraving: Vec::new(),
            features,
        }
    }

    fn rect() -> Vec<Point> {
        vec![
            Point::new(0.0, 0.0),
            Point::new(100.0, 0.0),
            Point::new(100.0, 50.0),
            Point::new(0.0, 50.0),
        ]
    }

    #[test]
    fn a_rectangle_grows_by_d_all_round() {
        let g = grown_outline(&part(PartKind::ShearBlock, rect(), Vec::new()), 2.0);
        assert!((signed_area_mm2(&g) - 104.0 * 54.0).abs() < 1e-9);
        assert!(g.contains(&Point::new(-2.0, -2.0)) && g.contains(&Point::new(102.0, 52.0)));
    }

    #[test]
    fn lamella_notches_narrow_and_close() {
        let slot = |x: f64, w: f64| Feature {
            kind: FeatureKind::Slot,
            hole_use: None,
            node: None,
            crossing: None,
            center_part_mm: Point::new(x, 37.5),
            width_mm: w,
            depth_mm: 25.0,
            edge: Some(SlotEdge::Top),
            angle_range_deg: None,
            station_mm: None,
        };
        let p = part(
            PartKind::Lamella,
            rect(),
            vec![slot(30.0, 10.0), slot(70.0, 3.0)],
        );
        let g = grown_outline(&p, 2.0);
        // The 10 mm slot stays, 6 mm wide, its root 2 mm higher (25 mm below
        // the grown edge); the 3 mm one closes.
        let area = 104.0 * 54.0 - 6.0 * 25.0;
        assert!(
            (signed_area_mm2(&g) - area).abs() < 1e-9,
            "{}",
            signed_area_mm2(&g)
        );
    }
}
