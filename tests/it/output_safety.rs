//! Nothing lost, nothing let in: files lamella did not write are never
//! changed or deleted (a `sheets` link, a manifest naming paths outside
//! DIR, a file changed since lamella wrote it, a foreign plan.json under
//! every command), an `--out` link is followed and kept, devices and
//! FIFOs are never replaced, every output is checked before anything is
//! written, and a build killed at any step of its commit leaves the old
//! kit or the new one, whole, with the next build finishing the job.

use crate::support::{lamella_command, ok, root, scratch};
use lamella::formats::out::manifest::{is_lamella_name, MANIFEST};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;

/// `lamella build samples/hypar-small.yaml` with `profile` into `out`,
/// with `env` set: fast, and one sheet (beech-veneer) or two
/// (poplar-ply-4).
fn build_env(profile: &str, out: &Path, env: &[(&str, &str)]) -> Output {
    let mut c = lamella_command();
    c.args(["build", "samples/hypar-small.yaml", "--profile"])
        .arg(format!("profiles/{profile}.yaml"))
        .arg("--out")
        .arg(out)
        .arg("--quiet");
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("run lamella")
}

fn build(profile: &str, out: &Path) -> Output {
    build_env(profile, out, &[])
}

/// `lamella ARGS…` in the repository root.
fn run(args: &[&str]) -> Output {
    lamella_command().args(args).output().expect("run lamella")
}

#[track_caller]
fn refused(o: &Output, what: &str) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains(what), "{err}");
    err
}

/// Every file under `dir` (links not followed) with its bytes; a link
/// as `-> target`.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(list) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in list.flatten() {
            let p = e.path();
            let rel = p
                .strip_prefix(dir)
                .expect("rel")
                .to_string_lossy()
                .into_owned();
            let meta = std::fs::symlink_metadata(&p).expect("meta");
            if meta.file_type().is_symlink() {
                let to = std::fs::read_link(&p).expect("link");
                out.insert(rel, format!("-> {}", to.display()).into_bytes());
            } else if meta.is_dir() {
                stack.push(p);
            } else {
                out.insert(rel, std::fs::read(&p).expect("read"));
            }
        }
    }
    out
}

/// Lamella's files of a snapshot (the manifest and the names it writes).
fn kit_of(snap: &BTreeMap<String, Vec<u8>>) -> BTreeMap<String, Vec<u8>> {
    snap.iter()
        .filter(|(k, _)| k.as_str() == MANIFEST || is_lamella_name(k))
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect()
}

/// The user's files of a snapshot.
fn users_of(snap: &BTreeMap<String, Vec<u8>>) -> BTreeMap<String, Vec<u8>> {
    snap.iter()
        .filter(|(k, _)| k.as_str() != MANIFEST && !is_lamella_name(k))
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect()
}

fn restore(dir: &Path, files: &BTreeMap<String, Vec<u8>>) {
    for (rel, bytes) in files {
        let p = dir.join(rel);
        std::fs::create_dir_all(p.parent().expect("parent")).expect("mkdir");
        std::fs::write(&p, bytes).expect("write");
    }
}

fn names_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("ls")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[cfg(unix)]
fn symlink(to: impl AsRef<Path>, at: &Path) {
    std::os::unix::fs::symlink(to, at).expect("symlink");
}

#[cfg(unix)]
fn mkfifo(at: &Path) {
    let o = std::process::Command::new("mkfifo")
        .arg(at)
        .output()
        .expect("mkfifo");
    assert!(o.status.success());
}

#[cfg(unix)]
fn is_fifo(p: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_fifo())
}

