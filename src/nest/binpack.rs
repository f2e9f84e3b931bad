//! One-dimensional bin packing: which lamella goes into which lane.
//!
//! An item is a part's length plus the gap a cut needs (kerf and part
//! spacing); a bin is a lane of usable stock length plus one gap. [`pack`]
//! assigns items to as few bins as it can, [`lower_bound_l1`] and
//! [`lower_bound_l2`] say how few bins any packing needs.
//!
//! **Fits.** Every comparison uses the effective capacity
//! C′ = C·(1 + [`FIT_TOLERANCE`]): a bin holds items whose sizes sum to at
//! most C′, so ten items of 0.1 fill a bin of 1.0 although their float sum
//! is 1.0000000000000002. The lower bounds use the same C′, so they stay
//! bounds for what `pack` calls a fit.
//!
//! **Algorithm.** Best-fit decreasing (items by decreasing size, each into
//! the open bin it leaves least room in, found in an ordered set of
//! residual capacities: O(n log n)), then, while there are more bins than
//! [`lower_bound_l2`], an improvement phase after the dominance-based local
//! search of Levine & Ducatelle (2004) (Martello & Toth's dominance: a bin
//! is better off with fewer, larger items) and the bin-emptying moves of
//! Fleszar & Hindi (2002), with a tabu search to leave local optima. Each
//! round:
//!
//! 1. take out the r least-filled bins that hold no item > C/2 (those keep
//!    a bin each in any packing); their items are *free* (r = 1 first);
//! 2. descent: visit every other bin in turn and make the move or swap that
//!    fills it most: up to two of its items out to the free set, up to two
//!    free items in (0↔1, 0↔2, 1↔1, 1↔2, 2↔1, 2↔2), only when the bin's
//!    load rises by more than C·[`FIT_TOLERANCE`] and stays within C′;
//!    passes repeat until one changes nothing;
//! 3. tabu search over the same moves, each step the best over all bins
//!    whatever its gain (swaps of equal sizes excepted), an item that left
//!    a bin kept out of it for 10 steps; it stops as soon as the free items
//!    fit in r − 1 bins, or after 200 steps without a lighter free set;
//! 4. repack the free items best-fit decreasing. Fewer bins: keep, and
//!    start again with r = 1. Otherwise keep an r = 1 result with as many
//!    bins (a different packing to start from), undo anything worse and
//!    any r ≥ 2 round, and go on with r + 1.
//!
//! **Effort bound.** At most 64 rounds, r ≤ 8, 16 descent passes per round,
//! and 4,000,000 work units for the whole phase (one unit per subset of a
//! bin's items tried, per free offer built, per bin scanned in a tabu step
//! or a repack); pairs of free items are offered only while there are at
//! most 96 free items. The phase stops at the first of: bins = L2, a round
//! with r = 8 failing, or a bound reached. Deterministic: no threads, no
//! randomness, every tie broken by item or bin index.
//!
//! **Quality** (this module's tests): on 500 random instances of 1–9
//! items solved exhaustively, `pack` finds the optimum every time (L2 is
//! the optimum on 482). On 200 random lamella-like instances of 50–300
//! items (200–2980 mm into 2980 mm, half of them mostly short pieces) it
//! reaches L2 on 157 and L2 + 1 on 39 more; L2 + 1 is not always
//! reachable (on some the Fekete–Schepers bound is L2 + 2), and `pack` is
//! within one bin of the better bound on all 200, at it (so optimal) on
//! 173. Triplet instances (items of 0.25–0.5 C filling bins exactly by
//! threes, built to defeat best-fit decreasing) are its weak spot: one bin
//! over the optimum at 20–60 bins, 3–4 at 120, 28 (11 %) at 249.
//!
//! **Speed** (release build, one core): 60,000 items pack in about 120 ms
//! (200–2980 mm into 2980 mm: 32,410 bins, L2 32,390) and 145 ms (mostly
//! short pieces: 15,455 bins, L2 15,372), the improvement phase running to
//! its effort bound (`cargo test --release --lib nest::binpack::tests::timing
//! -- --ignored --nocapture`).

use std::collections::BTreeSet;

/// Relative tolerance of "fits": a bin of capacity C holds items whose
/// sizes sum to at most C·(1 + `FIT_TOLERANCE`), absorbing the rounding of
/// sums of decimal lengths (1e-9 of a 3 m lane is 3 nm).
pub const FIT_TOLERANCE: f64 = 1e-9;

