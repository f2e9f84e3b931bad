//! A single-stroke engraving font: our own table, public domain.
//!
//! Every glyph is a few open polylines (pen strokes) on a grid of tenths of
//! the cap height: y runs from 0 (the baseline) to 1 (the cap height),
//! nothing descends below the baseline or rises above the caps, and x runs
//! from 0 to the glyph's width (at most 0.7). Round letters are drawn as
//! chamfered polygons, which a laser or a pen draws cleanly and which stay
//! legible from 3 to 10 mm cap height. The zero is slashed so it is never
//! read as an O; the I has serifs and the one a flag and a foot, so neither
//! is read as the other.
//!
//! Glyphs: digits `0`–`9`, capitals `A`–`Z`, `- . _ / : + ( ) # °`, a space,
//! and `>`, drawn as an arrow (shaft and head) so it can serve as a
//! direction mark. Lowercase ASCII letters are drawn as capitals. Any other
//! character is drawn as a small open box ([`FALLBACK_WIDTH`] wide), so a
//! missing glyph shows on the part instead of silently vanishing.
//!
//! Beside the glyphs, the orientation mark ([`orientation_mark_strokes`]):
//! an arrow with a tick, on the same grid, that shows which way a part is
//! mounted.
//!
//! Text is set with a fixed gap of [`LETTER_SPACING`] between glyph boxes:
//! each glyph advances by its width plus the gap, and a string's width is
//! the sum of its glyphs' widths plus one gap between each two (no gap after
//! the last).

use kurbo::Point;

/// The font's name (plan.json's `engraving_font.name`).
pub const NAME: &str = "lamella single-stroke";

/// The gap between two glyph boxes, as a fraction of the cap height.
pub const LETTER_SPACING: f64 = 0.2;

/// Width of the box drawn for a character without a glyph, as a fraction of
/// the cap height.
pub const FALLBACK_WIDTH: f64 = 0.4;

/// A glyph: its width and its strokes, in tenths of the cap height.
struct Table {
    /// Width in tenths of the cap height.
    width: f64,
    /// Open polylines, (x, y) in tenths of the cap height.
    strokes: &'static [&'static [(f64, f64)]],
}

const fn g(width: f64, strokes: &'static [&'static [(f64, f64)]]) -> Table {
    Table { width, strokes }
}

/// The box drawn for a character without a glyph.
const FALLBACK: Table = g(
    4.0,
    &[&[(0.0, 0.0), (4.0, 0.0), (4.0, 6.0), (0.0, 6.0), (0.0, 0.0)]],
);

