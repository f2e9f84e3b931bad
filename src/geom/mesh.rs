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
