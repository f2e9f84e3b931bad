//! A linear pre-scan of YAML text before it reaches the parser.
//!
//! serde_yaml (libyaml) spends time quadratic in the nesting depth before it
//! reports its recursion limit (100,000 nested `[` take seconds), expands
//! aliases before it counts them, and reports a duplicate top-level key at
//! line 1. lamella's files (network files, trace specs, profiles) need none of
//! that, so the scan refuses, with the line:
//!
//! * nesting deeper than [`MAX_DEPTH`] levels (block indentation levels,
//!   sequence entries and flow brackets together);
//! * anchors (`&name`) and aliases (`*name`);
//! * a key repeated in one block mapping (naming both lines).
//!
//! It understands enough YAML to skip quoted strings, block scalars (`|`,
//! `>`), multi-line plain scalars and comments, so `&` and `*` inside text
//! are not mistaken for anchors. What it does not understand it leaves to
//! the parser.

use crate::error::{Error, Location, Result};
use std::collections::HashMap;
use std::path::Path;

/// Deepest nesting lamella reads (its own files nest 4 levels).
pub const MAX_DEPTH: usize = 64;

/// Largest trace spec or profile, bytes.
pub const MAX_SMALL_FILE_BYTES: u64 = 1 << 20;

/// Largest network file (YAML, JSON, OBJ), bytes.
pub const MAX_NETWORK_FILE_BYTES: u64 = 256 << 20;

enum Level {
    /// A block mapping at this column: its keys and their lines.
    Map(usize, HashMap<String, usize>),
    /// A block sequence whose `-` sit at this column.
    Seq(usize),
}

impl Level {
    fn col(&self) -> usize {
        match self {
            Level::Map(c, _) | Level::Seq(c) => *c,
        }
    }
}

/// Skip lines while they are indented more than this column (or blank):
/// the body of a block scalar or the continuation of a plain scalar.
struct Skip(usize);

struct Scan<'a> {
    path: &'a Path,
    levels: Vec<Level>,
    flow: usize,
    /// Inside a quoted scalar that spans lines: its quote character.
    quote: Option<char>,
    skip: Option<Skip>,
}

/// Check YAML text for excessive nesting, anchors/aliases and duplicate keys.
pub fn check(text: &str, path: &Path) -> Result<()> {
    let mut s = Scan {
        path,
        levels: Vec::new(),
        flow: 0,
        quote: None,
        skip: None,
    };
    for (i, line) in text.lines().enumerate() {
        s.line(i + 1, line)?;
    }
    Ok(())
}

fn indent_of(line: &str) -> usize {
    line.len() - line.trim_start_matches(' ').len()
}

