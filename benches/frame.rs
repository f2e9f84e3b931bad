//! Benchmark of the structure stage on generated Enneper networks of n × n
//! curves with the prototype's cell size (n = 100: 10,000 nodes; 400:
//! 160,000) and the steel prototype's profile (doubled lamellas, so every
//! strip is two chains of beams tied at its blocks and joints), under the
//! pavilion's loads file (samples/loads/pavilion.yaml: 11 ULS and 8 SLS
//! combinations), supports at every boundary joint.
//!
//! Per size, in a fresh child process (its peak memory its own): the
//! model's size (nodes, degrees of freedom, beams, links) and the wall
//! time of each phase:
//! * `model`: the frame built from the analysis and the kit, supported
//!   and loaded (`build_frame`, `supports`, `load_cases`, combinations);
//! * `factor`: K assembled and factorised (sparse Cholesky), once;
//! * `static`: every combination solved on that factor, with its section
//!   forces and reactions;
//! * `α_cr`: the first 6 critical factors and modes of the governing ULS
//!   combination (shift-invert Lanczos), and `2nd order`: that
//!   combination on the imperfect geometry, to convergence (n ≤ 200 only:
//!   `LAMELLA_BENCH_STATIC=1` skips them);
//! * peak MiB: the process's peak resident memory, reading, analysis and
//!   kit included.
//!
//! The network's reading, analysis and kit come before and are timed apart
//! (`before s`).
//!
//! The sizes with a published limit ([`LIMITS`]) fail the benchmark when
//! the frame's time (`frame s`) or the peak memory passes it.
//!
//! ```text
//! cargo bench --profile dev --bench frame            # n = 100, 200 (all), 400 (static)
//! cargo bench --profile dev --bench frame -- 20 40   # these sizes
//! ```

mod support;
use lamella_synth as synth;

use lamella::formats::read::{self as io, loads_file};
use lamella::pipeline::{Inputs, Session};
use lamella::structure::analyse::imperfection_of;
use lamella::structure::buckling::critical_factors_given;
use lamella::structure::build::{build_frame, FrameOptions};
use lamella::structure::loads::{combinations, combine, deflection_span_mm, load_cases, supports};
use lamella::structure::model::{CableState, Combination, LimitState};
use lamella::structure::second_order::second_order_of;
use lamella::structure::solve::LinearFrame;
use lamella::structure::stage::{IMPERFECTION_SPAN_OVER, MODES, SECOND_ORDER_TOLERANCE};
use std::path::Path;
use std::time::Instant;

/// (n, most seconds for `frame s`, most MiB at the peak): the 100 × 100
/// grid's static, α_cr (6 modes) and second order in 10 s and 2 GiB; the
/// 400 × 400 grid's statics in 60 s and 8 GiB.
const LIMITS: [(usize, f64, f64); 2] = [(100, 10.0, 2048.0), (400, 60.0, 8192.0)];

fn main() {
    if let Some(path) = support::child_network() {
        measure(&path);
        return;
    }
    println!(
        "{:>5} {:>8} {:>9} {:>9} {:>8} {:>9} {:>8} {:>8} {:>8} {:>8} {:>9} {:>8} {:>9}",
        "n",
        "nodes",
        "model n.",
        "dofs",
        "before s",
        "model s",
        "factor s",
        "static s",
        "α_cr s",
        "2nd s",
        "frame s",
        "α_cr",
        "peak MiB"
    );
    for n in support::sizes() {
        let path = support::generated(&format!("enneper-parts-{n}.json"), || {
            io::network_file::to_json(&synth::enneper_prototype_grid(n), 3)
        });
        support::run_child(&path);
    }
}

