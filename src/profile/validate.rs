//! The checks a raw profile passes before it becomes a [`Profile`](super::Profile)
//! (the guarantees in [`super`]'s documentation): one function per section,
//! in the order a profile file lists them, each a list of named checks.
//! The first failure is the answer, under the field's dotted path as the
//! file writes it (`lamella.thickness_mm`, `stock.sizes[1].width_mm`).

use super::{
    Bolt, Bracing, Cutting, FieldError, Grain, Joint, JointSystem, Material, RawProfile, RawStock,
    Section, ShearBlock, Splice, StockKind, StockSize, Stud, Washer,
};

/// What a check gives: nothing, or the field that fails and why.
type Check = Result<(), FieldError>;

/// Check every section of `raw`, in file order.
pub fn profile(raw: &RawProfile) -> Check {
    name(&raw.name)?;
    material(&raw.material)?;
    section(&raw.section)?;
    joint(&raw.joint, &raw.section, raw.stud.is_some())?;
    if let Some(b) = &raw.node_bolt {
        node_bolt(b, &raw.section)?;
    }
    if let Some(w) = &raw.washer {
        washer(w, raw.node_bolt.is_some())?;
    }
    if let Some(s) = &raw.shear_block {
        shear_block(s, &raw.section)?;
    }
    if let Some(s) = &raw.stud {
        stud(s)?;
    }
    if let Some(s) = &raw.splice {
        splice(s)?;
    }
    if let Some(b) = &raw.bracing {
        bracing(b)?;
        // The eye plate goes under the node bolt (and the edge bolt).
        let Some(bolt) = &raw.node_bolt else {
            return fail(
                "bracing",
                "needs node_bolt: each cable's eye plate is held under the node bolt",
            );
        };
        let edge_mm = raw.edge_joint.bolt_diameter_mm.unwrap_or(bolt.diameter_mm);
        eye_plate_holes(
            &b.eye_plate,
            bolt.diameter_mm.max(edge_mm) + bolt.hole_clearance_mm,
        )?;
        match b.eye_plate.yield_mpa {
            Some(fy) => positive("bracing.eye_plate.yield_mpa", fy)?,
            None if raw.material.grain == Grain::AlongStrip => {
                return fail(
                    "bracing.eye_plate.yield_mpa",
                    "is needed: the eye plates are steel, the profile's material is timber",
                )
            }
            None => {}
        }
    }
    if let Some(c) = &raw.hardware.bolt_class {
        if !super::BOLT_CLASSES.contains(&c.as_str()) {
            return fail(
                "hardware.bolt_class",
                format!(
                    "`{c}` is no property class this lamella has tightening torques for: write {}, or leave it out",
                    super::BOLT_CLASSES.join(" or ")
                ),
            );
        }
    }
    stock(&raw.stock, raw.section.height_mm)?;
    cutting(&raw.cutting, raw.material.grain)?;
    if let Some(m) = raw.check.max_sagitta_mm {
        positive("check.max_sagitta_mm", m)?;
    }
    edge_joint(raw)?;
    stocks(raw)
}

