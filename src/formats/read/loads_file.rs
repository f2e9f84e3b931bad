//! The loads file (YAML, `version: 1`): load cases, supports, factors and
//! the deflection limit of a frame analysis (`lamella frame … --loads
//! FILE`). Every quantity names its unit (`_kn_per_m2`, `_kn`, `_kn_per_m`,
//! `_mm`); unknown fields are errors.
//!
//! [`load`] reads a file into a [`LoadSpec`]: the YAML guard, the version,
//! the file types here (a parse error names its line and column), their
//! conversion (defaults filled in, a roller's direction normalised), then
//! [`LoadSpec::validate`] (a bad value names its field:
//! `cases[2].snow_kn_per_m2`). The semantics of every field are
//! [`crate::loads`]'s.
//!
//! ```yaml
//! version: 1
//! cases:
//!   - {name: G, action: permanent}          # the kit's self-weight
//!   - {name: S, action: snow, snow_kn_per_m2: 0.68}
//!   - {name: W-, action: wind, wind_kn_per_m2: -0.42}
//! supports:                                  # default: pinned at the boundary
//!   - {at: boundary, kind: pinned}
//! factors: {psi0_snow: 0.5}                  # EN 1990 defaults otherwise
//! deflection: {span_over: 300}               # or {limit_mm: 20}
//! bracing:                                   # optional: diagonal cables
//!   layout: designed                         # or all, alternate
//!   diagonals: single                        # or crossed
//!   pretension_kn: auto                      # or a value
//!   targets: {alpha_cr: 10, deflection: true, utilisation: 1.0}
//! ```

use crate::error::{Error, Location, Result};
use crate::loads::{
    Action, BracingLayout, BracingSpec, BracingTargets, Deflection, Diagonals, Factors, FieldError,
    LineLoad, LoadCase, LoadSpec, PointLoad, Pretension, Selection, SupportKind, SupportSpec,
};
use glam::DVec3;
use serde::Deserialize;
use std::path::Path;

/// The newest loads file version this build reads.
pub const CURRENT_VERSION: u32 = 1;

/// A loads file as written.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LoadsFile {
    /// Format version; this build reads [`CURRENT_VERSION`].
    pub version: u32,
    /// Free text for people; optional.
    #[serde(default)]
    pub description: String,
    /// The load cases (at least one).
    pub cases: Vec<CaseFile>,
    /// The supports; default: pinned at every boundary joint.
    #[serde(default)]
    pub supports: Option<Vec<SupportFile>>,
    /// Partial and combination factors; EN 1990's by default.
    #[serde(default)]
    pub factors: FactorsFile,
    /// The SLS deflection limit; default span/300.
    #[serde(default)]
    pub deflection: DeflectionFile,
    /// Diagonal cable bracing; none by default.
    #[serde(default)]
    pub bracing: Option<BracingFile>,
}

/// `bracing:` which quads get cables, and what a designed layout reaches.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BracingFile {
    /// `all`, `alternate` or `designed`.
    pub layout: LayoutFile,
    /// `single` (default) or `crossed`.
    #[serde(default)]
    pub diagonals: Option<DiagonalsFile>,
    /// kN, or `auto` (default): the least that keeps every cable taut.
    #[serde(default)]
    pub pretension_kn: Option<PretensionFile>,
    /// The targets; default α_cr ≥ 10, the deflection limit,
    /// utilisation ≤ 1. When given, only the targets it names.
    #[serde(default)]
    pub targets: Option<TargetsFile>,
}

/// `bracing.layout`.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum LayoutFile {
    /// Every quad.
    All,
    /// Every other quad.
    Alternate,
    /// Chosen by the analysis.
    Designed,
}

/// `bracing.diagonals`.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum DiagonalsFile {
    /// One per quad.
    Single,
    /// Two per quad.
    Crossed,
}

/// `bracing.pretension_kn`: a number or `auto`.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum PretensionFile {
    /// kN.
    Kn(f64),
    /// `auto`.
    Word(AutoWord),
}

/// The word `auto`.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum AutoWord {
    /// Chosen by the analysis.
    Auto,
}

