//! Form finding: the soap film spanned by closed boundary
//! polylines, as a triangle mesh with a planar chart.
//!
//! Method:
//! 1. **Boundaries.** Each loop is checked (finite, ≥ 3 distinct points, a
//!    repeated closing point dropped) and resampled: every straight segment
//!    is split into equal pieces, so the given vertices (corners) are kept
//!    exactly and every boundary point lies on the polyline (a soap film's
//!    boundary is the polyline itself). The coarsest mesh is made at
//!    spacing h₀ = target × 2^k with the largest k ≤
//!    [`FormFindOptions::max_refinements`] for which no given segment is
//!    shorter than [`COARSE_SHORTEST`] × h₀ and each loop keeps at least
//!    [`MIN_COARSE_LOOP_POINTS`] points (finely sampled curves, such as
//!    circles with chords of about the target, get k = 0: one level).
//! 2. **Initial mesh and chart.** If the loops projected onto their
//!    best-fit plane (PCA of all boundary points, normal = least variance)
//!    are simple, disjoint and nested as one outer loop around holes, the
//!    planar domain is triangulated by a constrained Delaunay triangulation
//!    (spade) refined to triangles of at most h₀²/2 and angles of at least
//!    [`initial::CDT_MIN_ANGLE_DEG`] (input angles excepted); the chart is
//!    the projection. Otherwise, with exactly two loops that project onto
//!    each other (two coaxial rings: every vertex of each within half the
//!    longest chord of the other's plan; two loops whose plans cross
//!    otherwise are a one-line error naming a crossing point), or with two
//!    loops bounding a steep annulus
//!    (their heights over the plane differ by more than their equivalent
//!    radii in it: the projection would squeeze the tube into a thin ring
//!    of slivers), a tube is lofted between them: both
//!    resampled to one count, the second aligned to the first (the cyclic
//!    shift and direction of least total distance), rows every ≈ h₀
//!    between them, quads split along alternating diagonals; the chart is an annulus
//!    (loop 0 on the inner circle, angle = 2π × arc-length fraction, radii
//!    so that the mid circle is as long as the loops on average). Otherwise
//!    a one-line error names the loops that cross, are not nested, or the
//!    loop that intersects itself in projection. The interior starts at
//!    the harmonic extension of the boundary with the chart's cotangent
//!    weights.
//!
//!    **A film steep over its plan.** Form finding keeps the chart's
//!    vertex distribution (below), so where the film rises steeply over
//!    its plan the plan's triangles stretch into slivers (over Enneper's
//!    boundary at r = 0.8, the normal 77° from the plan's at the rim:
//!    6.8°). A one-loop film whose smallest angle ends below
//!    [`STEEP_MIN_ANGLE_DEG`] is made again over a disk chart
//!    ([`initial::disk`]: the loop on a circle as long as itself, each
//!    point at 2π × its arc-length fraction, the disk triangulated and
//!    refined like the plan), and the result with the larger smallest
//!    angle is kept. On a minimal disk the harmonic extension over that
//!    chart is the conformal one wherever the film's conformal factor is
//!    constant along its boundary (Enneper over a circle of its parameter
//!    plane exactly: 28.1° smallest angle there, and two iterations from
//!    the harmonic start to the area tolerance), and a fair
//!    approximation elsewhere. The price is a second form finding, on
//!    steep one-loop films only (the loft plays this part for two loops).
//! 3. **Pinkall–Polthier iteration** (Pinkall & Polthier 1993, *Computing
//!    discrete minimal surfaces and their conjugates*): build the
//!    cotangent Laplacian of the current mesh M_i, solve the Dirichlet
//!    problem L(M_i) x = 0 for the interior positions with the boundary
//!    fixed (faer's sparse Cholesky; the matrix's pattern, the slots each
//!    triangle's weights are summed into, the symbolic factorisation and
//!    the factor's room are made once per level, [`solve::Dirichlet`]),
//!    until the relative area change of one iteration is below
//!    [`FormFindOptions::area_tolerance`]. The cotangents are exact, obtuse
//!    angles included: the matrix is the stiffness matrix of
//!    piecewise-linear maps, positive definite with the boundary fixed on
//!    any mesh without degenerate triangles, so the factorisation exists;
//!    a degenerate triangle (sine below [`solve::DEGENERATE_SINE`]), a
//!    failed factorisation or an angle below [`COLLAPSE_ANGLE_DEG`] (a film
//!    pinching off) ends form finding with a one-line error. The step also
//!    slides vertices along the surface, towards the vertex distribution of
//!    least discrete area, which squeezes triangles; by default
//!    ([`Tangential::Frozen`]) that part is dropped: each vertex moves along
//!    its area-weighted normal only, so the distribution stays the chart's
//!    and triangle shapes hold from level to level ([`Tangential`] has the
//!    alternatives). Each level ends on one full step, so the mesh is the
//!    iteration's own map of the one before.
//! 4. **Refinement.** After a level converges, every triangle is split 1 → 4
//!    (midpoints in 3D and in the chart; boundary midpoints lie on the
//!    straight boundary segments since the corners are coarse vertices)
//!    and the iteration runs again, while the mean edge length exceeds
//!    √2 × the target (the level nearest the target in log scale), at most
//!    [`FormFindOptions::max_refinements`] times.
//! 5. **Residual.** |H| at interior vertices from the cotangent mean
//!    curvature normal 2H·n = (1/A_i) Σ_j ½(cot α_ij + cot β_ij)(x_i − x_j),
//!    A_i the mixed Voronoi area (Meyer, Desbrun, Schröder & Barr 2003);
//!    its maximum and its A_i-weighted mean. At a converged level it is the
//!    discretisation's residual, not a convergence measure alone: it is
//!    largest where the film's curvature is singular (around a convex
//!    corner of the boundary as seen from the film, e.g. a raised hole's).
//!
//! Results are deterministic: the same input gives the same bits (spade's
//! refinement and faer's sequential Cholesky have no randomness).
//!
//! Orientation: triangles are counter-clockwise in the chart and the same
//! vertex order is used in 3D. For a planar domain the normals point to
//! the side from which the outer loop, in its given order, runs
//! counter-clockwise (right-hand rule); for a loft they point along
//! (direction from loop 0 to loop 1) × (loop 0's running direction), e.g.
//! towards the axis for two coaxial rings both running counter-clockwise
//! seen from above with loop 0 the lower.