/// The glyph table, tenths of the cap height.
fn table(c: char) -> Option<Table> {
    Some(match c {
        ' ' => g(4.0, &[]),
        '0' => g(
            6.0,
            &[
                &[
                    (1.5, 0.0),
                    (4.5, 0.0),
                    (6.0, 1.5),
                    (6.0, 8.5),
                    (4.5, 10.0),
                    (1.5, 10.0),
                    (0.0, 8.5),
                    (0.0, 1.5),
                    (1.5, 0.0),
                ],
                &[(1.0, 2.0), (5.0, 8.0)],
            ],
        ),
        '1' => g(
            4.0,
            &[
                &[(0.0, 8.0), (2.0, 10.0), (2.0, 0.0)],
                &[(0.0, 0.0), (4.0, 0.0)],
            ],
        ),
        '2' => g(
            6.0,
            &[&[
                (0.0, 8.5),
                (1.5, 10.0),
                (4.5, 10.0),
                (6.0, 8.5),
                (6.0, 6.5),
                (0.0, 0.0),
                (6.0, 0.0),
            ]],
        ),
        '3' => g(
            6.0,
            &[
                &[
                    (0.0, 8.5),
                    (1.5, 10.0),
                    (4.5, 10.0),
                    (6.0, 8.5),
                    (6.0, 6.5),
                    (4.5, 5.0),
                    (6.0, 3.5),
                    (6.0, 1.5),
                    (4.5, 0.0),
                    (1.5, 0.0),
                    (0.0, 1.5),
                ],
                &[(2.0, 5.0), (4.5, 5.0)],
            ],
        ),
        '4' => g(6.0, &[&[(4.5, 0.0), (4.5, 10.0), (0.0, 3.0), (6.0, 3.0)]]),
        '5' => g(
            6.0,
            &[&[
                (6.0, 10.0),
                (0.0, 10.0),
                (0.0, 6.0),
                (4.5, 6.0),
                (6.0, 4.5),
                (6.0, 1.5),
                (4.5, 0.0),
                (1.5, 0.0),
                (0.0, 1.5),
            ]],
        ),
        '6' => g(
            6.0,
            &[&[
                (6.0, 8.5),
                (4.5, 10.0),
                (1.5, 10.0),
                (0.0, 8.5),
                (0.0, 1.5),
                (1.5, 0.0),
                (4.5, 0.0),
                (6.0, 1.5),
                (6.0, 4.5),
                (4.5, 6.0),
                (1.5, 6.0),
                (0.0, 4.5),
            ]],
        ),
        '7' => g(6.0, &[&[(0.0, 10.0), (6.0, 10.0), (2.0, 0.0)]]),
        '8' => g(
            6.0,
            &[&[
                (1.5, 5.0),
                (0.0, 3.5),
                (0.0, 1.5),
                (1.5, 0.0),
                (4.5, 0.0),
                (6.0, 1.5),
                (6.0, 3.5),
                (4.5, 5.0),
                (6.0, 6.5),
                (6.0, 8.5),
                (4.5, 10.0),
                (1.5, 10.0),
                (0.0, 8.5),
                (0.0, 6.5),
                (1.5, 5.0),
                (4.5, 5.0),
            ]],
        ),
        '9' => g(
            6.0,
            &[&[
                (0.0, 1.5),
                (1.5, 0.0),
                (4.5, 0.0),
                (6.0, 1.5),
                (6.0, 8.5),
                (4.5, 10.0),
                (1.5, 10.0),
                (0.0, 8.5),
                (0.0, 5.5),
                (1.5, 4.0),
                (4.5, 4.0),
                (6.0, 5.5),
            ]],
        ),
        'A' => g(
            6.0,
            &[
                &[(0.0, 0.0), (3.0, 10.0), (6.0, 0.0)],
                &[(1.05, 3.5), (4.95, 3.5)],
            ],
        ),
        'B' => g(
            6.0,
            &[&[
                (0.0, 5.0),
                (4.5, 5.0),
                (6.0, 3.5),
                (6.0, 1.5),
                (4.5, 0.0),
                (0.0, 0.0),
                (0.0, 10.0),
                (4.5, 10.0),
                (6.0, 8.5),
                (6.0, 6.5),
                (4.5, 5.0),
            ]],
        ),
        'C' => g(
            6.0,
            &[&[
                (6.0, 8.5),
                (4.5, 10.0),
                (1.5, 10.0),
                (0.0, 8.5),
                (0.0, 1.5),
                (1.5, 0.0),
                (4.5, 0.0),
                (6.0, 1.5),
            ]],
        ),
        'D' => g(
            6.0,
            &[&[
                (0.0, 0.0),
                (0.0, 10.0),
                (4.0, 10.0),
                (6.0, 8.0),
                (6.0, 2.0),
                (4.0, 0.0),
                (0.0, 0.0),
            ]],
        ),
        'E' => g(
            6.0,
            &[
                &[(6.0, 10.0), (0.0, 10.0), (0.0, 0.0), (6.0, 0.0)],
                &[(0.0, 5.0), (4.5, 5.0)],
            ],
        ),
        'F' => g(
            6.0,
            &[
                &[(6.0, 10.0), (0.0, 10.0), (0.0, 0.0)],
                &[(0.0, 5.0), (4.5, 5.0)],
            ],
        ),
        'G' => g(
            6.0,
            &[&[
                (6.0, 8.5),
                (4.5, 10.0),
                (1.5, 10.0),
                (0.0, 8.5),
                (0.0, 1.5),
                (1.5, 0.0),
                (4.5, 0.0),
                (6.0, 1.5),
                (6.0, 4.5),
                (3.5, 4.5),
            ]],
        ),
        'H' => g(
            6.0,
            &[
                &[(0.0, 0.0), (0.0, 10.0)],
                &[(6.0, 0.0), (6.0, 10.0)],
                &[(0.0, 5.0), (6.0, 5.0)],
            ],
        ),
        'I' => g(
            4.0,
            &[
                &[(0.0, 10.0), (4.0, 10.0)],
                &[(2.0, 10.0), (2.0, 0.0)],
                &[(0.0, 0.0), (4.0, 0.0)],
            ],
        ),
        'J' => g(
            6.0,
            &[&[
                (6.0, 10.0),
                (6.0, 1.5),
                (4.5, 0.0),
                (1.5, 0.0),
                (0.0, 1.5),
                (0.0, 3.0),
            ]],
        ),
        'K' => g(
            6.0,
            &[
                &[(0.0, 0.0), (0.0, 10.0)],
                &[(6.0, 10.0), (0.0, 4.0)],
                &[(2.0, 6.0), (6.0, 0.0)],
            ],
        ),
        'L' => g(6.0, &[&[(0.0, 10.0), (0.0, 0.0), (6.0, 0.0)]]),
        'M' => g(
            7.0,
            &[&[(0.0, 0.0), (0.0, 10.0), (3.5, 4.0), (7.0, 10.0), (7.0, 0.0)]],
        ),
        'N' => g(6.0, &[&[(0.0, 0.0), (0.0, 10.0), (6.0, 0.0), (6.0, 10.0)]]),
        'O' => g(
            7.0,
            &[&[
                (2.0, 0.0),
                (5.0, 0.0),
                (7.0, 2.0),
                (7.0, 8.0),
                (5.0, 10.0),
                (2.0, 10.0),
                (0.0, 8.0),
                (0.0, 2.0),
                (2.0, 0.0),
            ]],
        ),
        'P' => g(
            6.0,
            &[&[
                (0.0, 0.0),
                (0.0, 10.0),
                (4.5, 10.0),
                (6.0, 8.5),
                (6.0, 6.0),
                (4.5, 4.5),
                (0.0, 4.5),
            ]],
        ),
        'Q' => g(
            7.0,
            &[
                &[
                    (2.0, 0.0),
                    (5.0, 0.0),
                    (7.0, 2.0),
                    (7.0, 8.0),
                    (5.0, 10.0),
                    (2.0, 10.0),
                    (0.0, 8.0),
                    (0.0, 2.0),
                    (2.0, 0.0),
                ],
                &[(4.0, 3.0), (7.0, 0.0)],
            ],
        ),
        'R' => g(
            6.0,
            &[
                &[
                    (0.0, 0.0),
                    (0.0, 10.0),
                    (4.5, 10.0),
                    (6.0, 8.5),
                    (6.0, 6.0),
                    (4.5, 4.5),
                    (0.0, 4.5),
                ],
                &[(3.0, 4.5), (6.0, 0.0)],
            ],
        ),
        'S' => g(
            6.0,
            &[&[
                (6.0, 8.5),
                (4.5, 10.0),
                (1.5, 10.0),
                (0.0, 8.5),
                (0.0, 6.5),
                (1.5, 5.0),
                (4.5, 5.0),
                (6.0, 3.5),
                (6.0, 1.5),
                (4.5, 0.0),
                (1.5, 0.0),
                (0.0, 1.5),
            ]],
        ),
        'T' => g(
            6.0,
            &[&[(0.0, 10.0), (6.0, 10.0)], &[(3.0, 10.0), (3.0, 0.0)]],
        ),
        'U' => g(
            6.0,
            &[&[
                (0.0, 10.0),
                (0.0, 1.5),
                (1.5, 0.0),
                (4.5, 0.0),
                (6.0, 1.5),
                (6.0, 10.0),
            ]],
        ),
        'V' => g(6.0, &[&[(0.0, 10.0), (3.0, 0.0), (6.0, 10.0)]]),
        'W' => g(
            7.0,
            &[&[(0.0, 10.0), (1.5, 0.0), (3.5, 6.0), (5.5, 0.0), (7.0, 10.0)]],
        ),
        'X' => g(
            6.0,
            &[&[(0.0, 0.0), (6.0, 10.0)], &[(0.0, 10.0), (6.0, 0.0)]],
        ),
        'Y' => g(
            6.0,
            &[
                &[(0.0, 10.0), (3.0, 5.0), (6.0, 10.0)],
                &[(3.0, 5.0), (3.0, 0.0)],
            ],
        ),
        'Z' => g(6.0, &[&[(0.0, 10.0), (6.0, 10.0), (0.0, 0.0), (6.0, 0.0)]]),
        '-' => g(4.0, &[&[(0.0, 5.0), (4.0, 5.0)]]),
        '.' => g(
            1.0,
            &[&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.0)]],
        ),
        '_' => g(6.0, &[&[(0.0, 0.0), (6.0, 0.0)]]),
        '/' => g(5.0, &[&[(0.0, 0.0), (5.0, 10.0)]]),
        ':' => g(
            1.0,
            &[
                &[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.0)],
                &[(0.0, 6.0), (1.0, 6.0), (1.0, 7.0), (0.0, 7.0), (0.0, 6.0)],
            ],
        ),
        '+' => g(6.0, &[&[(0.0, 5.0), (6.0, 5.0)], &[(3.0, 2.0), (3.0, 8.0)]]),
        '(' => g(2.0, &[&[(2.0, 10.0), (0.0, 7.0), (0.0, 3.0), (2.0, 0.0)]]),
        ')' => g(2.0, &[&[(0.0, 10.0), (2.0, 7.0), (2.0, 3.0), (0.0, 0.0)]]),
        '#' => g(
            6.0,
            &[
                &[(2.0, 1.0), (2.0, 9.0)],
                &[(4.0, 1.0), (4.0, 9.0)],
                &[(0.0, 3.5), (6.0, 3.5)],
                &[(0.0, 6.5), (6.0, 6.5)],
            ],
        ),
        '°' => g(
            3.0,
            &[&[
                (1.0, 10.0),
                (2.0, 10.0),
                (3.0, 9.0),
                (3.0, 8.0),
                (2.0, 7.0),
                (1.0, 7.0),
                (0.0, 8.0),
                (0.0, 9.0),
                (1.0, 10.0),
            ]],
        ),
        '>' => g(
            6.0,
            &[
                &[(0.0, 5.0), (6.0, 5.0)],
                &[(3.5, 8.0), (6.0, 5.0), (3.5, 2.0)],
            ],
        ),
        _ => return None,
    })
}