/// `bracing.targets`.
#[derive(Debug, Clone, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TargetsFile {
    /// α_cr at least this.
    #[serde(default)]
    pub alpha_cr: Option<f64>,
    /// Within the deflection limit.
    #[serde(default)]
    pub deflection: Option<bool>,
    /// Utilisation at most this.
    #[serde(default)]
    pub utilisation: Option<f64>,
}

fn bracing(b: BracingFile) -> BracingSpec {
    BracingSpec {
        layout: match b.layout {
            LayoutFile::All => BracingLayout::All,
            LayoutFile::Alternate => BracingLayout::Alternate,
            LayoutFile::Designed => BracingLayout::Designed,
        },
        diagonals: match b.diagonals {
            None | Some(DiagonalsFile::Single) => Diagonals::Single,
            Some(DiagonalsFile::Crossed) => Diagonals::Crossed,
        },
        pretension: match b.pretension_kn {
            None | Some(PretensionFile::Word(AutoWord::Auto)) => Pretension::Auto,
            Some(PretensionFile::Kn(t)) => Pretension::Kn(t),
        },
        targets: match b.targets {
            None => BracingTargets::default(),
            Some(t) => BracingTargets {
                alpha_cr: t.alpha_cr,
                deflection: t.deflection.unwrap_or(false),
                utilisation: t.utilisation,
            },
        },
    }
}

/// `cases[]:` one load case.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    /// Its name, unique.
    pub name: String,
    /// `permanent`, `snow`, `wind` or `imposed`.
    pub action: ActionFile,
    /// Factor on the kit's self-weight; default 1 in a permanent case.
    #[serde(default)]
    pub self_weight: Option<f64>,
    /// Further permanent load on the surface area, kN/m².
    #[serde(default)]
    pub surface_kn_per_m2: Option<f64>,
    /// Snow on the plan projection, kN/m².
    #[serde(default)]
    pub snow_kn_per_m2: Option<f64>,
    /// Wind pressure normal to the surface, kN/m² (+ toward the inside).
    #[serde(default)]
    pub wind_kn_per_m2: Option<f64>,
    /// Forces on joints.
    #[serde(default)]
    pub point_loads: Vec<PointLoadFile>,
    /// Forces along strips.
    #[serde(default)]
    pub line_loads: Vec<LineLoadFile>,
}

/// `cases[].action`.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ActionFile {
    /// G.
    Permanent,
    /// S.
    Snow,
    /// W.
    Wind,
    /// Q.
    Imposed,
}

/// `cases[].point_loads[]`.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PointLoadFile {
    /// Network node id.
    pub node: String,
    /// Force, kN, global `[x, y, z]`.
    pub force_kn: [f64; 3],
}

/// `cases[].line_loads[]`.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LineLoadFile {
    /// Strip id.
    pub strip: String,
    /// Force per metre of each lamella, kN/m, global `[x, y, z]`.
    pub force_kn_per_m: [f64; 3],
}

/// `supports[]:` a selection and a kind.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SupportFile {
    /// `boundary`, `lowest` or `nodes`.
    pub at: SelectionFile,
    /// `at: lowest`: the height band above the lowest joint, mm.
    #[serde(default)]
    pub band_mm: Option<f64>,
    /// `at: nodes`: network node ids.
    #[serde(default)]
    pub nodes: Option<Vec<String>>,
    /// `fixed`, `pinned` or `roller`.
    pub kind: SupportKindFile,
    /// `kind: roller`: the restrained direction `[x, y, z]` (any length).
    #[serde(default)]
    pub direction: Option<[f64; 3]>,
}

/// `supports[].at`.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum SelectionFile {
    /// Strip ends.
    Boundary,
    /// The lowest joints.
    Lowest,
    /// Listed joints.
    Nodes,
}

/// `supports[].kind`.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum SupportKindFile {
    /// Six degrees of freedom.
    Fixed,
    /// Three translations.
    Pinned,
    /// One direction.
    Roller,
}

/// `factors:` every field optional (EN 1990's value).
#[derive(Debug, Clone, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FactorsFile {
    /// γ_G,sup; default 1.35.
    #[serde(default)]
    pub gamma_g_sup: Option<f64>,
    /// γ_G,inf; default 1.0.
    #[serde(default)]
    pub gamma_g_inf: Option<f64>,
    /// γ_Q; default 1.5.
    #[serde(default)]
    pub gamma_q: Option<f64>,
    /// ψ_0 of snow; default 0.5.
    #[serde(default)]
    pub psi0_snow: Option<f64>,
    /// ψ_0 of wind; default 0.6.
    #[serde(default)]
    pub psi0_wind: Option<f64>,
    /// ψ_0 of imposed loads; default 0.
    #[serde(default)]
    pub psi0_imposed: Option<f64>,
    /// Imposed loads combined with snow and wind; default false.
    #[serde(default)]
    pub imposed_with_snow_or_wind: Option<bool>,
}