pub mod boundary;
pub mod initial;
pub mod refine;
pub mod solve;

use crate::error::{Error, Location, Result};
use crate::geom::mesh::TriMesh;
use glam::{DVec2, DVec3};
use std::path::Path;

/// No given segment is shorter than this fraction of the coarsest spacing
/// h₀: a shorter one would make the coarse mesh anisotropic there and end
/// up with edges well below the target.
pub const COARSE_SHORTEST: f64 = 0.75;

/// Each loop keeps at least this many points on the coarsest mesh.
pub const MIN_COARSE_LOOP_POINTS: usize = 8;

/// A level whose smallest triangle angle falls below this has collapsed
/// (a film pinching off, as a catenoid between rings too far apart):
/// form finding stops with an error, degrees.
pub const COLLAPSE_ANGLE_DEG: f64 = 1.0;

/// Options of form finding.
#[derive(Debug, Clone, PartialEq)]
pub struct FormFindOptions {
    /// Target edge length of the final mesh, mm (default 100).
    pub target_edge_mm: f64,
    /// Most 1 → 4 refinements after the coarsest mesh (default 6).
    pub max_refinements: usize,
    /// Most Pinkall–Polthier iterations per level (default 500).
    pub max_iterations: usize,
    /// A level has converged when one iteration changes the area by less
    /// than this, relative (default 1e-10: on the catenoid the vertices
    /// then sit within 1e-3 mm of where much tighter tolerances put them).
    pub area_tolerance: f64,
    /// What happens to the tangential part of each Pinkall–Polthier step
    /// (default [`Tangential::Frozen`]).
    pub tangential: Tangential,
}

