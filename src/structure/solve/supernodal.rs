//! The numeric Cholesky factorisation L·Lᵀ = A on a supernodal structure
//! ([`Layout`]: for a frame's stiffness made on its nodes), the factor's
//! subtrees shared between two threads.
//!
//! Left-looking, as faer's own: supernode by supernode in the postorder of
//! the elimination tree, each gathers A's columns into its dense block (the
//! diagonal block's rows, then the rows below, column-major), subtracts the
//! update L_d·L_dᵀ of every earlier supernode d whose rows below reach its
//! columns ([`Updates`]), factorises its diagonal block and solves the rows
//! below against it.
//!
//! What it does that faer's does not:
//! * **Two threads.** A subtree's supernodes read only their own
//!   subtree's blocks, so the [`Schedule`]'s pieces (whole subtrees, dealt
//!   to two threads) are factorised side by side, then the supernodes
//!   above them on one thread. Each supernode is computed the same way
//!   whichever thread computes it, with its updates in ascending order:
//!   the same bits for one thread or two.
//! * **A bounded workspace.** faer forms each update L_d·L_dᵀ whole before
//!   scattering it: at 400 × 400 benchmark curves its workspace was
//!   2.35 GB, the product of the largest separators. Here an update is
//!   scattered as it is made, in slices of at most [`TEMP_ENTRIES`]
//!   entries, and small updates (a frame's supernodes are mostly one or a
//!   few nodes wide) are subtracted in place with no product formed at all.

use super::layout::Layout;
use super::triangular::Schedule;
use super::Pattern;
use crate::geom::mesh::bucketed;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch};
use faer::{Accum, MatMut, MatRef, Par};

/// The most entries of an update made at once as a dense product before
/// it is scattered (8 MB).
const TEMP_ENTRIES: usize = 1 << 20;

/// Updates of fewer multiply-adds than this are subtracted in place, with
/// no dense product.
const PRODUCT_WORK: usize = 1 << 15;

/// Diagonal blocks up to this width are factorised by this module's own
/// loops (faer's dense kernels cost more than the arithmetic there).
const OWN_KERNEL_WIDTH: usize = 32;

/// Which supernodes update which: for supernode s, the earlier supernodes
/// d whose rows below reach s's columns, ascending.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Updates {
    start: Vec<usize>,
    from: Vec<u32>,
}

impl Updates {
    /// The updates of `layout`'s supernodes; `None` past 2³² supernodes.
    pub(crate) fn of(layout: &Layout) -> Option<Updates> {
        let count = layout.n_supernodes();
        u32::try_from(count).ok()?;
        let (begin, end) = (layout.supernode_begin(), layout.supernode_end());
        let row_start = layout.col_ptr_for_row_idx();
        let rows = layout.row_idx();
        let mut owner = vec![0u32; end.last().copied().unwrap_or(0)];
        for s in 0..count {
            owner[begin[s]..end[s]].fill(s as u32);
        }
        // Each supernode's rows below visit the supernodes it updates in
        // ascending order, each once per run of its rows.
        let owner = &owner;
        let targets = |d: usize| {
            let mut last = u32::MAX;
            rows[row_start[d]..row_start[d + 1]]
                .iter()
                .filter_map(move |&r| {
                    let s = owner[r as usize];
                    (s != last).then(|| {
                        last = s;
                        s
                    })
                })
        };
        let (start, from) = bucketed(
            count,
            (0..count).flat_map(|d| targets(d).map(move |s| (s as usize, d as u32))),
        );
        Some(Updates { start, from })
    }

    fn of_supernode(&self, s: usize) -> &[u32] {
        &self.from[self.start[s]..self.start[s + 1]]
    }
}

/// The lower triangle of A, column by column (row ≥ column), in the
/// factor's order.
#[derive(Clone, Copy)]
pub(crate) struct Lower<'a> {
    pub pattern: &'a Pattern,
    pub values: &'a [f64],
}

/// L's values (faer's layout for `layout`), or `None` when a pivot is
/// not positive (A is not positive definite in floating point).
pub(crate) fn factorise(
    layout: &Layout,
    updates: &Updates,
    schedule: Option<&Schedule>,
    a: Lower<'_>,
) -> Option<Vec<f64>> {
    factorise_in_slices(layout, updates, schedule, a, TEMP_ENTRIES)
}