/// Improvement rounds at most.
const MAX_ROUNDS: usize = 64;
/// Passes over the bins per round at most.
const MAX_PASSES: usize = 16;
/// Most bins emptied at once in a round.
const MAX_REMOVED_BINS: usize = 8;
/// Work units for the whole improvement phase.
const EFFORT: u64 = 4_000_000;
/// Steps an item stays put after it moved, in the tabu search.
const TABU_TENURE: usize = 10;
/// Tabu steps without a lighter free set before a round gives up.
const PATIENCE: usize = 200;
/// Offers looked at per subset of a bin in the tabu search (from the
/// largest that fits down).
const MAX_OFFER_SCAN: usize = 16;
/// Pairs of free items are offered only up to this many free items.
const MAX_FREE_FOR_PAIRS: usize = 96;

/// A packing: bins as lists of item indices (each bin's items sorted by
/// decreasing size, ties by index).
///
/// Every item is in exactly one bin, no bin is empty, no bin's sizes sum to
/// more than the capacity times 1 + [`FIT_TOLERANCE`], and the bins are
/// ordered by their first item (decreasing size, ties by index).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Packing {
    /// Item indices, one list per bin.
    pub bins: Vec<Vec<usize>>,
}

/// Packs `sizes` (each 0 < size ≤ `capacity`, in any one unit) into as few
/// bins of `capacity` as it can: best-fit decreasing, then the bounded
/// improvement phase of the module doc, which stops early when the number
/// of bins reaches [`lower_bound_l2`] (then the packing is optimal).
/// Deterministic: the same input gives the same packing. O(n log n) plus
/// the bounded improvement effort.
///
/// Fits use the tolerance [`FIT_TOLERANCE`]. An `Err` names the first item
/// whose size is not finite, not positive or larger than the capacity, or
/// says that the capacity is not positive and finite.
pub fn pack(sizes: &[f64], capacity: f64) -> Result<Packing, String> {
    if !(capacity.is_finite() && capacity > 0.0) {
        return Err(format!(
            "bin capacity {capacity} is not a positive finite number"
        ));
    }
    let cap = effective_capacity(capacity);
    if let Some((i, s)) = sizes
        .iter()
        .enumerate()
        .find(|&(_, &s)| !(s.is_finite() && s > 0.0 && s <= cap))
    {
        return Err(format!(
            "item {i}: size {s} is not in (0, {capacity}] (the bin capacity)"
        ));
    }
    let mut order: Vec<usize> = (0..sizes.len()).collect();
    order.sort_by(|&a, &b| by_decreasing_size(sizes, a, b));
    let mut bins = Vec::new();
    best_fit_into(&mut bins, &order, sizes, cap);
    let target = lower_bound_l2(sizes, capacity);
    if bins.len() > target {
        improve(sizes, cap, &mut bins, target);
    }
    let mut bins: Vec<Vec<usize>> = bins
        .into_iter()
        .map(|mut bin| {
            bin.items.sort_by(|&a, &b| by_decreasing_size(sizes, a, b));
            bin.items
        })
        .collect();
    bins.sort_by(|x, y| by_decreasing_size(sizes, x[0], y[0]));
    Ok(Packing { bins })
}

/// Martello–Toth L2 lower bound on the number of bins (Martello & Toth
/// 1990, "Lower bounds and reduction procedures for the bin packing
/// problem"): the maximum over α ∈ [0, C/2] of
/// |J1| + |J2| + max(0, ⌈(Σ_{J3} s − (|J2|·C − Σ_{J2} s))/C⌉), with
/// J1 = items > C − α, J2 = C/2 < s ≤ C − α, J3 = α ≤ s ≤ C/2.
///
/// Evaluated at the α that matter (0 and the distinct sizes ≤ C/2) in
/// O(n log n): one sort, prefix sums, a binary search per α. C here is the
/// effective capacity C·(1 + [`FIT_TOLERANCE`]) that [`pack`] fits to, so
/// the bound holds for its packings; never below [`lower_bound_l1`]. Meant
/// for the sizes `pack` accepts; 0 for no items.
pub fn lower_bound_l2(sizes: &[f64], capacity: f64) -> usize {
    if sizes.is_empty() {
        return 0;
    }
    let c = effective_capacity(capacity);
    let mut s = sizes.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    let mut prefix = Vec::with_capacity(n + 1);
    prefix.push(0.0);
    let mut total = 0.0;
    for &x in &s {
        total += x;
        prefix.push(total);
    }
    // Items ≤ C/2 are s[..n_small].
    let n_small = s.partition_point(|&x| x <= c / 2.0);
    // J3 = s[first..n_small] (sizes ≥ α), J2 = s[n_small..n_fit],
    // J1 = s[n_fit..] (sizes > C − α).
    let bound = |alpha: f64, first: usize| -> usize {
        let n_fit = s.partition_point(|&x| x <= c - alpha).max(n_small);
        let j1 = n - n_fit;
        let j2 = n_fit - n_small;
        let room_j2 = j2 as f64 * c - (prefix[n_fit] - prefix[n_small]);
        let rest = ((prefix[n_small] - prefix[first] - room_j2) / c).ceil();
        j1 + j2 + if rest > 0.0 { rest as usize } else { 0 }
    };
    let mut best = lower_bound_l1(sizes, capacity).max(bound(0.0, 0));
    for first in 0..n_small {
        if first == 0 || s[first] != s[first - 1] {
            best = best.max(bound(s[first], first));
        }
    }
    best
}

