//! Every size a user can write has a bound checked before the work it
//! sizes: an input beyond it gets a one-line error naming the file and the
//! field (with an estimate of the work where one is made) and exit status
//! 1, never a panic, an abort on an allocation or a run without end. The
//! bounds are listed in README.md (Limits).

use crate::support::{lamella, root, scratch};
use std::path::Path;

/// Run `lamella ARGS…`; expect exit 1 and one line of stderr holding every
/// fragment.
#[track_caller]
fn refused(args: &[&str], fragments: &[&str]) {
    let (code, _, stderr) = lamella(args);
    assert_eq!(code, Some(1), "{args:?}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    for f in fragments {
        assert!(stderr.contains(f), "`{f}` not in {stderr}");
    }
}

/// `lamella trace` of a spec with `text`, written to `dir/name.trace.yaml`.
#[track_caller]
fn trace_refused(dir: &Path, name: &str, text: &str, fragments: &[&str]) {
    let spec = dir.join(format!("{name}.trace.yaml"));
    std::fs::write(&spec, text).unwrap();
    let out = dir.join(format!("{name}.yaml"));
    refused(
        &[
            "trace",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        fragments,
    );
    assert!(!out.exists(), "{name}: a network was written");
}

/// The saddle of samples/film-saddle.trace.yaml (4 m × 4 m in plan), its
/// coordinates times `scale`, with a film edge of `edge_mm`.
fn saddle(scale: f64, edge_mm: f64) -> String {
    let corners = [
        [-2000.0, -2000.0, 800.0],
        [2000.0, -2000.0, -800.0],
        [2000.0, 2000.0, 800.0],
        [-2000.0, 2000.0, -800.0],
    ];
    let mut s = String::from("surface: minimal\nboundaries_mm:\n  -\n");
    for c in corners {
        let [x, y, z] = c.map(|v: f64| v * scale);
        s.push_str(&format!("    - [{x:e}, {y:e}, {z:e}]\n"));
    }
    s.push_str(&format!("film_edge_mm: {edge_mm}\nspacing_mm: 300\n"));
    s
}

#[test]
fn film_coordinates_beyond_ten_km_are_refused() {
    let dir = scratch("film-coordinates");
    // 1e150: once a panic (capacity overflow), 1e10: an abort on a 1 TB
    // allocation, 1e6: over a minute.
    for (name, scale) in [("e150", 1e150), ("e10", 1e10), ("e6", 1e6)] {
        trace_refused(
            &dir,
            name,
            &saddle(scale, 50.0),
            &[
                "field `boundaries[0]`",
                "point 0",
                "limited to 1e7 mm (10 km)",
            ],
        );
    }
}

#[test]
fn a_fine_film_edge_is_refused_with_its_triangle_estimate() {
    let dir = scratch("film-edge");
    for (name, edge, estimate) in [
        ("half", 0.5, "~1.5e8 triangles"),
        ("two", 2.0, "~9.2e6 triangles"),
    ] {
        trace_refused(
            &dir,
            name,
            &saddle(1.0, edge),
            &[
                &format!("{name}.trace.yaml: field `film_edge_mm`: {edge:.2} mm"),
                "a film of about 16.000 m²",
                estimate,
                "the limit is 500000",
            ],
        );
    }
}

#[test]
fn a_film_with_a_fine_spacing_and_fill_is_refused_before_form_finding() {
    // film_edge_mm defaults to a sixth of spacing_mm: 1.67 mm on the rings.
    let dir = scratch("film-spacing");
    let sample = std::fs::read_to_string(root().join("samples/film-rings.trace.yaml")).unwrap();
    let text: String = sample
        .lines()
        .filter(|l| !l.starts_with("film_edge_mm") && !l.starts_with("max_curves_per_side"))
        .map(|l| {
            if l.starts_with("spacing_mm") {
                "spacing_mm: 10".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert!(text.contains("fill: true"));
    trace_refused(
        &dir,
        "rings",
        &text,
        &[
            "field `film_edge_mm`: 1.67 mm",
            "triangles; the limit is 500000",
        ],
    );
}

#[test]
fn a_long_thin_film_boundary_is_refused_by_its_point_count() {
    // 4 km by 1 mm: a small area, but ~3.6e5 boundary points at 20 mm.
    let dir = scratch("film-boundary");
    let text = "surface: minimal\nboundaries_mm:\n  -\n    - [0, 0, 0]\n    - [4000000, 0, 0]\n    - [4000000, 1, 0]\n    - [0, 1, 0]\nfilm_edge_mm: 20\nspacing_mm: 300\n";
    trace_refused(
        &dir,
        "thin",
        text,
        &[
            "field `film_edge_mm`: 20.00 mm on boundaries 8000002 mm long",
            "~3.6e5 boundary points; the limit is 100000",
        ],
    );
}

/// A copy of `profiles/NAME.yaml` with `from` replaced by `to` (once,
/// checked), written into `dir`.
fn profile_with(dir: &Path, name: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(root().join(format!("profiles/{name}.yaml"))).unwrap();
    assert!(text.contains(from), "{from} not in {name}");
    let p = dir.join(format!("{name}.yaml"));
    std::fs::write(&p, text.replacen(from, to, 1)).unwrap();
    p.to_str().unwrap().to_string()
}

/// `lamella COMMAND samples/hypar-small.yaml --profile PROFILE --out DIR/out`.
#[track_caller]
fn profile_refused(command: &str, dir: &Path, profile: &str, fragments: &[&str]) {
    let sample = root().join("samples/hypar-small.yaml");
    let out = dir.join("out");
    refused(
        &[
            command,
            sample.to_str().unwrap(),
            "--profile",
            profile,
            "--out",
            out.to_str().unwrap(),
        ],
        fragments,
    );
    assert!(!out.exists(), "{command}: output written");
}

#[test]
fn four_billion_washers_per_node_are_refused() {
    // Once an abort after 15 s of making washers.
    let dir = scratch("washers");
    let p = profile_with(&dir, "steel-1.5", "per_node: 2 ", "per_node: 4000000000 ");
    profile_refused(
        "build",
        &dir,
        &p,
        &["field `washer.per_node`: must be at most 8, got 4000000000"],
    );
}

#[test]
fn many_splice_bolts_are_refused() {
    let dir = scratch("splice-bolts");
    let p = profile_with(
        &dir,
        "steel-1.5",
        "bolts_per_side: 2",
        "bolts_per_side: 100000",
    );
    profile_refused(
        "parts",
        &dir,
        &p,
        &["field `splice.bolts_per_side`: must be at most 16, got 100000"],
    );
}

#[test]
fn a_nanometre_lamella_is_refused_by_its_shear_block_count() {
    // Once an abort on a 12 GB vector of block stations.
    let dir = scratch("thin-lamella");
    let p = profile_with(
        &dir,
        "steel-1.5",
        "thickness_mm: 1.5\n",
        "thickness_mm: 1e-9\n",
    );
    for command in ["parts", "build"] {
        profile_refused(
            command,
            &dir,
            &p,
            &[
                "steel-1.5.yaml: strip A00: shear blocks at most",
                "lamella.thickness_mm",
                "blocks; the limit is 10000 a strip",
            ],
        );
    }
}

#[test]
fn two_hundred_stock_sizes_are_refused() {
    // Once about 0.9 s of nesting per size.
    let dir = scratch("stock-sizes");
    let mut sizes = String::from("  sizes:\n");
    for i in 0..200 {
        sizes.push_str(&format!(
            "    - length_mm: {}\n      width_mm: 1500.0\n      price_per_unit: 95.0\n",
            2000 + i
        ));
    }
    let p = profile_with(
        &dir,
        "steel-1.5",
        "  length_mm: 3000.0\n  width_mm: 1500.0\n  price_per_unit: 95.0 ",
        &format!("{sizes}  #"),
    );
    profile_refused(
        "nest",
        &dir,
        &p,
        &["field `stock.sizes`: 200 sizes", "the limit is 16"],
    );
}

#[test]
fn a_long_list_of_rotations_is_refused() {
    let dir = scratch("rotations");
    let p = profile_with(
        &dir,
        "steel-1.5",
        "allowed_rotations_deg: [0, 90, 180, 270]",
        "allowed_rotations_deg: [0, 90, 180, 270, 0, 90]",
    );
    profile_refused(
        "parts",
        &dir,
        &p,
        &["field `cutting.allowed_rotations_deg`: lists 6 rotations; at most 4"],
    );
}

#[test]
fn a_dxf_beyond_the_network_size_limit_is_refused_unread() {
    // A sparse file: 257 MiB on paper, no disk space.
    let dir = scratch("dxf-size");
    let p = dir.join("big.dxf");
    std::fs::File::create(&p)
        .unwrap()
        .set_len(257 << 20)
        .unwrap();
    refused(
        &[
            "nodes",
            p.to_str().unwrap(),
            "--out",
            dir.join("out").to_str().unwrap(),
        ],
        &["big.dxf: 269484032 bytes is more than the 256 MiB lamella reads in such a file"],
    );
}

/// `lamella trace` of a mesh spec naming `dir/file`.
#[track_caller]
fn mesh_refused(dir: &Path, file: &str, fragments: &[&str]) {
    let text = format!("surface: mesh\nmesh: {file}\nseed_mm: [0, 0, 0]\nspacing_mm: 300\n");
    trace_refused(dir, "m", &text, fragments);
}

#[test]
fn a_ply_header_counting_billions_is_refused_before_its_body() {
    let dir = scratch("ply-count");
    std::fs::write(
        dir.join("big.ply"),
        "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
    )
    .unwrap();
    mesh_refused(
        &dir,
        "big.ply",
        &[
            "big.ply: 4000000000 `vertex` elements in the header",
            "at most 1000000 triangles",
        ],
    );
}

#[test]
fn a_binary_stl_of_more_than_a_million_triangles_is_refused_before_its_body() {
    // 84 + 50 × 1000001 bytes, sparse: the header's count matches the length.
    let dir = scratch("stl-count");
    let count: u32 = 1_000_001;
    let p = dir.join("big.stl");
    let mut head = vec![0u8; 84];
    head[80..84].copy_from_slice(&count.to_le_bytes());
    std::fs::write(&p, &head).unwrap();
    std::fs::OpenOptions::new()
        .write(true)
        .open(&p)
        .unwrap()
        .set_len(84 + 50 * u64::from(count))
        .unwrap();
    mesh_refused(
        &dir,
        "big.stl",
        &[
            "big.stl: 1000001 triangles in the binary STL header",
            "at most 1000000 triangles",
        ],
    );
}

#[test]
fn a_mesh_design_filled_at_a_fine_spacing_is_refused_in_seconds() {
    // Spacing 10 mm with fill over the 3 m clip of mesh-enneper: the fill
    // rebuilt one point index of every curve so far for each curve it
    // added, and took over five minutes to reach its curve limit.
    let dir = scratch("mesh-fill");
    let sample = std::fs::read_to_string(root().join("samples/mesh-enneper.trace.yaml")).unwrap();
    let mesh = root().join("samples/meshes/enneper-4m.obj");
    let text = sample
        .replace(
            "mesh: meshes/enneper-4m.obj",
            &format!("mesh: {}", mesh.display()),
        )
        .replace(
            "spacing_mm: 270",
            "spacing_mm: 10\nfill: true\nmax_curves_per_side: 1000",
        );
    trace_refused(
        &dir,
        "fine",
        &text,
        &["field `fill`: filling needs more than 2001 curves of family A"],
    );
}
