//! Stock groups: every part is cut from one material of one thickness, and
//! the parts of one material and thickness are nested together onto one
//! stock (README, "Stock groups").
//!
//! The pieces and what they are cut from:
//!
//! | piece | thickness | default stock |
//! |---|---|---|
//! | lamella | `lamella.thickness_mm` | `stock:` |
//! | edge band, splice plate | `lamella.thickness_mm` | the lamellas' |
//! | star washer | `washer.thickness_mm` | the lamella stock's sizes |
//! | shear block | `lamella.gap_mm` (it fills the gap) | the lamella stock's sizes |
//! | eye plate (bracing) | `bracing.eye_plate.thickness_mm` | the lamella stock's sizes |
//! | stud | bar `gap × gap`, `stud.bar_length_mm` long | that bar |
//!
//! The material is the profile's (`material.name`) unless `stocks.<piece>`
//! names another. A plate group without sizes of its own takes the lamella
//! stock's sizes, priced by thickness (the lamella price × t / t_lamella:
//! steel and plywood sell by weight, roughly), and the lamellas' cutting;
//! `stocks.<piece>` may give its own sizes (any form `stock:` takes),
//! price, kerf, spacing, margin and rotations. Pieces of the same material
//! and thickness share a group (and its stock): the first one's, in the
//! order of the table. A group is named `ROLE-T` after its first piece and
//! thickness (`lamella-1.5`, `washer-3`, `shear-block-10`, `stud-20x20`)
//! unless the file names it.

use super::{Cutting, Profile, RawProfile, RawStock, Stock, StockKind, StockSize};

/// What a part is, as the stock sees it (the fabricate stage maps its part
/// kinds onto these).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Piece {
    /// A lamella.
    Lamella,
    /// An edge band (an edge strip unrolled).
    EdgeBand,
    /// A splice plate.
    SplicePlate,
    /// A star washer.
    Washer,
    /// A shear block.
    ShearBlock,
    /// A bracing cable's eye plate.
    EyePlate,
    /// A stud, sawn from bar.
    Stud,
}

impl Piece {
    /// Every piece, in the order groups are formed.
    pub const ALL: [Piece; 7] = [
        Piece::Lamella,
        Piece::EdgeBand,
        Piece::SplicePlate,
        Piece::Washer,
        Piece::ShearBlock,
        Piece::EyePlate,
        Piece::Stud,
    ];

    /// The key of its entry under `stocks:` (the lamellas' stock is `stock:`).
    pub fn key(self) -> &'static str {
        match self {
            Piece::Lamella => "stock",
            Piece::EdgeBand => "edge",
            Piece::SplicePlate => "splice",
            Piece::Washer => "washer",
            Piece::ShearBlock => "shear_block",
            Piece::EyePlate => "eye_plate",
            Piece::Stud => "stud",
        }
    }

    /// The word a group it names starts with.
    pub fn role(self) -> &'static str {
        match self {
            Piece::Lamella => "lamella",
            Piece::EdgeBand => "edge-band",
            Piece::SplicePlate => "splice-plate",
            Piece::Washer => "washer",
            Piece::ShearBlock => "shear-block",
            Piece::EyePlate => "eye-plate",
            Piece::Stud => "stud",
        }
    }

    /// The field path of its stock entry (`stocks.washer`, or `stock`).
    pub fn field(self) -> String {
        match self {
            Piece::Lamella => "stock".into(),
            p => format!("stocks.{}", p.key()),
        }
    }
}

/// The form of a group's stock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StockForm {
    /// Flat sheets.
    Sheet,
    /// A coil cut to length.
    Coil,
    /// Bars of one length, sawn into lengths (a cut list, nested in one
    /// dimension).
    Bar,
}

impl StockForm {
    /// The name plan.json and the takeoff use.
    pub fn as_str(self) -> &'static str {
        match self {
            StockForm::Sheet => "sheet",
            StockForm::Coil => "coil",
            StockForm::Bar => "bar",
        }
    }
}

/// One entry of `stocks:` as written: what a piece is cut from, where it
/// is not the default ([`super::groups`]). Every field optional.
#[derive(Debug, Clone, PartialEq)]
pub struct PieceStock {
    /// Which piece.
    pub piece: Piece,
    /// The group's name (file names, plan.json), if the file gives one.
    pub name: Option<String>,
    /// The material, if not the profile's.
    pub material: Option<String>,
    /// Its own sizes (any form of `stock:`), if given.
    pub stock: Option<RawStock>,
    /// Without sizes of its own: the price of one sheet of the lamella
    /// stock's (one) size, or of one bar.
    pub price_per_unit: Option<f64>,
    /// Without sizes of its own: the currency of that price.
    pub currency: Option<String>,
    /// Kerf, if not the profile's, mm.
    pub kerf_mm: Option<f64>,
    /// Part spacing, if not the profile's, mm.
    pub part_spacing_mm: Option<f64>,
    /// Edge margin, if not the profile's, mm.
    pub edge_margin_mm: Option<f64>,
    /// Allowed rotations, if not the profile's, degrees.
    pub allowed_rotations_deg: Option<Vec<u32>>,
}

