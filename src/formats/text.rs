//! The one byte formatter every writer shares: numbers written in place at
//! the end of a byte buffer, at fixed decimals, by integer arithmetic.

/// Append `x` with at most `decimals` decimals (at most 9), trailing zeros
/// dropped, `-0` written as `0`; with `keep_point`, at least one decimal
/// (`3.0`, as DXF writers do). Integer arithmetic on the scaled, rounded
/// value: several times faster than `format!("{x:.N}")`, whose exact
/// formatting dominated writing big kits. Coordinates are bounded by the
/// network's ±10 km, far inside i64 at 9 decimals. The writers build their
/// files as bytes (ASCII): a `String` would validate every number pushed.
#[inline]
pub(crate) fn push_decimal(out: &mut Vec<u8>, x: f64, decimals: u32, keep_point: bool) {
    let decimals = decimals.min(9);
    let scaled = round_half_away(x.abs() * POW10[decimals as usize] as f64);
    push_scaled(out, x < 0.0, scaled, decimals, keep_point);
}

/// [`push_decimal`] into a `String` (for text that is not a big file's).
pub(crate) fn push_decimal_str(out: &mut String, x: f64, decimals: u32, keep_point: bool) {
    let mut t = Vec::with_capacity(32);
    push_decimal(&mut t, x, decimals, keep_point);
    // ASCII digits, point and sign only.
    out.extend(t.iter().map(|&b| char::from(b)));
}

/// Powers of ten up to 10⁹.
const POW10: [u64; 10] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
];

/// Append `scaled` units of 10^−`decimals` (at most 9; negative when
/// `negative`, but never `-0`) as [`push_decimal`] writes numbers.
#[inline]
pub(crate) fn push_scaled(
    out: &mut Vec<u8>,
    negative: bool,
    scaled: u64,
    decimals: u32,
    keep_point: bool,
) {
    push_digits(out, negative, scaled, decimals, keep_point, true);
}

/// [`push_scaled`], and without the zero before the point when
/// `!zero_before_point` (`.5`, `-.25`, as SVG paths allow).
///
/// The length is found first and the digits are written right to left,
/// two at a time, into their place at the end of `out`, with divisions by
/// constants only (the serial chain of divisions was most of formatting a
/// big kit). Not through a buffer on the stack: copying one filled byte by
/// byte stalls the processor (its wide loads cannot be forwarded from the
/// narrow stores), which was most of the time of formatting a number.
#[inline]
pub(crate) fn push_digits(
    out: &mut Vec<u8>,
    negative: bool,
    scaled: u64,
    decimals: u32,
    keep_point: bool,
    zero_before_point: bool,
) {
    debug_assert!(decimals <= 9, "{decimals} decimals: at most 9 are written");
    // Most numbers of a kit's files: sheet coordinates on the 1 µm grid,
    // PDF coordinates in tenths of a point. Inlined, so that the decimals
    // (a constant where called) fold the test into one division by a
    // constant.
    match thousandths(scaled, decimals) {
        Some(m) => push_milli(out, negative, m, keep_point, zero_before_point),
        None => push_digits_general(
            out,
            negative,
            scaled,
            decimals,
            keep_point,
            zero_before_point,
        ),
    }
}

/// `scaled` units of 10^−`decimals` as thousandths, if exactly so and
/// below 10⁷.
#[inline]
fn thousandths(scaled: u64, decimals: u32) -> Option<u64> {
    let m = match decimals {
        0..=3 => scaled.checked_mul(POW10[3 - decimals as usize])?,
        4..=9 => {
            let p = POW10[decimals as usize - 3];
            if !scaled.is_multiple_of(p) {
                return None;
            }
            scaled / p
        }
        _ => return None,
    };
    (m < 10_000_000).then_some(m)
}

