//! A supernodal Cholesky factor's structure: its supernodes (runs of
//! columns with the same rows below), each one's rows below, and where its
//! dense block of values starts (faer's layout: column-major, each column
//! its diagonal block's rows, then the rows below).
//!
//! A frame's stiffness is a matrix of 6 × 6 blocks, one per pair of joined
//! nodes, and its unknowns are numbered node by node in the order they are
//! eliminated in ([`super::ordering`]). Its factor's structure is then the
//! structure of the nodes' graph with each node widened to its run of
//! unknowns ([`Layout::widened`]): the symbolic factorisation runs on the
//! nodes, 36 times fewer entries than the unknowns' (at 400 × 400
//! benchmark curves faer's symbolic factorisation of the 12 million
//! unknowns took 11–18 s and a 2.1 GB transposed copy of the pattern).

use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;

/// A supernodal factor's structure, with faer's accessors.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Layout {
    nrows: usize,
    /// Each supernode's first column, then the number of columns.
    begin: Vec<usize>,
    /// Where each supernode's rows below start in `rows`, then their count.
    row_start: Vec<usize>,
    /// Where each supernode's block of values starts, then their count.
    value_start: Vec<usize>,
    /// Every supernode's rows below, as `u32` (a layout is made only for
    /// fewer than 2³² unknowns): 111 MB at 400 × 400 benchmark curves
    /// rather than 222.
    rows: Vec<u32>,
}

impl Layout {
    /// faer's structure, copied; `None` past 2³² unknowns.
    pub(crate) fn of_faer(s: &SymbolicSupernodalCholesky<usize>) -> Option<Layout> {
        u32::try_from(s.nrows()).ok()?;
        let mut begin = s.supernode_begin().to_vec();
        begin.push(s.nrows());
        Some(Layout {
            nrows: s.nrows(),
            begin,
            row_start: s.col_ptr_for_row_idx().to_vec(),
            value_start: s.col_ptr_for_val().to_vec(),
            rows: s.row_idx().iter().map(|&r| r as u32).collect(),
        })
    }

    /// The structure of a factor over the nodes, each node widened to its
    /// run of unknowns: node k's unknowns are `first[k]..first[k + 1]`
    /// (none where the two are equal: a node of the graph without unknowns,
    /// which the stiffness's graph does not have). A supernode of nodes
    /// becomes one of their unknowns (a supernode of nodes without unknowns
    /// is left out), and each node row below becomes its unknowns' rows.
    /// `None` past 2³² unknowns.
    pub(crate) fn widened(
        nodes: &SymbolicSupernodalCholesky<usize>,
        first: &[usize],
    ) -> Option<Layout> {
        u32::try_from(*first.last().unwrap_or(&0)).ok()?;
        let count = nodes.n_supernodes();
        let (node_begin, node_end) = (nodes.supernode_begin(), nodes.supernode_end());
        let node_row_start = nodes.col_ptr_for_row_idx();
        let node_rows = nodes.row_idx();
        let mut layout = Layout {
            nrows: *first.last().unwrap_or(&0),
            begin: vec![0],
            row_start: vec![0],
            value_start: vec![0],
            rows: Vec::new(),
        };
        // Every row counted first, so the rows are made in one allocation
        // of their size: grown by doubling they took 268 MB at 400 × 400
        // benchmark curves for 222 MB of rows, and left the smaller
        // copies' memory behind.
        let widened = |r: &usize| first[*r + 1] - first[*r];
        let total = (0..count)
            .filter(|&s| first[node_begin[s]] != first[node_end[s]])
            .map(|s| {
                node_rows[node_row_start[s]..node_row_start[s + 1]]
                    .iter()
                    .map(widened)
                    .sum::<usize>()
            })
            .sum();
        layout.rows.reserve_exact(total);
        layout.begin.reserve_exact(count);
        layout.row_start.reserve_exact(count);
        layout.value_start.reserve_exact(count);
        for s in 0..count {
            let (from, to) = (first[node_begin[s]], first[node_end[s]]);
            if from == to {
                continue;
            }
            for &r in &node_rows[node_row_start[s]..node_row_start[s + 1]] {
                layout.rows.extend(first[r] as u32..first[r + 1] as u32);
            }
            let width = to - from;
            let below = layout.rows.len() - layout.row_start.last().copied().unwrap_or(0);
            layout.begin.push(to);
            layout.row_start.push(layout.rows.len());
            let values = layout.value_start.last().copied().unwrap_or(0) + width * (width + below);
            layout.value_start.push(values);
        }
        Some(layout)
    }

    pub(crate) fn n_supernodes(&self) -> usize {
        self.begin.len() - 1
    }

    pub(crate) fn nrows(&self) -> usize {
        self.nrows
    }

    /// Each supernode's first column.
    pub(crate) fn supernode_begin(&self) -> &[usize] {
        &self.begin[..self.n_supernodes()]
    }

    /// Each supernode's end (one past its last column).
    pub(crate) fn supernode_end(&self) -> &[usize] {
        &self.begin[1..]
    }

    /// Where each supernode's rows below start in [`Layout::row_idx`],
    /// then their count.
    pub(crate) fn col_ptr_for_row_idx(&self) -> &[usize] {
        &self.row_start
    }

    /// Where each supernode's block of values starts, then their count.
    pub(crate) fn col_ptr_for_val(&self) -> &[usize] {
        &self.value_start
    }

    /// Every supernode's rows below, ascending.
    pub(crate) fn row_idx(&self) -> &[u32] {
        &self.rows
    }

    /// The number of values of the factor.
    #[cfg(test)]
    pub(crate) fn len_val(&self) -> usize {
        *self.value_start.last().unwrap_or(&0)
    }
}
