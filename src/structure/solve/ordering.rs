//! The fill-reducing order of a frame's unknowns, found on its nodes.
//!
//! A frame's stiffness couples whole nodes: every element adds its whole
//! 12 × 12 block (zeros included) and a node's free unknowns are numbered
//! together, so the matrix is the node graph with a dense block per node
//! and per edge. The approximate minimum degree ordering is therefore
//! computed on the node graph, six times smaller each way than the
//! unknowns' (and 36 times fewer entries), and each node's unknowns are
//! then numbered together in its place. Ordering and symbolic
//! factorisation of the 100 × 100 benchmark grid took 0.74 s with faer
//! ordering the unknowns, 0.27 s so (the order 0.06 s of it); of the
//! 400 × 400 grid's 12.3 million unknowns 29–33 s, 14 s so. Minimum
//! degree breaks its ties otherwise on the nodes: the factor holds 2.3 %
//! more entries at 100 × 100, 5.7 % at 400 × 400.
//!
//! The nodes are then put in a postorder of their elimination tree (each
//! subtree a range, children before parents). With every node's block
//! dense, each node's unknowns are a chain in the unknowns' elimination
//! tree, so the expanded order is a postorder there too: the supernodes of
//! the factor come out numbered in a postorder, as the triangular solves'
//! schedule wants ([`super::triangular`]), without a second symbolic
//! factorisation.
//!
//! A model's unknowns are numbered in that order from the start
//! ([`number_in_order`], from its elements' node pairs, before any matrix
//! is assembled), so its stiffness is assembled in the order it is
//! eliminated in and factorised as it stands: faer, given an order, first
//! makes a permuted copy of the matrix, every entry with its row (2.2 GB
//! at 400 × 400). A pattern not of those elements (a sum with the cables'
//! matrices) is ordered from its own node graph ([`by_nodes`]).

use super::{Dofs, Pattern, NONE};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMatRef;

/// The unknowns of the matrix with `pattern` (lower triangle, `n`
/// unknowns of `dofs`) in a fill-reducing order: `order[k]` is the
/// unknown eliminated k-th. `None` when the pattern is not of `dofs`'
/// unknowns or the ordering fails (the caller then orders the unknowns
/// themselves).
pub(crate) fn by_nodes(pattern: &Pattern, n: usize, dofs: &Dofs) -> Option<Vec<usize>> {
    let nodes = Nodes::of(dofs, n)?;
    let graph = nodes.graph(pattern);
    let minimum_degree = approximate_minimum_degree(&graph)?;
    let order = postorder(&graph, &minimum_degree);
    Some(
        order
            .iter()
            .flat_map(|&c| nodes.first[c] as usize..nodes.first[c + 1] as usize)
            .collect(),
    )
}

/// Numbers `dofs`' unknowns node by node in a fill-reducing order of the
/// nodes (approximate minimum degree on the graph of the elements' node
/// pairs `pairs`, in a postorder of its elimination tree), so the
/// stiffness assembled on them is factorised as it stands: its pattern
/// has the graph of `pairs`, each node's block dense. Each node's
/// unknowns keep their order among themselves. Returns whether it did;
/// `dofs` is left as it was where its unknowns are not numbered node by
/// node or the ordering fails.
pub(crate) fn number_in_order(
    dofs: &mut Dofs,
    pairs: impl Iterator<Item = [usize; 2]> + Clone,
) -> bool {
    let Some(nodes) = Nodes::of(dofs, dofs.free) else {
        return false;
    };
    let joined = pairs
        .filter_map(|[p, q]| Some((nodes.of_model_node(dofs, p)?, nodes.of_model_node(dofs, q)?)));
    let graph = Graph::of_pairs(nodes.count(), joined);
    let Some(minimum_degree) = approximate_minimum_degree(&graph) else {
        return false;
    };
    let order = postorder(&graph, &minimum_degree);
    let mut renumbered = vec![0; dofs.free];
    let mut next = 0;
    for &c in &order {
        for new in &mut renumbered[nodes.first[c] as usize..nodes.first[c + 1] as usize] {
            *new = next;
            next += 1;
        }
    }
    for u in dofs.index.iter_mut().filter(|u| **u != NONE) {
        *u = renumbered[*u];
    }
    dofs.in_order = true;
    true
}

/// The nodes that have unknowns, numbered as their unknowns are.
struct Nodes {
    /// Per unknown, its node (among those with unknowns).
    of_unknown: Vec<u32>,
    /// Node c's unknowns are `first[c]..first[c + 1]`.
    first: Vec<u32>,
}

