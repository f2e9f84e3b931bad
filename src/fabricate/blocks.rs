//! Shear blocks between the two lamellas of a doubled strip
//! (docs/fabrication.md): evenly spaced in each interval between supports (nodes,
//! or the lamella's ends), no farther apart than the profile allows, clear
//! of what sits at the nodes.

/// The largest distance between supports of one lamella (nodes or blocks),
/// mm: the profile's maximum spacing, and the length at which one lamella
/// reaches the slenderness limit λ = L / i with i = t / √12.
pub fn max_spacing_mm(max_spacing_mm: f64, slenderness_limit: f64, thickness_mm: f64) -> f64 {
    max_spacing_mm.min(slenderness_limit * thickness_mm / 12f64.sqrt())
}

/// One interval between two supports along a strip's centre line, with the
/// region where a block's centre may go.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// Station of the first support (a node, or the line's start), mm.
    pub start_mm: f64,
    /// Station of the second support, mm.
    pub end_mm: f64,
    /// Where block centres may lie: clear of the node zones by the
    /// clearance and half a block, mm.
    pub free_lo_mm: f64,
    /// Upper end of that region, mm.
    pub free_hi_mm: f64,
}

/// Block centres in one interval: the fewest blocks, evenly spaced between
/// the supports (moved into the free region where they fall outside it),
/// such that no two consecutive supports are more than `spacing_mm` apart
/// and neighbouring blocks (each `block_mm` long) keep `gap_mm` between
/// them. Err with what is wrong when no number of blocks does.
pub fn place(
    iv: Interval,
    spacing_mm: f64,
    block_mm: f64,
    gap_mm: f64,
) -> Result<Vec<f64>, String> {
    let span = iv.end_mm - iv.start_mm;
    if span <= spacing_mm {
        return Ok(Vec::new());
    }
    if iv.free_hi_mm < iv.free_lo_mm {
        return Err(format!(
            "{span:.1} mm between supports needs shear blocks (at most {spacing_mm:.1} mm apart) but \
             there is no room for one clear of the nodes"
        ));
    }
    let first = (span / spacing_mm).ceil() as usize - 1;
    let most = ((iv.free_hi_mm - iv.free_lo_mm) / (block_mm + gap_mm)).floor() as usize + 1;
    // No number of blocks helps when more than fit apart are needed, or
    // when a support is farther than the spacing from the free region:
    // refused before any block is placed.
    let reach = (iv.free_lo_mm - iv.start_mm).max(iv.end_mm - iv.free_hi_mm);
    if first > most || reach > spacing_mm + 1e-9 {
        return Err(cannot_keep(iv, spacing_mm, block_mm));
    }
    for n in first.max(1)..=most.max(first.max(1)) {
        let centres: Vec<f64> = (1..=n)
            .map(|k| {
                (iv.start_mm + span * k as f64 / (n + 1) as f64).clamp(iv.free_lo_mm, iv.free_hi_mm)
            })
            .collect();
        let mut supports = Vec::with_capacity(n + 2);
        supports.push(iv.start_mm);
        supports.extend_from_slice(&centres);
        supports.push(iv.end_mm);
        let widest = supports.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
        let apart = centres
            .windows(2)
            .all(|w| w[1] - w[0] >= block_mm + gap_mm - 1e-9);
        if widest <= spacing_mm + 1e-9 && apart {
            return Ok(centres);
        }
    }
    Err(cannot_keep(iv, spacing_mm, block_mm))
}

/// Why no number of blocks keeps the spacing in `iv`.
fn cannot_keep(iv: Interval, spacing_mm: f64, block_mm: f64) -> String {
    format!(
        "shear blocks cannot keep {spacing_mm:.1} mm spacing in the {:.1} mm left between the nodes' \
         zones",
        (iv.free_hi_mm - iv.free_lo_mm).max(0.0) + block_mm
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interval from 0 to `end_mm` with block centres allowed in
    /// `free_lo_mm..=free_hi_mm`.
    fn from_zero(end_mm: f64, free_lo_mm: f64, free_hi_mm: f64) -> Interval {
        Interval {
            start_mm: 0.0,
            end_mm,
            free_lo_mm,
            free_hi_mm,
        }
    }

    #[test]
    fn slenderness_caps_the_spacing() {
        // 1.5 mm steel, λ = 700: 700 · 1.5/√12 = 303.1 mm, so the profile's
        // 300 mm governs; at 400 mm allowed, slenderness does.
        assert!((max_spacing_mm(300.0, 700.0, 1.5) - 300.0).abs() < 1e-12);
        assert!((max_spacing_mm(400.0, 700.0, 1.5) - 303.108_891_324_553_7).abs() < 1e-9);
    }

    #[test]
    fn blocks_are_even_within_both_limits() {
        let iv = from_zero(1000.0, 60.0, 940.0);
        let c = place(iv, 300.0, 30.0, 30.0).unwrap();
        assert_eq!(c.len(), 3);
        for (k, x) in c.iter().enumerate() {
            assert!((x - 250.0 * (k + 1) as f64).abs() < 1e-9);
        }
        // A short interval needs none.
        let short = Interval {
            end_mm: 280.0,
            ..iv
        };
        assert!(place(short, 300.0, 30.0, 30.0).unwrap().is_empty());
    }

    #[test]
    fn blocks_move_off_the_node_zones_and_add_up() {
        // Zones reach 200 mm into a 600 mm interval on one side: the even
        // position (300) is free, but 2 blocks' 200/400 would not be.
        let iv = from_zero(600.0, 250.0, 560.0);
        let c = place(iv, 300.0, 30.0, 30.0).unwrap();
        let mut s = vec![0.0];
        s.extend(&c);
        s.push(600.0);
        assert!(s.windows(2).all(|w| w[1] - w[0] <= 300.0 + 1e-9), "{s:?}");
        assert!(c.iter().all(|x| (250.0..=560.0).contains(x)));
    }

    #[test]
    fn no_room_is_an_error() {
        let iv = from_zero(700.0, 400.0, 300.0);
        assert!(place(iv, 300.0, 30.0, 30.0).is_err());
        // Room for blocks, but not where the spacing needs them.
        let far = from_zero(700.0, 500.0, 520.0);
        assert!(place(far, 300.0, 30.0, 30.0).is_err());
    }

    #[test]
    fn more_blocks_than_fit_are_refused_before_any_is_placed() {
        // A 1e-9 mm lamella's slenderness spacing asks for ~3.5e9 blocks in
        // 700 mm (once a 28 GB vector of stations); 11 fit apart.
        let iv = Interval {
            start_mm: 0.0,
            end_mm: 700.0,
            free_lo_mm: 30.0,
            free_hi_mm: 670.0,
        };
        let e = place(iv, 2e-7, 30.0, 30.0).unwrap_err();
        assert!(
            e.starts_with("shear blocks cannot keep 0.0 mm spacing"),
            "{e}"
        );
        // Tiny blocks fit by the billion, but the supports reach farther
        // than the spacing into the free region.
        let e = place(iv, 2e-7, 1e-9, 0.0).unwrap_err();
        assert!(e.starts_with("shear blocks cannot keep"), "{e}");
    }
}