/// [`factorise`], an update's dense product made in slices of at most
/// `temp_entries` entries.
pub(crate) fn factorise_in_slices(
    layout: &Layout,
    updates: &Updates,
    schedule: Option<&Schedule>,
    a: Lower<'_>,
    temp_entries: usize,
) -> Option<Vec<f64>> {
    let value_start = layout.col_ptr_for_val();
    let mut values = vec![0.0; *value_start.last().unwrap_or(&0)];
    let count = layout.n_supernodes();
    let n = layout.nrows();
    let job = Job {
        layout,
        updates,
        a,
        temp_entries,
    };
    let top: Vec<usize> = match schedule {
        Some(schedule) => {
            // Each piece's values apart, so the two threads hold disjoint
            // slices.
            let mut pieces: Vec<(usize, std::ops::Range<usize>)> = schedule
                .pieces()
                .iter()
                .enumerate()
                .flat_map(|(t, share)| share.iter().map(move |r| (t, r.clone())))
                .collect();
            pieces.sort_unstable_by_key(|(_, r)| r.start);
            let mut shares: [Vec<(std::ops::Range<usize>, &mut [f64])>; 2] = [vec![], vec![]];
            let (mut rest, mut offset) = (&mut values[..], 0);
            for (t, r) in pieces {
                let (lo, hi) = (value_start[r.start], value_start[r.end]);
                let (_, from_lo) = std::mem::take(&mut rest).split_at_mut(lo - offset);
                let (piece, after) = from_lo.split_at_mut(hi - lo);
                rest = after;
                offset = hi;
                shares[t].push((r, piece));
            }
            let [first, second] = shares;
            let run = |share: Vec<(std::ops::Range<usize>, &mut [f64])>| -> bool {
                let mut worker = Worker::new(n);
                share.into_iter().all(|(range, piece)| {
                    let base = value_start[range.start];
                    range
                        .into_iter()
                        .all(|s| worker.supernode(&job, piece, base, s))
                })
            };
            let (a_ok, b_ok) = rayon::join(|| run(first), || run(second));
            if !(a_ok && b_ok) {
                return None;
            }
            schedule.top().to_vec()
        }
        None => (0..count).collect(),
    };
    let mut worker = Worker::new(n);
    for s in top {
        if !worker.supernode(&job, &mut values, 0, s) {
            return None;
        }
    }
    Some(values)
}

/// What every supernode reads.
struct Job<'a> {
    layout: &'a Layout,
    updates: &'a Updates,
    a: Lower<'a>,
    temp_entries: usize,
}

/// A thread's buffers.
struct Worker {
    /// Per row: its place in the present supernode's block (rows below
    /// only; `u32::MAX` elsewhere).
    local: Vec<u32>,
    /// An update's rows' places in the block.
    places: Vec<u32>,
    /// A slice of an update as a dense product.
    temp: Vec<f64>,
    /// faer's dense Cholesky's workspace.
    memory: MemBuffer,
    memory_width: usize,
}

impl Worker {
    fn new(n: usize) -> Worker {
        Worker {
            local: vec![u32::MAX; n],
            places: Vec::new(),
            temp: Vec::new(),
            memory: MemBuffer::new(cholesky_in_place_scratch::<f64>(
                0,
                Par::Seq,
                Default::default(),
            )),
            memory_width: 0,
        }
    }

