//! Triangular solves L·Lᵀ·x = b on a supernodal Cholesky factor, the
//! factor's subtrees shared between two threads.
//!
//! Every supernode is a dense block of its columns' rows (the diagonal
//! block, then the rows below), column-major. Up to eight right-hand sides
//! are solved side by side (a row's values together), so each entry of L is
//! read once per block: a solve is bound by reading the factor from memory.
//!
//! **Two threads, two halves of the factor.** The supernodes are numbered
//! in a postorder of their elimination tree (the stiffness's, made on its
//! nodes numbered in such a postorder, comes out so; where faer ordered
//! the unknowns itself, in the minimum degree's order, its symbolic
//! factorisation is redone in one, [`postorder`]), so a subtree is a range of
//! supernodes and of columns, and its columns' rows below reach
//! only its own columns and its ancestors'. A [`Schedule`] cuts the tree
//! into subtrees ("pieces") dealt to two threads with near-equal shares of
//! the factor's entries, and the supernodes above them (the "top"):
//! * forward, each thread eliminates its pieces, its updates of its own
//!   rows in place and of the top's rows into an accumulator of its own;
//!   the two accumulators are then subtracted and the top eliminated;
//! * backward, the top is solved first, then each thread its pieces,
//!   reading the top's values from a copy.
//!
//! Each thread reads half of the factor once, where a split by right-hand
//! sides had both threads read all of it. The sums of a top row are taken
//! in the schedule's order, which depends on the factor's structure only:
//! the same bits for any number of threads.

use super::layout::Layout;
use std::ops::Range;

/// A factor's supernodes dealt to two threads.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Schedule {
    /// Per thread, its pieces: ranges of supernodes, each a whole subtree.
    pieces: [Vec<Range<usize>>; 2],
    /// The supernodes above the pieces, ascending.
    top: Vec<usize>,
    /// Per column: its place among the top's columns (`NOT_TOP` for a
    /// piece's).
    top_place: Vec<u32>,
    /// The top's columns, ascending.
    top_columns: Vec<usize>,
}

const NOT_TOP: u32 = u32::MAX;

/// The pieces are dealt until the larger share of their entries is within
/// this factor of half the pieces' sum.
const BALANCE: f64 = 1.02;

/// At most this many subtrees are split to reach [`BALANCE`] (each split
/// moves a supernode to the top, which one thread solves; the 100 × 100
/// benchmark grid's factor took 4, leaving 5.6 % of its entries on top).
const SPLITS: usize = 256;

/// One supernode of a factor: its columns, the rows below them and its
/// block of values (column-major, each column its diagonal block's rows
/// and then those below).
struct Supernode<'a> {
    first_column: usize,
    width: usize,
    below: &'a [u32],
    block: &'a [f64],
}

