//! The commands short of `build`: each asks a [`Session`] for the stage it
//! stops at, makes its plan and writes its files. Every output path is
//! checked against the inputs, the other outputs and what is there before
//! anything is read ([`check_outputs`]); everything is computed before
//! anything is written.

use super::{check_outputs, Inputs, Output, Session};
use crate::design::DesignReport;
use crate::error::{Error, Result};
use crate::formats::out::write_atomic;
use crate::formats::read;
use crate::formats::write::{flat_svg, gltf, plan_json, view as view_html};
use crate::network::RawNetwork;
use crate::plan::Plan;
use crate::structure;
use std::path::{Path, PathBuf};

/// What a command made: the session with every stage it ran, the plan (when
/// one was made) and the files written, in the order written.
#[derive(Debug)]
pub struct Done {
    /// The stages' outputs.
    pub session: Session,
    /// The plan written to plan.json, if any.
    pub plan: Option<Plan>,
    /// The files written.
    pub written: Vec<PathBuf>,
    /// What the command left out and why, one line each (printed as
    /// warnings).
    pub notes: Vec<String>,
}

/// `DIR/plan.json`.
fn plan_path(dir: &Path) -> PathBuf {
    dir.join("plan.json")
}

/// Write a plan's JSON atomically, refusing one with a NaN or infinite
/// number (JSON would write it as null).
pub fn write_plan(target: &Path, plan: &mut Plan) -> Result<()> {
    if let Some(field) = plan_json::first_non_finite(plan) {
        return Err(Error::output(
            target,
            format!("not written: {field} is not a finite number"),
        ));
    }
    write_atomic(target, plan_json::to_json(plan).as_bytes())
}

/// `lamella nodes`: nodes, frames and curvatures; `DIR/plan.json`.
pub fn nodes(inputs: Inputs, out: &Path) -> Result<Done> {
    let real = check_outputs(&[Output::Dir(out, &["plan.json"])], &inputs.files())?;
    let mut session = Session::open(inputs)?;
    let mut plan = session.plan(false)?;
    write_plan(&plan_path(&real[0]), &mut plan)?;
    Ok(Done {
        session,
        plan: Some(plan),
        written: vec![plan_path(out)],
        notes: Vec::new(),
    })
}

/// `lamella check`: the elastic check (and, when `suggest`, the largest
/// section that passes); `DIR/plan.json` when `out` is given.
pub fn check(inputs: Inputs, out: Option<&Path>, suggest: bool) -> Result<Done> {
    let target = match out {
        Some(dir) => {
            let real = check_outputs(&[Output::Dir(dir, &["plan.json"])], &inputs.files())?;
            Some((plan_path(&real[0]), plan_path(dir)))
        }
        None => None,
    };
    let mut session = Session::open(inputs)?;
    session.check(false)?;
    if suggest {
        session.suggestion()?;
    }
    let mut done = Done {
        session,
        plan: None,
        written: Vec::new(),
        notes: Vec::new(),
    };
    if let Some((real, shown)) = target {
        let mut plan = done.session.plan(false)?;
        write_plan(&real, &mut plan)?;
        done.plan = Some(plan);
        done.written.push(shown);
    }
    Ok(done)
}

pub use crate::formats::out::manifest::STRUCTURE_FILES;

/// The structure folder's files of an analysed frame: the OpenSeesPy
/// script and the model's JSON (marked `"$schema": "lamella-frame-model/1"`),
/// each under every characteristic load case and every combination.
pub fn structure_files(session: &Session, dir_shown: &Path) -> Result<[Vec<u8>; 2]> {
    let Some(report) = session.framed() else {
        return Err(Error::output(
            dir_shown,
            "internal: the frame was not analysed",
        ));
    };
    let model = &report.built.model;
    let sets: Vec<_> = report
        .cases
        .iter()
        .map(|(set, _)| structure::model::LoadSet::clone(set))
        .chain(report.combinations.iter().map(|c| c.loads.clone()))
        .collect();
    let script = structure::opensees::script(model, &sets)
        .map_err(|e| Error::output(&dir_shown.join(STRUCTURE_FILES[0]), e.to_string()))?;
    let json_path = dir_shown.join(STRUCTURE_FILES[1]);
    let json = structure::opensees::model_json(model, &sets)
        .map_err(|e| Error::output(&json_path, e.to_string()))?;
    let mut doc: serde_json::Value =
        serde_json::from_str(&json).map_err(|e| Error::output(&json_path, e.to_string()))?;
    if let Some(map) = doc.as_object_mut() {
        map.insert(
            "$schema".into(),
            serde_json::Value::String(FRAME_MODEL_SCHEMA.into()),
        );
    }
    let json = serde_json::to_string_pretty(&doc)
        .map_err(|e| Error::output(&json_path, e.to_string()))?
        + "\n";
    Ok([script.into_bytes(), json.into_bytes()])
}

/// The schema mark of `structure/model.json` (its first key).
pub const FRAME_MODEL_SCHEMA: &str = "lamella-frame-model/1";

