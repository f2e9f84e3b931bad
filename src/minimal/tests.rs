use super::*;
use std::f64::consts::TAU;

fn ring(radius: f64, z: f64, n: usize) -> Vec<DVec3> {
    (0..n)
        .map(|i| {
            let t = TAU * i as f64 / n as f64;
            DVec3::new(radius * t.cos(), radius * t.sin(), z)
        })
        .collect()
}

#[test]
fn explore() {
    let p = Path::new("spec.yaml");
    for &(t, n) in &[(100.0, 64usize), (50.0, 128), (25.0, 256)] {
        let f = form_find(
            &[ring(1000.0, -400.0, n), ring(1000.0, 400.0, n)],
            &FormFindOptions::with_target_edge_mm(t),
            p,
        )
        .expect("ff");
        let a = 910.7379942737879_f64;
        let rad: Vec<f64> = f
            .mesh
            .positions_mm
            .iter()
            .map(|p| {
                let r = (p.x * p.x + p.y * p.y).sqrt();
                (r - a * (p.z / a).cosh()).abs()
            })
            .collect();
        eprintln!(
            "catenoid t={t} maxrad {:.4} meanrad {:.4} {:?}",
            rad.iter().fold(0.0f64, |a, &b| a.max(b)),
            rad.iter().sum::<f64>() / rad.len() as f64,
            f.report
        );
    }
    let quad = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1000.0, 0.0, 300.0),
        DVec3::new(1000.0, 1000.0, 0.0),
        DVec3::new(0.0, 1000.0, 300.0),
    ];
    let f = form_find(&[quad], &FormFindOptions::with_target_edge_mm(25.0), p).expect("ff");
    eprintln!("quad {:?}", f.report);
    let six: Vec<DVec3> = (0..6)
        .map(|i| {
            let t = TAU * i as f64 / 6.0;
            DVec3::new(
                3000.0 * t.cos(),
                3000.0 * t.sin(),
                if i % 2 == 0 { 1500.0 } else { 0.0 },
            )
        })
        .collect();
    let f = form_find(&[six], &FormFindOptions::with_target_edge_mm(50.0), p).expect("ff");
    eprintln!("six {:?}", f.report);
    let sq = |h: f64, z: f64| {
        vec![
            DVec3::new(-h, -h, z),
            DVec3::new(h, -h, z),
            DVec3::new(h, h, z),
            DVec3::new(-h, h, z),
        ]
    };
    let f = form_find(
        &[sq(1000.0, 0.0), sq(300.0, 400.0)],
        &FormFindOptions::with_target_edge_mm(25.0),
        p,
    )
    .expect("ff");
    eprintln!("hole {:?}", f.report);
}