/// The table entry a character is drawn with: lowercase ASCII as capitals,
/// the fallback box for characters without a glyph.
fn lookup(c: char) -> Table {
    table(c.to_ascii_uppercase()).unwrap_or(FALLBACK)
}

/// Whether `c` has a glyph of its own (lowercase ASCII letters count: they
/// are drawn as capitals); `false` means it is drawn as the fallback box.
pub fn has_glyph(c: char) -> bool {
    table(c.to_ascii_uppercase()).is_some()
}

/// Width of the glyph `c` draws, as a fraction of the cap height (the
/// fallback box's for a character without a glyph).
pub fn glyph_width(c: char) -> f64 {
    lookup(c).width / 10.0
}

/// The strokes of the glyph `c` at cap height 1, origin at its baseline's
/// left, +y up; every point lies in [0, [`glyph_width`]] × [0, 1].
pub fn glyph_strokes(c: char) -> Vec<Vec<Point>> {
    lookup(c)
        .strokes
        .iter()
        .map(|s| {
            s.iter()
                .map(|&(x, y)| Point::new(x / 10.0, y / 10.0))
                .collect()
        })
        .collect()
}

/// Width of `text` set at cap height `height_mm`, mm: the glyphs' widths
/// plus [`LETTER_SPACING`] between each two; 0 for an empty string.
pub fn text_width_mm(text: &str, height_mm: f64) -> f64 {
    let mut width = 0.0;
    let mut n = 0usize;
    for c in text.chars() {
        width += glyph_width(c);
        n += 1;
    }
    if n > 1 {
        width += LETTER_SPACING * (n - 1) as f64;
    }
    width * height_mm
}