/// The tangential part of a Pinkall–Polthier step: the iteration slides
/// vertices along the surface (towards the discrete minimum of area over
/// the vertex distribution), which can squeeze triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tangential {
    /// Dropped: every vertex moves along its area-weighted normal only, so
    /// the vertex distribution stays that of the chart (harmonic on the
    /// coarsest mesh, midpoints after each split) and triangle shapes do not
    /// degrade from level to level.
    Frozen,
    /// Kept, then every interior vertex moves within its tangent plane to the
    /// area-weighted centroid of its one-ring (better triangles where the
    /// film is steep over its chart, e.g. around a raised hole; on other
    /// films this local smoothing squeezes triangles a little more at each
    /// level). The relaxation and the step's own slide pull against each
    /// other, so the area changes stall near 1e-8 relative: use an
    /// [`FormFindOptions::area_tolerance`] of 1e-7 or looser with it.
    Relaxed,
    /// Kept: plain Pinkall–Polthier (slow to meet the area tolerance on
    /// coarse meshes).
    Free,
}

impl Default for FormFindOptions {
    fn default() -> Self {
        FormFindOptions {
            target_edge_mm: 100.0,
            max_refinements: 6,
            max_iterations: 500,
            area_tolerance: 1e-10,
            tangential: Tangential::Frozen,
        }
    }
}

impl FormFindOptions {
    /// The defaults with another target edge length.
    pub fn with_target_edge_mm(target_edge_mm: f64) -> Self {
        FormFindOptions {
            target_edge_mm,
            ..Self::default()
        }
    }
}

/// How the initial mesh was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InitialMesh {
    /// A constrained Delaunay triangulation of the planar domain; the chart
    /// is the projection onto the best-fit plane.
    PlanarDomain,
    /// A tube lofted between two loops; the chart is an annulus.
    Loft,
}

/// What form finding did and how good the result is.
#[derive(Debug, Clone, PartialEq)]
pub struct FormFindReport {
    /// How the initial mesh was made.
    pub initial: InitialMesh,
    /// Pinkall–Polthier iterations, all levels.
    pub iterations: usize,
    /// Iterations per level, coarsest first.
    pub iterations_per_level: Vec<usize>,
    /// Whether every level met the area tolerance.
    pub converged: bool,
    /// Area of the initial (harmonic) coarse mesh, mm².
    pub initial_area_mm2: f64,
    /// Area of the result, mm².
    pub area_mm2: f64,
    /// Largest |H| at an interior vertex, 1/mm.
    pub max_mean_curvature_per_mm: f64,
    /// Area-weighted mean |H| over the interior vertices, 1/mm.
    pub mean_mean_curvature_per_mm: f64,
    /// 1 → 4 refinements made.
    pub refinements: usize,
    /// Vertices of the result.
    pub vertices: usize,
    /// Triangles of the result.
    pub triangles: usize,
    /// Mean edge length of the result, mm.
    pub mean_edge_mm: f64,
    /// Smallest triangle angle of the result, degrees.
    pub min_angle_deg: f64,
}

/// The film: mesh, chart and report.
#[derive(Debug, Clone, PartialEq)]
pub struct FormFound {
    /// The mesh, triangles counter-clockwise (see the module doc for the side).
    pub mesh: TriMesh,
    /// A planar chart: one uv per vertex, mm-like scale, every triangle
    /// counter-clockwise with positive area.
    pub chart_uv: Vec<DVec2>,
    /// What form finding did.
    pub report: FormFindReport,
}

/// A mesh being form-found: positions, chart, triangles, fixed (boundary)
/// vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    /// Positions, mm.
    pub positions: Vec<DVec3>,
    /// Chart, one uv per vertex.
    pub chart: Vec<DVec2>,
    /// Triangles, counter-clockwise in the chart.
    pub triangles: Vec<[u32; 3]>,
    /// Boundary vertices (kept in place).
    pub fixed: Vec<bool>,
}

