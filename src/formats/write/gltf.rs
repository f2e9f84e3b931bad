//! `model.glb`: the erected grid as a binary glTF 2.0 file, written by
//! hand from the plan's shape ([`crate::plan::PlanShape`]).
//!
//! * **Frame**: glTF is in metres with y up. A point (x, y, z) of the
//!   network's frame (mm, z up) is (x − cx, z − cz, −(y − cy)) / 1000 in
//!   the vertices, and the scene's one root node `grid` moves them back
//!   by its translation (cx, cz, −cy) / 1000, where c is the centre of
//!   the grid's bounding box rounded to whole mm: the f32 vertices are
//!   small numbers near the origin, the translation an exact decimal.
//! * **Nodes**: one glTF node per strip (A, B and edge), its mesh one
//!   primitive holding every lamella of the strip as a solid (height along
//!   the normal, thickness across, the interlocking slots cut from the
//!   edges where the parts have them), `extras` {id, family, material,
//!   utilisation, length_mm, lamellas}; a node `washers` (star washers,
//!   two crossed bars on top of and below each node), `studs` (two-level
//!   joints), `cables` (a braced grid's cables pin to pin, square rods of
//!   the strand's diameter, `extras` {kind, ids, diameter_mm}), and
//!   `nodes` (every node as a point, in plan order).
//! * **Colours**: `COLOR_0` by the elastic check's utilisation of each
//!   lamella ([`UTILISATION_STOPS`], linear between stops; above 1 purple;
//!   unchecked grey).
//! * **Flat state**: where the plan holds the flat layout, each strip's
//!   mesh and the nodes' have one morph target, `flat` (weight 0 erected,
//!   1 flat).
//! * **Level of detail**: past [`crate::plan::ShapeOptions::BIG_NODES`]
//!   nodes, lamellas are ribbons (the height without the thickness), and
//!   slots, washers and studs are left out.
//!
//! No normals are written (glTF viewers then shade flat); every number is
//! a function of the plan alone, so equal plans give equal bytes.

use crate::plan::{Plan, PlanFeatureKind, PlanSlotEdge, ShapeFrame, ShapeLine, ShapeOptions};
use serde_json::{json, Value};

/// Utilisation → colour (sRGB 0–255), linear between the stops.
pub const UTILISATION_STOPS: [(f64, [u8; 3]); 4] = [
    (0.0, [43, 131, 186]),
    (0.5, [171, 221, 164]),
    (0.75, [253, 174, 97]),
    (1.0, [215, 25, 28]),
];

/// The colour of a lamella above utilisation 1.
pub const OVERSTRESSED: [u8; 3] = [120, 0, 120];
/// The colour of a lamella without a check.
pub const UNCHECKED: [u8; 3] = [170, 170, 170];
/// The colour of edge strips.
pub const EDGE: [u8; 3] = [110, 110, 120];
/// The colour of washers and studs.
pub const HARDWARE: [u8; 3] = [60, 60, 66];
/// The colour of bracing cables.
pub const CABLE: [u8; 3] = [200, 30, 30];

/// The colour of a utilisation (None: unchecked).
pub fn utilisation_colour(u: Option<f64>) -> [u8; 3] {
    let Some(u) = u else {
        return UNCHECKED;
    };
    if u > 1.0 {
        return OVERSTRESSED;
    }
    let u = u.max(0.0);
    for w in UTILISATION_STOPS.windows(2) {
        let ((u0, c0), (u1, c1)) = (w[0], w[1]);
        if u <= u1 {
            let t = (u - u0) / (u1 - u0);
            let mix = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * t).round() as u8;
            return [mix(c0[0], c1[0]), mix(c0[1], c1[1]), mix(c0[2], c1[2])];
        }
    }
    UTILISATION_STOPS[3].1
}

/// Whether the model of `plan` is drawn at full detail (solids, slots,
/// hardware) rather than as ribbons.
pub fn full_detail(plan: &Plan) -> bool {
    plan.nodes.len() <= ShapeOptions::BIG_NODES
}

/// One mesh being built: f32 positions (glTF frame, about the centre),
/// colours, the flat state's displacements, triangle indices.
#[derive(Default)]
struct Geo {
    pos: Vec<[f32; 3]>,
    col: Vec<[u8; 4]>,
    morph: Vec<[f32; 3]>,
    idx: Vec<u32>,
}