/// The strokes of `text` at cap height `height_mm`, mm: origin at the left
/// end of the baseline, +y up. Every point lies in
/// [0, [`text_width_mm`]] × [0, `height_mm`]. Spaces draw nothing; characters
/// without a glyph draw the fallback box.
pub fn text_strokes(text: &str, height_mm: f64) -> Vec<Vec<Point>> {
    let mut out = Vec::new();
    let mut x = 0.0;
    for c in text.chars() {
        let glyph = lookup(c);
        for stroke in glyph.strokes {
            out.push(
                stroke
                    .iter()
                    .map(|&(gx, gy)| Point::new((x + gx / 10.0) * height_mm, gy / 10.0 * height_mm))
                    .collect(),
            );
        }
        x += glyph.width / 10.0 + LETTER_SPACING;
    }
    out
}

/// Length of the orientation mark, in multiples of its height.
pub const ORIENTATION_MARK_LENGTH: f64 = 2.0;

/// The orientation mark at height `height_mm`, one stroke, origin at its
/// box's lower left, box [0, [`ORIENTATION_MARK_LENGTH`] × h] × [0, h]: an
/// arrow along +x (a lamella's start → end) with a closed triangular head,
/// and at its tail a tick up to the top of the box (toward the part's top
/// edge, +y). Turned over or end for end, the tick points down or the arrow
/// backwards, so a part cannot be mounted flipped unnoticed.
pub fn orientation_mark_strokes(height_mm: f64) -> Vec<Vec<Point>> {
    ORIENTATION_MARK
        .iter()
        .map(|s| {
            s.iter()
                .map(|&(x, y)| Point::new(x * height_mm, y * height_mm))
                .collect()
        })
        .collect()
}