/// `deflection:` one of the two, or neither (span/300).
#[derive(Debug, Clone, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct DeflectionFile {
    /// The limit is span / this.
    #[serde(default)]
    pub span_over: Option<f64>,
    /// An absolute limit, mm.
    #[serde(default)]
    pub limit_mm: Option<f64>,
}

/// Read and check a loads file.
pub fn load(path: &Path) -> Result<LoadSpec> {
    if !path.exists() {
        return Err(Error::input(path, Location::File, "no such file"));
    }
    let text = super::read_text(path)?;
    parse(&text, path)
}

/// Parse and check loads text (`path` names it in messages and becomes the
/// spec's `source`).
pub fn parse(text: &str, path: &Path) -> Result<LoadSpec> {
    if text.trim().is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    super::yaml_guard::check(text, path)?;
    let value: serde_yaml::Value = serde_yaml::from_str(text).map_err(|e| yaml_error(path, &e))?;
    match value.get("version") {
        None => {
            return Err(Error::input(
                path,
                Location::Field("version".into()),
                format!("missing; this lamella reads loads version {CURRENT_VERSION}"),
            ))
        }
        Some(v) => match v.as_u64() {
            Some(1) => {}
            Some(n) => {
                return Err(Error::input(
                    path,
                    Location::Field("version".into()),
                    format!("unknown loads version {n} (this lamella reads {CURRENT_VERSION})"),
                ))
            }
            None => {
                return Err(Error::input(
                    path,
                    Location::Field("version".into()),
                    "must be a whole number",
                ))
            }
        },
    }
    let file: LoadsFile = serde_yaml::from_str(text).map_err(|e| yaml_error(path, &e))?;
    let mut spec = LoadSpec::try_from(file)
        .map_err(|e| Error::input(path, Location::Field(e.field), e.message))?;
    spec.source = path.to_path_buf();
    Ok(spec)
}

/// A YAML error as one line with its location.
fn yaml_error(path: &Path, e: &serde_yaml::Error) -> Error {
    let (at, msg) = crate::error::yaml_error_parts(e);
    Error::input(path, at, msg)
}

fn field_error<T>(field: String, message: impl Into<String>) -> Result<T, FieldError> {
    Err(FieldError {
        field,
        message: message.into(),
    })
}

impl TryFrom<LoadsFile> for LoadSpec {
    type Error = FieldError;

    /// Fill in the defaults, check the fields that go together (a roller's
    /// direction, a selection's parameters, one deflection limit), then
    /// [`LoadSpec::validate`]. `source` is left empty.
    fn try_from(f: LoadsFile) -> std::result::Result<LoadSpec, FieldError> {
        let cases = f.cases.into_iter().map(case).collect();
        let supports = match f.supports {
            None => SupportSpec::default_list(),
            Some(list) => list
                .into_iter()
                .enumerate()
                .map(|(i, s)| support(i, s))
                .collect::<std::result::Result<_, _>>()?,
        };
        let d = Factors::default();
        let g = f.factors;
        let factors = Factors {
            gamma_g_sup: g.gamma_g_sup.unwrap_or(d.gamma_g_sup),
            gamma_g_inf: g.gamma_g_inf.unwrap_or(d.gamma_g_inf),
            gamma_q: g.gamma_q.unwrap_or(d.gamma_q),
            psi0_snow: g.psi0_snow.unwrap_or(d.psi0_snow),
            psi0_wind: g.psi0_wind.unwrap_or(d.psi0_wind),
            psi0_imposed: g.psi0_imposed.unwrap_or(d.psi0_imposed),
            imposed_with_snow_or_wind: g
                .imposed_with_snow_or_wind
                .unwrap_or(d.imposed_with_snow_or_wind),
        };
        let deflection = match (f.deflection.span_over, f.deflection.limit_mm) {
            (Some(_), Some(_)) => {
                return field_error(
                    "deflection".into(),
                    "give `span_over` or `limit_mm`, not both",
                )
            }
            (Some(n), None) => Deflection::SpanOver(n),
            (None, Some(d)) => Deflection::LimitMm(d),
            (None, None) => Deflection::default(),
        };
        let spec = LoadSpec {
            source: std::path::PathBuf::new(),
            description: f.description,
            cases,
            supports,
            factors,
            deflection,
            bracing: f.bracing.map(bracing),
        };
        spec.validate()?;
        Ok(spec)
    }
}

