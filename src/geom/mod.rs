//! Geometry every stage shares, knowing no stage and no file format:
//! smooth curves through samples ([`curve`]), NURBS evaluation ([`nurbs`]),
//! closest points of segments ([`closest`]), plane predicates on points,
//! segments and polygons ([`plane`]), eigenvectors of symmetric 3 × 3
//! matrices ([`eigen`]), the surface interface ([`surface`]), triangle
//! meshes ([`mesh`]) and the dot product of long vectors ([`dot`]).

pub mod closest;
pub mod curve;
pub mod eigen;
pub mod mesh;
pub mod nurbs;
pub mod plane;
pub mod surface;

/// Σ aᵢ·bᵢ over the shorter of the two, in four interleaved partial sums
/// (vector lanes) added pairwise, then the remainder: the same sum in the
/// same order on every machine.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .map(|(x, y)| x * y)
        .sum();
    let mut s = [0.0f64; 4];
    for (x, y) in a4.zip(b4) {
        for l in 0..4 {
            s[l] += x[l] * y[l];
        }
    }
    (s[0] + s[1]) + (s[2] + s[3]) + tail
}
