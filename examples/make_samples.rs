//! Regenerates the closed-form sample networks in samples/:
//! `cargo run --example make_samples`.

use lamella::io::network_file::to_yaml;
use lamella::synth::{self, coordinate_lines, spread, Hypar, Sampling};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples");
    std::fs::create_dir_all(&dir)?;

    let sampling = Sampling {
        step_mm: 25.0,
        normals: true,
    };
    let mut enneper = synth::enneper_4m(sampling);
    enneper.tolerance = Some(0.5);
    let text = to_yaml(
        &enneper,
        4,
        "Enneper asymptotic network of the 4 m steel prototype, sampled from the\n\
         closed-form asymptotic lines u ± v = const (|u ± v| <= 0.5, 4400 mm per unit:
         4.0 m diagonal span, 2.2 m rise).\n\
         Regenerate: cargo run --example make_samples",
    );
    std::fs::write(dir.join("enneper-4m.yaml"), text)?;

    // A small hyperbolic paraboloid z = xy/c: 7 × 7 rulings, 1.2 m square.
    let c = 1500.0;
    let xs = spread(600.0, 7);
    let lines = coordinate_lines(&xs, &xs);
    let mut hypar = synth::network(
        "hypar-small",
        &Hypar { c },
        &lines,
        1.0,
        Sampling {
            step_mm: 50.0,
            normals: false,
        },
    );
    hypar.tolerance = Some(0.5);
    let text = to_yaml(
        &hypar,
        4,
        "Hyperbolic paraboloid z = xy/1500 mm, its rulings as the asymptotic lines\n\
         (anticlastic, not minimal: the families do not cross at 90 degrees).\n\
         Regenerate: cargo run --example make_samples",
    );
    std::fs::write(dir.join("hypar-small.yaml"), text)?;
    Ok(())
}