/// The trivial lower bound ⌈Σ s / C⌉ on the number of bins, with C the
/// effective capacity C·(1 + [`FIT_TOLERANCE`]) that [`pack`] fits to.
/// 0 for no items.
pub fn lower_bound_l1(sizes: &[f64], capacity: f64) -> usize {
    let total: f64 = sizes.iter().sum();
    let bins = (total / effective_capacity(capacity)).ceil();
    if bins > 0.0 {
        bins as usize
    } else {
        0
    }
}

fn effective_capacity(capacity: f64) -> f64 {
    capacity * (1.0 + FIT_TOLERANCE)
}

/// Decreasing size, ties by increasing index.
fn by_decreasing_size(sizes: &[f64], a: usize, b: usize) -> std::cmp::Ordering {
    sizes[b].total_cmp(&sizes[a]).then(a.cmp(&b))
}

/// A bin while packing: its items (kept by decreasing size during the
/// improvement phase) and the sum of their sizes.
#[derive(Debug, Clone)]
struct Bin {
    items: Vec<usize>,
    load: f64,
}

impl Bin {
    fn refresh(&mut self, sizes: &[f64]) {
        self.items.sort_by(|&a, &b| by_decreasing_size(sizes, a, b));
        self.load = self.items.iter().map(|&i| sizes[i]).sum();
    }
}

/// Best fit of `order` (in that order) into `bins` and new bins: each item
/// into the bin with the least room that still holds it (ties: the lowest
/// bin index). The open bins live in an ordered set keyed by their room;
/// rooms are ≥ 0, so their bit patterns order like the numbers.
fn best_fit_into(bins: &mut Vec<Bin>, order: &[usize], sizes: &[f64], cap: f64) {
    let room = |load: f64| {
        let r = cap - load;
        if r > 0.0 {
            r
        } else {
            0.0
        }
    };
    let mut open: BTreeSet<(u64, usize)> = bins
        .iter()
        .enumerate()
        .map(|(b, bin)| (room(bin.load).to_bits(), b))
        .collect();
    for &i in order {
        let s = sizes[i];
        let b = match open.range((s.to_bits(), 0)..).next().copied() {
            Some(key) => {
                open.remove(&key);
                key.1
            }
            None => {
                bins.push(Bin {
                    items: Vec::new(),
                    load: 0.0,
                });
                bins.len() - 1
            }
        };
        bins[b].items.push(i);
        bins[b].load += s;
        open.insert((room(bins[b].load).to_bits(), b));
    }
}

/// What is left of the improvement phase's work units.
struct Effort(u64);

impl Effort {
    fn charge(&mut self, units: usize) {
        self.0 = self.0.saturating_sub(units as u64);
    }
    fn spent(&self) -> bool {
        self.0 == 0
    }
}

/// The improvement phase of the module doc.
fn improve(sizes: &[f64], cap: f64, bins: &mut Vec<Bin>, target: usize) {
    let mut effort = Effort(EFFORT);
    let mut removed = 1;
    for _ in 0..MAX_ROUNDS {
        if bins.len() <= target
            || removed > MAX_REMOVED_BINS
            || removed >= bins.len()
            || effort.spent()
        {
            break;
        }
        let before = bins.len();
        let saved = bins.clone();
        effort.charge(before);
        // The `removed` least-filled bins without a large item (ties: the
        // later bin) are emptied: every item > C/2 keeps a bin of its own.
        let mut by_load: Vec<usize> = (0..before)
            .filter(|&b| bins[b].items.iter().all(|&i| sizes[i] <= cap / 2.0))
            .collect();
        if by_load.len() < removed {
            break;
        }
        by_load.sort_by(|&a, &b| bins[a].load.total_cmp(&bins[b].load).then(b.cmp(&a)));
        let mut taken = by_load[..removed].to_vec();
        taken.sort_unstable_by(|a, b| b.cmp(a));
        let mut free = Vec::new();
        for b in taken {
            free.extend(bins.remove(b).items);
        }
        local_search(sizes, cap, bins, &mut free, &mut effort);
        tabu_search(sizes, cap, bins, &mut free, removed - 1, &mut effort);
        free.sort_by(|&a, &b| by_decreasing_size(sizes, a, b));
        effort.charge(bins.len());
        best_fit_into(bins, &free, sizes, cap);
        if bins.len() < before {
            removed = 1;
        } else {
            if bins.len() > before || removed > 1 {
                *bins = saved;
            }
            removed += 1;
        }
    }
}

