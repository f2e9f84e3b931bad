//! The loads model: what acts on the erected grid (load cases), where it is
//! held (supports), how cases combine (EN 1990 partial and combination
//! factors) and how far it may deflect. Plain data in the units of the
//! loads file (kN, kN/m, kN/m², mm); `formats::read::loads_file` reads
//! and checks a file into it, `structure::loads` turns it into the frame
//! model's loads (N, mm) and combinations.
//!
//! # Load cases
//!
//! A case is one characteristic action, named (`G`, `S`, `W+`), of one
//! [`Action`]: permanent (G), snow (S), wind (W) or imposed (Q). It may
//! carry, each optional:
//!
//! * `self_weight` (permanent cases only): a factor on the kit's weight —
//!   the lamellas' material and the hardware the frame model lumps at its
//!   nodes; default 1 in a permanent case;
//! * `surface_kn_per_m2` (permanent only): a further dead load on the
//!   surface's area (a cover and its fixings), acting along −z;
//! * `snow_kn_per_m2` (snow only, ≥ 0): uniform snow on the plan
//!   projection, acting along −z: a node carrying the area vector a (its
//!   tributary area times the unit normal) takes −z · s · |a_z|;
//! * `wind_kn_per_m2` (wind only, signed): a pressure normal to the
//!   surface. The surface's unit normal n is oriented with n_z ≥ 0 (up);
//!   a **positive** value is pressure toward the surface's inside, along −n
//!   (down on a level roof), a **negative** one suction, along +n (uplift):
//!   the node takes −p · a. This is EN 1991-1-4's sign of c_p,net for
//!   canopies (positive: net downward);
//! * `point_loads`: forces on joints, by network node id, kN (global
//!   x, y, z);
//! * `line_loads`: forces per metre along every lamella of a strip, by
//!   strip id, kN/m (global x, y, z). A strip of two lamellas takes the
//!   value on each of them.
//!
//! Cases of one variable action (snow arrangements, wind directions and
//! signs, imposed load positions) are alternatives: a combination takes at
//! most one of each. All permanent cases act together.
//!
//! # Supports
//!
//! A list of entries, each a selection of joints and a kind:
//!
//! * `at: boundary` — every joint at a strip's end (the network's
//!   boundary); `at: lowest` with `band_mm` — every joint whose z lies
//!   within `band_mm` of the lowest joint's; `at: nodes` with `nodes` — the
//!   joints of those network node ids;
//! * `kind: fixed` (all six degrees of freedom), `pinned` (the three
//!   translations), or `roller` with `direction` (translation restrained
//!   along that one direction only; rotations free).
//!
//! Entries apply in order: a joint selected again takes the later entry's
//! kind. **Without a `supports` section every boundary joint is pinned**
//! ([`SupportSpec::default_list`]).
//!
//! # Factors (EN 1990)
//!
//! Fundamental combinations of the ultimate limit state, EN 1990 (6.10):
//! Σ γ_G·G + γ_Q·Q_1 + Σ γ_Q·ψ_0,i·Q_i, each variable action leading in
//! turn; the characteristic combination of the serviceability limit state
//! (6.14b): Σ G + Q_1 + Σ ψ_0,i·Q_i. Defaults ([`Factors::default`]):
//! γ_G,sup = 1.35, γ_G,inf = 1.00, γ_Q = 1.5 (EN 1990 Table A1.2(B));
//! ψ_0 = 0.5 for snow (sites at most 1000 m above sea level), 0.6 for
//! wind, 0 for imposed loads on roofs (category H), and roof imposed loads
//! not combined with snow or wind (EN 1990 Table A1.1; EN 1991-1-1
//! §3.3.2(1)). γ_G,inf replaces γ_G,sup where a case of the combination
//! can relieve the permanent load ([`LoadCase::can_relieve`]: wind suction
//! or an upward point or line load); all permanent cases take the same γ_G
//! (they come from one source, the kit and its cover).
//!
//! # Deflection
//!
//! The serviceability limit is `span / span_over` (default span/300) or an
//! absolute `limit_mm`. The span is the largest plan (x–y) distance between
//! two supported nodes: across a grid held along its boundary, its largest
//! opening. Where all supports stand on one vertical (a cantilever), the
//! span is twice the largest plan distance from the support to a node (the
//! convention that makes a cantilever's limit l/150 for span/300).
//!
//! # Bracing
//!
//! An optional `bracing` section asks for diagonal cables on the grid's
//! quads (the cables' sizes and fittings are the profile's `bracing`):
//! `layout` `all` (every quad), `alternate` (every other quad, as a
//! chessboard) or `designed` (the fewest that reach the targets, chosen by
//! the analysis); `diagonals` `single` (default) or `crossed`;
//! `pretension_kn` a value or `auto` (default: the least that keeps single
//! diagonals taut under every combination, snug for crossed pairs);
//! `targets` `alpha_cr` (the smallest ULS α_cr at least this),
//! `deflection` (`true`: within the deflection limit above) and
//! `utilisation` (every ULS utilisation at most this), by default all
//! three (10, true, 1.0), and when given only those named. The structure
//! stage's `bracing` module says how it designs them.