/// `DIR/sheets` a link to another folder: the build stops, and the
/// user's sheet there is not overwritten.
#[cfg(unix)]
#[test]
fn a_sheets_link_is_never_written_through() {
    let dir = scratch("sheets-link");
    let other = dir.join("other");
    std::fs::create_dir_all(&other).expect("mkdir");
    std::fs::write(other.join("sheet-001.dxf"), "mine").expect("write");
    std::fs::write(other.join("sheet-001.svg"), "mine too").expect("write");
    let out = dir.join("kit");
    std::fs::create_dir_all(&out).expect("mkdir");
    symlink("../other", &out.join("sheets"));
    refused(&build("beech-veneer", &out), "symbolic link");
    assert_eq!(
        std::fs::read(other.join("sheet-001.dxf")).expect("kept"),
        b"mine"
    );
    assert_eq!(
        std::fs::read(other.join("sheet-001.svg")).expect("kept"),
        b"mine too"
    );
    // The same with an earlier kit in DIR (foreign files checked at the commit).
    let out2 = dir.join("kit2");
    ok(&build("beech-veneer", &out2));
    std::fs::remove_dir_all(out2.join("sheets")).expect("rm");
    symlink("../other", &out2.join("sheets"));
    refused(&build("beech-veneer", &out2), "symbolic link");
    assert_eq!(
        std::fs::read(other.join("sheet-001.dxf")).expect("kept"),
        b"mine"
    );
    assert_eq!(names_in(&dir), ["kit", "kit2", "other"]);
}

/// A manifest is input: lines naming paths outside DIR delete nothing,
/// and a file changed since lamella wrote it is the user's.
#[test]
fn a_manifest_vouches_only_for_lamellas_unchanged_files() {
    let dir = scratch("manifest");
    let out = dir.join("kit");
    ok(&build("poplar-ply-4", &out));
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, "mine").expect("write");
    let abs_victim = dir.join("abs-victim.txt");
    std::fs::write(&abs_victim, "mine").expect("write");
    let mut manifest = std::fs::read_to_string(out.join(MANIFEST)).expect("manifest");
    for p in [
        "../victim.txt".to_string(),
        abs_victim.display().to_string(),
    ] {
        manifest.push_str(&format!("4 {:08x} {p}\n", crc32fast::hash(b"mine")));
        manifest.push_str(&format!("{p}\n"));
    }
    std::fs::write(out.join(MANIFEST), manifest).expect("write");
    // A sheet the next build does not make, edited by the user.
    std::fs::write(
        out.join("sheets/lamella-4-sheet-002.svg"),
        "my notes on sheet 2",
    )
    .expect("edit");
    // A user's file named as lamella names its sheets.
    std::fs::write(out.join("sheets/lamella-0.6-sheet-009.dxf"), "mine").expect("write");
    ok(&build("beech-veneer", &out));
    assert_eq!(std::fs::read(&victim).expect("kept"), b"mine");
    assert_eq!(std::fs::read(&abs_victim).expect("kept"), b"mine");
    assert_eq!(
        std::fs::read(out.join("sheets/lamella-4-sheet-002.svg")).expect("kept"),
        b"my notes on sheet 2"
    );
    assert_eq!(
        std::fs::read(out.join("sheets/lamella-0.6-sheet-009.dxf")).expect("kept"),
        b"mine"
    );
    assert!(
        !out.join("sheets/lamella-4-sheet-002.dxf").exists(),
        "lamella's own stale sheet is removed"
    );
    // A file the new kit writes, changed since: refused, and kept.
    std::fs::write(out.join("sheets/lamella-0.6-sheet-001.dxf"), "edited").expect("edit");
    refused(&build("beech-veneer", &out), "not written by lamella");
    assert_eq!(
        std::fs::read(out.join("sheets/lamella-0.6-sheet-001.dxf")).expect("kept"),
        b"edited"
    );
    assert_eq!(names_in(&dir), ["abs-victim.txt", "kit", "victim.txt"]);
}

/// `--out` a link to an earlier kit: followed; the link stays a link and
/// the folder it points to holds the new kit.
#[cfg(unix)]
#[test]
fn an_out_link_is_followed_and_kept() {
    let dir = scratch("out-link");
    let fresh = dir.join("fresh");
    ok(&build("beech-veneer", &fresh));
    let want = snapshot(&fresh);
    let kits = dir.join("kits");
    let v1 = kits.join("v1");
    ok(&build("poplar-ply-4", &v1));
    let link = dir.join("kit");
    symlink("kits/v1", &link);
    ok(&build("beech-veneer", &link));
    assert_eq!(
        std::fs::read_link(&link).expect("still a link"),
        Path::new("kits/v1")
    );
    assert!(snapshot(&v1) == want, "the linked folder holds the new kit");
    assert_eq!(names_in(&dir), ["fresh", "kit", "kits"]);
    assert_eq!(names_in(&kits), ["v1"]);
    // A link to nowhere is not followed.
    let dangling = dir.join("nowhere");
    symlink("kits/v2", &dangling);
    refused(&build("beech-veneer", &dangling), "does not exist");
    assert!(!kits.join("v2").exists());
}

