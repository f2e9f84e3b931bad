//! Bad input through the real binary: `lamella nodes NETWORK --out DIR` must
//! exit with status 1, print exactly one `error: ` line on stderr that names
//! the file and what is wrong (and the curve or line where it applies), and
//! write nothing into DIR.

use crate::support::{lamella, lamella_command, root, scratch};
use std::path::Path;
use std::process::Output;

fn run_nodes(network: &Path, out: &Path) -> Output {
    lamella_command()
        .arg("nodes")
        .arg(network)
        .arg("--out")
        .arg(out)
        .output()
        .expect("run lamella")
}

/// Assert the one-line error contract and return the message.
fn assert_failed(output: &Output, network: &Path, out: &Path, fragments: &[&str]) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(
        output.status.code(),
        Some(1),
        "exit status {:?}, stderr: {stderr:?}",
        output.status
    );
    assert!(
        stderr.ends_with('\n'),
        "stderr must end with a newline: {stderr:?}"
    );
    assert_eq!(
        stderr.matches('\n').count(),
        1,
        "stderr must be exactly one line: {stderr:?}"
    );
    assert!(
        stderr.starts_with("error: "),
        "stderr must start with 'error: ': {stderr:?}"
    );
    let name = network.file_name().expect("file name").to_string_lossy();
    assert!(
        stderr.contains(&*name),
        "message must name the file {name}: {stderr:?}"
    );
    for f in fragments {
        assert!(stderr.contains(f), "message must contain {f:?}: {stderr:?}");
    }
    assert!(
        !out.join("plan.json").exists(),
        "no plan.json may be written on failure ({stderr:?})"
    );
    stderr
}

/// Write `content` to `file_name` in a scratch dir, run `lamella nodes`, and
/// check the failure. Returns the message.
fn expect_error(test: &str, file_name: &str, content: &str, fragments: &[&str]) -> String {
    let dir = scratch(test);
    let network = dir.join(file_name);
    std::fs::write(&network, content).expect("write input");
    let out = dir.join("out");
    let output = run_nodes(&network, &out);
    let msg = assert_failed(&output, &network, &out, fragments);
    let _ = std::fs::remove_dir_all(&dir);
    msg
}

/// Two crossing straight curves A00 and B00, plus whatever `extra` adds.
fn yaml_with(extra: &str) -> String {
    format!(
        "units: mm\ncurves:\n  - id: A00\n    family: A\n    points: [[0, -100, 0], [0, 0, 0], [0, 100, 0]]\n  \
         - id: B00\n    family: B\n    points: [[-100, 0, 0], [0, 0, 0], [100, 0, 0]]\n{extra}"
    )
}