use glam::DVec3;
use std::path::PathBuf;

/// γ_G,sup: permanent actions, unfavourable (EN 1990 Table A1.2(B)).
pub const GAMMA_G_SUP: f64 = 1.35;
/// γ_G,inf: permanent actions, favourable (EN 1990 Table A1.2(B)).
pub const GAMMA_G_INF: f64 = 1.0;
/// γ_Q: variable actions, unfavourable (EN 1990 Table A1.2(B)).
pub const GAMMA_Q: f64 = 1.5;
/// ψ_0 of snow, sites at most 1000 m above sea level (EN 1990 Table A1.1).
pub const PSI0_SNOW: f64 = 0.5;
/// ψ_0 of wind (EN 1990 Table A1.1).
pub const PSI0_WIND: f64 = 0.6;
/// ψ_0 of imposed loads on roofs, category H (EN 1990 Table A1.1).
pub const PSI0_IMPOSED: f64 = 0.0;
/// The default deflection limit: span / 300.
pub const SPAN_OVER: f64 = 300.0;

/// The kind of action a load case is (EN 1990 §4.1.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Action {
    /// Permanent (G): self-weight, cover.
    Permanent,
    /// Snow (S), variable.
    Snow,
    /// Wind (W), variable.
    Wind,
    /// Imposed (Q), variable: on a roof, maintenance (category H).
    Imposed,
}

impl Action {
    /// Every action, in the order combinations list them.
    pub const ALL: [Action; 4] = [
        Action::Permanent,
        Action::Snow,
        Action::Wind,
        Action::Imposed,
    ];

    /// The file's name of it: `permanent`, `snow`, `wind`, `imposed`.
    pub fn as_str(self) -> &'static str {
        match self {
            Action::Permanent => "permanent",
            Action::Snow => "snow",
            Action::Wind => "wind",
            Action::Imposed => "imposed",
        }
    }

    /// EN 1990's letter: G, S, W or Q.
    pub fn symbol(self) -> &'static str {
        match self {
            Action::Permanent => "G",
            Action::Snow => "S",
            Action::Wind => "W",
            Action::Imposed => "Q",
        }
    }

    /// Whether it is a variable action (everything but permanent).
    pub fn is_variable(self) -> bool {
        self != Action::Permanent
    }
}

/// A force on a joint.
#[derive(Debug, Clone, PartialEq)]
pub struct PointLoad {
    /// The joint's network node id.
    pub node: String,
    /// The force, global, kN.
    pub force_kn: DVec3,
}

/// A force per length along a strip's lamellas.
#[derive(Debug, Clone, PartialEq)]
pub struct LineLoad {
    /// The strip's id.
    pub strip: String,
    /// The force per metre of each lamella, global, kN/m.
    pub force_kn_per_m: DVec3,
}

/// One characteristic load case (see the module documentation for each
/// load's direction).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadCase {
    /// Its name, unique in the file (`G`, `S`, `W+`).
    pub name: String,
    /// Its kind of action.
    pub action: Action,
    /// Factor on the kit's self-weight (0: none); permanent cases only.
    pub self_weight: f64,
    /// Further permanent load on the surface area, along −z, kN/m².
    pub surface_kn_per_m2: f64,
    /// Uniform snow on the plan projection, along −z, kN/m² (≥ 0).
    pub snow_kn_per_m2: f64,
    /// Wind pressure normal to the surface, kN/m²: + toward the inside
    /// (along −n, n_z ≥ 0), − suction.
    pub wind_kn_per_m2: f64,
    /// Forces on joints.
    pub point_loads: Vec<PointLoad>,
    /// Forces along strips.
    pub line_loads: Vec<LineLoad>,
}