/// Outputs onto a FIFO or a device (through a link: the test must not
/// risk the real /dev/null) are refused, and nothing is replaced.
#[cfg(unix)]
#[test]
fn devices_and_fifos_are_never_replaced() {
    let dir = scratch("devices");
    let fifo = dir.join("fifo");
    mkfifo(&fifo);
    let null = dir.join("null");
    symlink("/dev/null", &null);
    let out = dir.join("kit");
    let (f, n, o) = (
        fifo.to_string_lossy().into_owned(),
        null.to_string_lossy().into_owned(),
        out.to_string_lossy().into_owned(),
    );
    for target in [&f, &n] {
        let nest = run(&[
            "nest",
            "samples/hypar-small.yaml",
            "--profile",
            "profiles/beech-veneer.yaml",
            "--out",
            &o,
            "--export-instance",
            target,
        ]);
        refused(&nest, "not a regular file");
        let trace = run(&["trace", "samples/hypar-small.trace.yaml", "--out", target]);
        refused(&trace, "not a regular file");
    }
    assert!(is_fifo(&fifo), "the FIFO is still a FIFO");
    assert_eq!(
        std::fs::read_link(&null).expect("still a link"),
        Path::new("/dev/null")
    );
    assert!(!out.exists(), "nothing written");
    // A FIFO or a link inside DIR where lamella writes a file.
    std::fs::create_dir_all(&out).expect("mkdir");
    mkfifo(&out.join("plan.json"));
    refused(
        &run(&["nodes", "samples/hypar-small.yaml", "--out", &o]),
        "not a regular file",
    );
    assert!(is_fifo(&out.join("plan.json")));
    std::fs::remove_file(out.join("plan.json")).expect("rm");
    symlink("../elsewhere.json", &out.join("plan.json"));
    refused(
        &run(&["nodes", "samples/hypar-small.yaml", "--out", &o]),
        "symbolic link",
    );
    assert!(!dir.join("elsewhere.json").exists());
    assert_eq!(names_in(&out), ["plan.json"]);
}

/// Every output is checked against the others before anything is
/// written: an instance onto a folder, onto the plan the command writes,
/// or onto the output folder.
#[test]
fn every_output_is_checked_before_anything_is_written() {
    let dir = scratch("all-outputs");
    let out = dir.join("kit");
    let o = out.to_string_lossy().into_owned();
    let nest = |instance: &Path| {
        run(&[
            "nest",
            "samples/hypar-small.yaml",
            "--profile",
            "profiles/beech-veneer.yaml",
            "--out",
            &o,
            "--export-instance",
            &instance.to_string_lossy(),
        ])
    };
    let folder = dir.join("folder");
    std::fs::create_dir_all(&folder).expect("mkdir");
    refused(&nest(&folder), "is a directory");
    assert!(!out.exists(), "no plan.json written");
    refused(
        &nest(&out.join("plan.json")),
        "is also where this command writes",
    );
    assert!(!out.exists());
    refused(
        &nest(&out.join("..").join("kit").join("plan.json")),
        "is also where this command writes",
    );
    refused(&nest(&out), "is also where this command writes");
    assert!(!out.exists());
    // The same with the folder there.
    std::fs::create_dir_all(&out).expect("mkdir");
    refused(
        &nest(&out.join("plan.json")),
        "is also where this command writes",
    );
    refused(&nest(&out), "is a directory");
    assert!(names_in(&out).is_empty());
    // A group's instance file (named by the group beside the one named)
    // is checked too, before anything is written.
    std::fs::create_dir_all(out.join("x.lamella-0.6.json")).expect("mkdir");
    refused(&nest(&out.join("x.json")), "is a directory");
    assert_eq!(names_in(&out), ["x.lamella-0.6.json"]);
    std::fs::remove_dir(out.join("x.lamella-0.6.json")).expect("rmdir");
    // Beside the plan is fine.
    ok(&nest(&out.join("instance.json")));
    assert_eq!(names_in(&out), ["instance.lamella-0.6.json", "plan.json"]);
    assert_eq!(names_in(&dir), ["folder", "kit"]);
}