impl Scan<'_> {
    fn err(&self, line: usize, column: usize, what: impl Into<String>) -> Error {
        Error::input(self.path, Location::LineColumn { line, column }, what)
    }

    fn depth_check(&self, line: usize, column: usize) -> Result<()> {
        if self.levels.len() + self.flow > MAX_DEPTH {
            return Err(self.err(
                line,
                column,
                format!("nesting deeper than {MAX_DEPTH} levels"),
            ));
        }
        Ok(())
    }

    fn line(&mut self, no: usize, line: &str) -> Result<()> {
        let line = line.strip_suffix('\r').unwrap_or(line);
        let b = line.as_bytes();
        // Continuation of a quoted scalar or a flow collection.
        if self.quote.is_some() || self.flow > 0 {
            return self.rest(no, line, 0);
        }
        let indent = indent_of(line);
        let body = &line[indent..];
        if body.is_empty() || body.starts_with('#') {
            return Ok(());
        }
        if let Some(Skip(col)) = self.skip {
            if indent > col || (body.starts_with('\t') && indent >= col) {
                return Ok(());
            }
            self.skip = None;
        }
        if indent == 0
            && (body.starts_with("---") || body.starts_with("...") || body.starts_with('%'))
        {
            self.levels.clear();
            return Ok(());
        }
        let mut pos = indent;
        let mut dash = None;
        // Sequence entries: `- ` (possibly several on one line).
        while pos < b.len() && b[pos] == b'-' && (pos + 1 == b.len() || b[pos + 1] == b' ') {
            self.enter(pos, false, no)?;
            dash = Some(pos);
            pos += 1;
            while pos < b.len() && b[pos] == b' ' {
                pos += 1;
            }
            if pos == b.len() {
                return Ok(());
            }
        }
        let col = pos;
        // A key at `col`?
        if let Some((key, value_at)) = key_of(line, pos) {
            self.enter(col, true, no)?;
            if let Some(Level::Map(_, keys)) = self.levels.last_mut() {
                if let Some(&first) = keys.get(&key) {
                    return Err(self.err(
                        no,
                        col + 1,
                        format!("duplicate key `{key}` (first at line {first})"),
                    ));
                }
                keys.insert(key, no);
            }
            return self.value(no, line, value_at, col);
        }
        self.value(no, line, pos, dash.unwrap_or(indent))
    }

    /// A structural token (`-` or a key) at column `col`.
    fn enter(&mut self, col: usize, key: bool, no: usize) -> Result<()> {
        while self.levels.last().is_some_and(|l| l.col() > col) {
            self.levels.pop();
        }
        // A key at the column of a sequence's `-`: the sequence ended (a
        // sequence may sit at its parent key's indentation).
        if key && matches!(self.levels.last(), Some(Level::Seq(c)) if *c == col) {
            self.levels.pop();
        }
        let same = match self.levels.last() {
            Some(Level::Map(c, _)) => *c == col && key,
            Some(Level::Seq(c)) => *c == col && !key,
            None => false,
        };
        if !same {
            self.levels.push(if key {
                Level::Map(col, HashMap::new())
            } else {
                Level::Seq(col)
            });
        }
        self.depth_check(no, col + 1)
    }

    /// A value node starting at byte `pos`; `parent` is the column of the key
    /// or `-` it belongs to.
    fn value(&mut self, no: usize, line: &str, pos: usize, parent: usize) -> Result<()> {
        let b = line.as_bytes();
        let mut pos = pos;
        while pos < b.len() && b[pos] == b' ' {
            pos += 1;
        }
        // Tags (`!!str`, `!foo`) before the node.
        while pos < b.len() && b[pos] == b'!' {
            while pos < b.len() && b[pos] != b' ' {
                pos += 1;
            }
            while pos < b.len() && b[pos] == b' ' {
                pos += 1;
            }
        }
        let Some(&c) = b.get(pos) else {
            return Ok(());
        };
        match c {
            b'&' | b'*' => Err(self.anchor(no, pos, c)),
            b'|' | b'>' => {
                self.skip = Some(Skip(parent));
                Ok(())
            }
            b'#' => Ok(()),
            b'"' | b'\'' | b'[' | b'{' => self.rest(no, line, pos),
            _ => {
                // A plain scalar: the lines indented further continue it.
                self.skip = Some(Skip(parent));
                Ok(())
            }
        }
    }

    fn anchor(&self, no: usize, pos: usize, c: u8) -> Error {
        let what = if c == b'&' { "anchor" } else { "alias" };
        self.err(
            no,
            pos + 1,
            format!("YAML {what}s (`&name`, `*name`) are not supported: write the value out"),
        )
    }

    /// Scan flow collections and quoted scalars from byte `pos` to the end
    /// of the line, carrying their state over to the next line.
    fn rest(&mut self, no: usize, line: &str, pos: usize) -> Result<()> {
        let b = line.as_bytes();
        let mut i = pos;
        // At the start of a node inside a flow collection.
        let mut node_start = self.flow > 0 && self.quote.is_none();
        while i < b.len() {
            if let Some(q) = self.quote {
                let c = b[i];
                if q == '"' && c == b'\\' {
                    i += 2;
                    continue;
                }
                if c == q as u8 {
                    if q == '\'' && b.get(i + 1) == Some(&b'\'') {
                        i += 2;
                        continue;
                    }
                    self.quote = None;
                }
                i += 1;
                continue;
            }
            let c = b[i];
            match c {
                b' ' | b'\t' => {
                    i += 1;
                    continue;
                }
                b'#' if i == 0 || matches!(b[i - 1], b' ' | b'\t') => return Ok(()),
                b'"' | b'\'' if node_start || self.flow == 0 => {
                    self.quote = Some(c as char);
                    node_start = false;
                    i += 1;
                    continue;
                }
                b'&' | b'*' if node_start => return Err(self.anchor(no, i, c)),
                b'[' | b'{' => {
                    self.flow += 1;
                    self.depth_check(no, i + 1)?;
                    node_start = true;
                    i += 1;
                    continue;
                }
                b']' | b'}' => {
                    self.flow = self.flow.saturating_sub(1);
                    node_start = false;
                }
                b',' if self.flow > 0 => node_start = true,
                b':' if self.flow > 0 && matches!(b.get(i + 1), None | Some(b' ') | Some(b',')) => {
                    node_start = true
                }
                b'?' if node_start => {}
                _ => {
                    if self.flow == 0 {
                        // After a closed collection or quote: the rest is
                        // trailing text the parser judges.
                        return Ok(());
                    }
                    node_start = false;
                }
            }
            i += 1;
        }
        Ok(())
    }
}