impl LoadCase {
    /// An empty case of `action` (no load; a permanent one without
    /// self-weight too).
    pub fn new(name: &str, action: Action) -> LoadCase {
        LoadCase {
            name: name.to_string(),
            action,
            self_weight: 0.0,
            surface_kn_per_m2: 0.0,
            snow_kn_per_m2: 0.0,
            wind_kn_per_m2: 0.0,
            point_loads: Vec::new(),
            line_loads: Vec::new(),
        }
    }

    /// Whether the case can act against gravity and so relieve the
    /// permanent load: wind suction, or a point or line load with an
    /// upward component. A combination with such a case is made with
    /// γ_G,inf as well as γ_G,sup.
    pub fn can_relieve(&self) -> bool {
        self.wind_kn_per_m2 < 0.0
            || self.point_loads.iter().any(|p| p.force_kn.z > 0.0)
            || self.line_loads.iter().any(|l| l.force_kn_per_m.z > 0.0)
    }

    /// Whether it carries any load at all.
    pub fn is_empty(&self) -> bool {
        self.self_weight == 0.0
            && self.surface_kn_per_m2 == 0.0
            && self.snow_kn_per_m2 == 0.0
            && self.wind_kn_per_m2 == 0.0
            && self.point_loads.is_empty()
            && self.line_loads.is_empty()
    }
}

/// Which joints a support entry holds.
#[derive(Debug, Clone, PartialEq)]
pub enum Selection {
    /// Every joint at a strip's end.
    Boundary,
    /// Every joint within this height (mm) above the lowest joint.
    Lowest {
        /// The band above the lowest joint's z, mm (≥ 0).
        band_mm: f64,
    },
    /// These joints, by network node id.
    Nodes(Vec<String>),
}

/// How a support holds its joints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SupportKind {
    /// All three translations and all three rotations.
    Fixed,
    /// The three translations; rotations free.
    Pinned,
    /// Translation along one direction only (a roller on a bearing of that
    /// normal); the direction is a unit vector.
    Roller {
        /// The restrained direction, unit.
        direction: DVec3,
    },
}

impl SupportKind {
    /// The file's name of it: `fixed`, `pinned`, `roller`.
    pub fn as_str(self) -> &'static str {
        match self {
            SupportKind::Fixed => "fixed",
            SupportKind::Pinned => "pinned",
            SupportKind::Roller { .. } => "roller",
        }
    }
}

/// A support entry: a selection of joints and how they are held.
#[derive(Debug, Clone, PartialEq)]
pub struct SupportSpec {
    /// Which joints.
    pub at: Selection,
    /// How.
    pub kind: SupportKind,
}

impl SupportSpec {
    /// The supports of a loads file without a `supports` section: every
    /// boundary joint pinned.
    pub fn default_list() -> Vec<SupportSpec> {
        vec![SupportSpec {
            at: Selection::Boundary,
            kind: SupportKind::Pinned,
        }]
    }
}

/// Partial and combination factors (EN 1990 Annex A1); every one
/// overridable in the file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Factors {
    /// γ_G,sup (≥ 1).
    pub gamma_g_sup: f64,
    /// γ_G,inf (between 0 and γ_G,sup).
    pub gamma_g_inf: f64,
    /// γ_Q (≥ 1).
    pub gamma_q: f64,
    /// ψ_0 of snow, in [0, 1].
    pub psi0_snow: f64,
    /// ψ_0 of wind, in [0, 1].
    pub psi0_wind: f64,
    /// ψ_0 of imposed loads, in [0, 1].
    pub psi0_imposed: f64,
    /// Whether imposed loads combine with snow and wind (on roofs they do
    /// not, EN 1991-1-1 §3.3.2(1)).
    pub imposed_with_snow_or_wind: bool,
}

impl Default for Factors {
    fn default() -> Self {
        Factors {
            gamma_g_sup: GAMMA_G_SUP,
            gamma_g_inf: GAMMA_G_INF,
            gamma_q: GAMMA_Q,
            psi0_snow: PSI0_SNOW,
            psi0_wind: PSI0_WIND,
            psi0_imposed: PSI0_IMPOSED,
            imposed_with_snow_or_wind: false,
        }
    }
}

impl Factors {
    /// ψ_0 of a variable action (1 for permanent, which never accompanies).
    pub fn psi0(&self, action: Action) -> f64 {
        match action {
            Action::Permanent => 1.0,
            Action::Snow => self.psi0_snow,
            Action::Wind => self.psi0_wind,
            Action::Imposed => self.psi0_imposed,
        }
    }

