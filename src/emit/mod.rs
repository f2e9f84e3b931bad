//! Emit: the files a workshop cuts and buys from (issue 10). Plain data in
//! (a plan with parts and sheets, the kit, the nest), files out:
//!
//! * [`drawing`]: every placed part in sheet coordinates, by operation;
//! * [`dxf_out`], [`svg_out`]: one cutting file per sheet in each format;
//! * [`takeoff`]: parts, stock, hardware and totals as CSV and JSON;
//! * [`assembly`]: the assembly sheets, `assembly.pdf`;
//! * [`outdir`]: staging beside the output directory, moved into place
//!   only once complete;
//! * [`build`]: `lamella build`, every stage from the network to the files.

pub mod assembly;
pub mod build;
pub mod drawing;
pub mod dxf_out;
pub mod outdir;
pub mod svg_out;
pub mod takeoff;

/// Append `x` with at most `decimals` decimals (at most 9), trailing zeros
/// dropped, `-0` written as `0`; with `keep_point`, at least one decimal
/// (`3.0`, as DXF writers do). Integer arithmetic on the scaled, rounded
/// value: several times faster than `format!("{x:.N}")`, whose exact
/// formatting dominated writing big kits. Coordinates are bounded by the
/// network's ±10 km, far inside i64 at 9 decimals.
pub(crate) fn push_decimal(out: &mut String, x: f64, decimals: u32, keep_point: bool) {
    let decimals = decimals.min(9);
    let scale = 10u64.pow(decimals);
    let scaled = (x.abs() * scale as f64).round() as u64;
    let (int, mut frac) = (scaled / scale, scaled % scale);
    if x < 0.0 && scaled != 0 {
        out.push('-');
    }
    push_digits(out, int, 1);
    if frac == 0 {
        if keep_point {
            out.push_str(".0");
        }
        return;
    }
    let mut width = decimals as usize;
    while frac % 10 == 0 {
        frac /= 10;
        width -= 1;
    }
    out.push('.');
    push_digits(out, frac, width);
}

/// Append `n` in decimal, zero-padded to at least `width` digits.
fn push_digits(out: &mut String, mut n: u64, width: usize) {
    let mut buf = [b'0'; 20];
    let mut i = buf.len();
    while n > 0 || buf.len() - i < width {
        i -= 1;
        buf[i] = b'0' + (n % 10) as u8;
        n /= 10;
    }
    // ASCII digits only.
    out.push_str(std::str::from_utf8(&buf[i..]).unwrap_or("0"));
}

#[cfg(test)]
mod tests {
    use super::push_decimal;

    fn d(x: f64, n: u32, keep: bool) -> String {
        let mut s = String::new();
        push_decimal(&mut s, x, n, keep);
        s
    }

    /// Against the standard library's exact formatting, trimmed.
    #[test]
    fn decimals_match_std_formatting() {
        for &x in &[
            0.0,
            1.0,
            -1.0,
            0.1,
            12.345678,
            -0.00001,
            2999.99994,
            1234.0001,
            -17.25,
            1e7 + 0.123456,
        ] {
            for n in [4u32, 6] {
                let std = format!("{x:.prec$}", prec = n as usize);
                let std = if std.contains('.') {
                    std.trim_end_matches('0').trim_end_matches('.').to_string()
                } else {
                    std
                };
                let std = if std == "-0" { "0".to_string() } else { std };
                assert_eq!(d(x, n, false), std, "{x} at {n}");
            }
        }
        assert_eq!(d(3.0, 6, true), "3.0");
        assert_eq!(d(0.05, 1, false), "0.1");
    }
}
