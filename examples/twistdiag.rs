// scratch diagnostics (not committed)
use glam::{DVec2, DVec3};
use lamella::network::{Network, RawNetwork, Family};
use lamella::synth::{self, Catenoid, Enneper, Helicoid, Sampling};
use lamella::{analyze, AnalysisOptions};
use std::path::Path;
fn round(r: &RawNetwork) -> RawNetwork { let mut r = r.clone(); for c in &mut r.curves { for p in &mut c.points { *p = (*p / 0.001).round() * 0.001; } c.normals=None;} r }
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args[1].as_str(); let step: f64 = args[2].parse().unwrap();
    let (surf, lines, scale): (Box<dyn synth::ParamSurface>, _, f64) = match which {
        "enneper" => (Box::new(Enneper), synth::diagonal_lines(0.5, 13, DVec2::ZERO), 4400.0),
        "enneper18" => (Box::new(Enneper), synth::diagonal_lines(0.5, 13, DVec2::ZERO), 1800.0),
        "catenoid" => (Box::new(Catenoid{c:1000.0}), synth::diagonal_lines(1.0, 11, DVec2::new(0.3,0.1)), 1.0),
        _ => { let us: Vec<f64> = synth::spread(0.75, 9).iter().map(|u| u + 0.75).collect();
            let vs: Vec<f64> = synth::spread(600.0, 9).iter().map(|v| v + 900.0).collect();
            (Box::new(Helicoid{c:1000.0}), synth::coordinate_lines(&us,&vs), 1.0) }
    };
    let exact = synth::network("x", surf.as_ref(), &lines, scale, Sampling{step_mm: step, normals: true});
    let rounded = round(&exact);
    let ne = Network::new(exact, Path::new("e.yaml")).unwrap();
    let nr = Network::new(rounded, Path::new("r.yaml")).unwrap();
    eprintln!("precision {}", nr.precision_mm);
    let ae = analyze(&ne, AnalysisOptions::for_network(&ne)).unwrap();
    let ar = analyze(&nr, AnalysisOptions::for_network(&nr)).unwrap();
    let only = args.get(3).cloned();
    for i in 0..ne.curves.len() {
        let (se, sr) = (&ae.strips[i], &ar.strips[i]);
        if se.family == Family::Edge { continue; }
        if let Some(o) = &only { if &se.id != o { continue; } }
        let (ce, cr) = (&ae.curves[i], &ar.curves[i]);
        let len = se.length_mm; let mut worst=(0.0f64,0.0,0.0,0.0);
        let mut s = 0.0;
        while s <= len { let fe = se.frame_at(ce, s); let fr = sr.frame_at(cr, s);
            let e = (fr.tg_per_mm - fe.tg_per_mm).abs()/se.max_abs_tg_per_mm;
            if only.is_some() { println!("{:8.1} tg {:.6e} {:.6e} err {:.4} kg {:.5e} {:.5e}", s, fe.tg_per_mm, fr.tg_per_mm, e, fe.kg_per_mm, fr.kg_per_mm); }
            if e > worst.0 { worst=(e,s,fe.tg_per_mm,fr.tg_per_mm); }
            s += 5.0; }
        println!("{} {:?} smooth {:.1} len {:.0} maxtg {:.4e} vs {:.4e} ({:+.4}) worst pointwise {:.4} at {:.0} ({:.4e} vs {:.4e})", se.id, sr.normal_source, cr.smoothing_mm(), len, sr.max_abs_tg_per_mm, se.max_abs_tg_per_mm, sr.max_abs_tg_per_mm/se.max_abs_tg_per_mm-1.0, worst.0, worst.1, worst.2, worst.3);
    }
    let _ = DVec3::ZERO;
}