    /// Whether actions `a` and `b` (both variable, different) may act in
    /// one combination.
    pub fn combine(&self, a: Action, b: Action) -> bool {
        let imposed_and_weather =
            |x: Action, y: Action| x == Action::Imposed && matches!(y, Action::Snow | Action::Wind);
        a != b
            && (self.imposed_with_snow_or_wind
                || !(imposed_and_weather(a, b) || imposed_and_weather(b, a)))
    }
}

/// The serviceability deflection limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Deflection {
    /// span / this (the span: see the module documentation).
    SpanOver(f64),
    /// An absolute limit, mm.
    LimitMm(f64),
}

impl Default for Deflection {
    fn default() -> Self {
        Deflection::SpanOver(SPAN_OVER)
    }
}

/// A loads file: cases, supports, factors and the deflection limit.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadSpec {
    /// The file it was read from (named in errors).
    pub source: PathBuf,
    /// Free text for people.
    pub description: String,
    /// The load cases, in file order (at least one).
    pub cases: Vec<LoadCase>,
    /// The support entries, in order (at least one).
    pub supports: Vec<SupportSpec>,
    /// Partial and combination factors.
    pub factors: Factors,
    /// The SLS deflection limit.
    pub deflection: Deflection,
    /// Diagonal cable bracing, when the file asks for it.
    pub bracing: Option<BracingSpec>,
}

/// Which quads of the grid get diagonal cables.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BracingLayout {
    /// Every quad.
    All,
    /// Every other quad, as a chessboard's black squares.
    Alternate,
    /// The fewest diagonals that bring the grid to the targets, chosen
    /// one by one by their effect.
    Designed,
}

impl BracingLayout {
    /// As the loads file writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            BracingLayout::All => "all",
            BracingLayout::Alternate => "alternate",
            BracingLayout::Designed => "designed",
        }
    }
}

/// One diagonal per braced quad, or both.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Diagonals {
    /// One, pretensioned so that it stays taut whichever way the load
    /// shears the quad.
    Single,
    /// Both: a crossed pair, one of which the load tightens.
    Crossed,
}

/// The pretension of every cable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pretension {
    /// The least that keeps every cable taut under every combination.
    Auto,
    /// A given value, kN.
    Kn(f64),
}

/// What a designed bracing must reach; `None` / `false`: not a target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BracingTargets {
    /// The smallest α_cr of any ULS combination at least this.
    pub alpha_cr: Option<f64>,
    /// Every SLS deflection within the file's deflection limit.
    pub deflection: bool,
    /// Every ULS utilisation at most this.
    pub utilisation: Option<f64>,
}

impl Default for BracingTargets {
    /// α_cr ≥ 10 (EN 1993-1-1 §5.2.1(3): first order suffices),
    /// the deflection limit, utilisation ≤ 1.
    fn default() -> Self {
        BracingTargets {
            alpha_cr: Some(10.0),
            deflection: true,
            utilisation: Some(1.0),
        }
    }
}

/// The loads file's `bracing`: diagonal cables on the grid's quads (the
/// cables themselves, their fittings and sizes are the profile's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BracingSpec {
    /// Which quads.
    pub layout: BracingLayout,
    /// One diagonal or two per quad.
    pub diagonals: Diagonals,
    /// The cables' pretension.
    pub pretension: Pretension,
    /// What a designed layout must reach (the others are judged by it too).
    pub targets: BracingTargets,
}

/// A field of a loads file that fails a check, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FieldError {
    /// Dotted path of the field, as in the file (`cases[2].snow_kn_per_m2`).
    pub field: String,
    /// What is wrong, one line.
    pub message: String,
}

fn fail<T>(field: impl Into<String>, message: impl Into<String>) -> Result<T, FieldError> {
    Err(FieldError {
        field: field.into(),
        message: message.into(),
    })
}

/// A finite number.
fn finite(field: &str, x: f64) -> Result<(), FieldError> {
    if x.is_finite() {
        Ok(())
    } else {
        fail(field, format!("must be a finite number, got {x}"))
    }
}

/// A finite number ≥ 0.
fn non_negative(field: &str, x: f64) -> Result<(), FieldError> {
    finite(field, x)?;
    if x < 0.0 {
        return fail(field, format!("must be ≥ 0, got {x}"));
    }
    Ok(())
}

/// A finite vector.
fn finite_vec(field: &str, v: DVec3) -> Result<(), FieldError> {
    if v.is_finite() {
        Ok(())
    } else {
        fail(field, format!("must be three finite numbers, got {v}"))
    }
}