/// The network frame (mm) → glTF (m) about the centre `c` (mm).
fn to_gltf(p: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    [
        (p[0] - c[0]) / 1000.0,
        (p[2] - c[2]) / 1000.0,
        -(p[1] - c[1]) / 1000.0,
    ]
}

fn f32s(p: [f64; 3]) -> [f32; 3] {
    [p[0] as f32, p[1] as f32, p[2] as f32]
}

fn add(a: [f64; 3], b: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s]
}

fn normalized(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n > 0.0 {
        [v[0] / n, v[1] / n, v[2] / n]
    } else {
        v
    }
}

/// The frame at station `s` on a line, linear between its frames.
fn frame_at(frames: &[ShapeFrame], s: f64) -> ShapeFrame {
    let i = frames
        .partition_point(|f| f.station_mm <= s)
        .saturating_sub(1)
        .min(frames.len().saturating_sub(2));
    let (a, b) = (&frames[i], &frames[(i + 1).min(frames.len() - 1)]);
    let span = b.station_mm - a.station_mm;
    let t = if span > 0.0 {
        ((s - a.station_mm) / span).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let lerp = |x: [f64; 3], y: [f64; 3]| {
        [
            x[0] + (y[0] - x[0]) * t,
            x[1] + (y[1] - x[1]) * t,
            x[2] + (y[2] - x[2]) * t,
        ]
    };
    ShapeFrame {
        station_mm: s,
        point_mm: lerp(a.point_mm, b.point_mm),
        tangent: normalized(lerp(a.tangent, b.tangent)),
        normal: normalized(lerp(a.normal, b.normal)),
        across: normalized(lerp(a.across, b.across)),
    }
}

/// A slot cut from one edge over [from, to] on the lamella's own line.
#[derive(Clone, Copy)]
struct Cut {
    from_mm: f64,
    to_mm: f64,
    top: bool,
    depth_mm: f64,
}

/// The cross-section columns of a lamella: (station, bottom, top) heights
/// about its line, two at a station where a slot begins or ends.
fn columns(frames: &[ShapeFrame], half_h: f64, cuts: &[Cut]) -> Vec<(f64, f64, f64)> {
    let (first, last) = (frames[0].station_mm, frames[frames.len() - 1].station_mm);
    let mut st: Vec<f64> = frames.iter().map(|f| f.station_mm).collect();
    for c in cuts {
        st.push(c.from_mm.clamp(first, last));
        st.push(c.to_mm.clamp(first, last));
    }
    st.sort_by(f64::total_cmp);
    st.dedup();
    // The section just off a station (`side` −1 before, +1 after).
    let section = |s: f64, side: f64| {
        let (mut bottom, mut top) = (-half_h, half_h);
        for c in cuts {
            let inside = if side < 0.0 {
                s > c.from_mm && s <= c.to_mm
            } else {
                s >= c.from_mm && s < c.to_mm
            };
            if inside {
                if c.top {
                    top = top.min(half_h - c.depth_mm);
                } else {
                    bottom = bottom.max(-half_h + c.depth_mm);
                }
            }
        }
        (bottom, top)
    };
    let mut out = Vec::with_capacity(st.len() + 2 * cuts.len());
    for (k, &s) in st.iter().enumerate() {
        let before = if k == 0 {
            section(s, 1.0)
        } else {
            section(s, -1.0)
        };
        let after = if k + 1 == st.len() {
            before
        } else {
            section(s, 1.0)
        };
        out.push((s, before.0, before.1));
        if after != before {
            out.push((s, after.0, after.1));
        }
    }
    out
}

impl Geo {
    fn vertex(&mut self, p: [f64; 3], flat: Option<[f64; 3]>, c: [f64; 3], colour: [u8; 3]) -> u32 {
        let e = to_gltf(p, c);
        self.pos.push(f32s(e));
        self.col.push([colour[0], colour[1], colour[2], 255]);
        let d = match flat {
            Some(q) => {
                let f = to_gltf(q, c);
                [f[0] - e[0], f[1] - e[1], f[2] - e[2]]
            }
            None => [0.0; 3],
        };
        self.morph.push(f32s(d));
        (self.pos.len() - 1) as u32
    }

    fn quad(&mut self, a: u32, b: u32, c: u32, d: u32) {
        self.idx.extend_from_slice(&[a, b, c, a, c, d]);
    }

    /// A lamella (or edge strip) along its frames: a box section of
    /// `across` × `height` (a ribbon when `across` is 0), `cuts` taken from
    /// its edges along the height.
    #[allow(clippy::too_many_arguments)]
    fn strip(
        &mut self,
        line: &ShapeLine,
        height_mm: f64,
        across_mm: f64,
        height_along_normal: bool,
        cuts: &[Cut],
        c: [f64; 3],
        colour: [u8; 3],
    ) {
        if line.frames.len() < 2 {
            return;
        }
        let cols = columns(&line.frames, height_mm / 2.0, cuts);
        let corners: &[(f64, usize)] = if across_mm > 0.0 {
            // (across sign, bottom 0 / top 1), around the section.
            &[(-1.0, 0), (1.0, 0), (1.0, 1), (-1.0, 1)]
        } else {
            &[(0.0, 0), (0.0, 1)]
        };
        let n = corners.len() as u32;
        let mut first = None;
        let mut prev: Option<u32> = None;
        for &(s, bottom, top) in &cols {
            let f = frame_at(&line.frames, s);
            let g = line.flat.as_deref().map(|fl| frame_at(fl, s));
            let base = self.pos.len() as u32;
            for &(side, level) in corners {
                let h = if level == 0 { bottom } else { top };
                let place = |fr: &ShapeFrame| {
                    let (hdir, adir) = if height_along_normal {
                        (fr.normal, fr.across)
                    } else {
                        (fr.across, fr.normal)
                    };
                    add(add(fr.point_mm, hdir, h), adir, side * across_mm / 2.0)
                };
                self.vertex(place(&f), g.as_ref().map(place), c, colour);
            }
            if let Some(p) = prev {
                if n == 2 {
                    self.quad(p, p + 1, base + 1, base);
                } else {
                    for k in 0..n {
                        let k1 = (k + 1) % n;
                        self.quad(p + k, p + k1, base + k1, base + k);
                    }
                }
            }
            first.get_or_insert(base);
            prev = Some(base);
        }
        if let (Some(a), Some(b), 4) = (first, prev, n) {
            self.quad(a, a + 3, a + 2, a + 1);
            self.quad(b, b + 1, b + 2, b + 3);
        }
    }

    /// A box about `centre` with half-extents along three unit axes.
    fn cuboid(
        &mut self,
        centre: [f64; 3],
        axes: [([f64; 3], f64); 3],
        c: [f64; 3],
        colour: [u8; 3],
    ) {
        let base = self.pos.len() as u32;
        for k in 0..8 {
            let mut p = centre;
            for (j, (axis, half)) in axes.iter().enumerate() {
                let sign = if k >> j & 1 == 1 { 1.0 } else { -1.0 };
                p = add(p, *axis, sign * half);
            }
            self.vertex(p, None, c, colour);
        }
        for [a, b, cc, d] in [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ] {
            self.quad(base + a, base + b, base + cc, base + d);
        }
    }
}

/// The binary buffer and the JSON arrays that describe it.
#[derive(Default)]
struct Bin {
    data: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Bin {
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.data.len().is_multiple_of(4) {
            self.data.push(0);
        }
        let mut v = json!({"buffer": 0, "byteOffset": self.data.len(), "byteLength": bytes.len()});
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.data.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    fn vec3(&mut self, v: &[[f32; 3]]) -> usize {
        let mut bytes = Vec::with_capacity(v.len() * 12);
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for p in v {
            for k in 0..3 {
                bytes.extend_from_slice(&p[k].to_le_bytes());
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let view = self.view(&bytes, Some(34962));
        let num = |a: [f32; 3]| json!([a[0] as f64, a[1] as f64, a[2] as f64]);
        self.accessors.push(json!({
            "bufferView": view, "componentType": 5126, "count": v.len(), "type": "VEC3",
            "min": num(lo), "max": num(hi)
        }));
        self.accessors.len() - 1
    }

    fn colours(&mut self, v: &[[u8; 4]]) -> usize {
        let bytes: Vec<u8> = v.iter().flatten().copied().collect();
        let view = self.view(&bytes, Some(34962));
        self.accessors.push(json!({
            "bufferView": view, "componentType": 5121, "normalized": true,
            "count": v.len(), "type": "VEC4"
        }));
        self.accessors.len() - 1
    }

    fn indices(&mut self, idx: &[u32], vertices: usize) -> usize {
        let (bytes, ctype): (Vec<u8>, u32) = if vertices <= 65535 {
            (
                idx.iter().flat_map(|&i| (i as u16).to_le_bytes()).collect(),
                5123,
            )
        } else {
            (idx.iter().flat_map(|&i| i.to_le_bytes()).collect(), 5125)
        };
        let view = self.view(&bytes, Some(34963));
        self.accessors.push(json!({
            "bufferView": view, "componentType": ctype, "count": idx.len(), "type": "SCALAR"
        }));
        self.accessors.len() - 1
    }

    /// A mesh of one primitive (`mode` 4 triangles, 0 points); the flat
    /// state as its morph target when `morph`.
    fn mesh(&mut self, geo: &Geo, name: &str, material: usize, morph: bool, mode: u32) -> Value {
        let pos = self.vec3(&geo.pos);
        let col = self.colours(&geo.col);
        let mut prim = json!({
            "attributes": {"POSITION": pos, "COLOR_0": col},
            "material": material,
            "mode": mode
        });
        if mode == 4 {
            prim["indices"] = json!(self.indices(&geo.idx, geo.pos.len()));
        }
        let mut mesh = json!({"name": name, "primitives": [prim]});
        if morph {
            let t = self.vec3(&geo.morph);
            mesh["primitives"][0]["targets"] = json!([{"POSITION": t}]);
            mesh["weights"] = json!([0.0]);
            mesh["extras"] = json!({"targetNames": ["flat"]});
        }
        mesh
    }
}

/// The slots of every lamella part, by (strip id, lamella number).
fn cuts_of(plan: &Plan) -> std::collections::HashMap<(&str, u32), Vec<Cut>> {
    let mut m: std::collections::HashMap<(&str, u32), Vec<Cut>> = Default::default();
    for p in plan.parts.iter().flatten() {
        let (Some(strip), Some(lam)) = (&p.strip, p.lamella) else {
            continue;
        };
        if p.kind != "lamella" {
            continue;
        }
        for f in &p.features {
            if let (
                PlanFeatureKind::Slot,
                Some(st),
                Some(edge @ (PlanSlotEdge::Top | PlanSlotEdge::Bottom)),
            ) = (f.kind, f.line_station_mm, f.edge)
            {
                m.entry((strip.as_str(), lam)).or_default().push(Cut {
                    from_mm: st - f.width_mm / 2.0,
                    to_mm: st + f.width_mm / 2.0,
                    top: edge == PlanSlotEdge::Top,
                    depth_mm: f.depth_mm,
                });
            }
        }
    }
    m
}

/// The centre of the grid's bounding box, rounded to whole mm.
fn centre(plan: &Plan) -> [f64; 3] {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let points = plan
        .shape
        .iter()
        .flat_map(|s| &s.lines)
        .flat_map(|l| &l.frames)
        .map(|f| f.point_mm)
        .chain(plan.nodes.iter().map(|n| n.position_mm));
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if !lo[0].is_finite() {
        return [0.0; 3];
    }
    [0, 1, 2].map(|k| ((lo[k] + hi[k]) / 2.0).round())
}

/// The model of a plan as GLB bytes. An error when the plan has no shape
/// ([`crate::plan::add_shape`]).
pub fn to_glb(plan: &Plan) -> Result<Vec<u8>, String> {
    let shape = plan
        .shape
        .as_ref()
        .ok_or("internal: the plan has no shape for the model")?;
    let full = full_detail(plan);
    let c = centre(plan);
    let cuts = if full {
        cuts_of(plan)
    } else {
        Default::default()
    };
    let material = plan
        .profile
        .as_ref()
        .map(|p| p.material.clone())
        .unwrap_or_default();
    let mut bin = Bin::default();
    let (mut nodes, mut meshes, mut children) = (Vec::new(), Vec::new(), Vec::new());
    // Lines by strip, in plan order.
    let mut by_strip: Vec<Vec<&ShapeLine>> = vec![Vec::new(); plan.strips.len()];
    for l in &shape.lines {
        if let Some(v) = by_strip.get_mut(l.strip) {
            v.push(l);
        }
    }
    let (h, t) = (shape.height_mm, shape.thickness_mm);
    for (strip, lines) in plan.strips.iter().zip(&by_strip) {
        if lines.is_empty() {
            continue;
        }
        let mut geo = Geo::default();
        let morph = lines.iter().all(|l| l.flat.is_some());
        let mut lam_extras = Vec::new();
        for l in lines {
            let lam = strip
                .lamellas
                .as_ref()
                .and_then(|ls| ls.iter().find(|x| x.lamella == l.lamella));
            let u = lam
                .and_then(|x| x.checked.as_ref())
                .map(|c| c.check.utilization);
            if l.lamella == 0 {
                // An edge strip: a band in the surface, the height across.
                geo.strip(l, h, if full { t } else { 0.0 }, false, &[], c, EDGE);
            } else {
                let cs = cuts
                    .get(&(strip.id.as_str(), l.lamella))
                    .map(Vec::as_slice)
                    .unwrap_or(&[]);
                let colour = utilisation_colour(u);
                geo.strip(l, h, if full { t } else { 0.0 }, true, cs, c, colour);
                lam_extras.push(json!({
                    "lamella": l.lamella,
                    "utilisation": u,
                    "length_mm": lam.map(|x| x.length_mm)
                }));
            }
        }
        let utilisation = strip.check.as_ref().map(|c| c.stress.utilization);
        meshes.push(bin.mesh(&geo, &strip.id, 0, morph, 4));
        nodes.push(json!({
            "name": strip.id,
            "mesh": meshes.len() - 1,
            "extras": {
                "id": strip.id,
                "family": strip.family,
                "material": material,
                "utilisation": utilisation,
                "length_mm": strip.length_mm,
                "lamellas": lam_extras,
                "flat": morph
            }
        }));
        children.push(nodes.len() - 1);
    }
    // Washers and studs, at full detail.
    if full {
        let mut washers = Geo::default();
        let mut studs = Geo::default();
        for (n, sn) in plan.nodes.iter().zip(&shape.nodes) {
            let (ta, tb, z) = (sn.tangent_a, sn.tangent_b, n.normal);
            if let (Some(w), true) = (shape.washer, n.joint.starts_with('W')) {
                let level = h / 2.0 + w.thickness_mm / 2.0;
                for k in 0..w.per_node {
                    let side = if k % 2 == 0 { 1.0 } else { -1.0 };
                    let at = add(n.position_mm, z, side * level);
                    for u in [ta, tb] {
                        let across = normalized(cross(z, u));
                        washers.cuboid(
                            at,
                            [
                                (u, w.arm_length_mm),
                                (across, w.arm_width_mm / 2.0),
                                (z, w.thickness_mm / 2.0),
                            ],
                            c,
                            HARDWARE,
                        );
                    }
                }
            }
            if let (Some(st), true) = (shape.stud, n.joint == "ST") {
                let across = normalized(cross(z, ta));
                let along = normalized(cross(across, z));
                studs.cuboid(
                    n.position_mm,
                    [
                        (along, st.section_mm / 2.0),
                        (across, st.section_mm / 2.0),
                        (z, st.length_mm / 2.0),
                    ],
                    c,
                    HARDWARE,
                );
            }
        }
        for (geo, name) in [(washers, "washers"), (studs, "studs")] {
            if geo.pos.is_empty() {
                continue;
            }
            meshes.push(bin.mesh(&geo, name, 1, false, 4));
            nodes.push(json!({"name": name, "mesh": meshes.len() - 1, "extras": {"kind": name}}));
            children.push(nodes.len() - 1);
        }
    }
    // A braced grid's cables, pin to pin, as square rods of the strand's
    // diameter (erected only: no flat state).
    if let Some((st, b)) = plan
        .structure
        .as_ref()
        .and_then(|st| Some((st, st.bracing.as_ref()?)))
    {
        let ends = st.drawing.as_ref().map_or(&[][..], |d| &d.cables[..]);
        let mut geo = Geo::default();
        for [p, q] in ends {
            let (p, q) = ([p.x, p.y, p.z], [q.x, q.y, q.z]);
            let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
            let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if length == 0.0 {
                continue;
            }
            let u = normalized(d);
            let up = if u[2].abs() < 0.9 {
                [0.0, 0.0, 1.0]
            } else {
                [1.0, 0.0, 0.0]
            };
            let v = normalized(cross(u, up));
            let w = cross(u, v);
            let r = 0.5 * b.diameter_mm;
            geo.cuboid(
                add(p, d, 0.5),
                [(u, 0.5 * length), (v, r), (w, r)],
                c,
                CABLE,
            );
        }
        if !geo.pos.is_empty() {
            meshes.push(bin.mesh(&geo, "cables", 1, false, 4));
            let ids: Vec<&str> = b.cables.iter().map(|k| k.id.as_str()).collect();
            nodes.push(json!({
                "name": "cables",
                "mesh": meshes.len() - 1,
                "extras": {"kind": "cables", "ids": ids, "diameter_mm": b.diameter_mm}
            }));
            children.push(nodes.len() - 1);
        }
    }
    // Every node as a point, in plan order.
    if !plan.nodes.is_empty() {
        let mut geo = Geo::default();
        let morph = shape.nodes.iter().any(|n| n.flat_mm.is_some());
        for (n, sn) in plan.nodes.iter().zip(&shape.nodes) {
            geo.vertex(n.position_mm, sn.flat_mm, c, [20, 20, 20]);
        }
        meshes.push(bin.mesh(&geo, "nodes", 2, morph, 0));
        nodes.push(json!({"name": "nodes", "mesh": meshes.len() - 1, "extras": {"kind": "nodes"}}));
        children.push(nodes.len() - 1);
    }
    let root = nodes.len();
    nodes.push(json!({
        "name": "grid",
        "translation": [c[0] / 1000.0, c[2] / 1000.0, -c[1] / 1000.0],
        "children": children
    }));
    let stops: Vec<Value> = UTILISATION_STOPS
        .iter()
        .map(|(u, rgb)| json!([u, rgb]))
        .collect();
    let flat = plan.flat.is_some() && shape.lines.iter().any(|l| l.flat.is_some());
    // The asset first, so a reader of the first bytes sees whose file it is.
    let asset = json!({
        "version": "2.0",
        "generator": format!("lamella {}", env!("CARGO_PKG_VERSION"))
    });
    let about = json!({
                "frame": "glTF (x, y, z) m = (x, z, -y) mm of the network / 1000; root translation = the grid's centre",
                "network": plan.network.name,
                "profile": plan.profile.as_ref().map(|p| p.name.clone()),
                "utilisation_stops": stops,
                "overstressed": OVERSTRESSED,
                "unchecked": UNCHECKED,
                "detail": if full { "solids" } else { "ribbons" },
                "flat": flat,
                "max_utilisation": plan.check.as_ref().map(|c| c.max_utilization)
    });
    let doc = json!({
        "scene": 0,
        "scenes": [{"name": plan.network.name, "nodes": [root], "extras": about}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [
            {"name": "lamella", "doubleSided": true,
             "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.7}},
            {"name": "hardware", "doubleSided": true,
             "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.5, "roughnessFactor": 0.5}},
            {"name": "node",
             "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        ],
        "buffers": [{"byteLength": bin.data.len()}],
        "bufferViews": bin.views,
        "accessors": bin.accessors
    });
    let rest = serde_json::to_string(&doc).map_err(|e| e.to_string())?;
    let asset = serde_json::to_string(&asset).map_err(|e| e.to_string())?;
    let mut text = format!("{{\"asset\":{asset},{}", &rest[1..]).into_bytes();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let mut data = bin.data;
    while !data.len().is_multiple_of(4) {
        data.push(0);
    }
    let total = 12 + 8 + text.len() + 8 + data.len();
    let total = u32::try_from(total).map_err(|_| "the model is over 4 GiB".to_string())?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.extend_from_slice(&(data.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&data);
    Ok(out)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_colour_ramp_meets_its_stops() {
        assert_eq!(utilisation_colour(Some(0.0)), UTILISATION_STOPS[0].1);
        assert_eq!(utilisation_colour(Some(0.5)), UTILISATION_STOPS[1].1);
        assert_eq!(utilisation_colour(Some(1.0)), UTILISATION_STOPS[3].1);
        assert_eq!(utilisation_colour(Some(1.01)), OVERSTRESSED);
        assert_eq!(utilisation_colour(None), UNCHECKED);
        // Half way from 0.5 to 0.75.
        assert_eq!(utilisation_colour(Some(0.625)), [212, 198, 131]);
    }

    #[test]
    fn a_slot_steps_the_section() {
        let f = |s: f64| ShapeFrame {
            station_mm: s,
            point_mm: [s, 0.0, 0.0],
            tangent: [1.0, 0.0, 0.0],
            normal: [0.0, 0.0, 1.0],
            across: [0.0, 1.0, 0.0],
        };
        let frames = [f(0.0), f(100.0)];
        let cut = Cut {
            from_mm: 40.0,
            to_mm: 60.0,
            top: true,
            depth_mm: 25.0,
        };
        let cols = columns(&frames, 25.0, &[cut]);
        assert_eq!(
            cols,
            vec![
                (0.0, -25.0, 25.0),
                (40.0, -25.0, 25.0),
                (40.0, -25.0, 0.0),
                (60.0, -25.0, 0.0),
                (60.0, -25.0, 25.0),
                (100.0, -25.0, 25.0)
            ]
        );
    }
}