/// Form-find the soap film spanning `boundaries_mm` (closed polylines, last
/// point not repeated; a repeated closing point is dropped). `path` is the
/// spec file named in errors.
pub fn form_find(
    boundaries_mm: &[Vec<DVec3>],
    opts: &FormFindOptions,
    path: &Path,
) -> Result<FormFound> {
    check_options(opts, path)?;
    let loops = boundary::clean_loops(boundaries_mm, path)?;
    let frame = boundary::best_fit_frame(&loops);
    let domain = match boundary::planar_domain(&loops, frame) {
        Ok(d) if loops.len() == 2 && boundary::steep_annulus(&loops, &d) => None,
        Ok(d) => Some(d),
        // Two loops whose plans cross (not two rings projecting onto each
        // other): a tube lofted between them would pass through itself.
        Err(boundary::DomainProblem::Crossing(..))
            if loops.len() == 2
                && !boundary::project_onto_each_other(&loops[0], &loops[1], frame) =>
        {
            let (a, b, p) = boundary::plan_crossing(&loops, frame).unwrap_or((0, 1, loops[0][0]));
            return Err(Error::input(
                path,
                Location::Field(format!("boundaries[{a}]")),
                format!(
                    "loops {a} and {b} cross in projection onto the boundaries' best-fit plane at ({:.1}, {:.1}, {:.1}) mm (on loop {a}): two loops must nest (a hole) or project onto each other (coaxial rings)",
                    p.x, p.y, p.z
                ),
            ));
        }
        Err(_) if loops.len() == 2 => None,
        Err(p) => {
            return Err(Error::input(
                path,
                Location::Field(format!("boundaries[{}]", p.first_loop())),
                p.message(),
            ))
        }
    };
    let lengths: Vec<Vec<f64>> = loops.iter().map(|l| boundary::segment_lengths(l)).collect();
    check_work(
        &estimate(&loops, &lengths, domain.as_ref(), opts.target_edge_mm),
        opts.target_edge_mm,
        path,
    )?;
    let levels = coarse_levels(&lengths, opts);
    let h0_mm = opts.target_edge_mm * f64::from(1u32 << levels);
    let mut pieces: Vec<Vec<usize>> = lengths.iter().map(|l| boundary::pieces(l, h0_mm)).collect();
    let (film, initial) = match &domain {
        Some(d) => {
            let film = initial::planar(&loops, &pieces, d, 0.5 * h0_mm * h0_mm).ok_or_else(|| {
                Error::input(
                    path,
                    Location::Field("boundaries".into()),
                    "the constrained Delaunay triangulation of the projected loops failed (points too close in projection)",
                )
            })?;
            (film, InitialMesh::PlanarDomain)
        }
        None => {
            let count = pieces
                .iter()
                .map(|p| p.iter().sum::<usize>())
                .max()
                .unwrap_or(0);
            for (l, p) in pieces.iter_mut().enumerate() {
                boundary::add_pieces(&lengths[l], p, count);
            }
            (initial::loft(&loops, &pieces, h0_mm), InitialMesh::Loft)
        }
    };
    let mut run = relax(film, opts, path)?;
    // A film steep over its plan (one loop): the plan's triangles squeeze
    // into slivers there; made again over a disk chart by arc length, the
    // one with the larger smallest angle is kept.
    if let (Some(d), [single]) = (&domain, loops.as_slice()) {
        let squeezed = solve::min_angle_deg(&run.film, &run.film.positions);
        if squeezed < STEEP_MIN_ANGLE_DEG {
            if let Some(film) =
                initial::disk(single, &pieces[0], d.reversed[0], 0.5 * h0_mm * h0_mm)
            {
                // A disk that fails (where the plan's film did not) is dropped.
                if let Ok(disk) = relax(film, opts, path) {
                    if solve::min_angle_deg(&disk.film, &disk.film.positions) > squeezed {
                        run = disk;
                    }
                }
            }
        }
    }
    let Relaxed {
        film,
        initial_area_mm2,
        iterations_per_level,
        converged,
        refinements,
    } = run;
    let h = solve::mean_curvature(&film, &film.positions).ok_or_else(|| {
        failure(
            path,
            solve::SolveFailure::NotPositiveDefinite,
            refinements,
            0,
        )
    })?;
    let (max_h, mut sum_h, mut sum_a) = (h.iter().map(|p| p.0).fold(0.0, f64::max), 0.0, 0.0);
    for &(hv, a) in &h {
        sum_h += hv * a;
        sum_a += a;
    }
    let report = FormFindReport {
        initial,
        iterations: iterations_per_level.iter().sum(),
        iterations_per_level,
        converged,
        initial_area_mm2,
        area_mm2: solve::area_mm2(&film, &film.positions),
        max_mean_curvature_per_mm: max_h,
        mean_mean_curvature_per_mm: if sum_a > 0.0 { sum_h / sum_a } else { 0.0 },
        refinements,
        vertices: film.positions.len(),
        triangles: film.triangles.len(),
        mean_edge_mm: solve::mean_edge_mm(&film, &film.positions),
        min_angle_deg: solve::min_angle_deg(&film, &film.positions),
    };
    // Invariant: 1 → 4 splits keep every chart triangle positive.
    if let Some(t) = chart_inverted(&film) {
        return Err(Error::input(
            path,
            Location::Field("boundaries".into()),
            format!("form finding produced an inverted chart triangle {t} (an internal error)"),
        ));
    }
    Ok(FormFound {
        mesh: TriMesh {
            positions_mm: film.positions,
            triangles: film.triangles,
        },
        chart_uv: film.chart,
        report,
    })
}