impl PieceStock {
    /// An entry that names nothing but its piece.
    pub fn new(piece: Piece) -> PieceStock {
        PieceStock {
            piece,
            name: None,
            material: None,
            stock: None,
            price_per_unit: None,
            currency: None,
            kerf_mm: None,
            part_spacing_mm: None,
            edge_margin_mm: None,
            allowed_rotations_deg: None,
        }
    }
}

/// The parts of one material and thickness and the stock they are nested
/// onto.
#[derive(Debug, Clone, PartialEq)]
pub struct StockGroup {
    /// Its name: letters, digits, `-`, `_`, `.` (file names carry it).
    pub name: String,
    /// The material's name.
    pub material: String,
    /// The thickness every part of it has, mm (a bar: its section's side).
    pub thickness_mm: f64,
    /// The pieces cut from it, in [`Piece::ALL`] order.
    pub pieces: Vec<Piece>,
    /// Sheets, a coil, or bars.
    pub form: StockForm,
    /// Its stock (a bar is one "sheet" size: length × section).
    pub stock: Stock,
    /// Its cutting allowances and rotations.
    pub cutting: Cutting,
}

/// A length as a group name writes it: no trailing zeros (`1.5`, `3`).
pub fn trim_mm(x: f64) -> String {
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

impl<S> super::ProfileOf<S> {
    /// Whether the profile makes this piece at all (lamellas, edge bands
    /// and splice plates always may).
    pub fn makes(&self, piece: Piece) -> bool {
        match piece {
            Piece::Washer => self.washer.is_some(),
            Piece::ShearBlock => self.shear_block.is_some(),
            Piece::Stud => self.stud.is_some(),
            Piece::SplicePlate => self.splice.is_some(),
            Piece::EyePlate => self.bracing.is_some(),
            Piece::Lamella | Piece::EdgeBand => true,
        }
    }

    /// The thickness a piece is cut from, mm: the lamella's; a washer's
    /// plate; a shear block fills the gap; a stud is a gap × gap bar.
    pub fn piece_thickness_mm(&self, piece: Piece) -> f64 {
        match piece {
            Piece::Lamella | Piece::EdgeBand | Piece::SplicePlate => self.section.thickness_mm,
            Piece::Washer => self.washer.as_ref().map_or(0.0, |w| w.thickness_mm),
            Piece::ShearBlock | Piece::Stud => self.section.gap_mm,
            Piece::EyePlate => self
                .bracing
                .as_ref()
                .map_or(0.0, |b| b.eye_plate.thickness_mm),
        }
    }

    /// The `stocks:` entry of a piece, if the file has one.
    pub fn piece_stock(&self, piece: Piece) -> Option<&PieceStock> {
        self.stocks.iter().find(|e| e.piece == piece)
    }

    /// The material a piece is cut from.
    pub fn piece_material(&self, piece: Piece) -> String {
        self.piece_stock(piece)
            .and_then(|e| e.material.clone())
            .unwrap_or_else(|| self.material.name.clone())
    }

    /// The form of a piece's stock.
    fn piece_form(&self, piece: Piece, lamella_kind: StockKind) -> StockForm {
        let kind = match (
            piece,
            self.piece_stock(piece).and_then(|e| e.stock.as_ref()),
        ) {
            (Piece::Stud, _) => return StockForm::Bar,
            (_, Some(st)) => st.kind,
            _ => lamella_kind,
        };
        match kind {
            StockKind::Sheet => StockForm::Sheet,
            StockKind::Coil => StockForm::Coil,
        }
    }
}

impl Profile {
    /// The stock groups, in [`Piece::ALL`] order of their first piece
    /// (the lamellas' first): every piece the profile makes is in exactly
    /// one.
    pub fn stock_groups(&self) -> Vec<StockGroup> {
        let mut groups: Vec<StockGroup> = Vec::new();
        for piece in Piece::ALL.into_iter().filter(|&p| self.makes(p)) {
            let material = self.piece_material(piece);
            let thickness_mm = self.piece_thickness_mm(piece);
            let form = self.piece_form(piece, self.stock.kind);
            if let Some(g) = groups.iter_mut().find(|g| {
                g.material == material && g.thickness_mm == thickness_mm && g.form == form
            }) {
                g.pieces.push(piece);
                continue;
            }
            groups.push(self.new_group(piece, material, thickness_mm, form));
        }
        groups
    }

    /// The index in `groups` ([`Profile::stock_groups`]) of the group a
    /// piece is cut from (the lamellas' for a piece the profile does not
    /// make).
    pub fn group_of(groups: &[StockGroup], piece: Piece) -> usize {
        groups
            .iter()
            .position(|g| g.pieces.contains(&piece))
            .unwrap_or(0)
    }

    /// The cutting allowances a piece is cut with: its group's (its
    /// `stocks:` entry's where that gives them, else `cutting:`).
    pub fn piece_cutting(&self, piece: Piece) -> Cutting {
        let groups = self.stock_groups();
        groups
            .get(Profile::group_of(&groups, piece))
            .map_or_else(|| self.cutting.clone(), |g| g.cutting.clone())
    }

    fn new_group(
        &self,
        piece: Piece,
        material: String,
        thickness_mm: f64,
        form: StockForm,
    ) -> StockGroup {
        let entry = self.piece_stock(piece);
        let t = trim_mm(thickness_mm);
        let name = entry.and_then(|e| e.name.clone()).unwrap_or_else(|| {
            if form == StockForm::Bar {
                format!("{}-{t}x{t}", piece.role())
            } else {
                format!("{}-{t}", piece.role())
            }
        });
        let c = &self.cutting;
        let pick = |f: fn(&PieceStock) -> Option<f64>, d: f64| entry.and_then(f).unwrap_or(d);
        let mut cutting = Cutting {
            kerf_mm: pick(|e| e.kerf_mm, c.kerf_mm),
            part_spacing_mm: pick(|e| e.part_spacing_mm, c.part_spacing_mm),
            edge_margin_mm: pick(|e| e.edge_margin_mm, c.edge_margin_mm),
            allowed_rotations_deg: entry
                .and_then(|e| e.allowed_rotations_deg.clone())
                .unwrap_or_else(|| c.allowed_rotations_deg.clone()),
        };
        let currency = || {
            entry
                .and_then(|e| e.currency.clone())
                .or_else(|| self.stock.currency.clone())
        };
        let stock = if piece == Piece::Lamella {
            self.stock.clone()
        } else if form == StockForm::Bar {
            // A bar: one "sheet" as long as the bar and as wide as its
            // section, sawn with no margin or spacing, lengths end to end.
            let (bar_mm, side_mm) = (
                self.stud.as_ref().map_or(0.0, |s| s.bar_length_mm),
                thickness_mm,
            );
            cutting.part_spacing_mm = pick(|e| e.part_spacing_mm, 0.0);
            cutting.edge_margin_mm = pick(|e| e.edge_margin_mm, 0.0);
            cutting.allowed_rotations_deg = vec![0];
            Stock {
                kind: StockKind::Sheet,
                sizes: vec![StockSize {
                    name: Some(format!("{t} × {t} × {}", trim_mm(bar_mm))),
                    length_mm: Some(bar_mm),
                    width_mm: side_mm,
                    price_per_unit: entry.and_then(|e| e.price_per_unit),
                    max_count: None,
                }],
                listed: false,
                currency: currency(),
                price_per_m: None,
                length_step_mm: None,
            }
        } else if let Some(st) = entry.and_then(|e| e.stock.clone()) {
            Stock::from(st)
        } else {
            // The lamella stock's sizes, priced by thickness unless the
            // entry prices its sheet.
            let scale = thickness_mm / self.section.thickness_mm;
            let own = entry.and_then(|e| e.price_per_unit);
            let mut st = self.stock.clone();
            for z in &mut st.sizes {
                z.price_per_unit = own.or(z.price_per_unit.map(|p| round_price(p * scale)));
            }
            st.price_per_m = st.price_per_m.map(|p| round_price(p * scale));
            st.currency = currency();
            st
        };
        StockGroup {
            name,
            material,
            thickness_mm,
            pieces: vec![piece],
            form,
            stock,
            cutting,
        }
    }
}

/// A price to the cent.
fn round_price(p: f64) -> f64 {
    (p * 100.0).round() / 100.0
}

impl Profile {
    /// The groups of a raw profile, for the checks (its stock as the
    /// working form).
    pub fn raw_groups(raw: &RawProfile) -> Vec<StockGroup> {
        let p = Profile {
            name: raw.name.clone(),
            description: String::new(),
            source: raw.source.clone(),
            material: raw.material.clone(),
            section: raw.section.clone(),
            joint: raw.joint.clone(),
            node_bolt: raw.node_bolt.clone(),
            washer: raw.washer.clone(),
            shear_block: raw.shear_block.clone(),
            stud: raw.stud.clone(),
            splice: raw.splice.clone(),
            hardware: raw.hardware.clone(),
            stock: Stock::from(raw.stock.clone()),
            cutting: raw.cutting.clone(),
            check: raw.check.clone(),
            edge_joint: raw.edge_joint.clone(),
            bracing: raw.bracing.clone(),
            stocks: raw.stocks.clone(),
        };
        p.stock_groups()
    }
}
