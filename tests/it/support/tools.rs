//! The outside readers the tests check files with (pypdf, ezdxf, the
//! glTF-Validator, chromium): whether one is there, and the PDF's text
//! runs as pypdf reads them. A missing tool skips its check, unless CI's
//! `LAMELLA_REQUIRE_…` variable asks for it: then the test fails.

use super::root;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;
use std::sync::Mutex;

/// Whether `program ARGS…` runs and succeeds (a tool's `--version`, or
/// `python3 -c "import M"`): asked once per test process (an import of
/// ezdxf alone takes most of a second, and the tests ask dozens of
/// times).
pub fn runs(program: &str, args: &[&str]) -> bool {
    static ASKED: Mutex<BTreeMap<Vec<String>, bool>> = Mutex::new(BTreeMap::new());
    let key: Vec<String> = std::iter::once(program)
        .chain(args.iter().copied())
        .map(str::to_owned)
        .collect();
    let mut asked = ASKED.lock().unwrap_or_else(|e| e.into_inner());
    *asked.entry(key).or_insert_with(|| {
        Command::new(program)
            .args(args)
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// Whether a tool the test needs is there (`have`); when it is not, fails
/// if the environment variable `require` is set (CI), else says on stderr
/// that `what` is skipped. `install` tells how to get it.
#[track_caller]
pub fn present(have: bool, require: &str, tool: &str, install: &str, what: &str) -> bool {
    if !have {
        assert!(
            std::env::var_os(require).is_none(),
            "{tool} is required ({install})"
        );
        eprintln!("{tool} not installed: {what} skipped (CI runs it)");
    }
    have
}

/// Run a Python tool of `tests/tools/` on `path` and read its JSON.
#[track_caller]
pub fn python_json(script: &str, path: &Path) -> Value {
    python_json_with(script, path, &[])
}

/// [`python_json`] with further arguments after the path.
pub fn python_json_with(script: &str, path: &Path, args: &[&str]) -> Value {
    let o = Command::new("python3")
        .arg(root().join("tests/tools").join(script))
        .arg(path)
        .args(args)
        .output()
        .expect("python3");
    assert!(
        o.status.success(),
        "{script} could not read {}: {}",
        path.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("json")
}

/// Whether pypdf is there (or required: see [`present`]).
pub fn have_pypdf() -> bool {
    present(
        runs("python3", &["-c", "import pypdf"]),
        "LAMELLA_REQUIRE_PYPDF",
        "pypdf",
        "pip install -r tests/tools/requirements.txt",
        "reading the PDF back",
    )
}

/// pypdf's reading of a PDF (`tests/tools/pdf_text.py`), or `None`
/// when pypdf is not installed.
pub fn read_pdf(path: &Path) -> Option<Value> {
    have_pypdf().then(|| python_json("pdf_text.py", path))
}

/// pypdf's reading of every text run with its place on the page
/// (`tests/tools/pdf_words.py`), or `None` without pypdf.
pub fn read_runs(path: &Path) -> Option<Value> {
    have_pypdf().then(|| python_json("pdf_words.py", path))
}

/// The runs of a page (from [`read_runs`]) line by line, top to bottom as
/// the page's y runs, each line's cells (x, text) left to right: runs on
/// one baseline (to 0.1 mm) are a line.
pub fn lines<'a>(runs: impl IntoIterator<Item = &'a Value>) -> Vec<Vec<(f64, String)>> {
    let mut lines: BTreeMap<i64, Vec<(f64, String)>> = BTreeMap::new();
    for r in runs {
        let y = (r["y_mm"].as_f64().expect("y") * 10.0).round() as i64;
        lines.entry(y).or_default().push((
            r["x_mm"].as_f64().expect("x"),
            r["text"].as_str().expect("t").to_string(),
        ));
    }
    lines
        .into_values()
        .map(|mut cells| {
            cells.sort_by(|a, b| a.0.total_cmp(&b.0));
            cells
        })
        .collect()
}