/// One or two free items offered to a bin, with their total size.
#[derive(Debug, Clone, Copy)]
struct Offer {
    total: f64,
    first: usize,
    second: Option<usize>,
}

/// The distinct single and pair offers of the free items, by increasing
/// total (pairs only up to [`MAX_FREE_FOR_PAIRS`] free items).
fn offers(free: &[usize], sizes: &[f64]) -> Vec<Offer> {
    let mut items = free.to_vec();
    items.sort_by(|&a, &b| by_decreasing_size(sizes, a, b));
    let mut out = Vec::new();
    for (k, &a) in items.iter().enumerate() {
        if k > 0 && sizes[a] == sizes[items[k - 1]] {
            continue;
        }
        out.push(Offer {
            total: sizes[a],
            first: a,
            second: None,
        });
        if items.len() > MAX_FREE_FOR_PAIRS {
            continue;
        }
        for (l, &b) in items.iter().enumerate().skip(k + 1) {
            if l > k + 1 && sizes[b] == sizes[items[l - 1]] {
                continue;
            }
            out.push(Offer {
                total: sizes[a] + sizes[b],
                first: a,
                second: Some(b),
            });
        }
    }
    out.sort_by(|x, y| {
        x.total
            .total_cmp(&y.total)
            .then(x.first.cmp(&y.first))
            .then(x.second.cmp(&y.second))
    });
    out
}

/// Step 2 of the module doc: passes over `bins`, each bin making the move
/// or swap with the free items that fills it most, until a pass changes
/// nothing, the free set is empty or a bound is reached.
fn local_search(
    sizes: &[f64],
    cap: f64,
    bins: &mut [Bin],
    free: &mut Vec<usize>,
    effort: &mut Effort,
) -> bool {
    let min_gain = cap * FIT_TOLERANCE;
    let mut offered = offers(free, sizes);
    effort.charge(offered.len());
    let mut any = false;
    for _ in 0..MAX_PASSES {
        let mut changed = false;
        for bin in bins.iter_mut() {
            if free.is_empty() || effort.spent() {
                return any;
            }
            let Some((_, out, offer)) = best_swap(
                bin,
                sizes,
                cap,
                &offered,
                |_| true,
                |gain, _, _| gain > min_gain,
                effort,
            ) else {
                continue;
            };
            apply_swap(bin, free, out, offer, sizes);
            offered = offers(free, sizes);
            effort.charge(offered.len());
            changed = true;
            any = true;
        }
        if !changed {
            break;
        }
    }
    any
}

/// The move or swap that raises `bin`'s load most within `cap` among
/// those `accept(gain, given, taken)` admits (items given up, items taken
/// in), taking in only offers `offer_ok` admits (of the
/// [`MAX_OFFER_SCAN`] largest that fit each subset): the gain, positions
/// (increasing) of the items to give up, and the offer to take in.
fn best_swap(
    bin: &Bin,
    sizes: &[f64],
    cap: f64,
    offered: &[Offer],
    offer_ok: impl Fn(&Offer) -> bool,
    accept: impl Fn(f64, usize, usize) -> bool,
    effort: &mut Effort,
) -> Option<(f64, [Option<usize>; 2], Offer)> {
    let room = cap - bin.load;
    let mut best: Option<(f64, [Option<usize>; 2], Offer)> = None;
    let mut tries = 0;
    let mut consider = |out: [Option<usize>; 2], given: f64| {
        tries += 1;
        let k = offered.partition_point(|o| o.total <= given + room);
        let Some(&offer) = offered[..k]
            .iter()
            .rev()
            .take(MAX_OFFER_SCAN)
            .find(|o| offer_ok(o))
        else {
            return;
        };
        let gain = offer.total - given;
        let n_out = out.iter().flatten().count();
        let n_in = 1 + usize::from(offer.second.is_some());
        if accept(gain, n_out, n_in) && best.as_ref().is_none_or(|b| gain > b.0) {
            best = Some((gain, out, offer));
        }
    };
    consider([None, None], 0.0);
    // Items are by decreasing size: equal sizes give equal subsets, so
    // only the first of a run is tried in each place.
    let items: Vec<usize> = (0..bin.items.len()).collect();
    let size = |k: usize| sizes[bin.items[items[k]]];
    for i in 0..items.len() {
        if i > 0 && size(i) == size(i - 1) {
            continue;
        }
        consider([Some(items[i]), None], size(i));
        for j in i + 1..items.len() {
            if j > i + 1 && size(j) == size(j - 1) {
                continue;
            }
            consider([Some(items[i]), Some(items[j])], size(i) + size(j));
        }
    }
    effort.charge(tries);
    best
}