/// A plan.json lamella did not write stops every command that writes
/// one; lamella's own (by schema) is written over by every command.
#[test]
fn a_foreign_plan_is_refused_by_every_command() {
    let dir = scratch("foreign-plan");
    let out = dir.join("kit");
    std::fs::create_dir_all(&out).expect("mkdir");
    let plan = out.join("plan.json");
    let o = out.to_string_lossy().into_owned();
    let with_profile = |cmd: &'static str| -> Vec<String> {
        [
            cmd,
            "samples/hypar-small.yaml",
            "--profile",
            "profiles/beech-veneer.yaml",
            "--out",
            &o,
        ]
        .map(String::from)
        .to_vec()
    };
    let commands: Vec<Vec<String>> = vec![
        ["nodes", "samples/hypar-small.yaml", "--out", &o]
            .map(String::from)
            .to_vec(),
        with_profile("check"),
        with_profile("parts"),
        with_profile("nest"),
        with_profile("flat"),
        with_profile("build"),
    ];
    std::fs::write(&plan, "{\"mine\": true}\n").expect("write");
    for args in &commands {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&run(&args), "not written by lamella");
        assert_eq!(std::fs::read(&plan).expect("kept"), b"{\"mine\": true}\n");
    }
    std::fs::remove_file(&plan).expect("rm");
    for args in &commands {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        ok(&run(&args));
    }
    // flat.svg: lamella's flat layout is written over, a foreign one not.
    let flat = with_profile("flat");
    let flat: Vec<&str> = flat.iter().map(String::as_str).collect();
    ok(&run(&flat));
    std::fs::write(out.join("flat.svg"), "<svg/>").expect("write");
    refused(&run(&flat), "not written by lamella");
    assert_eq!(
        std::fs::read(out.join("flat.svg")).expect("kept"),
        b"<svg/>"
    );
}