/// The largest load lamella takes in any unit (kN, kN/m, kN/m²): a value
/// beyond is a typo (N for kN), not a pavilion.
pub const MAX_LOAD: f64 = 1.0e4;

fn bounded(field: &str, x: f64) -> Result<(), FieldError> {
    if x.abs() > MAX_LOAD {
        return fail(
            field,
            format!("{x} is beyond ±{MAX_LOAD}: loads are in kN, kN/m and kN/m²"),
        );
    }
    Ok(())
}

impl LoadSpec {
    /// Check every value: names unique and non-empty, each load on a case
    /// of its action, magnitudes finite and signed as documented, factors
    /// in their ranges, supports well formed, the deflection limit
    /// positive. The first failure is the answer, under the field's path
    /// as the file writes it.
    pub fn validate(&self) -> Result<(), FieldError> {
        if self.cases.is_empty() {
            return fail("cases", "lists no load case: give at least one");
        }
        for (i, c) in self.cases.iter().enumerate() {
            let at = |f: &str| format!("cases[{i}].{f}");
            validate_case(c, &at)?;
            if let Some(j) = self.cases[..i].iter().position(|d| d.name == c.name) {
                return fail(
                    at("name"),
                    format!("`{}` is also the name of cases[{j}]", c.name),
                );
            }
        }
        if self.supports.is_empty() {
            return fail(
                "supports",
                "lists no support: leave the section out for pinned boundary joints",
            );
        }
        for (i, s) in self.supports.iter().enumerate() {
            validate_support(s, i)?;
        }
        validate_factors(&self.factors)?;
        if let Some(b) = &self.bracing {
            validate_bracing(b)?;
        }
        match self.deflection {
            Deflection::SpanOver(n) => {
                finite("deflection.span_over", n)?;
                if n < 1.0 {
                    return fail(
                        "deflection.span_over",
                        format!("must be ≥ 1 (the limit is span / span_over), got {n}"),
                    );
                }
            }
            Deflection::LimitMm(d) => {
                finite("deflection.limit_mm", d)?;
                if d <= 0.0 {
                    return fail("deflection.limit_mm", format!("must be > 0, got {d}"));
                }
            }
        }
        Ok(())
    }
}

fn validate_bracing(b: &BracingSpec) -> Result<(), FieldError> {
    if let Pretension::Kn(t) = b.pretension {
        non_negative("bracing.pretension_kn", t)?;
        bounded("bracing.pretension_kn", t)?;
    }
    let t = &b.targets;
    if let Some(a) = t.alpha_cr {
        finite("bracing.targets.alpha_cr", a)?;
        if a <= 1.0 {
            return fail(
                "bracing.targets.alpha_cr",
                format!("must be above 1 (the grid buckles at α_cr = 1), got {a}"),
            );
        }
    }
    if let Some(u) = t.utilisation {
        finite("bracing.targets.utilisation", u)?;
        if u <= 0.0 {
            return fail(
                "bracing.targets.utilisation",
                format!("must be > 0, got {u}"),
            );
        }
    }
    if b.layout == BracingLayout::Designed
        && t.alpha_cr.is_none()
        && !t.deflection
        && t.utilisation.is_none()
    {
        return fail(
            "bracing.targets",
            "sets no target for the designed layout: give alpha_cr, deflection or utilisation",
        );
    }
    Ok(())
}