/// A film relaxed to a discrete minimal surface: the mesh, the area of
/// its harmonic start, iterations per level, whether every level met the
/// area tolerance, refinements made.
struct Relaxed {
    film: Film,
    initial_area_mm2: f64,
    iterations_per_level: Vec<usize>,
    converged: bool,
    refinements: usize,
}

/// Below this smallest triangle angle (degrees; half the angle the
/// triangulation of the plan aims for) a one-loop film is made again over
/// a disk chart ([`initial::disk`]).
pub const STEEP_MIN_ANGLE_DEG: f64 = 14.0;

/// Harmonic start, then Pinkall–Polthier level by level with 1 → 4 splits
/// down to the target edge.
fn relax(mut film: Film, opts: &FormFindOptions, path: &Path) -> Result<Relaxed> {
    if let Some(t) = chart_inverted(&film) {
        return Err(Error::input(
            path,
            Location::Field("boundaries".into()),
            format!("the initial chart has an inverted triangle {t}: the loops are too close to each other for the target edge length"),
        ));
    }
    // Harmonic extension with the chart's weights.
    let chart3: Vec<DVec3> = film.chart.iter().map(|q| q.extend(0.0)).collect();
    let mut dirichlet = solve::Dirichlet::new(&film);
    film.positions = dirichlet
        .solve(&film, &chart3, &film.positions)
        .map_err(|e| failure(path, e, 0, 0))?;
    let initial_area_mm2 = solve::area_mm2(&film, &film.positions);
    let mut iterations_per_level = Vec::new();
    let mut converged = true;
    let mut refinements = 0;
    loop {
        let (its, ok) = iterate(&mut film, &mut dirichlet, opts)
            .map_err(|(e, it)| failure(path, e, refinements, it))?;
        iterations_per_level.push(its);
        converged &= ok;
        if refinements >= opts.max_refinements
            || solve::mean_edge_mm(&film, &film.positions)
                <= std::f64::consts::SQRT_2 * opts.target_edge_mm
        {
            break;
        }
        film = refine::split(&film);
        dirichlet = solve::Dirichlet::new(&film);
        refinements += 1;
    }
    Ok(Relaxed {
        film,
        initial_area_mm2,
        iterations_per_level,
        converged,
        refinements,
    })
}

fn check_options(opts: &FormFindOptions, path: &Path) -> Result<()> {
    if !(opts.target_edge_mm.is_finite() && opts.target_edge_mm > 0.0) {
        return Err(Error::input(
            path,
            Location::Field("target_edge_mm".into()),
            format!(
                "must be a positive length in mm, got {}",
                opts.target_edge_mm
            ),
        ));
    }
    if !(opts.area_tolerance.is_finite() && opts.area_tolerance > 0.0) {
        return Err(Error::input(
            path,
            Location::Field("area_tolerance".into()),
            format!("must be a positive number, got {}", opts.area_tolerance),
        ));
    }
    if opts.max_iterations == 0 {
        return Err(Error::input(
            path,
            Location::Field("max_iterations".into()),
            "must be at least 1",
        ));
    }
    if opts.max_refinements > 12 {
        return Err(Error::input(
            path,
            Location::Field("max_refinements".into()),
            format!(
                "at most 12 (each multiplies the triangles by 4), got {}",
                opts.max_refinements
            ),
        ));
    }
    Ok(())
}