/// [`push_digits`] of any number.
#[inline(never)]
fn push_digits_general(
    out: &mut Vec<u8>,
    negative: bool,
    scaled: u64,
    decimals: u32,
    keep_point: bool,
    zero_before_point: bool,
) {
    let mut n = scaled;
    let mut frac_digits = decimals.min(9) as usize;
    // Trailing zeros of the fraction are not written (three at a time
    // first: coordinates on a 1 µm grid written with 6 decimals).
    while frac_digits >= 3 && n.is_multiple_of(1000) {
        n /= 1000;
        frac_digits -= 3;
    }
    while frac_digits > 0 && n.is_multiple_of(10) {
        n /= 10;
        frac_digits -= 1;
    }
    let digits = n.checked_ilog10().map_or(1, |d| d as usize + 1);
    let int_digits = if digits > frac_digits {
        digits - frac_digits
    } else {
        usize::from(zero_before_point || frac_digits == 0)
    };
    let sign = usize::from(negative && scaled != 0);
    let len = sign
        + int_digits
        + match (frac_digits, keep_point) {
            (0, true) => 2,
            (0, false) => 0,
            (f, _) => f + 1,
        };
    // At most 1 + 20 + 2 or 1 + 1 + 1 + 9 bytes.
    const ROOM: usize = 32;
    let start = out.len();
    out.extend_from_slice(&[0u8; ROOM]);
    let w = &mut out[start..start + ROOM];
    let mut i = len;
    if frac_digits > 0 {
        let mut left = frac_digits;
        while left >= 2 {
            let d = (n % 100) as usize;
            n /= 100;
            i -= 2;
            w[i..i + 2].copy_from_slice(&DIGIT_PAIRS[2 * d..2 * d + 2]);
            left -= 2;
        }
        if left == 1 {
            i -= 1;
            w[i] = b'0' + (n % 10) as u8;
            n /= 10;
        }
        i -= 1;
        w[i] = b'.';
    } else if keep_point {
        i -= 2;
        w[i] = b'.';
        w[i + 1] = b'0';
    }
    if int_digits > 0 {
        while n >= 100 {
            let d = (n % 100) as usize;
            n /= 100;
            i -= 2;
            w[i..i + 2].copy_from_slice(&DIGIT_PAIRS[2 * d..2 * d + 2]);
        }
        if n >= 10 {
            let d = n as usize;
            i -= 2;
            w[i..i + 2].copy_from_slice(&DIGIT_PAIRS[2 * d..2 * d + 2]);
        } else {
            i -= 1;
            w[i] = b'0' + n as u8;
        }
    }
    if sign == 1 {
        w[0] = b'-';
    }
    out.truncate(start + len);
}

/// [`push_digits`] of `m` < 10⁷ thousandths: the digits before the point
/// two at a time, the fraction from [`FRACTIONS`].
#[inline]
fn push_milli(
    out: &mut Vec<u8>,
    negative: bool,
    m: u64,
    keep_point: bool,
    zero_before_point: bool,
) {
    let (int, frac) = ((m / 1000) as usize, (m % 1000) as usize);
    let start = out.len();
    // A sign, four digits, the point and three decimals.
    out.extend_from_slice(&[0u8; 16]);
    let w = &mut out[start..start + 16];
    let mut i = 0;
    if negative && m != 0 {
        w[0] = b'-';
        i = 1;
    }
    let pair = |d: usize| [DIGIT_PAIRS[2 * d], DIGIT_PAIRS[2 * d + 1]];
    if int >= 1000 {
        w[i..i + 2].copy_from_slice(&pair(int / 100));
        w[i + 2..i + 4].copy_from_slice(&pair(int % 100));
        i += 4;
    } else if int >= 100 {
        w[i] = b'0' + (int / 100) as u8;
        w[i + 1..i + 3].copy_from_slice(&pair(int % 100));
        i += 3;
    } else if int >= 10 {
        w[i..i + 2].copy_from_slice(&pair(int));
        i += 2;
    } else if int > 0 || zero_before_point || frac == 0 {
        w[i] = b'0' + int as u8;
        i += 1;
    }
    let (bytes, len) = FRACTIONS[frac];
    if len > 0 {
        w[i..i + 4].copy_from_slice(&bytes);
        i += len as usize;
    } else if keep_point {
        w[i..i + 2].copy_from_slice(b".0");
        i += 2;
    }
    out.truncate(start + i);
}

/// Thousandths 0–999 as their decimal fraction, trailing zeros dropped
/// (`.468`, `.47`, `.5`; nothing for 0), and its length.
static FRACTIONS: [([u8; 4], u8); 1000] = fractions();

