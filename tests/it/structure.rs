//! The structure stage on shipped networks: every combination's linear
//! solution in equilibrium (Σ reactions + Σ loads = 0 to 1e-6), a verdict
//! with α_cr, the governing utilisation and the deflection.

use lamella::analysis::lines::NetworkLines;
use lamella::analysis::{analyze, AnalysisOptions};
use lamella::fabricate::fabricate;
use lamella::formats::read::{loads_file, profile_file, read_network, ReadOptions};
use lamella::structure::analyse::load_sum;
use lamella::structure::build::FrameOptions;
use lamella::structure::solve::LinearFrame;
use lamella::structure::stage::{run, FrameReport};
use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn report(sample: &str, profile: &str, loads: &str) -> FrameReport {
    let net = read_network(&root().join(sample), ReadOptions::default()).expect("network");
    let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
    let p = profile_file::load(&root().join(profile)).expect("profile");
    let kit = fabricate(&net, &an, &p, None, NetworkLines::default()).expect("kit");
    let spec = loads_file::load(&root().join(loads)).expect("loads");
    run(&net, &an, &p, &kit, &spec, &FrameOptions::default()).expect("frame")
}

#[test]
fn the_pavilion_on_enneper_balances_every_combination() {
    let r = report(
        "samples/enneper-4m.yaml",
        "profiles/steel-1.5.yaml",
        "samples/loads/pavilion.yaml",
    );
    let model = &r.built.model;
    assert!(!r.results.combinations.is_empty());
    let linear = LinearFrame::new(model).expect("linear");
    for c in &r.combinations {
        let res = linear.solve(&c.loads).expect("solve");
        let loads = load_sum(model, &c.loads);
        let reactions: glam::DVec3 = res.reactions.iter().map(|x| x.force_n).sum();
        let scale = loads.length()
            + c.loads
                .nodes
                .iter()
                .map(|l| l.force_n.length())
                .sum::<f64>();
        assert!(
            (loads + reactions).length() <= 1e-6 * scale,
            "{}: loads {loads} reactions {reactions}",
            c.loads.name
        );
    }
    let (_, alpha) = r.alpha_cr().expect("α_cr");
    let (_, _, utilisation) = r.governing().expect("governing");
    let (_, _, deflection) = r.deflection().expect("deflection");
    eprintln!("α_cr {alpha:.2}, utilisation {utilisation:.3}, deflection {deflection:.2} mm");
    for c in &r.results.combinations {
        eprintln!(
            "{}: α_cr {:?} second order {:?} max {:.2} mm",
            c.name,
            c.alpha_cr(),
            c.second_order_iterations,
            c.max_translation_mm
        );
    }
    assert!(alpha.is_finite() && alpha > 0.0);
}