/// Gives up the items of `bin` at positions `out` to `free` and takes in
/// `offer`'s items from `free`.
fn apply_swap(
    bin: &mut Bin,
    free: &mut Vec<usize>,
    out: [Option<usize>; 2],
    offer: Offer,
    sizes: &[f64],
) {
    let taken_in = [Some(offer.first), offer.second];
    free.retain(|&i| !taken_in.contains(&Some(i)));
    for k in out.into_iter().flatten().rev() {
        free.push(bin.items.remove(k));
    }
    bin.items.extend(taken_in.into_iter().flatten());
    bin.refresh(sizes);
}

/// Step 3 of the module doc: a tabu search over the same moves and swaps,
/// each step the best over all bins whatever its gain (a swap of equal
/// sizes excepted), no item entering a bin again within [`TABU_TENURE`]
/// steps of leaving it. Stops with `true` once the free items pack into
/// `keep` bins, with `false` after [`PATIENCE`] steps without a new
/// lightest free set or when the effort is spent.
fn tabu_search(
    sizes: &[f64],
    cap: f64,
    bins: &mut [Bin],
    free: &mut Vec<usize>,
    keep: usize,
    effort: &mut Effort,
) -> bool {
    let tol = cap * FIT_TOLERANCE;
    // (item, bin) → the step from which the item may enter the bin again.
    let mut tabu_until: std::collections::HashMap<(usize, usize), usize> = Default::default();
    let weight = |free: &[usize]| free.iter().map(|&i| sizes[i]).sum::<f64>();
    let mut lightest = weight(free);
    let mut since = 0;
    for step in 1.. {
        if packs_into(free, keep, sizes, cap) {
            return true;
        }
        if since > PATIENCE || effort.spent() {
            return false;
        }
        let offered = offers(free, sizes);
        effort.charge(offered.len() + bins.len());
        let mut best: Option<(f64, usize, [Option<usize>; 2], Offer)> = None;
        for (b, bin) in bins.iter().enumerate() {
            let allowed = |i: usize| tabu_until.get(&(i, b)).is_none_or(|&t| t <= step);
            let found = best_swap(
                bin,
                sizes,
                cap,
                &offered,
                |o| allowed(o.first) && o.second.is_none_or(allowed),
                |gain, n_out, n_in| gain.abs() > tol || n_out != n_in,
                effort,
            );
            if let Some((gain, out, offer)) = found {
                if best.as_ref().is_none_or(|x| gain > x.0 + tol) {
                    best = Some((gain, b, out, offer));
                }
            }
        }
        let Some((_, b, out, offer)) = best else {
            return false;
        };
        let given: Vec<usize> = out.iter().flatten().map(|&k| bins[b].items[k]).collect();
        apply_swap(&mut bins[b], free, out, offer, sizes);
        for i in given {
            tabu_until.insert((i, b), step + TABU_TENURE);
        }
        let w = weight(free);
        if w < lightest - tol {
            lightest = w;
            since = 0;
        } else {
            since += 1;
        }
    }
    false
}

/// Whether best-fit decreasing packs `items` into at most `bins` bins.
fn packs_into(items: &[usize], bins: usize, sizes: &[f64], cap: f64) -> bool {
    let total: f64 = items.iter().map(|&i| sizes[i]).sum();
    if items.is_empty() {
        return true;
    }
    if bins == 0 || total > bins as f64 * cap {
        return false;
    }
    let mut order = items.to_vec();
    order.sort_by(|&a, &b| by_decreasing_size(sizes, a, b));
    let mut packed = Vec::new();
    best_fit_into(&mut packed, &order, sizes, cap);
    packed.len() <= bins
}

#[cfg(test)]
mod tests {
    use super::*;

    /// SplitMix64: a small deterministic generator for the property tests.
    struct Rng(u64);

    impl Rng {
        fn next_u64(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        }
        /// Uniform in [0, 1).
        fn unit(&mut self) -> f64 {
            (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
        }
        fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
            lo + (hi - lo) * self.unit()
        }
        /// Uniform in lo..=hi.
        fn int(&mut self, lo: usize, hi: usize) -> usize {
            lo + (self.next_u64() % (hi - lo + 1) as u64) as usize
        }
        fn shuffle<T>(&mut self, v: &mut [T]) {
            for k in (1..v.len()).rev() {
                v.swap(k, self.int(0, k));
            }
        }
    }

    /// The packing's guarantees: every item once, no bin over capacity (to
    /// the tolerance), no empty bin, items and bins in the documented order.
    fn check(sizes: &[f64], capacity: f64, packing: &Packing) {
        let mut seen = vec![0; sizes.len()];
        for bin in &packing.bins {
            assert!(!bin.is_empty(), "empty bin");
            let load: f64 = bin.iter().map(|&i| sizes[i]).sum();
            assert!(
                load <= capacity * (1.0 + FIT_TOLERANCE),
                "bin {bin:?} holds {load} > {capacity}"
            );
            for w in bin.windows(2) {
                assert!(
                    by_decreasing_size(sizes, w[0], w[1]).is_lt(),
                    "bin {bin:?} not by decreasing size"
                );
            }
            for &i in bin {
                seen[i] += 1;
            }
        }
        for w in packing.bins.windows(2) {
            assert!(by_decreasing_size(sizes, w[0][0], w[1][0]).is_lt());
        }
        assert!(seen.iter().all(|&k| k == 1), "items not packed once each");
    }