fn case(c: CaseFile) -> LoadCase {
    let action = match c.action {
        ActionFile::Permanent => Action::Permanent,
        ActionFile::Snow => Action::Snow,
        ActionFile::Wind => Action::Wind,
        ActionFile::Imposed => Action::Imposed,
    };
    let default_self_weight = if action == Action::Permanent {
        1.0
    } else {
        0.0
    };
    LoadCase {
        name: c.name,
        action,
        self_weight: c.self_weight.unwrap_or(default_self_weight),
        surface_kn_per_m2: c.surface_kn_per_m2.unwrap_or(0.0),
        snow_kn_per_m2: c.snow_kn_per_m2.unwrap_or(0.0),
        wind_kn_per_m2: c.wind_kn_per_m2.unwrap_or(0.0),
        point_loads: c
            .point_loads
            .into_iter()
            .map(|p| PointLoad {
                node: p.node,
                force_kn: DVec3::from_array(p.force_kn),
            })
            .collect(),
        line_loads: c
            .line_loads
            .into_iter()
            .map(|l| LineLoad {
                strip: l.strip,
                force_kn_per_m: DVec3::from_array(l.force_kn_per_m),
            })
            .collect(),
    }
}

fn support(i: usize, s: SupportFile) -> std::result::Result<SupportSpec, FieldError> {
    let at = |f: &str| format!("supports[{i}].{f}");
    let at_name = match s.at {
        SelectionFile::Boundary => "boundary",
        SelectionFile::Lowest => "lowest",
        SelectionFile::Nodes => "nodes",
    };
    if s.band_mm.is_some() && s.at != SelectionFile::Lowest {
        return field_error(
            at("band_mm"),
            format!("belongs to `at: lowest`, this entry is `at: {at_name}`"),
        );
    }
    if s.nodes.is_some() && s.at != SelectionFile::Nodes {
        return field_error(
            at("nodes"),
            format!("belongs to `at: nodes`, this entry is `at: {at_name}`"),
        );
    }
    let selection = match s.at {
        SelectionFile::Boundary => Selection::Boundary,
        SelectionFile::Lowest => match s.band_mm {
            Some(band_mm) => Selection::Lowest { band_mm },
            None => {
                return field_error(
                    at("band_mm"),
                    "missing: `at: lowest` takes the joints within `band_mm` of the lowest one",
                )
            }
        },
        SelectionFile::Nodes => match s.nodes {
            Some(ids) => Selection::Nodes(ids),
            None => return field_error(at("nodes"), "missing: `at: nodes` lists node ids"),
        },
    };
    let kind = match (s.kind, s.direction) {
        (SupportKindFile::Roller, None) => {
            return field_error(
                at("direction"),
                "missing: a roller restrains translation along one `direction: [x, y, z]`",
            )
        }
        (SupportKindFile::Roller, Some(d)) => {
            let v = DVec3::from_array(d);
            if !v.is_finite() {
                return field_error(at("direction"), "must be three finite numbers");
            }
            let n = v.length();
            if n <= 1e-12 || !n.is_finite() {
                return field_error(at("direction"), "must not be zero");
            }
            SupportKind::Roller { direction: v / n }
        }
        (k, Some(_)) => {
            let name = if k == SupportKindFile::Fixed {
                "fixed"
            } else {
                "pinned"
            };
            return field_error(
                at("direction"),
                format!("belongs to `kind: roller`, this entry is `kind: {name}`"),
            );
        }
        (SupportKindFile::Fixed, None) => SupportKind::Fixed,
        (SupportKindFile::Pinned, None) => SupportKind::Pinned,
    };
    Ok(SupportSpec {
        at: selection,
        kind,
    })
}
