//! The house rule: imports run one way, from higher layers to lower ones,
//! and never in a circle. Every `crate::` and `super::` path in `src/`
//! (outside the test module that closes a file) is resolved to the file it
//! names; an import from a folder to one it may not use, or a circle of
//! files importing each other, fails with the offending lines.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// What each top-level folder of `src/` may import (besides itself). The
/// order is the layering: the shared geometry and errors, the working
/// models, the stages, the plan, the formats, the pipeline.
fn allowed(folder: &str) -> Option<&'static [&'static str]> {
    Some(match folder {
        "error" => &[],
        "geom" => &["error"],
        "network" => &["error", "geom"],
        "profile" => &["error", "geom", "network"],
        "spec" => &["error", "geom"],
        "loads" => &["error", "geom"],
        "analysis" => &["error", "geom", "network", "profile"],
        "design" => &["error", "geom", "network", "spec", "analysis"],
        "check" => &["error", "geom", "network", "profile", "analysis"],
        "flat" => &["error", "geom", "network", "profile", "analysis"],
        "fabricate" => &["error", "geom", "network", "profile", "analysis", "check"],
        "nest" => &["error", "geom", "profile", "fabricate"],
        "structure" => &[
            "error",
            "geom",
            "network",
            "profile",
            "loads",
            "analysis",
            "check",
            "fabricate",
        ],
        "plan" => &[
            "error",
            "geom",
            "network",
            "profile",
            "analysis",
            "check",
            "flat",
            "fabricate",
            "nest",
            "loads",
            "structure",
        ],
        // Readers build the models; writers format the plan.
        "formats/read" => &["error", "geom", "network", "profile", "spec", "loads"],
        "formats/write" => &["error", "geom", "plan", "formats/text"],
        "formats/out" => &["error"],
        "formats/text" => &[],
        "pipeline" => &[
            "error",
            "geom",
            "network",
            "profile",
            "spec",
            "loads",
            "analysis",
            "design",
            "check",
            "flat",
            "fabricate",
            "nest",
            "structure",
            "plan",
            "formats/read",
            "formats/write",
            "formats/out",
            "formats/text",
        ],
        _ => return None,
    })
}