#[test]
fn good_yaml_template_succeeds() {
    // The template used by the other cases is itself valid.
    let dir = scratch("good_yaml_template_succeeds");
    let network = dir.join("cross.yaml");
    std::fs::write(&network, yaml_with("")).expect("write input");
    let out = dir.join("out");
    let output = run_nodes(&network, &out);
    assert!(
        output.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(out.join("plan.json").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn empty_file() {
    expect_error("empty_file", "empty.yaml", "", &["empty"]);
    expect_error("empty_file_ws", "blank.json", "  \n\n", &["empty"]);
}

#[test]
fn broken_yaml() {
    let text = "units: mm\ncurves:\n  - id: A00\n    family: A\n    points: [[0, 0, 0], [1, 0, 0]\n  - id: B00\n";
    let msg = expect_error(
        "broken_yaml",
        "broken.yaml",
        text,
        &["invalid YAML", "line 6, column 3"],
    );
    // The location is reported once, by us, not repeated from the parser.
    assert_eq!(msg.matches("line").count(), 1, "{msg:?}");
}

#[test]
fn broken_json() {
    let text = "{\"units\": \"mm\",\n \"curves\": [\n  {\"id\": \"A00\", \"family\": \"A\", \"points\": [[0,0,0] [1,0,0]]}\n]}\n";
    let msg = expect_error(
        "broken_json",
        "broken.json",
        text,
        &["invalid JSON", "line 3, column"],
    );
    assert_eq!(msg.matches("line").count(), 1, "{msg:?}");
}

#[test]
fn missing_units() {
    let text = yaml_with("").replacen("units: mm\n", "", 1);
    expect_error(
        "missing_units",
        "nounits.yaml",
        &text,
        &["units", "missing"],
    );
}

#[test]
fn missing_units_json() {
    let text =
        "{\"curves\": [{\"id\": \"A00\", \"family\": \"A\", \"points\": [[0,0,0],[1,0,0]]}]}\n";
    expect_error(
        "missing_units_json",
        "nounits.json",
        text,
        &["units", "missing"],
    );
}

#[test]
fn unknown_unit() {
    let text = yaml_with("").replacen("units: mm", "units: furlong", 1);
    expect_error(
        "unknown_unit",
        "furlong.yaml",
        &text,
        &["units", "unknown unit", "furlong"],
    );
}

#[test]
fn unknown_family() {
    let text = yaml_with("  - id: C07\n    family: C\n    points: [[0, 0, 0], [1, 1, 0]]\n");
    expect_error(
        "unknown_family",
        "family.yaml",
        &text,
        &["curve C07", "unknown family", "'C'"],
    );
}

#[test]
fn duplicate_id() {
    let text = yaml_with("  - id: A00\n    family: A\n    points: [[50, -100, 0], [50, 100, 0]]\n");
    expect_error(
        "duplicate_id",
        "dup.yaml",
        &text,
        &["curve A00", "duplicate"],
    );
}

#[test]
fn too_few_points() {
    let text = yaml_with("  - id: A01\n    family: A\n    points: [[50, -100, 0]]\n");
    expect_error(
        "too_few_points",
        "few.yaml",
        &text,
        &["curve A01", "1 point", "at least 2"],
    );
    let text = yaml_with("  - id: A02\n    family: A\n    points: []\n");
    expect_error(
        "no_points",
        "none.yaml",
        &text,
        &["curve A02", "0 point", "at least 2"],
    );
}

#[test]
fn nan_coordinate() {
    let text =
        yaml_with("  - id: A01\n    family: A\n    points: [[50, -100, 0], [50, .nan, 0]]\n");
    expect_error(
        "nan_coordinate",
        "nan.yaml",
        &text,
        &["curve A01", "point 1", "NaN or infinite"],
    );
}

#[test]
fn infinite_coordinate() {
    let text = yaml_with("  - id: B01\n    family: B\n    points: [[.inf, 50, 0], [100, 50, 0]]\n");
    expect_error(
        "infinite_coordinate",
        "inf.yaml",
        &text,
        &["curve B01", "point 0", "NaN or infinite"],
    );
    let text =
        yaml_with("  - id: B02\n    family: B\n    points: [[-100, 60, 0], [100, 60, -.inf]]\n");
    expect_error(
        "neg_infinite_coordinate",
        "neginf.yaml",
        &text,
        &["curve B02", "point 1", "NaN or infinite"],
    );
}

#[test]
fn normals_count_mismatch() {
    let text = yaml_with(
        "  - id: A01\n    family: A\n    points: [[50, -100, 0], [50, 0, 0], [50, 100, 0]]\n    \
         normals: [[0, 0, 1], [0, 0, 1]]\n",
    );
    expect_error(
        "normals_count_mismatch",
        "normals.yaml",
        &text,
        &["curve A01", "2 normals for 3 points"],
    );
}

#[test]
fn zero_length_curve() {
    let text =
        yaml_with("  - id: B05\n    family: B\n    points: [[7, 7, 7], [7, 7, 7], [7, 7, 7]]\n");
    expect_error(
        "zero_length_curve",
        "zero.yaml",
        &text,
        &["curve B05", "zero-length"],
    );
}

#[test]
fn no_crossing() {
    let text =
        "units: mm\ncurves:\n  - id: A00\n    family: A\n    points: [[0, 0, 0], [1000, 0, 0]]\n  \
                - id: B00\n    family: B\n    points: [[0, 500, 0], [1000, 500, 0]]\n";
    expect_error(
        "no_crossing",
        "parallel.yaml",
        text,
        &["no A×B crossing", "tolerance"],
    );
}

#[test]
fn missing_family_b() {
    let text =
        "units: mm\ncurves:\n  - id: A00\n    family: A\n    points: [[0, 0, 0], [1000, 0, 0]]\n";
    expect_error(
        "missing_family_b",
        "onlya.yaml",
        text,
        &["no curve of family B"],
    );
}

#[test]
fn file_does_not_exist() {
    let dir = scratch("file_does_not_exist");
    let network = dir.join("no-such-network.yaml");
    let out = dir.join("out");
    let output = run_nodes(&network, &out);
    assert_failed(&output, &network, &out, &["no such file"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn unknown_extension() {
    expect_error(
        "unknown_extension",
        "network.txt",
        &yaml_with(""),
        &["unknown network format", "'.txt'"],
    );
}

#[test]
fn no_extension() {
    expect_error(
        "no_extension",
        "network",
        &yaml_with(""),
        &["unknown network format"],
    );
}

#[test]
fn obj_and_dxf_errors_are_one_line() {
    // OBJ: a polyline before any object name, reported with its line.
    let obj = "v 0 0 0\nv 1 0 0\nl 1 2\n";
    expect_error(
        "obj_no_name",
        "noname.obj",
        obj,
        &["line 3", "object or group name"],
    );
    // OBJ: a bad vertex index.
    let obj = "o A00\nv 0 0 0\nv 1 0 0\nl 1 7\n";
    expect_error(
        "obj_bad_index",
        "index.obj",
        obj,
        &["line 4", "out of range"],
    );
    // DXF: not a DXF at all.
    expect_error(
        "dxf_garbage",
        "garbage.dxf",
        "this is\nnot\na drawing\n",
        &["invalid DXF"],
    );
}

#[test]
fn failed_run_leaves_out_dir_untouched() {
    let dir = scratch("failed_run_leaves_out_dir_untouched");
    let network = dir.join("dup.yaml");
    let text = yaml_with("  - id: B00\n    family: B\n    points: [[-100, 50, 0], [100, 50, 0]]\n");
    std::fs::write(&network, text).expect("write input");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).expect("out dir");
    let keep = out.join("keep.txt");
    std::fs::write(&keep, "unrelated contents\n").expect("write keep.txt");
    let output = run_nodes(&network, &out);
    assert_failed(&output, &network, &out, &["curve B00", "duplicate"]);
    assert_eq!(
        std::fs::read_to_string(&keep).expect("keep.txt"),
        "unrelated contents\n"
    );
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .expect("read out dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        vec!["keep.txt".to_string()],
        "nothing else may appear in the out dir"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sample_network_succeeds() {
    let dir = scratch("sample_network_succeeds");
    let network = root().join("samples/hypar-small.yaml");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).expect("out dir");
    std::fs::write(out.join("keep.txt"), "x").expect("write keep.txt");
    let output = run_nodes(&network, &out);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "stderr: {stderr}");
    assert!(!stderr.contains("error"), "stderr: {stderr}");
    let text = std::fs::read_to_string(out.join("plan.json")).expect("plan.json written");
    let plan: serde_json::Value = serde_json::from_str(&text).expect("plan.json is JSON");
    assert_eq!(plan["schema"], "lamella-plan/3");
    assert_eq!(plan["units"], "mm");
    assert_eq!(plan["network"]["source"], "hypar-small.yaml");
    assert!(plan["summary"]["nodes"].as_u64().expect("node count") > 0);
    assert_eq!(
        std::fs::read_to_string(out.join("keep.txt")).expect("keep.txt"),
        "x"
    );
    // No temporary file is left behind by the atomic write.
    let leftovers: Vec<_> = std::fs::read_dir(&out)
        .expect("read out dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("lamella-tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_tolerance_is_a_usage_error_about_the_option() {
    let dir = scratch("bad_tolerance");
    let network = dir.join("cross.yaml");
    std::fs::write(&network, yaml_with("")).expect("write input");
    for t in ["NaN", "inf", "0", "-1", "1e9", "wide"] {
        let output = lamella_command()
            .arg("nodes")
            .arg(&network)
            .arg(format!("--tolerance={t}"))
            .arg("--out")
            .arg(dir.join("out"))
            .output()
            .expect("run lamella");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{t}: {stderr}");
        assert!(stderr.contains("--tolerance"), "{t}: {stderr}");
        assert!(
            !stderr.contains("cross.yaml"),
            "{t}: blames the file: {stderr}"
        );
    }
    assert!(!dir.join("out").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_output_that_is_an_input_is_refused() {
    let dir = scratch("output_is_input");
    let root = root();
    // trace SPEC --out SPEC used to overwrite the spec.
    let spec = dir.join("s.trace.yaml");
    let spec_text =
        std::fs::read_to_string(root.join("samples/hypar-small.trace.yaml")).expect("sample spec");
    std::fs::write(&spec, &spec_text).expect("write spec");
    let (code, _, stderr) = lamella(&[
        "trace".as_ref(),
        spec.as_os_str(),
        "--out".as_ref(),
        spec.as_os_str(),
    ]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("refusing to overwrite an input"),
        "{stderr}"
    );
    // ... also through a symlink and a hard link.
    #[cfg(unix)]
    {
        let link = dir.join("link.yaml");
        std::os::unix::fs::symlink(&spec, &link).expect("symlink");
        let hard = dir.join("hard.yaml");
        std::fs::hard_link(&spec, &hard).expect("hard link");
        for out in [&link, &hard] {
            let (code, _, stderr) = lamella(&[
                "trace".as_ref(),
                spec.as_os_str(),
                "--out".as_ref(),
                out.as_os_str(),
            ]);
            assert_eq!(code, Some(1), "{stderr}");
            assert!(stderr.contains("trace spec"), "{stderr}");
        }
    }
    assert_eq!(std::fs::read_to_string(&spec).expect("spec"), spec_text);
    // nodes / check --out DIR where DIR/plan.json is the network or the profile.
    let net_dir = dir.join("net");
    std::fs::create_dir_all(&net_dir).expect("dir");
    let network = net_dir.join("plan.json");
    let json = "{\"units\": \"mm\", \"curves\": [{\"id\": \"A\", \"family\": \"A\", \"points\": [[0, -1, 0], [0, 1, 0]]}, {\"id\": \"B\", \"family\": \"B\", \"points\": [[-1, 0, 0], [1, 0, 0]]}]}\n";
    std::fs::write(&network, json).expect("write network");
    let (code, _, stderr) = lamella(&[
        "nodes".as_ref(),
        network.as_os_str(),
        "--out".as_ref(),
        net_dir.as_os_str(),
    ]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("is the network"), "{stderr}");
    let profile_dir = dir.join("prof");
    std::fs::create_dir_all(&profile_dir).expect("dir");
    let profile = profile_dir.join("plan.json");
    std::fs::copy(root.join("profiles/steel-1.5.yaml"), &profile).expect("copy profile");
    let (code, _, stderr) = lamella(&[
        "check".as_ref(),
        network.as_os_str(),
        "--profile".as_ref(),
        profile.as_os_str(),
        "--out".as_ref(),
        profile_dir.as_os_str(),
    ]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("is the profile"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&network).expect("network"), json);
    assert_eq!(
        std::fs::read(&profile).expect("profile"),
        std::fs::read(root.join("profiles/steel-1.5.yaml")).expect("profile")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `nodes` without `--out` is a usage error (clap's exit 2), not a
/// silent `out/`; the help texts name every part kind and every kind of
/// surface a trace takes.
#[test]
fn nodes_needs_out_and_help_names_every_kind() {
    let (code, _, stderr) = crate::support::lamella(&["nodes", "samples/hypar-small.yaml"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("--out"), "{stderr}");
    let (_, parts, _) = crate::support::lamella(&["parts", "--help"]);
    for kind in [
        "lamellas",
        "shear blocks",
        "star washers",
        "studs",
        "splice plates",
        "edge strips",
    ] {
        assert!(parts.contains(kind), "parts --help lacks {kind}:\n{parts}");
    }
    let (_, trace, _) = crate::support::lamella(&["trace", "--help"]);
    for kind in [
        "enneper",
        "catenoid",
        "helicoid",
        "scherk",
        "schwarz_d",
        "hypar",
        "mesh",
        "minimal",
    ] {
        assert!(trace.contains(kind), "trace --help lacks {kind}:\n{trace}");
    }
}