const fn fractions() -> [([u8; 4], u8); 1000] {
    let mut t = [([0u8; 4], 0u8); 1000];
    let mut f = 1;
    while f < 1000 {
        let d = [(f / 100) as u8, (f / 10 % 10) as u8, (f % 10) as u8];
        let len = if d[2] != 0 {
            4
        } else if d[1] != 0 {
            3
        } else {
            2
        };
        t[f] = ([b'.', b'0' + d[0], b'0' + d[1], b'0' + d[2]], len);
        f += 1;
    }
    t
}

/// "00" to "99".
const DIGIT_PAIRS: &[u8; 200] = b"\
0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// `y` rounded to the nearest integer, halves away from zero (see
/// [`round_half_away`]).
pub(crate) fn round_to_i64(y: f64) -> i64 {
    if y.is_nan() || y.abs() >= 1e15 {
        // Huge, infinite or NaN: the saturating cast of the library's rounding.
        return y.round() as i64;
    }
    let r = round_half_away(y.abs()) as i64;
    if y < 0.0 {
        -r
    } else {
        r
    }
}

/// `y` ≥ 0 rounded to the nearest integer, halves away from zero (as
/// `f64::round`, which is a library call on baseline x86-64): `y − ⌊y⌋` is
/// exact for a double.
fn round_half_away(y: f64) -> u64 {
    let t = y as u64;
    if y - t as f64 >= 0.5 {
        t.saturating_add(1)
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::push_decimal;

    fn d(x: f64, n: u32, keep: bool) -> String {
        let mut s = Vec::new();
        push_decimal(&mut s, x, n, keep);
        let mut t = String::new();
        super::push_decimal_str(&mut t, x, n, keep);
        let s = String::from_utf8(s).expect("ASCII");
        assert_eq!(s, t, "the two entry points");
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
        assert_eq!(d(-2.5, 0, false), "-3");
        assert_eq!(d(0.4999999999999999, 0, false), "0");
        assert_eq!(d(-1234567.123456789, 9, false), "-1234567.123456789");
        assert_eq!(d(1500.0, 4, false), "1500");
        assert_eq!(d(0.0, 6, true), "0.0");
        assert_eq!(d(-0.0, 6, false), "0");
        assert_eq!(d(2766.9, 6, true), "2766.9");
        assert_eq!(d(10.000001, 6, true), "10.000001");
        assert_eq!(d(1523.5, 6, true), "1523.5");
        assert_eq!(d(7.0, 3, false), "7");
        assert_eq!(d(99.99, 2, false), "99.99");
        assert_eq!(d(-0.001, 3, false), "-0.001");
        assert_eq!(d(12.3456789, 9, false), "12.3456789");
        // Whole u64 range, every decimal count, against integer formatting.
        // (The fast path of thousandths below 10⁷ and the general one meet
        // at 9,999,999 and 10,000,000, at 3 and at 6 decimals.)
        for &n in &[
            0u64,
            1,
            9,
            10,
            99,
            100,
            500,
            1_000,
            12_345,
            999_000,
            9_999_999,
            10_000_000,
            9_999_999_000,
            10_000_000_000,
            u64::MAX,
            u64::MAX - 1,
        ] {
            for decimals in 0..=9u32 {
                let p = 10u64.pow(decimals);
                let int = (n / p).to_string();
                let frac = format!("{:0w$}", n % p, w = decimals as usize);
                let frac = frac.trim_end_matches('0');
                let want = if frac.is_empty() {
                    int
                } else {
                    format!("{int}.{frac}")
                };
                let mut got = Vec::new();
                super::push_scaled(&mut got, true, n, decimals, false);
                let want_signed = if n == 0 {
                    want.clone()
                } else {
                    format!("-{want}")
                };
                assert_eq!(
                    String::from_utf8(got).expect("ASCII"),
                    want_signed,
                    "{n} {decimals}"
                );
                // Without the zero before the point.
                let mut got = b"x".to_vec();
                super::push_digits(&mut got, false, n, decimals, false, false);
                let short = want
                    .strip_prefix("0.")
                    .map_or(want.clone(), |r| format!(".{r}"));
                assert_eq!(got, format!("x{short}").as_bytes(), "{n} {decimals}");
            }
        }
        // Every value of a grid, against the standard library.
        for k in -30000i64..30000 {
            let x = k as f64 / 1000.0;
            let std = format!("{x:.3}");
            let std = std.trim_end_matches('0').trim_end_matches('.');
            let std = if std == "-0" { "0" } else { std };
            assert_eq!(d(x, 6, false), std, "{k}");
        }
    }
}
