//! Standard bolts, nuts and washers: the tables a bolt's length, its nut,
//! its washers and its tightening torque are read from. Every bolt is a
//! fully threaded hexagon head screw, ISO 4017 (thread to the head, so a
//! nut finds thread whatever the grip), with a hexagon nut ISO 4032 and,
//! where the joint has them, plain washers ISO 7089.
//!
//! **Length.** The shortest nominal length `l` of the series that is at
//! least grip + the washers under head and nut + the nut's height `m` +
//! two thread pitches past the nut (structural bolting asks for at least
//! one full thread beyond the nut, e.g. EN 1090-2; the second covers the
//! chamfered end). The series are the nominal lengths of ISO 4017 (ISO 4014
//! uses the same values above its shortest length), mm:
//!
//! 2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 25, 30, 35, 40, 45, 50, 55, 60, 65, 70,
//! 80, 90, 100, 110, 120, 130, 140, 150, 160, 180, 200
//!
//! each thread only within its range of commercial lengths (ISO 4017
//! Table 1, as stocked): M1.6 2–16, M2 4–20, M2.5 5–25, M3 6–30, M4 8–40,
//! M5 10–50, M6 12–60, M8 16–80, M10 20–100, M12 25–120, M16 30–150,
//! M20 40–160, M24 50–180. A joint that needs more is an error naming it.
//!
//! **Threads** (ISO 261 coarse pitch `P`), **nuts** (ISO 4032 height
//! `m` max) and **washers** (ISO 7089 normal series: hole `d1`, outside
//! `d2`, thickness `h`), mm:
//!
//! | thread | P | m | d1 | d2 | h |
//! |---|---|---|---|---|---|
//! | M1.6 | 0.35 | 1.3 | 1.7 | 4 | 0.3 |
//! | M2 | 0.4 | 1.6 | 2.2 | 5 | 0.3 |
//! | M2.5 | 0.45 | 2 | 2.7 | 6 | 0.5 |
//! | M3 | 0.5 | 2.4 | 3.2 | 7 | 0.5 |
//! | M4 | 0.7 | 3.2 | 4.3 | 9 | 0.8 |
//! | M5 | 0.8 | 4.7 | 5.3 | 10 | 1 |
//! | M6 | 1 | 5.2 | 6.4 | 12 | 1.6 |
//! | M8 | 1.25 | 6.8 | 8.4 | 16 | 1.6 |
//! | M10 | 1.5 | 8.4 | 10.5 | 20 | 2 |
//! | M12 | 1.75 | 10.8 | 13 | 24 | 2.5 |
//! | M16 | 2 | 14.8 | 17 | 30 | 3 |
//! | M20 | 2.5 | 18 | 21 | 37 | 3 |
//! | M24 | 3 | 21.5 | 25 | 44 | 4 |
//!
//! **Tightening torque** `M_A`, N·m, for the profile's property class
//! (`hardware.bolt_class`): VDI 2230 Part 1 (2015) Table A1, friction
//! µ_G = µ_K = 0.14 (lightly oiled), 90 % of the yield strength used by the
//! assembly stress; none below M4 (the table starts there):
//!
//! | class | M4 | M5 | M6 | M8 | M10 | M12 | M16 | M20 | M24 |
//! |---|---|---|---|---|---|---|---|---|---|
//! | 8.8 | 3.0 | 5.9 | 10 | 25 | 49 | 85 | 210 | 425 | 730 |
//! | 10.9 | 4.4 | 8.7 | 15 | 36 | 72 | 125 | 310 | 610 | 1050 |
//!
//! Nuts follow the bolt's class (8.8: nut class 8, 10.9: 10, ISO 898-2),
//! washers its hardness (8.8: 200 HV, 10.9: 300 HV).

/// One metric coarse thread and the nut and washer that go with it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thread {
    /// Nominal diameter d, mm.
    pub diameter_mm: f64,
    /// Pitch P, mm (ISO 261).
    pub pitch_mm: f64,
    /// Nut height m (max), mm (ISO 4032).
    pub nut_mm: f64,
    /// Washer hole d1, mm (ISO 7089).
    pub washer_hole_mm: f64,
    /// Washer outside diameter d2, mm (ISO 7089).
    pub washer_outside_mm: f64,
    /// Washer thickness h, mm (ISO 7089).
    pub washer_mm: f64,
    /// Shortest and longest commercial length, mm (ISO 4017).
    pub lengths_mm: (f64, f64),
    /// Tightening torque for 8.8 and 10.9, N·m (VDI 2230, µ = 0.14).
    pub torque_nm: Option<(f64, f64)>,
}

