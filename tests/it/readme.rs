//! The README's examples are what the current binary prints: every
//! ```sh block of one `cargo run -- …` line followed by a plain ``` block
//! is run (in a scratch folder that sees the repository's samples and
//! profiles) and its standard output compared line by line with the
//! block; a line `...` in the block stands for any number of lines.

use crate::support::{lamella_in, root, scratch};

/// (command line, expected output lines), in README order: a plain ```
/// block right after a ```sh block of one `cargo run -- …` line, or after
/// a line ending "It prints:" that follows a ```sh block whose first line
/// is such a command (the quick start: `# …` comments dropped).
fn examples(readme: &str) -> Vec<(String, Vec<String>)> {
    let lines: Vec<&str> = readme.lines().collect();
    let mut out = Vec::new();
    let mut pending: Option<(String, bool)> = None;
    let mut i = 0;
    while i < lines.len() {
        if lines[i] == "```sh" {
            let end = i + 1 + lines[i + 1..].iter().position(|l| *l == "```").unwrap_or(0);
            let first = lines[i + 1].split(" #").next().unwrap_or("").trim();
            pending = first
                .strip_prefix("cargo run -- ")
                .map(|a| (a.to_string(), end == i + 2));
            i = end + 1;
            continue;
        }
        if lines[i] == "```" {
            let end = i + 1 + lines[i + 1..].iter().position(|l| *l == "```").unwrap_or(0);
            let prev = lines[..i].iter().rev().find(|l| !l.trim().is_empty());
            if let Some((cmd, single)) = pending.take() {
                let right_after = prev == Some(&"```");
                if (single && right_after) || prev.is_some_and(|l| l.ends_with("It prints:")) {
                    let want = lines[i + 1..end].iter().map(|s| s.to_string()).collect();
                    out.push((cmd, want));
                }
            }
            i = end + 1;
            continue;
        }
        i += 1;
    }
    out
}

/// Whether `got` matches `want`, where a `...` line matches any lines.
fn matches(want: &[String], got: &[&str]) -> bool {
    match want.split_first() {
        None => got.is_empty(),
        Some((w, rest)) if w == "..." => (0..=got.len()).any(|k| matches(rest, &got[k..])),
        Some((w, rest)) => got.first().is_some_and(|g| g == w) && matches(rest, &got[1..]),
    }
}

#[test]
fn readme_examples_are_what_the_binary_prints() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let examples = examples(&readme);
    assert!(examples.len() >= 5, "{} examples", examples.len());
    let dir = scratch("readme");
    for name in ["samples", "profiles"] {
        let link = dir.join(name);
        if std::fs::symlink_metadata(&link).is_err() {
            std::os::unix::fs::symlink(root().join(name), &link).expect("link");
        }
    }
    let mut wrong = Vec::new();
    for (cmd, want) in &examples {
        let args: Vec<&str> = cmd.split_whitespace().collect();
        let (_, stdout, stderr) = lamella_in(&dir, &args);
        let got: Vec<&str> = stdout.lines().collect();
        if !matches(want, &got) {
            wrong.push(format!(
                "`{cmd}`:\nREADME:\n{}\nbinary:\n{stdout}{stderr}",
                want.join("\n")
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n\n"));
}

/// The README's refused combinations: (sample, profile, why).
pub fn refused(readme: &str) -> Vec<(String, String, String)> {
    let start = readme
        .find("### Refused combinations")
        .expect("a refused combinations section");
    readme[start..]
        .lines()
        .skip_while(|l| !l.starts_with("| sample |"))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let cells: Vec<&str> = l.trim_matches('|').split('|').map(str::trim).collect();
            (
                cells[0].trim_matches('`').to_string(),
                cells[1].trim_matches('`').to_string(),
                cells[2].to_string(),
            )
        })
        .collect()
}

/// Every refused combination of the README is refused, for its reason.
#[test]
fn readme_refused_combinations_are_refused_as_said() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let rows = refused(&readme);
    assert!(!rows.is_empty());
    let dir = scratch("readme-refused");
    let mut wrong = Vec::new();
    for (sample, profile, why) in &rows {
        let out = dir.join(format!("{sample}-{profile}"));
        let (code, _, stderr) = crate::support::lamella(&[
            "build",
            &format!("samples/{sample}.yaml"),
            "--profile",
            &format!("profiles/{profile}.yaml"),
            "--out",
            out.to_str().expect("utf-8"),
            "--quiet",
        ]);
        if code != Some(3) || !stderr.contains(&format!("error: {why}: nothing written")) {
            wrong.push(format!("{sample} {profile}: exit {code:?}: {stderr}"));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The README's table of parts per sample and profile: every count is
/// what `lamella parts` makes, every "cannot" a refusal naming the strip.
#[test]
fn readme_parts_table_is_what_parts_makes() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let start = readme
        .find("| sample | steel-1.5 | poplar-ply-4 | beech-veneer |")
        .expect("the parts table");
    let profiles = ["steel-1.5", "poplar-ply-4", "beech-veneer"];
    let dir = scratch("readme-parts");
    let mut cells = 0;
    let mut wrong = Vec::new();
    for row in readme[start..]
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
    {
        let c: Vec<&str> = row.trim_matches('|').split('|').map(str::trim).collect();
        for (k, profile) in profiles.iter().enumerate() {
            let cell = c[k + 1];
            let (code, stdout, stderr) = crate::support::lamella(&[
                "parts",
                &format!("samples/{}.yaml", c[0]),
                "--profile",
                &format!("profiles/{profile}.yaml"),
                "--out",
                dir.join(format!("{}-{profile}", c[0]))
                    .to_str()
                    .expect("utf-8"),
            ]);
            let ok = if cell.starts_with("cannot") {
                code == Some(1)
                    && stderr.contains("no room for a")
                    && stderr.contains("splice plate")
            } else {
                let n = cell.trim_end_matches(" parts");
                code == Some(0) && stdout.contains(&format!(": {n} parts to make"))
            };
            if !ok {
                wrong.push(format!(
                    "{} {profile}: README {cell:?}, binary: {stdout}{stderr}",
                    c[0]
                ));
            }
            cells += 1;
        }
    }
    assert_eq!(cells, 21);
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