/// Most points a film's boundary loops may have at the target edge length
/// (every segment split as [`boundary::pieces`] splits it there).
pub const MAX_BOUNDARY_POINTS: usize = 100_000;

/// Most triangles a film may be estimated to have at the target edge
/// length (about half a minute of form finding on two cores).
pub const MAX_TRIANGLES: usize = 500_000;

/// The size of a film, estimated from its loops before any mesh is made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmEstimate {
    /// Points on the boundary loops at the target edge length.
    pub boundary_points: f64,
    /// Length of all boundary loops, mm.
    pub boundary_mm: f64,
    /// The film's area, mm²: the planar domain's area in projection, or
    /// for a loft the loops' mean length times the distance between their
    /// centroids (at least the target edge).
    pub area_mm2: f64,
    /// Triangles at the target edge length: the area over an equilateral
    /// triangle's, target² × √3/4.
    pub triangles: f64,
}

/// Estimate a film's size at `target_edge_mm` from its cleaned loops, their
/// segment lengths and the planar domain (none: a loft between two loops).
pub fn estimate(
    loops: &[Vec<DVec3>],
    lengths: &[Vec<f64>],
    domain: Option<&boundary::PlanarDomain>,
    target_edge_mm: f64,
) -> FilmEstimate {
    let boundary_points = lengths
        .iter()
        .flatten()
        .map(|&l| {
            (l / (boundary::PIECE_SLACK * target_edge_mm))
                .ceil()
                .max(1.0)
        })
        .sum::<f64>();
    let boundary_mm = lengths.iter().flatten().sum::<f64>();
    let area_mm2 = match domain {
        Some(d) => {
            let area =
                |l: &[DVec3]| crate::geom::plane::signed_area_mm2(&d.frame.project_all(l)).abs();
            (0..loops.len())
                .map(|i| {
                    if i == d.outer {
                        area(&loops[i])
                    } else {
                        -area(&loops[i])
                    }
                })
                .sum::<f64>()
                .max(0.0)
        }
        None => {
            let centroid = |l: &[DVec3]| l.iter().copied().sum::<DVec3>() / l.len() as f64;
            let mean_length = boundary_mm / loops.len().max(1) as f64;
            let apart = match loops {
                [a, b] => centroid(a).distance(centroid(b)),
                _ => 0.0,
            };
            mean_length * apart.max(target_edge_mm)
        }
    };
    let triangles = area_mm2 / (target_edge_mm * target_edge_mm * 3f64.sqrt() / 4.0);
    FilmEstimate {
        boundary_points,
        boundary_mm,
        area_mm2,
        triangles,
    }
}

/// Refuse a film whose estimate exceeds [`MAX_BOUNDARY_POINTS`] or
/// [`MAX_TRIANGLES`], naming `film_edge_mm` (the spec's name of the target).
fn check_work(e: &FilmEstimate, target_edge_mm: f64, path: &Path) -> Result<()> {
    let at = || Location::Field("film_edge_mm".into());
    let hint =
        "raise film_edge_mm (by default a sixth of spacing_mm) or make the boundaries smaller";
    if e.boundary_points > MAX_BOUNDARY_POINTS as f64 {
        return Err(Error::input(
            path,
            at(),
            format!(
                "{target_edge_mm:.2} mm on boundaries {:.0} mm long means ~{:.1e} boundary points; the limit is {MAX_BOUNDARY_POINTS}: {hint}",
                e.boundary_mm, e.boundary_points
            ),
        ));
    }
    if e.triangles > MAX_TRIANGLES as f64 {
        return Err(Error::input(
            path,
            at(),
            format!(
                "{target_edge_mm:.2} mm on these boundaries (a film of about {:.3} m²) means ~{:.1e} triangles; the limit is {MAX_TRIANGLES}: {hint}",
                e.area_mm2 * 1e-6,
                e.triangles
            ),
        ));
    }
    Ok(())
}

