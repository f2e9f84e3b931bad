//! Typed errors of the library. Every variant renders as one line that names
//! the file and, where known, the line/column or the curve, and what is wrong.

use std::fmt;
use std::path::{Path, PathBuf};

/// Where in an input a problem sits.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Location {
    /// The file as a whole.
    File,
    /// A line and column (1-based) in a text file.
    LineColumn {
        /// Line, counted from 1.
        line: usize,
        /// Column, counted from 1.
        column: usize,
    },
    /// A line (1-based) in a text file.
    Line(usize),
    /// A curve, by id.
    Curve(String),
    /// A field of a structured file (profile, spec), dotted path.
    Field(String),
    /// An element of a mesh or a part, named in full: `triangle 12`,
    /// `vertex 5 at (1.000, 2.000, 0.000) mm`, `edge 3–7`.
    Element(String),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::File => Ok(()),
            Location::LineColumn { line, column } => write!(f, "line {line}, column {column}"),
            Location::Line(line) => write!(f, "line {line}"),
            Location::Curve(id) => write!(f, "curve {id}"),
            Location::Field(name) => write!(f, "field `{name}`"),
            Location::Element(name) => f.write_str(name),
        }
    }
}

/// Everything that can go wrong in lamella's stages.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system reported.
        #[source]
        source: std::io::Error,
    },
    /// An input file is malformed or invalid.
    #[error("{}: {}{what}", path.display(), located(at))]
    Input {
        /// The input file.
        path: PathBuf,
        /// Where in the file.
        at: Location,
        /// What is wrong, one line.
        what: String,
    },
    /// The network is well formed but cannot be processed.
    #[error("{}: {what}", path.display())]
    Network {
        /// The network's file.
        path: PathBuf,
        /// What is wrong, one line.
        what: String,
    },
    /// A profile cannot build a part of this network: names the profile,
    /// the strip and, where there is one, the node.
    #[error("{}: {at}{}: {what}", profile.display(), node.map(|n| format!(", node {n}")).unwrap_or_default())]
    Fabrication {
        /// The profile file.
        profile: PathBuf,
        /// Where: `strip A05`, or `part ST` for a shared part.
        at: String,
        /// The node (its plan.json id), if the problem is at one.
        node: Option<usize>,
        /// What is wrong, one line.
        what: String,
    },
    /// An output cannot be made or written as asked: names the file or
    /// directory and why (a foreign file in the way, an inconsistent plan).
    #[error("{}: {what}", path.display())]
    Output {
        /// The output file or directory.
        path: PathBuf,
        /// What is wrong, one line.
        what: String,
    },
}

fn located(at: &Location) -> String {
    match at {
        Location::File => String::new(),
        other => format!("{other}: "),
    }
}

impl Error {
    /// A read or write of `path` failed.
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        Error::Io {
            path: path.to_path_buf(),
            source,
        }
    }
    /// A malformed or invalid input at `at` in `path`; `what` is collapsed to one line.
    pub fn input(path: &Path, at: Location, what: impl Into<String>) -> Self {
        Error::Input {
            path: path.to_path_buf(),
            at,
            what: one_line(&what.into()),
        }
    }
    /// A fabrication error at a strip (and node).
    pub fn fabrication(
        profile: &Path,
        strip: &str,
        node: Option<usize>,
        what: impl Into<String>,
    ) -> Self {
        Error::Fabrication {
            profile: profile.to_path_buf(),
            at: format!("strip {strip}"),
            node,
            what: one_line(&what.into()),
        }
    }
    /// A fabrication error at a shared part (studs, washers of a class).
    pub fn fabrication_part(profile: &Path, part: &str, what: impl Into<String>) -> Self {
        Error::Fabrication {
            profile: profile.to_path_buf(),
            at: format!("part {part}"),
            node: None,
            what: one_line(&what.into()),
        }
    }
    /// A fabrication error at a kind of joint (its bolts: `splice bolt`).
    pub fn fabrication_joint(profile: &Path, joint: &str, what: impl Into<String>) -> Self {
        Error::Fabrication {
            profile: profile.to_path_buf(),
            at: format!("joint {joint}"),
            node: None,
            what: one_line(&what.into()),
        }
    }
    /// An output at `path` that cannot be made or written; `what` is collapsed to one line.
    pub fn output(path: &Path, what: impl Into<String>) -> Self {
        Error::Output {
            path: path.to_path_buf(),
            what: one_line(&what.into()),
        }
    }
    /// A network from `path` that cannot be processed; `what` is collapsed to one line.
    pub fn network(path: &Path, what: impl Into<String>) -> Self {
        Error::Network {
            path: path.to_path_buf(),
            what: one_line(&what.into()),
        }
    }
}

/// Collapse a (possibly multi-line) parser message to one line.
pub fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The library's result: [`Error`] unless said otherwise.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Where a YAML parser error sits and its message without serde's trailing
/// " at line L column C" (the location is reported by [`Location`]).
pub fn yaml_error_parts(e: &serde_yaml::Error) -> (Location, String) {
    let at = e
        .location()
        .map(|l| Location::LineColumn {
            line: l.line(),
            column: l.column(),
        })
        .unwrap_or(Location::File);
    (at, strip_serde_location(&e.to_string()))
}

/// Remove every " at line L column C" that serde puts into a message.
pub fn strip_serde_location(msg: &str) -> String {
    const AT: &str = " at line ";
    const COL: &str = " column ";
    let digits = |s: &str| s.len() - s.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    let msg = one_line(msg);
    let mut out = String::with_capacity(msg.len());
    let mut rest = msg.as_str();
    while let Some(i) = rest.find(AT) {
        let after = &rest[i + AT.len()..];
        let n = digits(after);
        if n > 0 {
            if let Some(col) = after[n..].strip_prefix(COL) {
                let m = digits(col);
                if m > 0 {
                    out.push_str(&rest[..i]);
                    rest = &col[m..];
                    continue;
                }
            }
        }
        out.push_str(&rest[..i + AT.len()]);
        rest = after;
    }
    out.push_str(rest);
    out
}