/// If a key (`key:` followed by a space or the line end) starts at `pos`,
/// its text and the byte where its value starts.
fn key_of(line: &str, pos: usize) -> Option<(String, usize)> {
    let b = line.as_bytes();
    let first = *b.get(pos)?;
    let after_colon = |i: usize| -> Option<usize> {
        let mut j = i;
        while j < b.len() && b[j] == b' ' {
            j += 1;
        }
        if b.get(j) == Some(&b':') && matches!(b.get(j + 1), None | Some(b' ')) {
            Some(j + 1)
        } else {
            None
        }
    };
    match first {
        b'"' | b'\'' => {
            let mut i = pos + 1;
            while i < b.len() {
                if first == b'"' && b[i] == b'\\' {
                    i += 2;
                    continue;
                }
                if b[i] == first {
                    if first == b'\'' && b.get(i + 1) == Some(&b'\'') {
                        i += 2;
                        continue;
                    }
                    let v = after_colon(i + 1)?;
                    return Some((line[pos + 1..i].to_string(), v));
                }
                i += 1;
            }
            None
        }
        b'[' | b'{' | b'&' | b'*' | b'|' | b'>' | b'!' | b'#' | b'?' | b'%' | b'@' | b'`' => None,
        _ => {
            let mut i = pos;
            while i < b.len() {
                if b[i] == b'#' && i > pos && b[i - 1] == b' ' {
                    return None;
                }
                if b[i] == b':' && matches!(b.get(i + 1), None | Some(b' ')) {
                    return Some((line[pos..i].trim_end().to_string(), i + 1));
                }
                i += 1;
            }
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan(text: &str) -> std::result::Result<(), String> {
        check(text, Path::new("t.yaml")).map_err(|e| e.to_string())
    }

    #[test]
    fn lamella_files_pass() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for dir in ["samples", "profiles"] {
            for e in std::fs::read_dir(root.join(dir)).expect("dir") {
                let p = e.expect("entry").path();
                if p.extension().is_some_and(|x| x == "yaml") {
                    let text = std::fs::read_to_string(&p).expect("read");
                    assert_eq!(scan(&text), Ok(()), "{}", p.display());
                }
            }
        }
    }

    #[test]
    fn text_is_not_taken_for_anchors() {
        let ok = "name: a & b *c\ndescription: |\n  *bold* &amp\n  - x: 1\n  x: 2\nnote: \"*a\" \nlist: [\"&x\", 'it''s *y']\nlong: one\n  *two: three\nsep: a:b\n";
        assert_eq!(scan(ok), Ok(()));
    }

    #[test]
    fn anchors_aliases_depth_and_duplicates_are_refused() {
        let e = scan("meta:\n  a: &x [1, 2]\n  b: *x\n").unwrap_err();
        assert!(
            e.contains("line 2, column 6") && e.contains("anchor"),
            "{e}"
        );
        let e = scan("meta: [1, *x]\n").unwrap_err();
        assert!(
            e.contains("line 1, column 11") && e.contains("alias"),
            "{e}"
        );
        let deep = format!("meta: {}{}\n", "[".repeat(100_000), "]".repeat(100_000));
        let e = scan(&deep).unwrap_err();
        assert!(
            e.contains("line 1, column 70") && e.contains("deeper than 64"),
            "{e}"
        );
        let block: String = (0..100)
            .map(|i| format!("{}k{i}:\n", " ".repeat(i)))
            .collect();
        let e = scan(&block).unwrap_err();
        assert!(e.contains("line 65") && e.contains("deeper than 64"), "{e}");
        let e = scan("units: mm\ncurves: []\nunits: cm\n").unwrap_err();
        assert!(
            e.contains("line 3, column 1") && e.contains("duplicate key `units` (first at line 1)"),
            "{e}"
        );
        let e =
            scan("curves:\n- id: A\n  family: A\n- id: B\n  family: B\n  family: A\n").unwrap_err();
        assert!(
            e.contains("line 6, column 3") && e.contains("(first at line 5)"),
            "{e}"
        );
        // The same key in different entries of a sequence is fine.
        assert_eq!(
            scan("curves:\n  - id: A\n    family: A\n  - id: B\n    family: B\n"),
            Ok(())
        );
    }
}