/// The layer a file belongs to: its top folder, or `formats/<sub>`.
fn layer_of(rel: &Path) -> String {
    let parts: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts[0] == "formats" && parts.len() > 1 && parts[1] != "mod" {
        format!("formats/{}", parts[1])
    } else {
        parts[0].clone()
    }
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("read src")
        .map(|e| e.expect("entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The code of a file that counts: without comments and without the test
/// module that closes it (`#[cfg(test)]` at the start of a line, then
/// `mod …`), as (line number, text).
fn code_lines(text: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let t = line.trim_start();
        if t.starts_with("#[cfg(test)]")
            && lines.get(i + 1).is_some_and(|n| {
                n.trim_start().starts_with("mod ") || n.trim_start().starts_with("pub(crate) mod ")
            })
            && !line.starts_with(' ')
        {
            // A test module at the top level of the file; a non-inline
            // one (`mod samples;`) is a file of its own, skipped below.
            if lines[i + 1].trim_end().ends_with('{') {
                break;
            }
            continue;
        }
        if t.starts_with("//") {
            continue;
        }
        let code = match t.find("//") {
            Some(k) if !t[..k].contains('"') => &t[..k],
            _ => t,
        };
        out.push((i + 1, code.to_string()));
    }
    out
}

/// Files only compiled for tests (`#[cfg(test)] mod x;`), relative to src.
fn test_only_files(src: &Path, files: &[PathBuf]) -> BTreeSet<PathBuf> {
    let mut out = BTreeSet::new();
    for f in files {
        let text = std::fs::read_to_string(f).expect("read");
        let lines: Vec<&str> = text.lines().collect();
        for w in lines.windows(2) {
            if w[0].trim() == "#[cfg(test)]" {
                let n = w[1].trim();
                let n = n
                    .trim_start_matches("pub(crate) ")
                    .trim_start_matches("pub ");
                if let Some(name) = n.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
                    let dir = if f
                        .file_name()
                        .is_some_and(|n| n == "mod.rs" || n == "lib.rs")
                    {
                        f.parent().expect("dir").to_path_buf()
                    } else {
                        f.with_extension("")
                    };
                    for cand in [
                        dir.join(format!("{name}.rs")),
                        dir.join(name).join("mod.rs"),
                    ] {
                        if cand.exists() {
                            out.insert(cand.strip_prefix(src).expect("in src").to_path_buf());
                        }
                    }
                }
            }
        }
    }
    out
}

/// The module path of a file (`analysis/lines.rs` → [analysis, lines]).
fn module_of(rel: &Path) -> Vec<String> {
    let mut m: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if m.last().is_some_and(|l| l == "mod" || l == "lib") {
        m.pop();
    }
    m
}

/// The file a module path names: the longest prefix that is a file.
fn file_of(src: &Path, path: &[String]) -> Option<PathBuf> {
    for n in (1..=path.len()).rev() {
        let p = path[..n].join("/");
        for cand in [format!("{p}.rs"), format!("{p}/mod.rs")] {
            if src.join(&cand).exists() {
                return Some(PathBuf::from(cand));
            }
        }
    }
    None
}

/// Every module path a line names: `crate::a::b`, `super::x`, and the
/// branches of `use crate::a::{b, c::d}`.
fn paths_in(line: &str, here: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for (start, _) in line
        .match_indices("crate::")
        .chain(line.match_indices("super::"))
    {
        if start > 0 {
            let prev = line.as_bytes()[start - 1];
            if prev.is_ascii_alphanumeric()
                || prev == b'_'
                || (prev == b':' && !line[..start].ends_with("super::"))
            {
                continue;
            }
            if line[..start].ends_with("super::") {
                continue;
            }
        }
        let mut base: Vec<String> = Vec::new();
        let mut rest = &line[start..];
        if let Some(r) = rest.strip_prefix("crate::") {
            rest = r;
        } else {
            base = here.to_vec();
            while let Some(r) = rest.strip_prefix("super::") {
                base.pop();
                rest = r;
            }
        }
        let mut segs = base;
        let mut prefix_len = segs.len();
        loop {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if name.is_empty() {
                if let Some(group) = rest.strip_prefix('{') {
                    // Branches of a group: each one its own path.
                    let inner: String = group.chars().take_while(|c| *c != '}').collect();
                    for b in inner.split(',') {
                        let b = b.trim();
                        let b: Vec<String> = b
                            .split("::")
                            .map(|s| s.trim().split(' ').next().unwrap_or("").to_string())
                            .filter(|s| !s.is_empty() && s != "self" && s != "*")
                            .collect();
                        let mut p = segs.clone();
                        p.extend(b);
                        out.push(p);
                    }
                    prefix_len = usize::MAX;
                }
                break;
            }
            rest = &rest[name.len()..];
            segs.push(name);
            match rest.strip_prefix("::") {
                Some(r) => rest = r,
                None => break,
            }
        }
        if prefix_len != usize::MAX {
            out.push(segs);
        }
    }
    out
}

struct Import {
    from: PathBuf,
    line: usize,
    to: PathBuf,
    text: String,
}

fn imports() -> (PathBuf, Vec<Import>) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let test_only = test_only_files(&src, &files);
    let mut out = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&src).expect("in src").to_path_buf();
        if rel.starts_with("cli") || rel == Path::new("lib.rs") || test_only.contains(&rel) {
            continue;
        }
        let here = module_of(&rel);
        let text = std::fs::read_to_string(f).expect("read");
        for (line, code) in code_lines(&text) {
            for p in paths_in(&code, &here) {
                if let Some(to) = file_of(&src, &p) {
                    if to != rel {
                        out.push(Import {
                            from: rel.clone(),
                            line,
                            to,
                            text: code.trim().to_string(),
                        });
                    }
                }
            }
        }
    }
    (src, out)
}