/// Shorthand for a table row.
const fn t(
    d: f64,
    p: f64,
    m: f64,
    w: (f64, f64, f64),
    l: (f64, f64),
    torque_nm: Option<(f64, f64)>,
) -> Thread {
    Thread {
        diameter_mm: d,
        pitch_mm: p,
        nut_mm: m,
        washer_hole_mm: w.0,
        washer_outside_mm: w.1,
        washer_mm: w.2,
        lengths_mm: l,
        torque_nm,
    }
}

/// The threads, ascending (see the module doc for the sources).
pub const THREADS: [Thread; 13] = [
    t(1.6, 0.35, 1.3, (1.7, 4.0, 0.3), (2.0, 16.0), None),
    t(2.0, 0.4, 1.6, (2.2, 5.0, 0.3), (4.0, 20.0), None),
    t(2.5, 0.45, 2.0, (2.7, 6.0, 0.5), (5.0, 25.0), None),
    t(3.0, 0.5, 2.4, (3.2, 7.0, 0.5), (6.0, 30.0), None),
    t(
        4.0,
        0.7,
        3.2,
        (4.3, 9.0, 0.8),
        (8.0, 40.0),
        Some((3.0, 4.4)),
    ),
    t(
        5.0,
        0.8,
        4.7,
        (5.3, 10.0, 1.0),
        (10.0, 50.0),
        Some((5.9, 8.7)),
    ),
    t(
        6.0,
        1.0,
        5.2,
        (6.4, 12.0, 1.6),
        (12.0, 60.0),
        Some((10.0, 15.0)),
    ),
    t(
        8.0,
        1.25,
        6.8,
        (8.4, 16.0, 1.6),
        (16.0, 80.0),
        Some((25.0, 36.0)),
    ),
    t(
        10.0,
        1.5,
        8.4,
        (10.5, 20.0, 2.0),
        (20.0, 100.0),
        Some((49.0, 72.0)),
    ),
    t(
        12.0,
        1.75,
        10.8,
        (13.0, 24.0, 2.5),
        (25.0, 120.0),
        Some((85.0, 125.0)),
    ),
    t(
        16.0,
        2.0,
        14.8,
        (17.0, 30.0, 3.0),
        (30.0, 150.0),
        Some((210.0, 310.0)),
    ),
    t(
        20.0,
        2.5,
        18.0,
        (21.0, 37.0, 3.0),
        (40.0, 160.0),
        Some((425.0, 610.0)),
    ),
    t(
        24.0,
        3.0,
        21.5,
        (25.0, 44.0, 4.0),
        (50.0, 180.0),
        Some((730.0, 1050.0)),
    ),
];

/// The nominal lengths of ISO 4017 / ISO 4014, mm, ascending.
pub const LENGTHS_MM: [f64; 31] = [
    2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 16.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0, 50.0, 55.0,
    60.0, 65.0, 70.0, 80.0, 90.0, 100.0, 110.0, 120.0, 130.0, 140.0, 150.0, 160.0, 180.0, 200.0,
];

/// Lengths closer than this count as equal, mm (a sum of table values).
const LENGTH_TOLERANCE_MM: f64 = 1e-9;

/// The thread of diameter `d_mm`, if the table holds it.
pub fn thread(d_mm: f64) -> Option<&'static Thread> {
    thread_index(d_mm).map(|k| &THREADS[k])
}

/// The index in [`THREADS`] of the thread of diameter `d_mm`, if any.
pub fn thread_index(d_mm: f64) -> Option<usize> {
    THREADS
        .iter()
        .position(|t| (t.diameter_mm - d_mm).abs() < LENGTH_TOLERANCE_MM)
}

