//! Eigenvalues and eigenvectors of symmetric 3 × 3 matrices (covariances of
//! point sets, for best-fit planes) by cyclic Jacobi rotations.

/// When the Jacobi sweeps stop and which rotations they skip. Sweeps stop
/// after 50, or once the off-diagonal entries' magnitudes sum to less than
/// 1e-300 or to at most `relative` × the diagonal's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sweeps {
    /// The off-diagonal sum, relative to the diagonal's, at which the
    /// sweeps stop (0: only at the absolute floor).
    pub relative: f64,
    /// Off-diagonal entries smaller in magnitude than this are left alone
    /// (0: only exact zeros).
    pub negligible: f64,
}

/// The eigenvalues of the symmetric matrix `a` (rows) and its eigenvectors
/// (the columns of the second matrix, orthonormal to rounding), in no
/// particular order: the diagonal left by Jacobi rotations A ← Jᵀ A J in
/// the planes (0, 1), (0, 2), (1, 2) in turn, and the product of the
/// rotations.
#[allow(clippy::needless_range_loop)] // rotations read as index algebra
pub fn symmetric_eigen3(mut a: [[f64; 3]; 3], sweeps: Sweeps) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let scale = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off < 1e-300 || off <= sweeps.relative * scale {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 || a[p][q].abs() < sweeps.negligible {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for row in a.iter_mut() {
                let (akp, akq) = (row[p], row[q]);
                row[p] = c * akp - s * akq;
                row[q] = s * akp + c * akq;
            }
            let (rp, rq) = (a[p], a[q]);
            a[p] = std::array::from_fn(|k| c * rp[k] - s * rq[k]);
            a[q] = std::array::from_fn(|k| s * rp[k] + c * rq[k]);
            for row in v.iter_mut() {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    ([a[0][0], a[1][1], a[2][2]], v)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TO_THE_END: Sweeps = Sweeps {
        relative: 0.0,
        negligible: 0.0,
    };

    #[test]
    fn a_diagonal_matrix_is_its_own_decomposition() {
        let (values, vectors) = symmetric_eigen3(
            [[3.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 2.0]],
            TO_THE_END,
        );
        assert_eq!(values, [3.0, 1.0, 2.0]);
        assert_eq!(vectors, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    }

    #[test]
    fn one_rotation_splits_a_two_by_two_block() {
        // [[2, 1], [1, 2]] has eigenvalues 1 along (1, −1)/√2 and 3 along
        // (1, 1)/√2: one rotation by 45° (θ = 0, t = 1, c = s = 1/√2).
        let (values, v) = symmetric_eigen3(
            [[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 5.0]],
            TO_THE_END,
        );
        let h = 0.5f64.sqrt();
        for (got, want) in values.iter().zip([1.0, 3.0, 5.0]) {
            assert!((got - want).abs() < 1e-15, "{values:?}");
        }
        let column = |k: usize| [v[0][k], v[1][k], v[2][k]];
        for (got, want) in [column(0), column(1), column(2)].iter().zip([
            [h, -h, 0.0],
            [h, h, 0.0],
            [0.0, 0.0, 1.0],
        ]) {
            for i in 0..3 {
                assert!((got[i] - want[i]).abs() < 1e-15, "{v:?}");
            }
        }
    }

    #[test]
    fn the_stops_and_skips() {
        let a = [[4.0, 1e-20, 0.0], [1e-20, 1.0, 0.0], [0.0, 0.0, 2.0]];
        // 1e-20 is below 1e-17 of the diagonal (7): no rotation.
        let relative = Sweeps {
            relative: 1e-17,
            negligible: 0.0,
        };
        assert_eq!(symmetric_eigen3(a, relative).0, [4.0, 1.0, 2.0]);
        let skip = Sweeps {
            relative: 0.0,
            negligible: 1e-10,
        };
        assert_eq!(symmetric_eigen3(a, skip).1[0], [1.0, 0.0, 0.0]);
        // To the end, it is rotated away: the first eigenvector is (1, x, 0)
        // with ε + x = 4x to first order (ε = 1e-20, eigenvalue ≈ 4), x = ε/3.
        let (_, v) = symmetric_eigen3(a, TO_THE_END);
        assert!((v[1][0] - 1e-20 / 3.0).abs() < 1e-35, "{v:?}");
    }
}
