//! `view.html`: one self-contained page that shows `model.glb` (inlined as
//! base64, nothing fetched): orbit, pan, zoom, pick a strip, toggle the
//! families, the utilisation colour bar and the flat ↔ erected slider.
//! The page is the template `view.html` beside this file, written by
//! hand (WebGL2, no library); the writer fills in the title and the model.

/// The page's template: `__LAMELLA_TITLE__` and `__LAMELLA_MODEL__` are
/// replaced.
pub const TEMPLATE: &str = include_str!("view.html");

/// The marker on the page's second line by which lamella knows its own
/// view.html (formats/out).
pub const MARKER: &str = "<!-- lamella view: a 3D model of a grid -->";

/// Standard base64 (RFC 4648, with padding).
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (c.get(1).copied().unwrap_or(0) as u32) << 8
            | c.get(2).copied().unwrap_or(0) as u32;
        out.push(A[(n >> 18) as usize & 63] as char);
        out.push(A[(n >> 12) as usize & 63] as char);
        out.push(if c.len() > 1 {
            A[(n >> 6) as usize & 63] as char
        } else {
            '='
        });
        out.push(if c.len() > 2 {
            A[n as usize & 63] as char
        } else {
            '='
        });
    }
    out
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The page for a model (`glb`, as [`super::gltf::to_glb`] wrote it)
/// titled `title`.
pub fn to_html(title: &str, glb: &[u8]) -> String {
    TEMPLATE
        .replacen("__LAMELLA_TITLE__", &escape(title), 1)
        .replacen("__LAMELLA_MODEL__", &base64(glb), 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_as_rfc_4648_gives_it() {
        // RFC 4648, section 10.
        for (raw, enc) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(raw.as_bytes()), enc);
        }
    }

    #[test]
    fn the_template_has_its_marker_and_slots() {
        assert_eq!(TEMPLATE.lines().nth(1), Some(MARKER));
        assert!(TEMPLATE.contains("__LAMELLA_TITLE__") && TEMPLATE.contains("__LAMELLA_MODEL__"));
        let page = to_html("a <b>", b"foo");
        assert!(page.contains("a &lt;b&gt;") && page.contains("Zm9v"));
    }
}