impl<'a> Supernode<'a> {
    fn of(layout: &'a Layout, values: &'a [f64], s: usize) -> Supernode<'a> {
        let first_column = layout.supernode_begin()[s];
        let row_start = layout.col_ptr_for_row_idx();
        let value_start = layout.col_ptr_for_val();
        Supernode {
            first_column,
            width: layout.supernode_end()[s] - first_column,
            below: &layout.row_idx()[row_start[s]..row_start[s + 1]],
            block: &values[value_start[s]..value_start[s + 1]],
        }
    }

    /// How many of the rows below lie in `own` (rows `offset`.. of y,
    /// `own_len` of them; the rest lie beyond it).
    fn inside(&self, offset: usize, own_len: usize) -> usize {
        self.below
            .partition_point(|&r| (r as usize) < offset + own_len)
    }

    /// Column k's values in its diagonal block, and the rows below with
    /// their values, split after the first `inside`.
    #[allow(clippy::type_complexity)]
    fn column(
        &self,
        k: usize,
        inside: usize,
    ) -> (&'a [f64], (&'a [u32], &'a [f64]), (&'a [u32], &'a [f64])) {
        let height = self.width + self.below.len();
        let column = &self.block[k * height..(k + 1) * height];
        let (near, far) = self.below.split_at(inside);
        let (l_near, l_far) = column[self.width..].split_at(inside);
        (&column[..self.width], (near, l_near), (far, l_far))
    }

    /// Forward elimination of its columns on `own`, the rows from
    /// `offset` on; an update of a row beyond `own` goes to
    /// `outside(row, l, x)` (to be subtracted: l·x).
    fn forward<const P: usize>(
        &self,
        own: &mut [[f64; P]],
        offset: usize,
        outside: &mut impl FnMut(usize, f64, &[f64; P]),
    ) {
        let (c0, inside) = (self.first_column - offset, self.inside(offset, own.len()));
        for k in 0..self.width {
            let (diagonal, (near, l_near), (far, l_far)) = self.column(k, inside);
            let d = 1.0 / diagonal[k];
            let mut xk = own[c0 + k];
            xk.iter_mut().for_each(|v| *v *= d);
            own[c0 + k] = xk;
            for (i, &l) in diagonal[k + 1..].iter().enumerate() {
                let row = &mut own[c0 + k + 1 + i];
                for c in 0..P {
                    row[c] -= l * xk[c];
                }
            }
            for (&r, &l) in near.iter().zip(l_near) {
                let row = &mut own[r as usize - offset];
                for c in 0..P {
                    row[c] -= l * xk[c];
                }
            }
            for (&r, &l) in far.iter().zip(l_far) {
                outside(r as usize, l, &xk);
            }
        }
    }

    /// Backward substitution of its columns on `own` (rows from `offset`
    /// on), the values of rows beyond `own` read by `outside(row)`.
    fn backward<const P: usize>(
        &self,
        own: &mut [[f64; P]],
        offset: usize,
        outside: &impl Fn(usize) -> [f64; P],
    ) {
        let (c0, inside) = (self.first_column - offset, self.inside(offset, own.len()));
        for k in (0..self.width).rev() {
            let (diagonal, (near, l_near), (far, l_far)) = self.column(k, inside);
            let mut acc = own[c0 + k];
            for (i, &l) in diagonal[k + 1..].iter().enumerate() {
                let row = &own[c0 + k + 1 + i];
                for c in 0..P {
                    acc[c] -= l * row[c];
                }
            }
            for (&r, &l) in near.iter().zip(l_near) {
                let row = &own[r as usize - offset];
                for c in 0..P {
                    acc[c] -= l * row[c];
                }
            }
            for (&r, &l) in far.iter().zip(l_far) {
                let row = outside(r as usize);
                for c in 0..P {
                    acc[c] -= l * row[c];
                }
            }
            let d = 1.0 / diagonal[k];
            acc.iter_mut().for_each(|v| *v *= d);
            own[c0 + k] = acc;
        }
    }
}

impl Schedule {
    /// The schedule of `layout`'s supernodes; `None` when they are not
    /// in a postorder (every subtree a range) or the tree does not split
    /// into two shares.
    pub(crate) fn of(layout: &Layout) -> Option<Schedule> {
        let count = layout.n_supernodes();
        let begin = layout.supernode_begin();
        let end = layout.supernode_end();
        let value_start = layout.col_ptr_for_val();
        let columns = end.last().copied().unwrap_or(0);
        // The elimination tree: each subtree's first supernode and its
        // share of the factor's entries.
        let parent = parents(layout);
        let mut first = (0..count).collect::<Vec<_>>();
        let mut size = vec![1usize; count];
        let mut work: Vec<usize> = (0..count)
            .map(|s| value_start[s + 1] - value_start[s])
            .collect();
        for s in 0..count {
            let p = parent[s];
            if p == usize::MAX {
                continue;
            }
            if p <= s {
                return None;
            }
            first[p] = first[p].min(first[s]);
            size[p] += size[s];
            work[p] += work[s];
        }
        if (0..count).any(|s| s + 1 - first[s] != size[s]) {
            return None;
        }
        let mut children = vec![Vec::new(); count];
        let mut pieces = Vec::new();
        for (s, &p) in parent.iter().enumerate() {
            match p {
                usize::MAX => pieces.push(s),
                p => children[p].push(s),
            }
        }
        // Split the heaviest piece into its children until the two
        // shares balance.
        let mut top = Vec::new();
        let mut dealt = deal(&pieces, &work);
        for _ in 0..SPLITS {
            if dealt.1 <= BALANCE {
                break;
            }
            let Some(heaviest) = (0..pieces.len()).max_by_key(|&i| (work[pieces[i]], pieces[i]))
            else {
                break;
            };
            let s = pieces.swap_remove(heaviest);
            top.push(s);
            pieces.extend(&children[s]);
            dealt = deal(&pieces, &work);
        }
        if dealt.0.iter().any(|share| share.is_empty()) {
            return None;
        }
        top.sort_unstable();
        let mut top_place = vec![NOT_TOP; columns];
        let mut top_columns = Vec::new();
        for &s in &top {
            for (c, place) in top_place.iter_mut().enumerate().take(end[s]).skip(begin[s]) {
                *place = u32::try_from(top_columns.len()).ok()?;
                top_columns.push(c);
            }
        }
        let ranges = dealt
            .0
            .map(|share| share.iter().map(|&s| first[s]..s + 1).collect());
        Some(Schedule {
            pieces: ranges,
            top,
            top_place,
            top_columns,
        })
    }