impl Nodes {
    /// `dofs`' nodes with unknowns, numbered as their unknowns are; `None`
    /// unless the `n` unknowns are numbered node by node (each node's a
    /// range, in any order of the nodes).
    fn of(dofs: &Dofs, n: usize) -> Option<Nodes> {
        if dofs.free != n || u32::try_from(n).is_err() {
            return None;
        }
        // Each node's (first, end) unknowns and how many it has.
        let mut runs: Vec<(usize, usize, usize)> = Vec::new();
        for six in dofs.index.chunks(6) {
            let free = six.iter().filter(|&&u| u != NONE);
            let count = free.clone().count();
            if count > 0 {
                let first = *free.clone().min()?;
                let end = free.max()? + 1;
                runs.push((first, end, count));
            }
        }
        runs.sort_unstable();
        let mut of_unknown = vec![0u32; n];
        let mut first = vec![0u32];
        for (c, &(from, to, count)) in runs.iter().enumerate() {
            // The runs tile 0..n, each its node's unknowns alone.
            if from != *first.last()? as usize || to - from != count || to > n {
                return None;
            }
            of_unknown[from..to].fill(c as u32);
            first.push(to as u32);
        }
        (first.last().copied() == Some(n as u32)).then_some(Nodes { of_unknown, first })
    }

    /// The node (as numbered here) of model node `p`, if it has unknowns.
    fn of_model_node(&self, dofs: &Dofs, p: usize) -> Option<u32> {
        let six = dofs.index.get(p * 6..p * 6 + 6)?;
        let u = *six.iter().find(|&&u| u != NONE)?;
        Some(self.of_unknown[u])
    }

    fn count(&self) -> usize {
        self.first.len() - 1
    }

    /// The node graph: per node, its neighbours of higher number (the
    /// lower triangle, by columns, ascending, no diagonal).
    fn graph(&self, pattern: &Pattern) -> Graph {
        let m = self.count();
        let mut start = Vec::with_capacity(m + 1);
        start.push(0u32);
        let mut rows: Vec<u32> = Vec::new();
        let mut seen = vec![u32::MAX; m];
        for c in 0..m {
            let begin = rows.len();
            for j in self.first[c] as usize..self.first[c + 1] as usize {
                for i in pattern.column(j) {
                    let d = self.of_unknown[i];
                    if d as usize != c && seen[d as usize] != c as u32 {
                        seen[d as usize] = c as u32;
                        rows.push(d);
                    }
                }
            }
            rows[begin..].sort_unstable();
            start.push(rows.len() as u32);
        }
        Graph { start, rows }
    }
}

/// A symmetric graph's lower triangle in compressed columns.
struct Graph {
    start: Vec<u32>,
    rows: Vec<u32>,
}

impl Graph {
    fn count(&self) -> usize {
        self.start.len() - 1
    }

    /// The graph of `m` nodes joined by `pairs` (each edge once however
    /// often it is listed; a node paired with itself adds none): per node,
    /// its neighbours of higher number, ascending.
    fn of_pairs(m: usize, pairs: impl Iterator<Item = (u32, u32)> + Clone) -> Graph {
        let lower = |(a, b): (u32, u32)| (a != b).then(|| (a.min(b), a.max(b)));
        let mut start = vec![0u32; m + 1];
        for (c, _) in pairs.clone().filter_map(lower) {
            start[c as usize + 1] += 1;
        }
        for c in 0..m {
            start[c + 1] += start[c];
        }
        let mut next = start.clone();
        let mut listed = vec![0u32; start[m] as usize];
        for (c, d) in pairs.filter_map(lower) {
            listed[next[c as usize] as usize] = d;
            next[c as usize] += 1;
        }
        // Sorted and each neighbour once, compacted in place.
        let mut rows = listed;
        let mut kept = 0;
        for c in 0..m {
            let (from, to) = (start[c] as usize, start[c + 1] as usize);
            rows[from..to].sort_unstable();
            start[c] = kept as u32;
            for k in from..to {
                if k == from || rows[k] != rows[k - 1] {
                    rows[kept] = rows[k];
                    kept += 1;
                }
            }
        }
        start[m] = kept as u32;
        rows.truncate(kept);
        Graph { start, rows }
    }
}