    /// Pack and check; the number of bins.
    fn bins(sizes: &[f64], capacity: f64) -> usize {
        let packing = pack(sizes, capacity).unwrap();
        check(sizes, capacity, &packing);
        packing.bins.len()
    }

    /// The optimum by exhaustive search over assignments (items by
    /// decreasing size, each into an earlier bin or a new one; bins of
    /// equal load are interchangeable), pruned by the best found so far.
    fn optimum(sizes: &[f64], capacity: f64) -> usize {
        fn search(k: usize, s: &[f64], cap: f64, loads: &mut Vec<f64>, best: &mut usize) {
            if loads.len() >= *best {
                return;
            }
            if k == s.len() {
                *best = loads.len();
                return;
            }
            for b in 0..loads.len() {
                let old = loads[b];
                if old + s[k] <= cap && !loads[..b].contains(&old) {
                    loads[b] = old + s[k];
                    search(k + 1, s, cap, loads, best);
                    loads[b] = old;
                }
            }
            if loads.len() + 1 < *best {
                loads.push(s[k]);
                search(k + 1, s, cap, loads, best);
                loads.pop();
            }
        }
        let mut s = sizes.to_vec();
        s.sort_by(|a, b| b.total_cmp(a));
        let mut best = s.len() + 1;
        search(
            0,
            &s,
            effective_capacity(capacity),
            &mut Vec::new(),
            &mut best,
        );
        best.min(s.len())
    }

    #[test]
    fn rejects_bad_items_by_index() {
        assert!(pack(&[1.0, 0.0], 2.0).unwrap_err().starts_with("item 1:"));
        assert!(pack(&[-1.0], 2.0).unwrap_err().starts_with("item 0:"));
        assert!(pack(&[1.0, 1.0, f64::NAN], 2.0)
            .unwrap_err()
            .starts_with("item 2:"));
        assert!(pack(&[2.5], 2.0).unwrap_err().starts_with("item 0:"));
        assert!(pack(&[1.0], 0.0).unwrap_err().contains("capacity"));
        assert!(pack(&[1.0], f64::INFINITY).is_err());
    }

    #[test]
    fn nothing_to_pack() {
        assert_eq!(pack(&[], 10.0).unwrap(), Packing::default());
        assert_eq!(lower_bound_l1(&[], 10.0), 0);
        assert_eq!(lower_bound_l2(&[], 10.0), 0);
    }

    #[test]
    fn items_of_exactly_the_capacity() {
        let sizes = [2980.0, 1490.0, 2980.0, 1490.0, 2980.0, 500.0];
        assert_eq!(bins(&sizes, 2980.0), 5);
        assert_eq!(lower_bound_l2(&sizes, 2980.0), 5);
        assert_eq!(lower_bound_l1(&sizes, 2980.0), 5);
        let packing = pack(&sizes, 2980.0).unwrap();
        assert_eq!(packing.bins[..3], [vec![0], vec![2], vec![4]]);
        assert_eq!(bins(&[1.0; 7], 1.0), 7);
    }

    #[test]
    fn decimal_sums_fit_to_the_tolerance() {
        assert_eq!(bins(&[0.1; 10], 1.0), 1);
        assert_eq!(bins(&[1.0 / 3.0; 3], 1.0), 1);
        assert_eq!(bins(&[0.7, 0.2, 0.1, 0.3, 0.6, 0.1], 1.0), 2);
        assert_eq!(lower_bound_l1(&[0.1; 10], 1.0), 1);
        assert_eq!(lower_bound_l2(&[0.1; 20], 1.0), 2);
        // A lane of 2980 mm holding 1234.5 + 1745.5 exactly.
        assert_eq!(bins(&[1234.5, 1745.5, 1745.5, 1234.5], 2980.0), 2);
    }

    #[test]
    fn many_equal_items() {
        assert_eq!(bins(&[0.3; 1000], 1.0), 334);
        assert_eq!(bins(&[0.5; 999], 1.0), 500);
        assert_eq!(bins(&[0.51; 100], 1.0), 100);
        assert_eq!(bins(&[600.0; 60_000], 2980.0), 15_000);
        // 0.4 ×5: L2 = 2 but only two fit in a bin.
        assert_eq!(lower_bound_l2(&[0.4; 5], 1.0), 2);
        assert_eq!(bins(&[0.4; 5], 1.0), 3);
    }