    /// Supernode s's block of L, made in `values` (the factor's values
    /// from `base` on, holding every supernode s reads); false when a
    /// pivot is not positive.
    fn supernode(&mut self, job: &Job<'_>, values: &mut [f64], base: usize, s: usize) -> bool {
        let layout = job.layout;
        let (begin, end) = (layout.supernode_begin(), layout.supernode_end());
        let row_start = layout.col_ptr_for_row_idx();
        let value_start = layout.col_ptr_for_val();
        let rows = layout.row_idx();
        let (first, last) = (begin[s], end[s]);
        let width = last - first;
        let below = &rows[row_start[s]..row_start[s + 1]];
        let height = width + below.len();
        for (i, &r) in below.iter().enumerate() {
            self.local[r as usize] = (width + i) as u32;
        }
        let (done, rest) = values.split_at_mut(value_start[s] - base);
        let block = &mut rest[..height * width];
        // Written before it is read: a page of a fresh allocation read
        // first is mapped twice (the shared zero page, then its own).
        block.fill(0.0);
        // A's columns.
        let a = job.a;
        let local = &self.local;
        for c in first..last {
            let column = &mut block[(c - first) * height..(c - first + 1) * height];
            a.pattern.for_each_in(c, |k, r| {
                if r < c {
                    return;
                }
                let place = if r < last {
                    r - first
                } else {
                    // Every row of A lies in the factor's structure.
                    debug_assert!(local[r] != u32::MAX, "row {r} outside the structure");
                    local[r] as usize
                };
                column[place] += a.values[k];
            });
        }
        // The updates of the supernodes below, ascending.
        for &d in job.updates.of_supernode(s) {
            let d = d as usize;
            let d_width = end[d] - begin[d];
            let d_below = &rows[row_start[d]..row_start[d + 1]];
            let d_height = d_width + d_below.len();
            let l_d = &done[value_start[d] - base..value_start[d + 1] - base];
            let p0 = d_below.partition_point(|&r| (r as usize) < first);
            let mid = d_below[p0..].partition_point(|&r| (r as usize) < last);
            let m = d_below.len() - p0;
            let local = &self.local;
            self.places.clear();
            self.places.extend(d_below[p0..].iter().map(|&r| {
                let r = r as usize;
                if r < last {
                    (r - first) as u32
                } else {
                    local[r]
                }
            }));
            if m * mid * d_width < PRODUCT_WORK {
                // Column j of the update, k by k: contiguous columns of L_d.
                for j in 0..mid {
                    let target = self.places[j] as usize * height;
                    let column = &mut block[target..target + height];
                    for k in 0..d_width {
                        let l = &l_d[k * d_height + d_width + p0..k * d_height + d_height];
                        let f = l[j];
                        if f == 0.0 {
                            continue;
                        }
                        for (&place, &x) in self.places[j..].iter().zip(&l[j..]) {
                            column[place as usize] -= x * f;
                        }
                    }
                }
            } else {
                let l = MatRef::from_column_major_slice_with_stride(
                    &l_d[d_width + p0..],
                    m,
                    d_width,
                    d_height,
                );
                let chunk = (job.temp_entries / mid).max(1);
                let mut r0 = 0;
                while r0 < m {
                    let rows_now = chunk.min(m - r0);
                    // Columns j < mid of rows r0..: only j ≤ row is needed.
                    let cols_now = mid.min(r0 + rows_now);
                    self.temp.clear();
                    self.temp.resize(rows_now * cols_now, 0.0);
                    let mut t =
                        MatMut::from_column_major_slice_mut(&mut self.temp, rows_now, cols_now);
                    faer::linalg::matmul::matmul(
                        t.as_mut(),
                        Accum::Replace,
                        l.subrows(r0, rows_now),
                        l.subrows(0, cols_now).transpose(),
                        1.0,
                        Par::Seq,
                    );
                    for j in 0..cols_now {
                        let target = self.places[j] as usize * height;
                        let column = &mut block[target..target + height];
                        let from = j.max(r0);
                        let t_col = &self.temp[j * rows_now..(j + 1) * rows_now];
                        for (&place, &x) in self.places[from..r0 + rows_now]
                            .iter()
                            .zip(&t_col[from - r0..])
                        {
                            column[place as usize] -= x;
                        }
                    }
                    r0 += rows_now;
                }
            }
        }
        for &r in below {
            self.local[r as usize] = u32::MAX;
        }
        if width <= OWN_KERNEL_WIDTH {
            own_kernel(block, width, height)
        } else {
            self.faer_kernel(block, width, height)
        }
    }

    /// The diagonal block factorised and the rows below solved by faer's
    /// dense kernels.
    fn faer_kernel(&mut self, block: &mut [f64], width: usize, height: usize) -> bool {
        if width > self.memory_width {
            self.memory = MemBuffer::new(cholesky_in_place_scratch::<f64>(
                width,
                Par::Seq,
                Default::default(),
            ));
            self.memory_width = width;
        }
        let ls = MatMut::from_column_major_slice_mut(block, height, width);
        let (mut top, bottom) = ls.split_at_row_mut(width);
        if cholesky_in_place(
            top.as_mut(),
            Default::default(),
            Par::Seq,
            MemStack::new(&mut self.memory),
            Default::default(),
        )
        .is_err()
        {
            return false;
        }
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            top.as_ref(),
            bottom.transpose_mut(),
            Par::Seq,
        );
        true
    }
}

/// The diagonal block (`width` wide, in a block of `height` rows)
/// factorised column by column and the rows below solved against it, by
/// plain loops; false when a pivot is not positive.
fn own_kernel(block: &mut [f64], width: usize, height: usize) -> bool {
    for k in 0..width {
        let (before, from_k) = block.split_at_mut(k * height);
        let column = &mut from_k[..height];
        // Column k less the columns before it (left-looking), every row
        // from the diagonal down.
        for j in 0..k {
            let done = &before[j * height..(j + 1) * height];
            let f = done[k];
            if f == 0.0 {
                continue;
            }
            for (x, &l) in column[k..].iter_mut().zip(&done[k..]) {
                *x -= l * f;
            }
        }
        let pivot = column[k];
        let positive = pivot > 0.0 && pivot.is_finite();
        if !positive {
            return false;
        }
        let d = pivot.sqrt();
        column[k] = d;
        let inv = 1.0 / d;
        for x in &mut column[k + 1..] {
            *x *= inv;
        }
    }
    true
}