fn measure(path: &Path) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let t0 = Instant::now();
    // The kit as every command makes it (the check's lamella lines carried
    // onto the parts).
    let mut session = Session::open(Inputs {
        network: path.to_path_buf(),
        profile: Some(root.join("profiles/steel-1.5.yaml")),
        ..Default::default()
    })
    .expect("open");
    session.kit().expect("kit");
    let spec = loads_file::load(&root.join("samples/loads/pavilion.yaml")).expect("loads");
    let (Some(an), Some(kit), Ok(profile)) =
        (session.analysed(), session.made(), session.profile())
    else {
        panic!("the session ran no kit");
    };
    let net = session.network();
    let before_s = t0.elapsed().as_secs_f64();
    let nodes = an.topology.nodes.len();
    let n = (nodes as f64).sqrt().round() as usize;

    let t = Instant::now();
    let mut built = build_frame(net, an, profile, kit, &FrameOptions::default()).expect("model");
    built.model.supports = supports(&spec, &built.model, &built.targets).expect("supports");
    let cases = load_cases(&spec, &built.model, &built.targets).expect("cases");
    let combos: Vec<Combination> = combinations(&spec)
        .iter()
        .map(|c| combine(&cases, c))
        .collect();
    let model_s = t.elapsed().as_secs_f64();
    let model = &built.model;

    let t = Instant::now();
    let linear = match LinearFrame::new(model) {
        Ok(l) => l,
        Err(e) => {
            // Name the place: the model node, its position, what ties it.
            if let lamella::structure::solve::FrameError::Mechanism { node, .. } = &e {
                let beams = model
                    .beams
                    .iter()
                    .filter(|b| b.nodes.contains(node))
                    .count();
                let links = model
                    .links
                    .iter()
                    .filter(|l| l.nodes.contains(node))
                    .count();
                let id = built
                    .targets
                    .node_ids
                    .iter()
                    .min_by(|a, b| {
                        let p = model.nodes_mm[*node];
                        model.nodes_mm[*a.1]
                            .distance(p)
                            .total_cmp(&model.nodes_mm[*b.1].distance(p))
                    })
                    .map(|(id, m)| {
                        (
                            id.clone(),
                            model.nodes_mm[*m].distance(model.nodes_mm[*node]),
                        )
                    });
                eprintln!(
                    "model node {node} at {:?}: {beams} beams, {links} links; nearest network node {id:?}",
                    model.nodes_mm[*node]
                );
            }
            panic!("n = {n}: {e}");
        }
    };
    let factor_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mut governing = 0;
    let mut largest = 0.0;
    let sets: Vec<&lamella::structure::model::LoadSet> = combos.iter().map(|c| &c.loads).collect();
    // As the stage: the combinations solved eight at a time as their
    // results are asked for in turn, each one's section forces and
    // reactions made then (the governing ULS combination's kept for α_cr).
    let static_only = std::env::var("LAMELLA_BENCH_STATIC").is_ok() || n > 200;
    let statics = linear.solve_each(&sets).expect("static");
    let mut kept = None;
    for (i, c) in combos.iter().enumerate() {
        let r = statics.result(i).expect("static");
        let moved = r
            .displacements
            .iter()
            .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
            .fold(0.0, f64::max);
        if c.limit_state == LimitState::Ultimate && moved > largest {
            (governing, largest) = (i, moved);
            // Kept for α_cr only where it runs (a result at 400 × 400
            // curves, with its section forces, is 0.45 GB).
            kept = (!static_only).then_some(r);
        }
    }
    let static_s = t.elapsed().as_secs_f64();

    let (mut alpha_s, mut second_s, mut alpha) = (f64::NAN, f64::NAN, f64::NAN);
    if !static_only {
        let loads = &combos[governing].loads;
        let t = Instant::now();
        // On the combination's static result, as the stage does.
        let modes =
            critical_factors_given(&linear, loads, kept.as_ref().expect("a ULS result"), MODES)
                .expect("α_cr");
        alpha_s = t.elapsed().as_secs_f64();
        alpha = modes.first().map_or(f64::NAN, |m| m.factor);
        if let Some(first) = modes.first() {
            let span = deflection_span_mm(model, &model.supports);
            let t = Instant::now();
            let imperfection = imperfection_of(first, span / IMPERFECTION_SPAN_OVER);
            // Not converging is a result too (the grid fails); its time counts.
            let _ = second_order_of(
                &linear,
                loads,
                &imperfection,
                SECOND_ORDER_TOLERANCE,
                CableState::TensionOnly,
            );
            second_s = t.elapsed().as_secs_f64();
        }
    }
    let frame_s = model_s
        + factor_s
        + static_s
        + if alpha_s.is_nan() { 0.0 } else { alpha_s }
        + if second_s.is_nan() { 0.0 } else { second_s };
    let show = |x: f64| {
        if x.is_nan() {
            "-".to_string()
        } else {
            format!("{x:.2}")
        }
    };
    println!(
        "{:>5} {:>8} {:>9} {:>9} {:>8.1} {:>9.2} {:>8.2} {:>8.2} {:>8} {:>8} {:>9.2} {:>8} {:>9.0}",
        n,
        nodes,
        model.nodes_mm.len(),
        6 * model.nodes_mm.len(),
        before_s,
        model_s,
        factor_s,
        static_s,
        show(alpha_s),
        show(second_s),
        frame_s,
        show(alpha),
        support::peak_mib()
    );
    println!(
        "      {} beams, {} links, {} supports, {} combinations; load average {}",
        model.beams.len(),
        model.links.len(),
        model.supports.len(),
        combos.len(),
        support::load_average()
    );
    if let Some(&(_, seconds, mib)) = LIMITS.iter().find(|l| l.0 == n) {
        let peak = support::peak_mib();
        if frame_s > seconds || peak > mib {
            eprintln!(
                "n = {n}: the frame took {frame_s:.2} s at a peak of {peak:.0} MiB, past the limit of {seconds} s and {mib} MiB"
            );
            std::process::exit(1);
        }
    }
}