    /// Per thread, its pieces: ranges of supernodes, each a whole subtree.
    pub(crate) fn pieces(&self) -> &[Vec<Range<usize>>; 2] {
        &self.pieces
    }

    /// The supernodes above the pieces, ascending.
    pub(crate) fn top(&self) -> &[usize] {
        &self.top
    }

    /// Each thread's share of the pieces' entries, as a fraction of the
    /// factor's.
    #[cfg(test)]
    pub(crate) fn shares(&self, layout: &Layout) -> [f64; 2] {
        let value_start = layout.col_ptr_for_val();
        let all = *value_start.last().unwrap_or(&0) as f64;
        self.pieces.clone().map(|share| {
            share
                .iter()
                .map(|r| (value_start[r.end] - value_start[r.start]) as f64)
                .sum::<f64>()
                / all
        })
    }
}

/// Supernode s's parent in the elimination tree (the owner of its first
/// row below; `usize::MAX` for a root), given each column's supernode.
fn parents(layout: &Layout) -> Vec<usize> {
    let count = layout.n_supernodes();
    let (begin, end) = (layout.supernode_begin(), layout.supernode_end());
    let row_start = layout.col_ptr_for_row_idx();
    let rows = layout.row_idx();
    let mut owner = vec![0usize; end.last().copied().unwrap_or(0)];
    for s in 0..count {
        owner[begin[s]..end[s]].fill(s);
    }
    (0..count)
        .map(|s| {
            if row_start[s] < row_start[s + 1] {
                owner[rows[row_start[s]] as usize]
            } else {
                usize::MAX
            }
        })
        .collect()
}

/// The factor's columns in a postorder of its supernodes (each subtree's
/// supernodes together, children before their parent, in ascending
/// order), as positions in the present order; `None` when they are so
/// already. The same elimination in another order of independent steps:
/// the factor's entries are the same, rearranged (faer leaves the
/// supernodes in the order of the minimum degree ordering).
pub(crate) fn postorder(layout: &Layout) -> Option<Vec<usize>> {
    let count = layout.n_supernodes();
    let parent = parents(layout);
    let mut children = vec![Vec::new(); count];
    let mut roots = Vec::new();
    for (s, &p) in parent.iter().enumerate() {
        match p {
            usize::MAX => roots.push(s),
            p => children[p].push(s),
        }
    }
    let mut order = Vec::with_capacity(count);
    let mut stack: Vec<(usize, usize)> = Vec::new();
    for &root in &roots {
        stack.push((root, 0));
        while let Some((s, next)) = stack.pop() {
            if let Some(&child) = children[s].get(next) {
                stack.push((s, next + 1));
                stack.push((child, 0));
            } else {
                order.push(s);
            }
        }
    }
    if order.iter().enumerate().all(|(i, &s)| i == s) {
        return None;
    }
    let (begin, end) = (layout.supernode_begin(), layout.supernode_end());
    Some(order.iter().flat_map(|&s| begin[s]..end[s]).collect())
}