/// The orientation mark at height 1 ([`orientation_mark_strokes`]),
/// [`ORIENTATION_MARK_LENGTH`] long: the shaft at 0.3, the head 0.6 tall
/// and 0.45 long.
pub const ORIENTATION_MARK: [&[(f64, f64)]; 1] = [&[
    (0.0, 1.0),
    (0.0, 0.3),
    (2.0, 0.3),
    (1.55, 0.6),
    (1.55, 0.0),
    (2.0, 0.3),
]];

#[cfg(test)]
mod tests {
    use super::*;

    /// Every character the font is meant to draw.
    const CHARSET: &str = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ-._/:+()#°> ";

    #[test]
    fn every_glyph_is_defined_and_inside_its_box() {
        for c in CHARSET.chars() {
            assert!(has_glyph(c), "{c:?} has no glyph");
            let w = glyph_width(c);
            assert!(w > 0.0 && w <= 0.7, "{c:?}: width {w}");
            let strokes = glyph_strokes(c);
            assert_eq!(strokes.is_empty(), c == ' ', "{c:?}");
            for s in &strokes {
                assert!(s.len() >= 2, "{c:?}: a stroke of {} points", s.len());
                for w2 in s.windows(2) {
                    assert!(w2[0] != w2[1], "{c:?}: a zero-length segment");
                }
                for p in s {
                    assert!(
                        (0.0..=w).contains(&p.x) && (0.0..=1.0).contains(&p.y),
                        "{c:?}: {p:?} outside [0, {w}] × [0, 1]"
                    );
                }
            }
        }
    }

    #[test]
    fn glyphs_fill_their_box() {
        // Each glyph's ink reaches both sides of its box (no hidden side
        // bearing), so the spacing between glyphs is what LETTER_SPACING says.
        for c in CHARSET.chars().filter(|&c| c != ' ') {
            let strokes = glyph_strokes(c);
            let xs = strokes.iter().flatten().map(|p| p.x);
            let lo = xs.clone().fold(f64::INFINITY, f64::min);
            let hi = xs.fold(f64::NEG_INFINITY, f64::max);
            assert_eq!(lo, 0.0, "{c:?}");
            assert!((hi - glyph_width(c)).abs() < 1e-12, "{c:?}");
        }
    }

    #[test]
    fn lowercase_is_drawn_as_capitals() {
        assert_eq!(text_strokes("abc", 5.0), text_strokes("ABC", 5.0));
        assert_eq!(text_width_mm("a05-1", 5.0), text_width_mm("A05-1", 5.0));
    }