    #[test]
    fn l2_counts_large_items_apart() {
        // L1 = ⌈2.4⌉ = 3; no two 0.6 share a bin.
        assert_eq!(lower_bound_l1(&[0.6; 4], 1.0), 3);
        assert_eq!(lower_bound_l2(&[0.6; 4], 1.0), 4);
        // α = 0.45: J1 = {0.6, 0.6} (0.45 does not fit beside them), J3 = 0.45 ×3.
        let sizes = [0.6, 0.6, 0.45, 0.45, 0.45];
        assert_eq!(lower_bound_l1(&sizes, 1.0), 3);
        assert_eq!(lower_bound_l2(&sizes, 1.0), 4);
        assert_eq!(bins(&sizes, 1.0), 4);
    }

    #[test]
    fn improvement_beats_best_fit_decreasing() {
        // BFD: {0.5, 0.4}, {0.4, 0.35, 0.2}, {0.35, 0.3, 0.3}, {0.2} → 4
        // bins; the optimum is 3 (sum 3.0 = L2): {0.5, 0.3, 0.2},
        // {0.4, 0.4, 0.2}, {0.35, 0.35, 0.3}.
        let sizes = [0.5, 0.4, 0.4, 0.35, 0.35, 0.3, 0.3, 0.2, 0.2];
        assert_eq!(lower_bound_l2(&sizes, 1.0), 3);
        assert_eq!(optimum(&sizes, 1.0), 3);
        assert_eq!(bins(&sizes, 1.0), 3);
    }

    #[test]
    fn deterministic() {
        let mut rng = Rng(7);
        let sizes: Vec<f64> = (0..500).map(|_| rng.uniform(200.0, 2980.0)).collect();
        assert_eq!(pack(&sizes, 2980.0), pack(&sizes, 2980.0));
    }

    /// Falkenauer-style triplets: k bins of 1000, each filled exactly by
    /// three integer items in [250, 500), shuffled. L2 = k = the optimum;
    /// best-fit decreasing alone opens many more bins.
    #[test]
    fn triplets() {
        let mut rng = Rng(2024);
        let (mut hits, mut total, mut worst) = (0, 0, 0);
        for k in [20, 40, 60, 120, 249] {
            for _ in 0..4 {
                let mut sizes = Vec::new();
                for _ in 0..k {
                    let a = rng.int(380, 490);
                    let b = rng.int(250, 1000 - a - 251);
                    sizes.extend([a, b, 1000 - a - b].map(|x| x as f64));
                }
                rng.shuffle(&mut sizes);
                assert!(sizes.iter().all(|&s| (250.0..500.0).contains(&s)));
                assert_eq!(lower_bound_l2(&sizes, 1000.0), k);
                let n = bins(&sizes, 1000.0);
                assert!(n <= k + k / 8 + 1, "{k} triplets in {n} bins");
                worst = worst.max(n - k);
                hits += usize::from(n <= k + 1);
                total += 1;
            }
        }
        // Measured: 21, 41, 61 bins for k = 20, 40, 60 (all four each);
        // 123–124 for 120; 277 for 249 (best-fit decreasing's count).
        eprintln!("triplets: within one bin on {hits}/{total}, worst {worst} over");
    }

    /// Random instances of up to 9 items against the exhaustive optimum:
    /// L1 ≤ L2 ≤ optimum, pack ≤ optimum + 1.
    ///
    /// Measured on these 500: pack = optimum on 500/500; L2 = optimum on
    /// 482/500 (L2 is a bound, not the optimum: 0.4 ×5 has L2 = 2, needs 3).
    #[test]
    fn small_instances_against_the_optimum() {
        let mut rng = Rng(1);
        let (mut pack_hits, mut l2_hits, mut total) = (0, 0, 0);
        for t in 0..500 {
            let n = rng.int(1, 9);
            let capacity = 2980.0;
            let (lo, hi) = match t % 4 {
                0 => (0.05, 1.0),
                1 => (0.2, 0.6),
                2 => (0.25, 0.5),
                _ => (0.1, 0.8),
            };
            let sizes: Vec<f64> = (0..n)
                .map(|_| {
                    // Lengths to 0.1 mm, as a kit gives them.
                    (rng.uniform(lo, hi) * capacity * 10.0).round() / 10.0
                })
                .collect();
            let opt = optimum(&sizes, capacity);
            let (l1, l2) = (
                lower_bound_l1(&sizes, capacity),
                lower_bound_l2(&sizes, capacity),
            );
            let got = bins(&sizes, capacity);
            assert!(
                l1 <= l2 && l2 <= opt,
                "{sizes:?}: L1 {l1}, L2 {l2}, opt {opt}"
            );
            assert!(got >= opt && got <= opt + 1, "{sizes:?}: {got} vs {opt}");
            pack_hits += usize::from(got == opt);
            l2_hits += usize::from(l2 == opt);
            total += 1;
        }
        eprintln!("small: pack = opt {pack_hits}/{total}, L2 = opt {l2_hits}/{total}");
        assert!(pack_hits * 100 >= total * 95);
    }