/// The pieces dealt largest first, each to the lighter thread: the two
/// shares (supernodes, ascending) and the larger one over half their sum.
fn deal(pieces: &[usize], work: &[usize]) -> ([Vec<usize>; 2], f64) {
    let mut order = pieces.to_vec();
    order.sort_unstable_by_key(|&s| (std::cmp::Reverse(work[s]), s));
    let mut shares = [Vec::new(), Vec::new()];
    let mut sums = [0usize; 2];
    for s in order {
        let t = usize::from(sums[1] < sums[0]);
        shares[t].push(s);
        sums[t] += work[s];
    }
    for share in &mut shares {
        share.sort_unstable();
    }
    let total = (sums[0] + sums[1]).max(1) as f64;
    (shares, sums[0].max(sums[1]) as f64 / (0.5 * total))
}

/// L·Lᵀ·y = b in place (P right-hand sides per row), on one thread.
pub(crate) fn solve_serial<const P: usize>(layout: &Layout, values: &[f64], y: &mut [[f64; P]]) {
    for s in 0..layout.n_supernodes() {
        Supernode::of(layout, values, s).forward(y, 0, &mut |_, _, _| {});
    }
    for s in (0..layout.n_supernodes()).rev() {
        Supernode::of(layout, values, s).backward(y, 0, &|_| unreachable!());
    }
}

/// A piece to solve: its supernodes, its first column, its rows.
type Piece<'y, const P: usize> = (Range<usize>, usize, &'y mut [[f64; P]]);

/// y's rows cut into the pieces of `schedule`, dealt to the two threads.
fn pieces_of<'y, const P: usize>(
    layout: &Layout,
    schedule: &Schedule,
    y: &'y mut [[f64; P]],
) -> [Vec<Piece<'y, P>>; 2] {
    let begin = layout.supernode_begin();
    let end = layout.supernode_end();
    let mut spans: Vec<(usize, Range<usize>)> = schedule
        .pieces
        .iter()
        .enumerate()
        .flat_map(|(t, share)| share.iter().map(move |r| (t, r.clone())))
        .collect();
    spans.sort_unstable_by_key(|(_, r)| r.start);
    let mut shares = [Vec::new(), Vec::new()];
    let mut rest = y;
    let mut at = 0;
    for (t, r) in spans {
        let columns = begin[r.start]..end[r.end - 1];
        let (_, from) = rest.split_at_mut(columns.start - at);
        let (own, after) = from.split_at_mut(columns.len());
        shares[t].push((r, columns.start, own));
        rest = after;
        at = columns.end;
    }
    shares
}

/// L·Lᵀ·y = b in place (P right-hand sides per row), the pieces of
/// `schedule` on two threads.
pub(crate) fn solve_scheduled<const P: usize>(
    layout: &Layout,
    values: &[f64],
    schedule: &Schedule,
    y: &mut [[f64; P]],
) {
    // Forward: the pieces, their updates of the top's rows summed apart;
    // then the top.
    let [a, b] = pieces_of(layout, schedule, y);
    let forward = |pieces: Vec<Piece<'_, P>>| {
        let mut sum = vec![[0.0; P]; schedule.top_columns.len()];
        for (range, offset, own) in pieces {
            for s in range {
                Supernode::of(layout, values, s).forward(own, offset, &mut |row, l, x| {
                    let place = &mut sum[schedule.top_place[row] as usize];
                    for c in 0..P {
                        place[c] += l * x[c];
                    }
                });
            }
        }
        sum
    };
    let sums = rayon::join(|| forward(a), || forward(b));
    for (place, &c) in schedule.top_columns.iter().enumerate() {
        for sum in [&sums.0, &sums.1] {
            for k in 0..P {
                y[c][k] -= sum[place][k];
            }
        }
    }
    for &s in &schedule.top {
        Supernode::of(layout, values, s).forward(y, 0, &mut |_, _, _| {});
    }

    // Backward: the top, then the pieces, reading the top from a copy.
    for &s in schedule.top.iter().rev() {
        Supernode::of(layout, values, s).backward(y, 0, &|_| unreachable!());
    }
    let top_values: Vec<[f64; P]> = schedule.top_columns.iter().map(|&c| y[c]).collect();
    let [a, b] = pieces_of(layout, schedule, y);
    let backward = |pieces: Vec<Piece<'_, P>>| {
        for (range, offset, own) in pieces {
            for s in range.rev() {
                Supernode::of(layout, values, s).backward(own, offset, &|row| {
                    top_values[schedule.top_place[row] as usize]
                });
            }
        }
    };
    rayon::join(|| backward(a), || backward(b));
}
