//! Placeholder (replaced by the bin-packing core): first-fit decreasing.

/// A packing: bins as lists of item indices.
pub struct Packing {
    /// Item indices per bin.
    pub bins: Vec<Vec<usize>>,
}

/// First-fit decreasing.
pub fn pack(sizes: &[f64], capacity: f64) -> Result<Packing, String> {
    let mut order: Vec<usize> = (0..sizes.len()).collect();
    order.sort_by(|&a, &b| sizes[b].total_cmp(&sizes[a]).then(a.cmp(&b)));
    let mut bins: Vec<(f64, Vec<usize>)> = Vec::new();
    for i in order {
        if sizes[i] > capacity * (1.0 + 1e-9) {
            return Err(format!("item {i} is larger than a bin"));
        }
        match bins
            .iter_mut()
            .find(|b| b.0 + sizes[i] <= capacity * (1.0 + 1e-9))
        {
            Some(b) => {
                b.0 += sizes[i];
                b.1.push(i);
            }
            None => bins.push((sizes[i], vec![i])),
        }
    }
    Ok(Packing {
        bins: bins.into_iter().map(|b| b.1).collect(),
    })
}

/// ⌈Σ s / C⌉ (placeholder for L2).
pub fn lower_bound_l2(sizes: &[f64], capacity: f64) -> usize {
    lower_bound_l1(sizes, capacity)
}

/// ⌈Σ s / C⌉.
pub fn lower_bound_l1(sizes: &[f64], capacity: f64) -> usize {
    (sizes.iter().sum::<f64>() / capacity * (1.0 - 1e-12)).ceil() as usize
}
