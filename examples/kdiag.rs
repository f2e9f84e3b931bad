use glam::DVec3;
use lamella::curve::SmoothCurve;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let h: f64 = args[1].parse().unwrap(); let prec: f64 = args[2].parse().unwrap();
    let (v, c) = (1500.0f64, 1000.0f64); let r = (v*v + c*c).sqrt();
    let n = (2700.0 / h) as usize;
    let pts: Vec<DVec3> = (0..=n).map(|i| { let a = i as f64 * h / r; DVec3::new(v*a.cos(), v*a.sin(), c*a) }).map(|p| if prec>0.0 {(p/prec).round()*prec} else {p}).collect();
    let sc = SmoothCurve::with_precision(&pts, prec);
    let kappa = v / (v*v + c*c);
    println!("smoothing {}", sc.smoothing_mm());
    let mut s = 0.0; let mut worst: f64 = 0.0; let mut worst_mid: f64=0.0;
    while s < sc.length_mm() { let (k,u)=sc.locate_station(s); let j=sc.jet_at(k,u);
        let kk = j.d1.cross(j.d2).length()/j.d1.length().powi(3);
        let e=(kk-kappa).abs()/kappa; if u < 0.01 || u > 0.99 { worst=worst.max(e);} else {worst_mid=worst_mid.max(e);}
        if s < 100.0 || (s > 1000.0 && s < 1060.0) { println!("{s:7.1} u {u:.2} k {kk:.6e} err {e:.2e} noise {:.2e}", sc.curvature_noise_per_mm(k)); }
        s += h/4.0; }
    println!("worst at samples {worst:.2e}, mid {worst_mid:.2e}");
}
