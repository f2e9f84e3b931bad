//! A triangle mesh: positions and triangles, the data mesh readers make
//! and the mesh stages (`design::mesh`) and form finding share.

use glam::DVec3;

/// A triangle mesh in mm.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions, mm.
    pub positions_mm: Vec<DVec3>,
    /// Triangles as vertex indices, counter-clockwise seen from the normals' side.
    pub triangles: Vec<[u32; 3]>,
}

/// Which vertices a walk over a mesh has visited, cleared in O(1): a stamp
/// per vertex and the current walk's number (for growing neighbourhoods
/// vertex after vertex without a set per walk).
#[derive(Debug, Clone)]
pub struct VisitMarks {
    stamp: Vec<u32>,
    walk: u32,
}

impl VisitMarks {
    /// Marks for `n` vertices, none visited.
    pub fn new(n: usize) -> VisitMarks {
        VisitMarks {
            stamp: vec![0; n],
            walk: 1,
        }
    }
    /// Forget every visit.
    pub fn clear(&mut self) {
        if self.walk == u32::MAX {
            self.stamp.fill(0);
            self.walk = 0;
        }
        self.walk += 1;
    }
    /// Visit `v`: true when it had not been visited since the last clear.
    pub fn insert(&mut self, v: u32) -> bool {
        let s = &mut self.stamp[v as usize];
        let fresh = *s != self.walk;
        *s = self.walk;
        fresh
    }
}

#[cfg(test)]
mod visit_tests {
    use super::VisitMarks;

    #[test]
    fn marks_forget_their_visits_on_clear() {
        let mut m = VisitMarks::new(4);
        assert!(m.insert(2));
        assert!(!m.insert(2));
        assert!(m.insert(3));
        m.clear();
        assert!(m.insert(2) && m.insert(3));
        // Past the last walk number the stamps start over.
        m.walk = u32::MAX;
        assert!(m.insert(1));
        m.clear();
        assert_eq!(m.walk, 1);
        assert!(m.insert(1) && !m.insert(1));
    }
}

/// Items grouped by a key below `buckets` (a counting sort, stable): the
/// items of key k are `items[start[k]..start[k + 1]]`, in the order given.
/// `keyed` is walked twice (to count, then to place).
pub fn bucketed<T: Copy + Default>(
    buckets: usize,
    keyed: impl Iterator<Item = (usize, T)> + Clone,
) -> (Vec<usize>, Vec<T>) {
    let mut start = vec![0usize; buckets + 1];
    for (k, _) in keyed.clone() {
        start[k + 1] += 1;
    }
    for k in 0..buckets {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut items = vec![T::default(); start[buckets]];
    for (k, item) in keyed {
        items[fill[k]] = item;
        fill[k] += 1;
    }
    (start, items)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bucketed_groups_by_key_in_order() {
        let (start, items) = bucketed(4, [(2, 'a'), (0, 'b'), (2, 'c'), (3, 'd')].into_iter());
        assert_eq!(start, [0, 1, 1, 3, 4]);
        assert_eq!(items, ['b', 'a', 'c', 'd']);
    }
}