#[test]
fn imports_run_from_higher_layers_to_lower_ones() {
    let (_, imports) = imports();
    assert!(
        imports.len() > 200,
        "the scan found {} imports",
        imports.len()
    );
    let mut wrong = Vec::new();
    for i in &imports {
        let (from, to) = (layer_of(&i.from), layer_of(&i.to));
        if from == to {
            continue;
        }
        let Some(ok) = allowed(&from) else {
            wrong.push(format!(
                "{}: a folder the layering does not know",
                i.from.display()
            ));
            continue;
        };
        if !ok.contains(&to.as_str()) {
            wrong.push(format!(
                "{}:{}: {from} may not import {to}: {}",
                i.from.display(),
                i.line,
                i.text
            ));
        }
    }
    wrong.dedup();
    assert!(
        wrong.is_empty(),
        "{} imports against the layering:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
}

#[test]
fn no_files_import_each_other_in_a_circle() {
    let (_, imports) = imports();
    // A child using what its own folder's mod.rs declares is how Rust
    // modules are built, not a circle between peers.
    let parent_of = |f: &Path| -> Option<PathBuf> {
        let dir = if f.file_name().is_some_and(|n| n == "mod.rs") {
            f.parent()?.parent()?
        } else {
            f.parent()?
        };
        Some(dir.join("mod.rs"))
    };
    let mut graph: BTreeMap<PathBuf, BTreeSet<PathBuf>> = BTreeMap::new();
    let mut example: BTreeMap<(PathBuf, PathBuf), String> = BTreeMap::new();
    for i in &imports {
        if parent_of(&i.from).as_ref() == Some(&i.to) {
            continue;
        }
        graph
            .entry(i.from.clone())
            .or_default()
            .insert(i.to.clone());
        example
            .entry((i.from.clone(), i.to.clone()))
            .or_insert_with(|| format!("{}:{}: {}", i.from.display(), i.line, i.text));
    }
    // Tarjan's strongly connected components.
    let nodes: Vec<PathBuf> = graph
        .keys()
        .chain(graph.values().flatten())
        .cloned()
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let index_of: BTreeMap<&PathBuf, usize> =
        nodes.iter().enumerate().map(|(i, n)| (n, i)).collect();
    let adj: Vec<Vec<usize>> = nodes
        .iter()
        .map(|n| {
            graph
                .get(n)
                .map_or(Vec::new(), |s| s.iter().map(|t| index_of[t]).collect())
        })
        .collect();
    let mut t = Tarjan::new(adj);
    for v in 0..nodes.len() {
        if t.index[v] == usize::MAX {
            t.visit(v);
        }
    }
    let circles = t.circles;
    let report: Vec<String> = circles
        .iter()
        .map(|c| {
            let members: BTreeSet<&PathBuf> = c.iter().map(|&i| &nodes[i]).collect();
            let lines: Vec<&String> = example
                .iter()
                .filter(|((a, b), _)| members.contains(a) && members.contains(b))
                .map(|(_, l)| l)
                .collect();
            format!(
                "{}\n    {}",
                members
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(" ↔ "),
                lines
                    .iter()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join("\n    ")
            )
        })
        .collect();
    assert!(
        report.is_empty(),
        "files importing each other in a circle:\n{}",
        report.join("\n")
    );
}

/// Tarjan's algorithm: the strongly connected components of more than one
/// file are the circles.
struct Tarjan {
    adj: Vec<Vec<usize>>,
    index: Vec<usize>,
    low: Vec<usize>,
    on_stack: Vec<bool>,
    stack: Vec<usize>,
    counter: usize,
    circles: Vec<Vec<usize>>,
}

impl Tarjan {
    fn new(adj: Vec<Vec<usize>>) -> Tarjan {
        let n = adj.len();
        Tarjan {
            adj,
            index: vec![usize::MAX; n],
            low: vec![0; n],
            on_stack: vec![false; n],
            stack: Vec::new(),
            counter: 0,
            circles: Vec::new(),
        }
    }

    fn visit(&mut self, v: usize) {
        self.index[v] = self.counter;
        self.low[v] = self.counter;
        self.counter += 1;
        self.stack.push(v);
        self.on_stack[v] = true;
        for k in 0..self.adj[v].len() {
            let w = self.adj[v][k];
            if self.index[w] == usize::MAX {
                self.visit(w);
                self.low[v] = self.low[v].min(self.low[w]);
            } else if self.on_stack[w] {
                self.low[v] = self.low[v].min(self.index[w]);
            }
        }
        if self.low[v] == self.index[v] {
            let mut comp = Vec::new();
            while let Some(w) = self.stack.pop() {
                self.on_stack[w] = false;
                comp.push(w);
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                self.circles.push(comp);
            }
        }
    }
}