    #[test]
    fn unknown_characters_are_a_box() {
        assert!(!has_glyph('€'));
        assert!(!has_glyph('?'));
        let s = text_strokes("€", 10.0);
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].len(), 5);
        assert_eq!(s[0][0], s[0][4]);
        assert!((text_width_mm("€", 10.0) - FALLBACK_WIDTH * 10.0).abs() < 1e-12);
    }

    #[test]
    fn widths_add_up() {
        let h = 7.0;
        let total = text_width_mm("A05-1.2", h);
        let sum: f64 = "A05-1.2".chars().map(glyph_width).sum::<f64>() * h;
        assert!((total - (sum + 6.0 * LETTER_SPACING * h)).abs() < 1e-9);
        // Concatenation adds one gap.
        let (a, b) = ("W90", "#12");
        let joined = text_width_mm(&format!("{a}{b}"), h);
        let parts = text_width_mm(a, h) + text_width_mm(b, h) + LETTER_SPACING * h;
        assert!((joined - parts).abs() < 1e-9);
        assert_eq!(text_width_mm("", h), 0.0);
        assert!((text_width_mm("I", h) - 0.4 * h).abs() < 1e-12);
    }

    #[test]
    fn strokes_are_counted_and_placed() {
        // H is three strokes, 0 two (the slash), O one, > two, a space none.
        assert_eq!(text_strokes("H", 5.0).len(), 3);
        assert_eq!(text_strokes("0", 5.0).len(), 2);
        assert_eq!(text_strokes("O", 5.0).len(), 1);
        assert_eq!(text_strokes(">", 5.0).len(), 2);
        assert_eq!(text_strokes("H0 O>", 5.0).len(), 8);
        assert!(text_strokes("", 5.0).is_empty());

        // The second glyph starts one advance to the right, scaled.
        let h = 4.0;
        let s = text_strokes("LL", h);
        assert_eq!(s.len(), 2);
        let adv = (glyph_width('L') + LETTER_SPACING) * h;
        for (p, q) in s[0].iter().zip(&s[1]) {
            assert!((q.x - p.x - adv).abs() < 1e-12 && q.y == p.y);
        }

        // A rendered string stays inside its box.
        let text = "A05-1.2 (B13) #7 90° >";
        let w = text_width_mm(text, h);
        for p in text_strokes(text, h).iter().flatten() {
            assert!(p.x >= 0.0 && p.x <= w + 1e-9 && p.y >= 0.0 && p.y <= h + 1e-9);
        }
    }

    #[test]
    fn digits_and_letters_differ() {
        // No two characters share a drawing (0/O, 1/I, 5/S, 8/B, 2/Z).
        let drawn: Vec<(char, Vec<Vec<Point>>)> = CHARSET
            .chars()
            .filter(|&c| c != ' ')
            .map(|c| (c, glyph_strokes(c)))
            .collect();
        for (i, (a, sa)) in drawn.iter().enumerate() {
            for (b, sb) in &drawn[i + 1..] {
                assert!(sa != sb, "{a:?} and {b:?} are drawn alike");
            }
        }
    }

    #[test]
    fn renders_a_sample_svg() {
        // A proof sheet to look at: every glyph at 10 mm, a label at 3 mm.
        let lines = [
            "0123456789",
            "ABCDEFGHIJKLM",
            "NOPQRSTUVWXYZ",
            "-._/:+()#°> €",
            "A05-1.2 B13 W90 #7",
        ];
        let mut svg = String::from(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200mm\" height=\"100mm\" viewBox=\"0 0 200 100\">\n",
        );
        let mut y = 15.0;
        for (i, line) in lines.iter().enumerate() {
            let h = if i == 4 { 3.0 } else { 10.0 };
            for s in text_strokes(line, h) {
                let pts: Vec<String> = s
                    .iter()
                    .map(|p| format!("{:.3},{:.3}", 5.0 + p.x, y - p.y))
                    .collect();
                svg += &format!(
                    "<polyline points=\"{}\" fill=\"none\" stroke=\"black\" stroke-width=\"0.3\"/>\n",
                    pts.join(" ")
                );
            }
            y += 18.0;
        }
        svg += "</svg>\n";
        let dir = std::env::temp_dir().join(format!("lamella-font-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        std::fs::write(dir.join("font.svg"), svg).expect("write svg");
    }

    #[test]
    fn orientation_mark_points_to_the_end_and_up() {
        let s = orientation_mark_strokes(10.0);
        assert_eq!(s.len(), 1);
        let m = &s[0];
        // The tick: from the top of the box down to the shaft at the tail.
        assert_eq!(m[0], Point::new(0.0, 10.0));
        assert_eq!(m[1].x, 0.0);
        assert!(m[1].y < m[0].y);
        // The tip is the rightmost point, on the shaft; the head closes on it.
        let tip = m[2];
        assert_eq!(tip.x, ORIENTATION_MARK_LENGTH * 10.0);
        assert_eq!(tip.y, m[1].y);
        assert_eq!(*m.last().expect("points"), tip);
        assert!(m
            .iter()
            .all(|q| q.x <= tip.x && q.x >= 0.0 && q.y >= 0.0 && q.y <= 10.0));
        // The tick rises above the head: the mark is not symmetric about its
        // shaft, so a flipped part shows it pointing down.
        let head_top = m[3..].iter().map(|q| q.y).fold(f64::NEG_INFINITY, f64::max);
        assert!(m[0].y > head_top);
    }
}
