//! Equilibrium of the frame on every shipped network: each sample's frame,
//! built with the first shipped profile that builds the sample (the README's
//! refused combinations skipped; else the first that makes its parts) and
//! loaded by the pavilion's loads file,
//! is solved linearly under every combination, and the supports' reactions
//! balance the applied loads to 1e-6 of their sum of magnitudes. (The
//! loads' totals themselves, areas times loads and the kit's weight, are
//! held by tests/it/loads.rs.)

use crate::support::{root, shipped_networks};
use glam::DVec3;
use lamella::analysis::lines::NetworkLines;
use lamella::analysis::{analyze, AnalysisOptions};
use lamella::fabricate::fabricate;
use lamella::formats::read::{loads_file, profile_file, read_network, ReadOptions};
use lamella::structure::analyse::load_sum;
use lamella::structure::build::{build_frame, BuiltFrame, FrameOptions};
use lamella::structure::loads::{combinations, combine, load_cases, supports};
use lamella::structure::model::{Combination, LoadSet};
use lamella::structure::solve::LinearFrame;
use rayon::prelude::*;

/// A sample's frame under the pavilion's loads: the model, its
/// characteristic load cases and its combinations; `None` when the profile cannot make the sample's parts
/// (slots that overlap, no room for a splice).
pub fn loaded_frame(
    sample: &str,
    profile: &str,
) -> Option<(BuiltFrame, Vec<std::sync::Arc<LoadSet>>, Vec<Combination>)> {
    loaded_frame_with(sample, profile, &FrameOptions::default())
}

/// [`loaded_frame`] with `options` (elements per span).
pub fn loaded_frame_with(
    sample: &str,
    profile: &str,
    options: &FrameOptions,
) -> Option<(BuiltFrame, Vec<std::sync::Arc<LoadSet>>, Vec<Combination>)> {
    let net = read_network(&root().join(sample), ReadOptions::default()).expect("network");
    let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
    let p = profile_file::load(&root().join(profile)).expect("profile");
    let kit = fabricate(&net, &an, &p, None, NetworkLines::default()).ok()?;
    let spec = loads_file::load(&root().join("samples/loads/pavilion.yaml")).expect("loads");
    let mut built = build_frame(&net, &an, &p, &kit, options).expect("frame");
    built.model.supports = supports(&spec, &built.model, &built.targets).expect("supports");
    let cases = load_cases(&spec, &built.model, &built.targets).expect("cases");
    let combos = combinations(&spec)
        .iter()
        .map(|c| combine(&cases, c))
        .collect();
    Some((built, cases, combos))
}

#[test]
fn every_shipped_network_is_in_equilibrium_under_every_combination() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let refused = crate::readme::refused(&readme);
    let names = shipped_networks();
    assert!(names.len() >= 10, "{names:?}");
    let checked: Vec<(String, usize, f64)> = names
        .par_iter()
        .map(|name| {
            // The profiles that build it first, then any that makes its
            // parts (a sample every profile refuses as overstressed is
            // still a frame).
            let profiles = [
                "steel-1.5",
                "poplar-ply-4",
                "beech-veneer",
                "steel-1.5-mixed",
            ];
            let (profile, (built, _, combos)) = profiles
                .iter()
                .filter(|p| !refused.iter().any(|r| r.0 == *name && r.1 == **p))
                .chain(profiles.iter())
                .find_map(|p| {
                    loaded_frame(
                        &format!("samples/{name}.yaml"),
                        &format!("profiles/{p}.yaml"),
                    )
                    .map(|f| (*p, f))
                })
                .unwrap_or_else(|| panic!("{name}: no profile makes its parts"));
            let model = &built.model;
            let linear =
                LinearFrame::new(model).unwrap_or_else(|e| panic!("{name} with {profile}: {e}"));
            let mut worst: f64 = 0.0;
            for c in &combos {
                let res = linear.solve(&c.loads).expect("solve");
                let loads = load_sum(model, &c.loads);
                let reactions: DVec3 = res.reactions.iter().map(|x| x.force_n).sum();
                // The loads' sizes, each times its factor in the
                // combination (its cases are its parts).
                let mut scale = loads.length();
                c.loads
                    .for_each_node_load(|l, factor| scale += (l.force_n * factor).length());
                c.loads.for_each_beam_load(|l, factor| {
                    let b = &model.beams[l.beam];
                    scale += (l.force_n_per_mm * factor).length()
                        * model.nodes_mm[b.nodes[0]].distance(model.nodes_mm[b.nodes[1]]);
                });
                assert!(scale > 0.0, "{name}/{}: no load", c.loads.name);
                let rel = (loads + reactions).length() / scale;
                worst = worst.max(rel);
                assert!(
                    rel <= 1e-6,
                    "{name} with {profile}, {}: loads {loads} reactions {reactions}",
                    c.loads.name
                );
            }
            (format!("{name} ({profile})"), combos.len(), worst)
        })
        .collect();
    for (name, n, worst) in &checked {
        eprintln!("{name}: {n} combinations, largest imbalance {worst:.1e} of the loads");
    }
    assert_eq!(checked.len(), names.len());
}