/// `edge_joint:` positive sizes; a bolted joint has a bolt (its own or
/// the node bolt) and a doubled strip whose gap takes its hole.
fn edge_joint(raw: &RawProfile) -> Check {
    let e = &raw.edge_joint;
    if let Some(d) = e.bolt_diameter_mm {
        positive("edge_joint.bolt_diameter_mm", d)?;
    }
    if let Some(b) = e.max_band_bow_mm {
        positive("edge_joint.max_band_bow_mm", b)?;
    }
    if e.kind == Some(super::EdgeJointKind::Bolt) {
        let clearance = raw.node_bolt.as_ref().map_or(1.0, |b| b.hole_clearance_mm);
        let Some(d) = e
            .bolt_diameter_mm
            .or(raw.node_bolt.as_ref().map(|b| b.diameter_mm))
        else {
            return fail(
                "edge_joint.kind",
                "a bolted edge joint needs edge_joint.bolt_diameter_mm (or a node_bolt)",
            );
        };
        if raw.section.per_strip != 2 || d + clearance > raw.section.gap_mm {
            return fail(
                "edge_joint.kind",
                format!(
                    "the edge bolt runs in the gap of a doubled strip: a {} mm hole needs lamella.per_strip 2 and a gap of at least that (write kind: slot)",
                    d + clearance
                ),
            );
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Number checks

/// The failure of `field`, for `why`.
fn fail(field: &str, why: impl Into<String>) -> Check {
    Err(FieldError {
        field: field.into(),
        message: why.into(),
    })
}

/// Every number has a sane upper bound, checked under its own name (a
/// length beyond 10 km is a typo, not a part): 1e7 for `_mm`, else 1e12.
fn at_most(field: &str, x: f64) -> Check {
    let (max, unit) = if field.ends_with("_mm") {
        (1e7, " mm")
    } else {
        (1e12, "")
    };
    if x <= max {
        Ok(())
    } else {
        fail(field, format!("must be at most {max:e}{unit}, got {x:e}"))
    }
}

/// Finite, above 0 and at most the bound.
fn positive(field: &str, x: f64) -> Check {
    if x.is_finite() && x > 0.0 {
        at_most(field, x)
    } else {
        fail(field, format!("must be positive, got {x}"))
    }
}

/// Finite, 0 or more and at most the bound.
fn non_negative(field: &str, x: f64) -> Check {
    if x.is_finite() && x >= 0.0 {
        at_most(field, x)
    } else {
        fail(field, format!("must be zero or more, got {x}"))
    }
}

/// A count, when given, is at least 1.
fn count(field: &str, n: Option<u32>) -> Check {
    if n == Some(0) {
        fail(field, "must be at least 1")
    } else {
        Ok(())
    }
}

/// A count of hardware per place, at least 1 and at most `max` (every one
/// is a part to make and nest).
fn count_at_most(field: &str, n: u32, max: u32) -> Check {
    count(field, Some(n))?;
    if n > max {
        return fail(field, format!("must be at most {max}, got {n}"));
    }
    Ok(())
}

/// Most washers per node (`washer.per_node`).
pub const MAX_WASHERS_PER_NODE: u32 = 8;

/// Most bolts on each side of a splice (`splice.bolts_per_side`).
pub const MAX_SPLICE_BOLTS_PER_SIDE: u32 = 16;

/// Most stock sizes (`stock.sizes`): the nest tries every size, at about a
/// second each on a big kit.
pub const MAX_STOCK_SIZES: usize = 16;

/// Most allowed rotations listed (`cutting.allowed_rotations_deg`): the
/// four quarter turns.
pub const MAX_ROTATIONS: usize = 4;

/// Text, when given, is not blank.
fn not_blank(field: &str, text: Option<&str>) -> Check {
    if text.is_some_and(|t| t.trim().is_empty()) {
        fail(field, "must not be empty")
    } else {
        Ok(())
    }
}

// ---------------------------------------------------------------------------
// Sections

/// `name:` not blank.
fn name(name: &str) -> Check {
    not_blank("name", Some(name))
}

/// `material:` positive values, γ_M ≥ 1, k_mod ≤ 1.1, G below E.
fn material(m: &Material) -> Check {
    positive("material.youngs_modulus_mpa", m.youngs_modulus_mpa)?;
    positive("material.shear_modulus_mpa", m.shear_modulus_mpa)?;
    positive(
        "material.characteristic_strength_mpa",
        m.characteristic_strength_mpa,
    )?;
    positive("material.partial_factor", m.partial_factor)?;
    positive("material.modification_factor", m.modification_factor)?;
    positive("material.density_kg_per_m3", m.density_kg_per_m3)?;
    if m.partial_factor < 1.0 {
        return fail(
            "material.partial_factor",
            format!("must be at least 1, got {}", m.partial_factor),
        );
    }
    if m.modification_factor > 1.1 {
        return fail(
            "material.modification_factor",
            format!("must be at most 1.1, got {}", m.modification_factor),
        );
    }
    if m.shear_modulus_mpa >= m.youngs_modulus_mpa {
        return fail(
            "material.shear_modulus_mpa",
            format!(
                "{} is not below Young's modulus {}",
                m.shear_modulus_mpa, m.youngs_modulus_mpa
            ),
        );
    }
    Ok(())
}

/// `lamella:` positive section, thinner than high, one or two per strip
/// (two with a gap).
fn section(l: &Section) -> Check {
    positive("lamella.thickness_mm", l.thickness_mm)?;
    positive("lamella.height_mm", l.height_mm)?;
    non_negative("lamella.gap_mm", l.gap_mm)?;
    non_negative("lamella.end_allowance_mm", l.end_allowance_mm)?;
    if l.thickness_mm >= l.height_mm {
        return fail(
            "lamella.thickness_mm",
            format!("{} is not below the height {}", l.thickness_mm, l.height_mm),
        );
    }
    match l.per_strip {
        1 => Ok(()),
        2 => positive("lamella.gap_mm", l.gap_mm).map_err(|_| FieldError {
            field: "lamella.gap_mm".into(),
            message: "a doubled strip (per_strip: 2) needs a gap above 0".into(),
        }),
        n => fail("lamella.per_strip", format!("must be 1 or 2, got {n}")),
    }
}

/// `joint:` clearances, a tolerance below 90°, and what the system needs:
/// two levels have studs, a doubled strip and a level offset; one level
/// has no offset.
fn joint(j: &Joint, l: &Section, has_studs: bool) -> Check {
    non_negative("joint.slot_clearance_mm", j.slot_clearance_mm)?;
    non_negative("joint.level_offset_mm", j.level_offset_mm)?;
    if !(0.0..90.0).contains(&j.rotation_tolerance_deg) {
        return fail(
            "joint.rotation_tolerance_deg",
            format!("must be in [0, 90), got {}", j.rotation_tolerance_deg),
        );
    }
    match j.system {
        JointSystem::TwoLevel => {
            if !has_studs {
                return fail("stud", "a two-level joint needs studs");
            }
            if l.per_strip != 2 {
                return fail(
                    "lamella.per_strip",
                    "a two-level joint puts its stud in the gap of a doubled strip: use 2",
                );
            }
            positive("joint.level_offset_mm", j.level_offset_mm)
        }
        JointSystem::Interlocking => {
            if j.level_offset_mm != 0.0 {
                return fail(
                    "joint.level_offset_mm",
                    "an interlocking joint has one level: use 0",
                );
            }
            Ok(())
        }
    }
}

/// `node_bolt:` a positive diameter that passes through a doubled strip's gap.
fn node_bolt(b: &Bolt, l: &Section) -> Check {
    positive("node_bolt.diameter_mm", b.diameter_mm)?;
    non_negative("node_bolt.hole_clearance_mm", b.hole_clearance_mm)?;
    if l.per_strip == 2 && b.diameter_mm > l.gap_mm {
        return fail(
            "node_bolt.diameter_mm",
            format!(
                "{} does not pass through the {} mm gap between the lamellas",
                b.diameter_mm, l.gap_mm
            ),
        );
    }
    Ok(())
}

/// `washer:` positive sizes, at least one per node, and a node bolt to
/// tighten them.
fn washer(w: &Washer, has_node_bolt: bool) -> Check {
    positive("washer.thickness_mm", w.thickness_mm)?;
    positive("washer.arm_length_mm", w.arm_length_mm)?;
    positive("washer.arm_width_mm", w.arm_width_mm)?;
    count_at_most("washer.per_node", w.per_node, MAX_WASHERS_PER_NODE)?;
    if !has_node_bolt {
        return fail(
            "washer",
            "washers are tightened by a node bolt: add node_bolt",
        );
    }
    Ok(())
}

/// `shear_block:` positive sizes, and two lamellas to couple.
fn shear_block(s: &ShearBlock, l: &Section) -> Check {
    positive("shear_block.length_mm", s.length_mm)?;
    positive("shear_block.max_spacing_mm", s.max_spacing_mm)?;
    positive("shear_block.slenderness_limit", s.slenderness_limit)?;
    non_negative("shear_block.clearance_mm", s.clearance_mm)?;
    positive("shear_block.bolt_diameter_mm", s.bolt_diameter_mm)?;
    if l.per_strip != 2 {
        return fail(
            "shear_block",
            "shear blocks couple two lamellas: needs lamella.per_strip 2",
        );
    }
    Ok(())
}

/// `stud:` positive sizes.
fn stud(s: &Stud) -> Check {
    positive("stud.length_mm", s.length_mm)?;
    positive("stud.fastener_diameter_mm", s.fastener_diameter_mm)?;
    positive("stud.bar_length_mm", s.bar_length_mm)
}

/// `splice:` positive sizes, at least one bolt a side.
fn splice(s: &Splice) -> Check {
    positive("splice.plate_length_mm", s.plate_length_mm)?;
    positive("splice.bolt_diameter_mm", s.bolt_diameter_mm)?;
    count_at_most(
        "splice.bolts_per_side",
        s.bolts_per_side,
        MAX_SPLICE_BOLTS_PER_SIDE,
    )
}

/// `bracing:` positive moduli and sizes, sizes ascending and each
/// stronger than the last, an eye plate whose holes do not meet.
fn bracing(b: &Bracing) -> Check {
    let c = &b.cable;
    not_blank("bracing.cable.designation", Some(&c.designation))?;
    positive("bracing.cable.youngs_modulus_mpa", c.youngs_modulus_mpa)?;
    positive("bracing.cable.partial_factor", c.partial_factor)?;
    if c.partial_factor < 1.0 {
        return fail(
            "bracing.cable.partial_factor",
            format!(
                "must be at least 1 (EN 1993-1-11: 1.5·γ_R), got {}",
                c.partial_factor
            ),
        );
    }
    if c.sizes.is_empty() {
        return fail("bracing.cable.sizes", "lists no size: give at least one");
    }
    for (i, s) in c.sizes.iter().enumerate() {
        let at = |f: &str| format!("bracing.cable.sizes[{i}].{f}");
        positive(&at("diameter_mm"), s.diameter_mm)?;
        positive(&at("area_mm2"), s.area_mm2)?;
        positive(&at("breaking_load_kn"), s.breaking_load_kn)?;
        if let Some(prev) = i.checked_sub(1).map(|j| c.sizes[j]) {
            if s.diameter_mm <= prev.diameter_mm || s.breaking_load_kn <= prev.breaking_load_kn {
                return fail(
                    &at("diameter_mm"),
                    "sizes must ascend: each thicker and stronger than the one before",
                );
            }
        }
    }
    positive("bracing.fitting_offset_mm", b.fitting_offset_mm)?;
    let e = &b.eye_plate;
    positive("bracing.eye_plate.thickness_mm", e.thickness_mm)?;
    positive("bracing.eye_plate.width_mm", e.width_mm)?;
    positive("bracing.eye_plate.hole_spacing_mm", e.hole_spacing_mm)?;
    positive("bracing.eye_plate.pin_hole_mm", e.pin_hole_mm)?;
    if e.pin_hole_mm >= e.width_mm {
        return fail(
            "bracing.eye_plate.pin_hole_mm",
            format!(
                "must be less than the plate's width {} mm, got {}",
                e.width_mm, e.pin_hole_mm
            ),
        );
    }
    non_negative("bracing.terminal_mm", b.terminal_mm)?;
    positive(
        "bracing.turnbuckle.mid_length_mm",
        b.turnbuckle.mid_length_mm,
    )?;
    non_negative("bracing.turnbuckle.take_up_mm", b.turnbuckle.take_up_mm)
}

/// An eye plate's bolt hole (`bolt_hole_mm`, the widest bolt's with its
/// clearance) inside its width, clear of the pin's hole.
fn eye_plate_holes(e: &super::EyePlate, bolt_hole_mm: f64) -> Check {
    if bolt_hole_mm >= e.width_mm {
        return fail(
            "bracing.eye_plate.width_mm",
            format!(
                "must be more than the bolt's {bolt_hole_mm} mm hole, got {}",
                e.width_mm
            ),
        );
    }
    let touch_mm = 0.5 * (bolt_hole_mm + e.pin_hole_mm);
    if e.hole_spacing_mm <= touch_mm {
        return fail(
            "bracing.eye_plate.hole_spacing_mm",
            format!(
                "the {bolt_hole_mm} mm bolt hole and the {} mm pin hole meet: \
                 the spacing must be more than {touch_mm} mm, got {}",
                e.pin_hole_mm, e.hole_spacing_mm
            ),
        );
    }
    Ok(())
}

/// `stock:` the values every form may give, then the fields its form
/// needs and allows ([`sheet`] or [`coil`]).
fn stock(st: &RawStock, height_mm: f64) -> Check {
    if let Some(p) = st.price_per_unit {
        non_negative("stock.price_per_unit", p)?;
    }
    if let Some(p) = st.price_per_m {
        non_negative("stock.price_per_m", p)?;
    }
    if let Some(x) = st.length_step_mm {
        positive("stock.length_step_mm", x)?;
    }
    count("stock.max_count", st.max_count)?;
    not_blank("stock.currency", st.currency.as_deref())?;
    match st.kind {
        StockKind::Sheet => sheet(st, height_mm),
        StockKind::Coil => coil(st, height_mm),
    }
}

/// A stock width holds a lamella's height.
fn wide_enough(field: &str, width_mm: f64, height_mm: f64) -> Check {
    if width_mm < height_mm {
        fail(
            field,
            format!("{width_mm} is narrower than a lamella ({height_mm} mm)"),
        )
    } else {
        Ok(())
    }
}

/// Sheets: no coil fields, then one size inline ([`one_sheet_size`]) or a
/// list ([`sheet_sizes`]).
fn sheet(st: &RawStock, height_mm: f64) -> Check {
    if st.price_per_m.is_some() {
        return fail(
            "stock.price_per_m",
            "is for a coil (kind: coil); a sheet has price_per_unit",
        );
    }
    if st.length_step_mm.is_some() {
        return fail(
            "stock.length_step_mm",
            "is for a coil (kind: coil); a sheet is not cut to length",
        );
    }
    match &st.sizes {
        None => one_sheet_size(st, height_mm),
        Some(list) => sheet_sizes(st, list, height_mm),
    }
}

/// One sheet size inline: its length and width, positive, wide enough.
fn one_sheet_size(st: &RawStock, height_mm: f64) -> Check {
    let missing = "missing: a sheet needs length_mm and width_mm, or a list of sizes";
    let Some(l) = st.length_mm else {
        return fail("stock.length_mm", missing);
    };
    let Some(w) = st.width_mm else {
        return fail("stock.width_mm", missing);
    };
    positive("stock.length_mm", l)?;
    positive("stock.width_mm", w)?;
    wide_enough("stock.width_mm", w, height_mm)
}

/// Several sheet sizes: nothing of one size beside the list; at least one
/// size; each named (if at all) by a non-blank name, positive, wide
/// enough, priced like the first, and given once.
fn sheet_sizes(st: &RawStock, list: &[StockSize], height_mm: f64) -> Check {
    for (field, present) in [
        ("stock.length_mm", st.length_mm.is_some()),
        ("stock.width_mm", st.width_mm.is_some()),
        ("stock.price_per_unit", st.price_per_unit.is_some()),
        ("stock.max_count", st.max_count.is_some()),
    ] {
        if present {
            return fail(field, "give it per size in stock.sizes, not beside them");
        }
    }
    if list.is_empty() {
        return fail("stock.sizes", "must list at least one size");
    }
    if list.len() > MAX_STOCK_SIZES {
        return fail(
            "stock.sizes",
            format!(
                "{} sizes means a nest per size (about a second each); the limit is {MAX_STOCK_SIZES}",
                list.len()
            ),
        );
    }
    let mut labels: Vec<String> = Vec::with_capacity(list.len());
    for (i, z) in list.iter().enumerate() {
        let f = |name: &str| format!("stock.sizes[{i}].{name}");
        not_blank(&f("name"), z.name.as_deref())?;
        let Some(length_mm) = z.length_mm else {
            return fail(&f("length_mm"), "missing");
        };
        positive(&f("length_mm"), length_mm)?;
        positive(&f("width_mm"), z.width_mm)?;
        wide_enough(&f("width_mm"), z.width_mm, height_mm)?;
        if let Some(p) = z.price_per_unit {
            non_negative(&f("price_per_unit"), p)?;
        }
        count(&f("max_count"), z.max_count)?;
        if z.price_per_unit.is_some() != list[0].price_per_unit.is_some() {
            return fail(
                &f("price_per_unit"),
                "give a price for every size or for none (costs compare only between priced sizes)",
            );
        }
        let label = z.label();
        if let Some(j) = labels.iter().position(|x| *x == label) {
            return fail(
                &f(if z.name.is_some() {
                    "name"
                } else {
                    "length_mm"
                }),
                format!("`{label}` is stock.sizes[{j}] again: give each size once"),
            );
        }
        labels.push(label);
    }
    Ok(())
}

/// A coil: one width (no list), positive and wide enough; a piece length,
/// if given, positive and at least the length step; without one, no price
/// or count per piece; one price, per metre or per piece.
fn coil(st: &RawStock, height_mm: f64) -> Check {
    if st.sizes.is_some() {
        return fail(
            "stock.sizes",
            "a coil has one width: give width_mm (and length_mm for the longest piece)",
        );
    }
    let Some(w) = st.width_mm else {
        return fail("stock.width_mm", "missing: a coil needs its width");
    };
    positive("stock.width_mm", w)?;
    wide_enough("stock.width_mm", w, height_mm)?;
    match st.length_mm {
        Some(l) => {
            positive("stock.length_mm", l)?;
            if st.length_step_mm.is_some_and(|x| x > l) {
                return fail(
                    "stock.length_step_mm",
                    "is longer than a piece (stock.length_mm)",
                );
            }
        }
        None => {
            if st.price_per_unit.is_some() {
                return fail(
                    "stock.price_per_unit",
                    "is per piece: give the piece length (length_mm), or price_per_m",
                );
            }
            if st.max_count.is_some() {
                return fail(
                    "stock.max_count",
                    "counts pieces: give the piece length (length_mm)",
                );
            }
        }
    }
    if st.price_per_unit.is_some() && st.price_per_m.is_some() {
        return fail(
            "stock.price_per_m",
            "give price_per_m or price_per_unit, not both",
        );
    }
    Ok(())
}

/// `cutting:` allowances ≥ 0; at least one rotation, each a quarter turn;
/// along the grain, no quarter turn across it.
fn cutting(c: &Cutting, grain: Grain) -> Check {
    non_negative("cutting.kerf_mm", c.kerf_mm)?;
    non_negative("cutting.part_spacing_mm", c.part_spacing_mm)?;
    non_negative("cutting.edge_margin_mm", c.edge_margin_mm)?;
    let rotations = &c.allowed_rotations_deg;
    if rotations.is_empty() {
        return fail(
            "cutting.allowed_rotations_deg",
            "must allow at least one rotation",
        );
    }
    if rotations.len() > MAX_ROTATIONS {
        return fail(
            "cutting.allowed_rotations_deg",
            format!(
                "lists {} rotations; at most {MAX_ROTATIONS} (0, 90, 180, 270, each once)",
                rotations.len()
            ),
        );
    }
    if let Some(r) = rotations.iter().find(|r| ![0, 90, 180, 270].contains(*r)) {
        return fail(
            "cutting.allowed_rotations_deg",
            format!("{r} is not one of 0, 90, 180, 270"),
        );
    }
    if grain == Grain::AlongStrip {
        if let Some(r) = rotations.iter().find(|r| **r == 90 || **r == 270) {
            return fail(
                "cutting.allowed_rotations_deg",
                format!("{r}° turns a strip across the grain (material.grain: along_strip allows 0 and 180)"),
            );
        }
    }
    Ok(())
}

/// The checks of `stocks:` (each entry's fields under `stocks.<piece>.`),
/// after every other section passed.
fn stocks(raw: &RawProfile) -> Check {
    let fail = |field: String, message: String| Err(FieldError { field, message });
    for e in &raw.stocks {
        let at = e.piece.field();
        let f = |name: &str| format!("{at}.{name}");
        if !raw.makes(e.piece) {
            return fail(
                at.clone(),
                format!(
                    "the profile makes no {}s (its `{}:` section is null)",
                    e.piece.role().replace('-', " "),
                    match e.piece {
                        super::Piece::EyePlate => "bracing",
                        p => p.key(),
                    }
                ),
            );
        }
        if let Some(n) = &e.name {
            let ok = !n.is_empty()
                && n.len() <= 64
                && !n.starts_with('.')
                && n.bytes()
                    .all(|b| b.is_ascii_alphanumeric() || matches!(b, b'-' | b'_' | b'.'));
            if !ok {
                return fail(
                    f("name"),
                    format!("`{n}`: a group name is 1 to 64 letters, digits, `-`, `_` or `.` (it names files), not starting with `.`"),
                );
            }
        }
        if e.material.as_deref().is_some_and(|m| m.trim().is_empty()) {
            return fail(f("material"), "is blank".into());
        }
        for (name, x) in [
            ("kerf_mm", e.kerf_mm),
            ("part_spacing_mm", e.part_spacing_mm),
            ("edge_margin_mm", e.edge_margin_mm),
            ("price_per_unit", e.price_per_unit),
        ] {
            if let Some(x) = x {
                if !(x.is_finite() && x >= 0.0) {
                    return fail(f(name), format!("must be a finite number ≥ 0 (got {x})"));
                }
            }
        }
        if e.currency.as_deref().is_some_and(|c| c.trim().is_empty()) {
            return fail(f("currency"), "is blank".into());
        }
        let currency = e
            .stock
            .as_ref()
            .and_then(|s| s.currency.as_deref())
            .or(e.currency.as_deref());
        if let (Some(c), Some(lamella)) = (currency, raw.stock.currency.as_deref()) {
            if c != lamella {
                return fail(
                    f("currency"),
                    format!("{c}, but the lamella stock prices in {lamella}: give every stock in one currency"),
                );
            }
        }
        if e.piece == super::Piece::Stud {
            if e.stock.is_some() {
                return fail(
                    at.clone(),
                    "studs are sawn from bars stud.bar_length_mm long (section gap × gap): give only name, material, price_per_unit, currency, kerf_mm".into(),
                );
            }
        } else if let Some(st) = &e.stock {
            stock(st, 0.0).map_err(|err| FieldError {
                field: err.field.replacen("stock", &at, 1),
                message: err.message.replace("stock.", &format!("{at}.")),
            })?;
        } else if e.price_per_unit.is_some()
            && (raw.stock.kind == StockKind::Coil
                || raw.stock.sizes.as_ref().is_some_and(|l| l.len() > 1))
        {
            return fail(
                f("price_per_unit"),
                "prices one sheet, but the lamella stock this group takes has several sizes or is a coil: give the group its sizes with their prices".into(),
            );
        }
        if let Some(r) = &e.allowed_rotations_deg {
            let c = Cutting {
                kerf_mm: 0.0,
                part_spacing_mm: 0.0,
                edge_margin_mm: 0.0,
                allowed_rotations_deg: r.clone(),
            };
            let grain = if e.material.is_some() {
                Grain::None
            } else {
                raw.material.grain
            };
            cutting(&c, grain).map_err(|err| FieldError {
                field: f("allowed_rotations_deg"),
                message: err.message,
            })?;
        }
    }
    // A piece that names its own stock must not share its material and
    // thickness with an earlier group (it would be nested with it).
    let mut seen: Vec<(String, f64, super::Piece)> = Vec::new();
    for piece in super::Piece::ALL.into_iter().filter(|&p| raw.makes(p)) {
        let key = (raw.piece_material(piece), raw.piece_thickness_mm(piece));
        let own = piece == super::Piece::Lamella
            || raw.piece_stock(piece).is_some_and(|e| {
                e.stock.is_some()
                    || e.name.is_some()
                    || e.kerf_mm.is_some()
                    || e.part_spacing_mm.is_some()
                    || e.edge_margin_mm.is_some()
                    || e.allowed_rotations_deg.is_some()
                    || e.price_per_unit.is_some()
            });
        if let Some((_, _, first)) = seen
            .iter()
            .find(|(m, t, _)| *m == key.0 && *t == key.1)
            .filter(|_| piece != super::Piece::Stud)
        {
            if own {
                return fail(
                    piece.field(),
                    format!(
                        "the {}s are {} mm of `{}` like the {}s, so they are cut from that stock: leave this entry out, or name another material",
                        piece.role().replace('-', " "),
                        super::groups::trim_mm(key.1),
                        key.0,
                        first.role().replace('-', " "),
                    ),
                );
            }
        } else {
            seen.push((key.0, key.1, piece));
        }
    }
    // Group names are unique (they name the sheet files).
    let groups = super::Profile::raw_groups(raw);
    for (i, g) in groups.iter().enumerate() {
        if let Some(j) = groups[..i].iter().position(|h| h.name == g.name) {
            return fail(
                format!("{}.name", g.pieces[0].field()),
                format!(
                    "`{}` already names the {} group: give each group its own name",
                    g.name,
                    groups[j].pieces[0].role()
                ),
            );
        }
    }
    Ok(())
}