/// One kill scenario: `old` (a profile, or none) in DIR with or without
/// the user's files, rebuilt with `new`; killed before each step of the
/// commit in turn until the build finishes. After each kill DIR holds the
/// old kit or the new one, whole (or, without the exchange, no DIR and the
/// old kit beside it), every user's file is in DIR or in the staging
/// folder; the next build finishes: the new kit and every user's file in
/// DIR, nothing else beside it. Returns the number of steps.
fn kill_at_every_step(
    name: &str,
    old: Option<&str>,
    new: &str,
    user: bool,
    exchange: bool,
) -> usize {
    let base = scratch(name);
    let reference = |profile: &str| {
        let d = base.join(format!("ref-{profile}"));
        ok(&build(profile, &d));
        snapshot(&d)
    };
    let new_kit = reference(new);
    let old_kit = old.map(reference).unwrap_or_default();
    let mut users = BTreeMap::new();
    if user {
        users.insert("notes.txt".to_string(), b"mine".to_vec());
        users.insert("photos/a.txt".to_string(), b"a photo".to_vec());
        if old.is_some() {
            users.insert("sheets/extra.dxf".to_string(), b"my sheet".to_vec());
        }
    }
    let mut env = vec![];
    if !exchange {
        env.push(("LAMELLA_NO_RENAME_EXCHANGE", "1"));
    }
    for n in 1.. {
        let parent = base.join(format!("n{n}"));
        let out = parent.join("kit");
        if old.is_some() || user {
            std::fs::create_dir_all(&out).expect("mkdir");
        }
        restore(&out, &old_kit);
        restore(&out, &users);
        let step = n.to_string();
        let mut env_n = env.clone();
        env_n.push(("LAMELLA_KILL_AT_STEP", &step));
        let o = build_env(new, &out, &env_n);
        if o.status.success() {
            assert!(n > 3, "{name}: only {} steps", n - 1);
            let snap = snapshot(&out);
            assert!(kit_of(&snap) == new_kit, "{name}: finished, the new kit");
            assert!(
                users_of(&snap) == users,
                "{name}: finished, the user's files"
            );
            assert_eq!(names_in(&parent), ["kit"], "{name}");
            return n - 1;
        }
        assert_eq!(
            o.status.code(),
            None,
            "{name}, step {n}: killed, not failed: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let snap = snapshot(&out);
        let kit = kit_of(&snap);
        if out.exists() {
            assert!(
                kit == old_kit || kit == new_kit,
                "{name}, killed at step {n}: DIR holds {:?}",
                kit.keys().collect::<Vec<_>>()
            );
        } else {
            assert!(old.is_none() || !exchange, "{name}, step {n}: DIR gone");
            if old.is_some() {
                // Set aside between the two renames.
                let aside = names_in(&parent)
                    .into_iter()
                    .find(|s| s.ends_with("-old"))
                    .expect("the old kit set aside");
                assert!(kit_of(&snapshot(&parent.join(aside))) == old_kit);
            }
        }
        // Every user's file is in DIR or in the staging folder.
        let beside: Vec<PathBuf> = names_in(&parent)
            .into_iter()
            .filter(|s| s != "kit")
            .map(|s| parent.join(s))
            .collect();
        for (rel, bytes) in &users {
            let found = std::iter::once(&out)
                .chain(&beside)
                .any(|d| std::fs::read(d.join(rel)).is_ok_and(|b| &b == bytes));
            assert!(found, "{name}, step {n}: {rel} lost");
        }
        // The next build finishes what the killed one left.
        ok(&build(new, &out));
        let snap = snapshot(&out);
        assert!(kit_of(&snap) == new_kit, "{name}, after step {n}: new kit");
        assert!(
            users_of(&snap) == users,
            "{name}, after step {n}: user's files {:?}",
            users_of(&snap).keys().collect::<Vec<_>>()
        );
        assert_eq!(names_in(&parent), ["kit"], "{name}, after step {n}");
    }
    unreachable!()
}

#[test]
fn a_kill_at_any_step_leaves_a_whole_kit_of_lamellas_files() {
    kill_at_every_step(
        "kill-lamella-only",
        Some("poplar-ply-4"),
        "beech-veneer",
        false,
        true,
    );
}

#[test]
fn a_kill_at_any_step_leaves_a_whole_kit_and_the_users_files() {
    let steps = kill_at_every_step(
        "kill-user",
        Some("beech-veneer"),
        "poplar-ply-4",
        true,
        true,
    );
    // The marker, three entries carried, the exchange, the old kit's
    // files (4 + 2 sheets + manifest) and folders, the journal.
    assert!(steps >= 12, "{steps} steps");
}

#[test]
fn a_kill_at_any_step_of_a_first_build_leaves_no_kit_or_the_kit() {
    kill_at_every_step("kill-new", None, "beech-veneer", false, true);
    kill_at_every_step("kill-new-user", None, "beech-veneer", true, true);
}

#[test]
fn a_kill_between_the_two_renames_is_undone_by_the_next_build() {
    kill_at_every_step(
        "kill-no-exchange",
        Some("poplar-ply-4"),
        "beech-veneer",
        true,
        false,
    );
}

/// `--out .`: a build replaces its output folder by a new one, which would
/// leave the shell in the old one; refused, and nothing written.
#[test]
fn the_current_directory_is_not_a_kit_folder() {
    let dir = scratch("cwd");
    let o = lamella_command()
        .current_dir(&dir)
        .args([
            "build",
            &root().join("samples/hypar-small.yaml").to_string_lossy(),
            "--profile",
            &root().join("profiles/beech-veneer.yaml").to_string_lossy(),
            "--out",
            ".",
            "--quiet",
        ])
        .output()
        .expect("run");
    refused(&o, "is the current directory");
    assert!(names_in(&dir).is_empty());
}