/// The table's threads as text (`M1.6, M2, …`), for messages.
pub fn thread_names() -> String {
    THREADS
        .iter()
        .map(|t| name(t.diameter_mm))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A thread's name: `M8`, `M1.6`.
pub fn name(d_mm: f64) -> String {
    format!("M{}", trim(d_mm))
}

/// The shortest nominal length of `thread` at least `needed_mm` long,
/// or `None` when its longest commercial length is shorter.
pub fn bolt_length_mm(thread: &Thread, needed_mm: f64) -> Option<f64> {
    let (lo, hi) = thread.lengths_mm;
    LENGTHS_MM
        .iter()
        .copied()
        .filter(|&l| l >= lo && l <= hi)
        .find(|&l| l + LENGTH_TOLERANCE_MM >= needed_mm)
}

/// The tightening torque of `thread` in property class `class`, N·m
/// (none for a thread below M4 or a class without a table).
pub fn torque_nm(thread: &Thread, class: &str) -> Option<f64> {
    let (c88, c109) = thread.torque_nm?;
    match class {
        "8.8" => Some(c88),
        "10.9" => Some(c109),
        _ => None,
    }
}

/// The nut class that goes with a bolt class (ISO 898-2).
pub fn nut_class(class: &str) -> Option<&'static str> {
    match class {
        "8.8" => Some("8"),
        "10.9" => Some("10"),
        _ => None,
    }
}

/// The washer hardness that goes with a bolt class (ISO 7089).
pub fn washer_grade(class: &str) -> Option<&'static str> {
    match class {
        "8.8" => Some("200 HV"),
        "10.9" => Some("300 HV"),
        _ => None,
    }
}

/// A length without trailing zeros: 8, 1.6.
pub fn trim(x: f64) -> String {
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Needs just below, at and just above a series value: the series
    /// value itself, then the next one (written out by hand).
    #[test]
    fn lengths_come_from_the_series() {
        let m8 = thread(8.0).expect("M8");
        assert_eq!(bolt_length_mm(m8, 64.9), Some(65.0));
        assert_eq!(bolt_length_mm(m8, 65.0), Some(65.0));
        assert_eq!(bolt_length_mm(m8, 65.01), Some(70.0));
        assert_eq!(bolt_length_mm(m8, 70.01), Some(80.0));
        // The shortest M8 is 16 mm; nothing past 80 mm.
        assert_eq!(bolt_length_mm(m8, 3.0), Some(16.0));
        assert_eq!(bolt_length_mm(m8, 80.0), Some(80.0));
        assert_eq!(bolt_length_mm(m8, 80.01), None);
        let m5 = thread(5.0).expect("M5");
        assert_eq!(bolt_length_mm(m5, 21.3), Some(25.0));
        assert_eq!(bolt_length_mm(m5, 24.99), Some(25.0));
        assert_eq!(bolt_length_mm(m5, 25.01), Some(30.0));
        assert_eq!(bolt_length_mm(m5, 50.5), None);
        let m6 = thread(6.0).expect("M6");
        assert_eq!(bolt_length_mm(m6, 13.4), Some(16.0));
        assert_eq!(bolt_length_mm(m6, 12.0), Some(12.0));
        let m1_6 = thread(1.6).expect("M1.6");
        assert_eq!(bolt_length_mm(m1_6, 3.8), Some(4.0));
    }

    #[test]
    fn threads_nuts_and_torques() {
        assert!(thread(1.5).is_none());
        assert!(thread(7.0).is_none());
        let m8 = thread(8.0).expect("M8");
        assert_eq!((m8.pitch_mm, m8.nut_mm, m8.washer_mm), (1.25, 6.8, 1.6));
        assert_eq!(torque_nm(m8, "8.8"), Some(25.0));
        assert_eq!(torque_nm(m8, "10.9"), Some(36.0));
        assert_eq!(torque_nm(thread(3.0).expect("M3"), "8.8"), None);
        assert_eq!(name(1.6), "M1.6");
        // Ascending, and every range inside the series.
        for w in THREADS.windows(2) {
            assert!(w[0].diameter_mm < w[1].diameter_mm);
        }
        for t in &THREADS {
            assert!(LENGTHS_MM.contains(&t.lengths_mm.0));
            assert!(LENGTHS_MM.contains(&t.lengths_mm.1));
        }
    }
}