fn validate_case(c: &LoadCase, at: &dyn Fn(&str) -> String) -> Result<(), FieldError> {
    if c.name.trim().is_empty() || c.name.chars().any(char::is_control) {
        return fail(at("name"), "must be a non-empty name on one line");
    }
    let only = |field: &str, x: f64, action: Action| -> Result<(), FieldError> {
        if x != 0.0 && c.action != action {
            return fail(
                at(field),
                format!(
                    "belongs to a case with `action: {}`, this one is `{}`",
                    action.as_str(),
                    c.action.as_str()
                ),
            );
        }
        Ok(())
    };
    non_negative(&at("self_weight"), c.self_weight)?;
    if c.self_weight > 100.0 {
        return fail(
            at("self_weight"),
            format!(
                "is a factor on the kit's weight (1: as built), got {}",
                c.self_weight
            ),
        );
    }
    only("self_weight", c.self_weight, Action::Permanent)?;
    finite(&at("surface_kn_per_m2"), c.surface_kn_per_m2)?;
    bounded(&at("surface_kn_per_m2"), c.surface_kn_per_m2)?;
    only("surface_kn_per_m2", c.surface_kn_per_m2, Action::Permanent)?;
    non_negative(&at("snow_kn_per_m2"), c.snow_kn_per_m2)?;
    bounded(&at("snow_kn_per_m2"), c.snow_kn_per_m2)?;
    only("snow_kn_per_m2", c.snow_kn_per_m2, Action::Snow)?;
    finite(&at("wind_kn_per_m2"), c.wind_kn_per_m2)?;
    bounded(&at("wind_kn_per_m2"), c.wind_kn_per_m2)?;
    only("wind_kn_per_m2", c.wind_kn_per_m2, Action::Wind)?;
    for (j, p) in c.point_loads.iter().enumerate() {
        if p.node.is_empty() {
            return fail(at(&format!("point_loads[{j}].node")), "must name a node");
        }
        let f = at(&format!("point_loads[{j}].force_kn"));
        finite_vec(&f, p.force_kn)?;
        for x in p.force_kn.to_array() {
            bounded(&f, x)?;
        }
    }
    for (j, l) in c.line_loads.iter().enumerate() {
        if l.strip.is_empty() {
            return fail(at(&format!("line_loads[{j}].strip")), "must name a strip");
        }
        let f = at(&format!("line_loads[{j}].force_kn_per_m"));
        finite_vec(&f, l.force_kn_per_m)?;
        for x in l.force_kn_per_m.to_array() {
            bounded(&f, x)?;
        }
    }
    if c.is_empty() {
        let what = match c.action {
            Action::Permanent => "`self_weight`, `surface_kn_per_m2`",
            Action::Snow => "`snow_kn_per_m2`",
            Action::Wind => "`wind_kn_per_m2`",
            Action::Imposed => "",
        };
        let sep = if what.is_empty() { "" } else { ", " };
        return fail(
            at("name"),
            format!(
                "case `{}` carries no load: give {what}{sep}`point_loads` or `line_loads`",
                c.name
            ),
        );
    }
    Ok(())
}

fn validate_support(s: &SupportSpec, i: usize) -> Result<(), FieldError> {
    match &s.at {
        Selection::Boundary => {}
        Selection::Lowest { band_mm } => {
            let f = format!("supports[{i}].band_mm");
            non_negative(&f, *band_mm)?;
        }
        Selection::Nodes(ids) => {
            if ids.is_empty() {
                return fail(format!("supports[{i}].nodes"), "lists no node");
            }
            for (j, id) in ids.iter().enumerate() {
                if id.is_empty() {
                    return fail(format!("supports[{i}].nodes[{j}]"), "must name a node");
                }
                if let Some(k) = ids[..j].iter().position(|x| x == id) {
                    return fail(
                        format!("supports[{i}].nodes[{j}]"),
                        format!("`{id}` is listed twice (also nodes[{k}])"),
                    );
                }
            }
        }
    }
    if let SupportKind::Roller { direction } = s.kind {
        let f = format!("supports[{i}].direction");
        finite_vec(&f, direction)?;
        if (direction.length() - 1.0).abs() > 1e-9 {
            return fail(f, "must be a unit vector (the reader normalises it)");
        }
    }
    Ok(())
}

fn validate_factors(f: &Factors) -> Result<(), FieldError> {
    for (field, g) in [
        ("factors.gamma_g_sup", f.gamma_g_sup),
        ("factors.gamma_q", f.gamma_q),
    ] {
        finite(field, g)?;
        if !(1.0..=3.0).contains(&g) {
            return fail(field, format!("must be between 1 and 3, got {g}"));
        }
    }
    finite("factors.gamma_g_inf", f.gamma_g_inf)?;
    if !(0.0..=f.gamma_g_sup).contains(&f.gamma_g_inf) {
        return fail(
            "factors.gamma_g_inf",
            format!(
                "must be between 0 and gamma_g_sup ({}), got {}",
                f.gamma_g_sup, f.gamma_g_inf
            ),
        );
    }
    for (field, psi) in [
        ("factors.psi0_snow", f.psi0_snow),
        ("factors.psi0_wind", f.psi0_wind),
        ("factors.psi0_imposed", f.psi0_imposed),
    ] {
        finite(field, psi)?;
        if !(0.0..=1.0).contains(&psi) {
            return fail(field, format!("must be between 0 and 1, got {psi}"));
        }
    }
    Ok(())
}