/// `lamella frame`: the erected grid as a frame under a loads file (every
/// stage up to the parts, whose masses and blocks the frame takes);
/// `DIR/plan.json` with `structure`, `DIR/structure/opensees.py` and
/// `DIR/structure/model.json`. Everything is computed before anything is
/// written.
pub fn frame(inputs: Inputs, out: &Path) -> Result<Done> {
    let mut names = vec!["plan.json", crate::formats::out::manifest::STRUCTURE];
    names.extend(STRUCTURE_FILES);
    let real = check_outputs(&[Output::Dir(out, &names)], &inputs.files())?;
    let mut session = Session::open(inputs)?;
    session.frame()?;
    let mut plan = session.plan(false)?;
    let files = structure_files(&session, out)?;
    if let Some(field) = plan_json::first_non_finite(&mut plan) {
        return Err(Error::output(
            &plan_path(out),
            format!("not written: {field} is not a finite number"),
        ));
    }
    let mut written = Vec::new();
    for (name, bytes) in STRUCTURE_FILES.iter().zip(&files) {
        write_atomic(&real[0].join(name), bytes)?;
        written.push(out.join(name));
    }
    write_plan(&plan_path(&real[0]), &mut plan)?;
    written.push(plan_path(out));
    Ok(Done {
        session,
        plan: Some(plan),
        written,
        notes: Vec::new(),
    })
}

/// How far `lamella parts` goes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PartsGoal {
    /// The parts only (`lamella parts`).
    Parts,
    /// The parts nested onto stock (`lamella nest`), and each stock
    /// group's parts as a sparrow strip-packing instance beside `instance`
    /// when given ([`instance_path`]).
    Nest {
        /// Where to write the instance.
        instance: Option<PathBuf>,
    },
}

/// `lamella parts` and `lamella nest`: every part (and its nest);
/// `DIR/plan.json`, and the sparrow instances when asked for (one per
/// stock group, [`instance_path`]).
pub fn parts(inputs: Inputs, out: &Path, goal: &PartsGoal) -> Result<Done> {
    let instance = match goal {
        PartsGoal::Nest {
            instance: Some(file),
        } => Some(file.clone()),
        _ => None,
    };
    let mut outputs = vec![Output::Dir(out, &["plan.json"])];
    if let Some(file) = &instance {
        outputs.push(Output::File("instance", file));
    }
    let real = check_outputs(&outputs, &inputs.files())?;
    let input_files = inputs.clone();
    let mut session = Session::open(inputs)?;
    session.kit()?;
    if let PartsGoal::Nest { .. } = goal {
        session.nest()?;
    }
    // The instances' files are named by the groups, known now: checked
    // like the named file, still before anything is written.
    let mut instances: Vec<(PathBuf, PathBuf, String)> = Vec::new();
    if let Some(file) = &instance {
        let (Some(kit), Ok(profile)) = (session.made(), session.profile()) else {
            return Err(Error::output(file, "internal: no parts to export"));
        };
        let named: Vec<(PathBuf, String)> =
            crate::plan::sparrow::instances(&session.network().name, kit, profile)
                .iter()
                .map(|(group, inst)| {
                    let path = instance_path(file, group);
                    let text = crate::formats::write::sparrow::to_json(inst)
                        .map_err(|e| Error::output(&path, e))?;
                    Ok((path, text))
                })
                .collect::<Result<_>>()?;
        let mut outputs = vec![Output::Dir(out, &["plan.json"])];
        outputs.extend(named.iter().map(|(p, _)| Output::File("instance", p)));
        let real = check_outputs(&outputs, &input_files.files())?;
        instances = named
            .into_iter()
            .zip(real.into_iter().skip(1))
            .map(|((path, text), real)| (path, real, text))
            .collect();
    }
    let mut plan = session.plan(false)?;
    write_plan(&plan_path(&real[0]), &mut plan)?;
    let mut written = vec![plan_path(out)];
    for (path, real_file, text) in instances {
        write_atomic(&real_file, text.as_bytes())?;
        written.push(path);
    }
    Ok(Done {
        session,
        plan: Some(plan),
        written,
        notes: Vec::new(),
    })
}

/// The file of a stock group's instance for `--export-instance FILE`: the
/// group's name before FILE's extension (`kit.json` → `kit.washer-3.json`).
pub fn instance_path(file: &Path, group: &str) -> PathBuf {
    let stem = file
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = match file.extension() {
        Some(ext) => format!("{stem}.{group}.{}", ext.to_string_lossy()),
        None => format!("{stem}.{group}"),
    };
    file.with_file_name(name)
}