/// The number of levels k below the target: the largest k ≤ the
/// refinement limit with every segment at least [`COARSE_SHORTEST`] × h₀
/// long and every loop at
/// least [`MIN_COARSE_LOOP_POINTS`] points at spacing h₀.
fn coarse_levels(lengths: &[Vec<f64>], opts: &FormFindOptions) -> usize {
    let shortest = lengths
        .iter()
        .flatten()
        .copied()
        .fold(f64::INFINITY, f64::min);
    (1..=opts.max_refinements)
        .rev()
        .find(|&k| {
            let h0 = opts.target_edge_mm * f64::from(1u32 << k);
            shortest >= COARSE_SHORTEST * h0
                && lengths.iter().all(|l| {
                    boundary::pieces(l, h0).iter().sum::<usize>() >= MIN_COARSE_LOOP_POINTS
                })
        })
        .unwrap_or(0)
}

/// The first triangle whose chart area is not positive.
pub fn chart_inverted(film: &Film) -> Option<usize> {
    film.triangles.iter().position(|t| {
        let [a, b, c] = t.map(|v| film.chart[v as usize]);
        let doubled_area = (b - a).perp_dot(c - a);
        doubled_area.is_nan() || doubled_area <= 0.0
    })
}

/// Pinkall–Polthier iterations on one level, their tangential part
/// handled as `opts.tangential` says, until one iteration changes the area
/// by less than the tolerance, relative; then (unless the mode is
/// [`Tangential::Free`]) one full Pinkall–Polthier step, so the level ends
/// on the iteration's own map: (iterations, converged).
fn iterate(
    film: &mut Film,
    dirichlet: &mut solve::Dirichlet,
    opts: &FormFindOptions,
) -> Result<(usize, bool), (solve::SolveFailure, usize)> {
    let mut area = solve::area_mm2(film, &film.positions);
    let mut converged = false;
    let mut iterations = 0;
    while iterations < opts.max_iterations {
        iterations += 1;
        let next = dirichlet
            .solve(film, &film.positions, &film.positions)
            .map_err(|e| (e, iterations))?;
        film.positions = match opts.tangential {
            Tangential::Frozen => solve::normal_only(film, &film.positions, &next),
            Tangential::Relaxed => solve::relax(film, &next),
            Tangential::Free => next,
        };
        let min_angle = solve::min_angle_deg(film, &film.positions);
        if min_angle < COLLAPSE_ANGLE_DEG {
            return Err((solve::SolveFailure::Collapsed(min_angle), iterations));
        }
        let a = solve::area_mm2(film, &film.positions);
        let change = (area - a).abs() / area.max(f64::MIN_POSITIVE);
        area = a;
        if change < opts.area_tolerance {
            converged = true;
            break;
        }
    }
    if opts.tangential != Tangential::Free {
        iterations += 1;
        film.positions = dirichlet
            .solve(film, &film.positions, &film.positions)
            .map_err(|e| (e, iterations))?;
    }
    Ok((iterations, converged))
}

fn failure(path: &Path, e: solve::SolveFailure, level: usize, iteration: usize) -> Error {
    let what = match e {
        solve::SolveFailure::Degenerate(t) => format!(
            "form finding failed at refinement {level}, iteration {iteration}: triangle {t} degenerated (the film collapses, e.g. two rings too far apart for a stable catenoid)"
        ),
        solve::SolveFailure::Collapsed(angle) => format!(
            "form finding failed at refinement {level}, iteration {iteration}: the film degenerates (a triangle angle of {angle:.2e}°), so no stable soap film spans these loops (e.g. two rings too far apart for a catenoid)"
        ),
        solve::SolveFailure::NotPositiveDefinite => format!(
            "form finding failed at refinement {level}, iteration {iteration}: the cotangent Laplacian could not be factorised (degenerate triangles)"
        ),
    };
    Error::input(path, Location::Field("boundaries".into()), what)
}

#[cfg(test)]
mod tests;