/// faer's approximate minimum degree order of the graph's nodes
/// (`order[k]` the node eliminated k-th).
fn approximate_minimum_degree(graph: &Graph) -> Option<Vec<u32>> {
    let m = graph.count();
    let matrix = SymbolicSparseColMatRef::new_checked(m, m, &graph.start, None, &graph.rows);
    let mut order = vec![0u32; m];
    let mut inverse = vec![0u32; m];
    let mut memory = MemBuffer::try_new(amd::order_scratch::<u32>(m, graph.rows.len())).ok()?;
    amd::order(
        &mut order,
        &mut inverse,
        matrix,
        amd::Control::default(),
        MemStack::new(&mut memory),
    )
    .ok()?;
    Some(order)
}

/// `order` rearranged into a postorder of the elimination tree of the
/// graph eliminated in `order` (children in ascending order, before their
/// parent): the same fill.
fn postorder(graph: &Graph, order: &[u32]) -> Vec<usize> {
    let m = graph.count();
    let mut place = vec![0u32; m];
    for (k, &c) in order.iter().enumerate() {
        place[c as usize] = k as u32;
    }
    // Each edge once, from the later-eliminated end: the neighbours
    // eliminated before each node, in elimination places.
    let mut earlier_count = vec![0u32; m + 1];
    for c in 0..m {
        for &d in &graph.rows[graph.start[c] as usize..graph.start[c + 1] as usize] {
            let (a, b) = (place[c], place[d as usize]);
            earlier_count[a.max(b) as usize + 1] += 1;
        }
    }
    for k in 0..m {
        earlier_count[k + 1] += earlier_count[k];
    }
    let mut next = earlier_count.clone();
    let mut earlier = vec![0u32; earlier_count[m] as usize];
    for c in 0..m {
        for &d in &graph.rows[graph.start[c] as usize..graph.start[c + 1] as usize] {
            let (a, b) = (place[c], place[d as usize]);
            let (late, early) = (a.max(b), a.min(b));
            earlier[next[late as usize] as usize] = early;
            next[late as usize] += 1;
        }
    }
    // Liu's elimination tree with path compression, in places.
    const ROOT: u32 = u32::MAX;
    let mut parent = vec![ROOT; m];
    let mut ancestor = vec![ROOT; m];
    for k in 0..m {
        for &i in &earlier[earlier_count[k] as usize..earlier_count[k + 1] as usize] {
            let mut r = i;
            while ancestor[r as usize] != ROOT && ancestor[r as usize] != k as u32 {
                let up = ancestor[r as usize];
                ancestor[r as usize] = k as u32;
                r = up;
            }
            if ancestor[r as usize] == ROOT {
                ancestor[r as usize] = k as u32;
                parent[r as usize] = k as u32;
            }
        }
    }
    // Children lists (ascending, as the places are visited in order),
    // then a depth-first postorder from each root in turn.
    let mut child_count = vec![0u32; m + 1];
    for &p in &parent {
        if p != ROOT {
            child_count[p as usize + 1] += 1;
        }
    }
    for k in 0..m {
        child_count[k + 1] += child_count[k];
    }
    let mut fill = child_count.clone();
    let mut children = vec![0u32; child_count[m] as usize];
    for (k, &p) in parent.iter().enumerate() {
        if p != ROOT {
            children[fill[p as usize] as usize] = k as u32;
            fill[p as usize] += 1;
        }
    }
    let mut out = Vec::with_capacity(m);
    let mut stack: Vec<(u32, u32)> = Vec::new();
    for root in (0..m as u32).filter(|&k| parent[k as usize] == ROOT) {
        stack.push((root, child_count[root as usize]));
        while let Some(&mut (k, ref mut at)) = stack.last_mut() {
            if *at < child_count[k as usize + 1] {
                let child = children[*at as usize];
                *at += 1;
                stack.push((child, child_count[child as usize]));
            } else {
                out.push(order[k as usize] as usize);
                stack.pop();
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    /// A pattern coupling whole nodes: each node's unknowns with each
    /// other and with those of the nodes `edges` joins.
    fn node_pattern(first: &[usize], edges: &[(usize, usize)]) -> Pattern {
        let nodes = first.len() - 1;
        let n = first[nodes];
        let mut joined: Vec<Vec<usize>> = (0..nodes).map(|c| vec![c]).collect();
        for &(a, b) in edges {
            joined[a.min(b)].push(a.max(b));
        }
        let mut start = vec![0];
        let mut rows = Vec::new();
        for c in 0..nodes {
            joined[c].sort_unstable();
            for j in first[c]..first[c + 1] {
                for &d in &joined[c] {
                    rows.extend((first[d]..first[d + 1]).filter(|&i| i >= j));
                }
                start.push(rows.len());
            }
        }
        assert_eq!(start.len(), n + 1);
        Pattern::listed(start, rows, false)
    }

    #[test]
    fn each_nodes_unknowns_stay_together_in_the_order() {
        // Five nodes: node 1 held in all six directions (no unknowns),
        // node 3 in three; a chain 0–2–3–4 and a brace 0–4.
        let mut index = Vec::new();
        let mut free = 0;
        for node in 0..5 {
            for k in 0..6 {
                let fixed = node == 1 || (node == 3 && k < 3);
                index.push(if fixed {
                    NONE
                } else {
                    free += 1;
                    free - 1
                });
            }
        }
        let dofs = Dofs {
            index,
            free,
            in_order: false,
            symbolic: Arc::default(),
        };
        let first = [0, 6, 12, 15, 21];
        let pattern = node_pattern(&first, &[(0, 1), (1, 2), (2, 3), (0, 3)]);
        let order = by_nodes(&pattern, free, &dofs).expect("an order");
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..free).collect::<Vec<_>>(), "a permutation");
        // Node by node, each node's unknowns ascending.
        let mut k = 0;
        while k < free {
            let c = first.iter().rposition(|&f| f <= order[k]).unwrap();
            let run = first[c + 1] - first[c];
            assert_eq!(order[k], first[c], "node {c} starts its run");
            assert_eq!(
                order[k..k + run],
                (first[c]..first[c + 1]).collect::<Vec<_>>()
            );
            k += run;
        }
        // A pattern of other unknowns is not ordered by these nodes.
        assert!(by_nodes(&pattern, free - 1, &dofs).is_none());
    }

    /// The elimination tree of a lower pattern in the given order, by
    /// the definition (parent(k) is the first row below k in column k of
    /// the factor, found by eliminating densely), and the factor's
    /// entries below the diagonal.
    fn eliminated(graph: &Graph, order: &[usize]) -> (Vec<Option<usize>>, usize) {
        let m = graph.count();
        let mut place = vec![0; m];
        for (k, &c) in order.iter().enumerate() {
            place[c] = k;
        }
        let mut adjacent = vec![vec![false; m]; m];
        for c in 0..m {
            for &d in &graph.rows[graph.start[c] as usize..graph.start[c + 1] as usize] {
                let (a, b) = (place[c], place[d as usize]);
                adjacent[a][b] = true;
                adjacent[b][a] = true;
            }
        }
        let mut parent = vec![None; m];
        let mut entries = 0;
        for k in 0..m {
            let below: Vec<usize> = (k + 1..m).filter(|&i| adjacent[k][i]).collect();
            parent[k] = below.first().copied();
            entries += below.len();
            for &a in &below {
                for &b in &below {
                    if a != b {
                        adjacent[a][b] = true;
                    }
                }
            }
        }
        (parent, entries)
    }

    #[test]
    fn a_postorder_puts_each_subtree_in_a_range_before_its_root() {
        // A 5 × 4 grid of nodes, eliminated in a scrambled order.
        let (w, h) = (5, 4);
        let m = w * h;
        let mut lists = vec![Vec::new(); m];
        for y in 0..h {
            for x in 0..w {
                let c = y * w + x;
                if x + 1 < w {
                    lists[c].push((c + 1) as u32);
                }
                if y + 1 < h {
                    lists[c].push((c + w) as u32);
                }
            }
        }
        let mut start = vec![0u32];
        let mut rows = Vec::new();
        for l in &lists {
            rows.extend(l);
            start.push(rows.len() as u32);
        }
        let graph = Graph { start, rows };
        let scrambled: Vec<u32> = (0..m as u32).map(|k| (k * 7) % m as u32).collect();
        let post = postorder(&graph, &scrambled);
        let mut sorted = post.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..m).collect::<Vec<_>>(), "a permutation");
        // In the postorder, every node's parent comes later, and a
        // subtree is the range ending at its root.
        let (parent, entries) = eliminated(&graph, &post);
        let mut first = (0..m).collect::<Vec<_>>();
        for k in 0..m {
            if let Some(p) = parent[k] {
                assert!(p > k);
                first[p] = first[p].min(first[k]);
            }
        }
        for (k, &from) in first.iter().enumerate() {
            // Everything in first[k]..k descends from k.
            for i in from..k {
                let mut a = i;
                while a != k {
                    a = parent[a].expect("descends from k");
                }
            }
        }
        // The same fill as the scrambled order's.
        let scrambled: Vec<usize> = scrambled.iter().map(|&c| c as usize).collect();
        assert_eq!(entries, eliminated(&graph, &scrambled).1);
    }
}