    #[test]
    fn l2_at_least_l1() {
        let mut rng = Rng(3);
        for _ in 0..300 {
            let n = rng.int(1, 400);
            let lo = rng.uniform(0.001, 0.9);
            let sizes: Vec<f64> = (0..n).map(|_| rng.uniform(lo, 1.0)).collect();
            let (l1, l2) = (lower_bound_l1(&sizes, 1.0), lower_bound_l2(&sizes, 1.0));
            assert!(l2 >= l1, "L2 {l2} < L1 {l1}");
            assert!(bins(&sizes, 1.0) >= l2);
        }
    }

    /// Fekete & Schepers (2001) lower bound, for the tests: L1 of the sizes
    /// through the dual feasible functions u⁽ᵏ⁾ ∘ f_ε (k = 1..=20, ε the
    /// sizes ≤ C/2 and 0). O(n²): tests only.
    fn lower_bound_fs(sizes: &[f64], capacity: f64) -> usize {
        let c = effective_capacity(capacity);
        let mut eps: Vec<f64> = sizes.iter().copied().filter(|&x| x <= c / 2.0).collect();
        eps.push(0.0);
        eps.sort_by(f64::total_cmp);
        eps.dedup();
        let mut best = 0;
        for &e in &eps {
            for k in 1..=20 {
                let k = k as f64;
                let total: f64 = sizes
                    .iter()
                    .map(|&x| {
                        let x = if x > c - e {
                            c
                        } else if x < e {
                            0.0
                        } else {
                            x
                        };
                        let y = (k + 1.0) * x / c;
                        if (y - y.round()).abs() < 1e-9 {
                            x
                        } else {
                            y.floor() * c / k
                        }
                    })
                    .sum();
                best = best.max((total / c - 1e-9).ceil() as usize);
            }
        }
        best
    }

    /// Lamella-like instances: 50–300 pieces of 200–2980 mm into 2980 mm
    /// lanes (even t), or mostly short pieces (odd t: 80 % of 200–900 mm).
    ///
    /// L2 + 1 cannot be promised: on some of these the optimum is L2 + 2
    /// (the Fekete–Schepers bound says so). What is asserted: never more
    /// than one bin over the better of L2 and that bound (LB).
    ///
    /// Measured on these 200: pack = L2 on 157, ≤ L2 + 1 on 196;
    /// pack = LB (proven optimal) on 173, LB + 1 on the other 27.
    #[test]
    fn lamella_instances_within_one_of_the_bounds() {
        let mut rng = Rng(42);
        let capacity = 2980.0;
        let (mut at_l2, mut near_l2, mut at_lb, mut total) = (0, 0, 0, 0);
        for t in 0..200 {
            let n = rng.int(50, 300);
            let sizes: Vec<f64> = (0..n)
                .map(|_| {
                    let s = if t % 2 == 1 && rng.unit() < 0.8 {
                        rng.uniform(200.0, 900.0)
                    } else {
                        rng.uniform(200.0, 2980.0)
                    };
                    (s * 10.0).round() / 10.0
                })
                .collect();
            let l2 = lower_bound_l2(&sizes, capacity);
            let lb = l2.max(lower_bound_fs(&sizes, capacity));
            let got = bins(&sizes, capacity);
            assert!(got >= lb && got <= lb + 1, "{got} bins, L2 {l2}, LB {lb}");
            at_l2 += usize::from(got == l2);
            near_l2 += usize::from(got <= l2 + 1);
            at_lb += usize::from(got == lb);
            total += 1;
        }
        eprintln!(
            "lamella: pack = L2 {at_l2}/{total}, ≤ L2 + 1 {near_l2}/{total}, = LB {at_lb}/{total}"
        );
    }

    /// 60,000 pieces; a figure, not a pass/fail limit (see the module doc).
    #[test]
    #[ignore = "timing: run in release with --ignored --nocapture"]
    fn timing() {
        let mut rng = Rng(60_000);
        for short in [false, true] {
            let sizes: Vec<f64> = (0..60_000)
                .map(|_| {
                    let s = if short && rng.unit() < 0.8 {
                        rng.uniform(200.0, 900.0)
                    } else {
                        rng.uniform(200.0, 2980.0)
                    };
                    (s * 10.0).round() / 10.0
                })
                .collect();
            let start = std::time::Instant::now();
            let packing = pack(&sizes, 2980.0).unwrap();
            let elapsed = start.elapsed();
            check(&sizes, 2980.0, &packing);
            eprintln!(
                "60,000 items (short: {short}): {} bins, L2 {}, {:.1} ms",
                packing.bins.len(),
                lower_bound_l2(&sizes, 2980.0),
                elapsed.as_secs_f64() * 1e3
            );
        }
    }
}
