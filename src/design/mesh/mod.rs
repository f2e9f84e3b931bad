//! Triangle meshes: the data every mesh stage shares.
//!
//! A [`TriMesh`] holds positions in mm and counter-clockwise triangles (seen
//! from the side the normals point to). Mesh files are read into it
//! (`read`: OBJ, PLY, STL), validated into an oriented, connected manifold
//! with one-rings and boundary loops (`topology`: everything downstream uses
//! its cleaned [`Topology::mesh`]), curvature tensors are estimated per
//! vertex by fitting cubic jets (`curvature`), and the asymptotic net's
//! extent and singular points (flat points, umbilics) are found from them
//! (`singular`). Form finding (`crate::design::minimal`) produces a mesh with a
//! planar chart, and tracing on meshes walks it through a chart (`surface`).
//!
//! ```text
//! let mesh = read_mesh(path)?;
//! let topo = Topology::build(&mesh, path)?;
//! let jets = vertex_jets(topo.mesh(), &topo);
//! let report = anticlastic_report(&topo, &jets);
//! require_anticlastic(&report, path)?;
//! ```

pub mod curvature;
#[cfg(test)]
pub(crate) mod samples;
pub mod singular;
pub mod topology;

pub use curvature::{vertex_curvatures, vertex_jets, VertexJet};
pub use singular::{
    anticlastic_report, require_anticlastic, singularities, AnticlasticReport, SingularKind,
    Singularity,
};
pub use topology::Topology;

pub use crate::geom::mesh::TriMesh;

pub mod chart;
pub mod surface;