/// `lamella flat`: the flat assembly state; `DIR/plan.json` (with `flat`)
/// and `DIR/flat.svg`.
pub fn flat(inputs: Inputs, out: &Path) -> Result<Done> {
    let real = check_outputs(
        &[Output::Dir(out, &["plan.json", "flat.svg"])],
        &inputs.files(),
    )?;
    let mut session = Session::open(inputs)?;
    session.flat()?;
    session.check(false)?;
    let mut plan = session.plan(true)?;
    let title = format!(
        "{} — flat assembly layout ({}), mm",
        session.network().name,
        session.profile()?.name
    );
    let drawing = plan
        .flat
        .as_ref()
        .map(|f| &f.drawing)
        .cloned()
        .unwrap_or_default();
    let svg = flat_svg::to_svg(&drawing, &title);
    write_plan(&plan_path(&real[0]), &mut plan)?;
    write_atomic(&real[0].join("flat.svg"), svg.as_bytes())?;
    Ok(Done {
        session,
        plan: Some(plan),
        written: vec![plan_path(out), out.join("flat.svg")],
        notes: Vec::new(),
    })
}

/// The files of the 3D model: the GLB and the page that shows it.
pub const MODEL_FILES: [&str; 2] = ["model.glb", "view.html"];

/// The model of a plan with its shape: `model.glb` and `view.html`'s
/// bytes, in [`MODEL_FILES`]' order.
pub fn model_files(plan: &Plan, glb_path: &Path) -> Result<[Vec<u8>; 2]> {
    let glb = gltf::to_glb(plan).map_err(|e| Error::output(glb_path, e))?;
    let title = match &plan.profile {
        Some(p) => format!("{} — {}", plan.network.name, p.name),
        None => plan.network.name.clone(),
    };
    let html = view_html::to_html(&title, &glb).into_bytes();
    Ok([glb, html])
}

/// `lamella view`: the 3D model of the erected grid with its parts'
/// slots and hardware and the check's utilisation (and, when `flat`, the
/// flat state as a morph target); `DIR/model.glb` and `DIR/view.html`.
pub fn view(inputs: Inputs, out: &Path, flat: bool) -> Result<Done> {
    let real = check_outputs(&[Output::Dir(out, &MODEL_FILES)], &inputs.files())?;
    let mut session = Session::open(inputs)?;
    if flat {
        session.flat()?;
    }
    session.check(true)?;
    // The shape while the check's lamella lines are there (the parts take
    // them).
    let mut plan = session.plan(flat)?;
    session.add_shape(&mut plan)?;
    // The slots and the hardware come from the parts; a grid the profile
    // cannot make is still shown, without them; a big grid's model has
    // neither (its level of detail): no parts.
    let mut notes = Vec::new();
    if plan.nodes.len() <= crate::plan::ShapeOptions::BIG_NODES {
        match session.kit() {
            Ok(_) => {
                if let (Some(kit), Ok(profile)) = (session.made(), session.profile()) {
                    crate::plan::add_parts(&mut plan, kit, profile);
                }
            }
            Err(e) => notes.push(format!("no slots or hardware in the model: {e}")),
        }
    }
    let files = model_files(&plan, &out.join(MODEL_FILES[0]))?;
    let mut written = Vec::new();
    for (name, bytes) in MODEL_FILES.iter().zip(&files) {
        write_atomic(&real[0].join(name), bytes)?;
        written.push(out.join(name));
    }
    Ok(Done {
        session,
        plan: Some(plan),
        written,
        notes,
    })
}

/// Decimals of a traced network's coordinates (mm): 1e-6 mm, so rounding
/// (±5e-7 mm) stays far below what curvature between samples 25 mm apart
/// can resolve (4·5e-7 / 25² ≈ 3e-9 1/mm).
pub const COORDINATE_DECIMALS: usize = 6;

/// What `lamella trace` made.
#[derive(Debug)]
pub struct Traced {
    /// The network written.
    pub network: RawNetwork,
    /// Counts, notes, warnings and how each curve ended.
    pub report: DesignReport,
    /// The file written.
    pub written: PathBuf,
}

/// `lamella trace`: the network a trace spec describes, written as a
/// network file (`.json`, else YAML with normals).
pub fn trace(spec_path: &Path, out: &Path) -> Result<Traced> {
    let output = [Output::File("network", out)];
    let mut real = check_outputs(&output, &[("trace spec", spec_path)])?;
    let spec = read::trace_spec::load(spec_path)?;
    if let Some(mesh) = crate::design::mesh_source::mesh_path(&spec, spec_path) {
        real = check_outputs(&output, &[("trace spec", spec_path), ("mesh", &mesh)])?;
    }
    let (network, report) = crate::design::design(&spec, spec_path, &read::mesh::read_mesh)?;
    let comment = format!(
        "Traced by lamella {} from {}.\nRegenerate: lamella trace {} --out {}",
        env!("CARGO_PKG_VERSION"),
        spec_path
            .file_name()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default(),
        spec_path.display(),
        out.display()
    );
    let text = match out.extension().and_then(|e| e.to_str()) {
        Some("json") => read::network_file::to_json(&network, COORDINATE_DECIMALS),
        _ => read::network_file::to_yaml(&network, COORDINATE_DECIMALS, &comment),
    };
    write_atomic(&real[0], text.as_bytes())?;
    Ok(Traced {
        network,
        report,
        written: out.to_path_buf(),
    })
}
