//! The pipeline: the one place the stages are put together.
//!
//! A [`Session`] reads its inputs once (the profile, then the network) and
//! runs each stage once, on demand, in the order the stages need one
//! another: analysis → check → (flat state) → parts → nest. Every command
//! asks the session for the stage it stops at, makes its plan from what
//! has run ([`Session::plan`]) and writes its files ([`commands`]); `lamella
//! build` is the session run to the end ([`build`]).
//!
//! Errors have one kind per failure: a bad input file is
//! [`Error::Input`], a network that cannot be analysed
//! [`Error::Network`], a part the profile cannot make
//! [`Error::Fabrication`], and an output that cannot be written as asked
//! (an input in its place, a number that is not finite, a foreign file)
//! [`Error::Output`].

pub mod build;
pub mod commands;

use crate::analysis::lines::NetworkLines;
use crate::analysis::{analyze, Analysis, AnalysisOptions};
use crate::check::{CheckReport, Suggestion};
use crate::error::{Error, Result};
use crate::fabricate::Kit;
use crate::flat::{FlatProblem, FlatState};
use crate::formats::out;
use crate::formats::read::{self, ReadOptions};
use crate::loads::LoadSpec;
use crate::nest::Nest;
use crate::network::Network;
use crate::plan::model::{Checked, Model};
use crate::plan::structure::PlanStructure;
use crate::plan::Plan;
use crate::profile::Profile;
use crate::structure::build::FrameOptions;
use crate::structure::stage::FrameReport;
use std::path::{Path, PathBuf};

/// What a session reads.
#[derive(Debug, Clone, Default)]
pub struct Inputs {
    /// The network file (`.yaml`, `.yml`, `.json`, `.obj`, `.dxf`).
    pub network: PathBuf,
    /// The material profile, for every stage after the analysis.
    pub profile: Option<PathBuf>,
    /// Units, tolerance and precision of the network file.
    pub read: ReadOptions,
    /// Size each slot from its node's rotation between the flat state and
    /// the erected one instead of the profile's blanket tolerance.
    pub slots_from_flat: bool,
    /// The loads file (supports, load cases, combinations): the erected
    /// grid is analysed as a frame ([`Session::frame`]).
    pub loads: Option<PathBuf>,
}

impl Inputs {
    /// The input files, named as an error names them (`network`, `profile`).
    pub fn files(&self) -> Vec<(&'static str, &Path)> {
        let mut v = vec![("network", self.network.as_path())];
        if let Some(p) = &self.profile {
            v.push(("profile", p.as_path()));
        }
        if let Some(p) = &self.loads {
            v.push(("loads file", p.as_path()));
        }
        v
    }
}

/// One run of the pipeline: the inputs read once and every stage's output,
/// each computed the first time it is asked for.
#[derive(Debug)]
pub struct Session {
    inputs: Inputs,
    profile: Option<Profile>,
    /// The profile in its file's form, for plan.json's `resolved`.
    resolved: serde_json::Value,
    network: Network,
    analysis: Option<Analysis>,
    check: Option<CheckReport>,
    lines: Option<NetworkLines>,
    suggestion: Option<Suggestion>,
    flat: Option<(FlatProblem, FlatState)>,
    kit: Option<Kit>,
    nest: Option<Nest>,
    loads: Option<LoadSpec>,
    frame: Option<FrameReport>,
}

/// A stage a session has not run and cannot run on its own (a program
/// error, not a user's).
fn not_run(inputs: &Inputs, what: &str) -> Error {
    Error::output(
        &inputs.network,
        format!("internal: {what} was not computed"),
    )
}

impl Session {
    /// Read the profile (when given), then the network.
    pub fn open(inputs: Inputs) -> Result<Session> {
        let profile = match &inputs.profile {
            Some(p) => Some(read::profile_file::load(p)?),
            None => None,
        };
        let loads = match &inputs.loads {
            Some(p) => Some(read::loads_file::load(p)?),
            None => None,
        };
        let network = read::read_network(&inputs.network, inputs.read)?;
        let resolved = profile
            .as_ref()
            .and_then(|p| serde_json::to_value(read::profile_file::ProfileFile::from(p)).ok())
            .unwrap_or(serde_json::Value::Null);
        Ok(Session {
            inputs,
            profile,
            resolved,
            network,
            analysis: None,
            check: None,
            lines: None,
            suggestion: None,
            flat: None,
            kit: None,
            nest: None,
            loads,
            frame: None,
        })
    }

    /// What the session read.
    pub fn inputs(&self) -> &Inputs {
        &self.inputs
    }

    /// The network, validated, in mm.
    pub fn network(&self) -> &Network {
        &self.network
    }

    /// The profile; an error when the session was opened without one.
    pub fn profile(&self) -> Result<&Profile> {
        self.profile
            .as_ref()
            .ok_or_else(|| not_run(&self.inputs, "the profile"))
    }

    /// Nodes, frames, curvatures and node-to-node lengths of every strip.
    pub fn analysis(&mut self) -> Result<&Analysis> {
        if self.analysis.is_none() {
            let opts = AnalysisOptions::for_network(&self.network);
            self.analysis = Some(analyze(&self.network, opts)?);
        }
        self.analysis
            .as_ref()
            .ok_or_else(|| not_run(&self.inputs, "the analysis"))
    }

    /// The analysis, once it has run.
    pub fn analysed(&self) -> Option<&Analysis> {
        self.analysis.as_ref()
    }

    /// The elastic check of every A and B strip against the profile. The
    /// lamella lines it integrates are kept for the parts when
    /// `for_parts` (they are dropped as each strip's parts are made).
    pub fn check(&mut self, for_parts: bool) -> Result<&CheckReport> {
        if self.check.is_none() {
            self.analysis()?;
            let (Some(an), Some(profile)) = (&self.analysis, &self.profile) else {
                return Err(not_run(&self.inputs, "the profile"));
            };
            let (report, lines) = crate::check::check(an, profile, for_parts);
            self.check = Some(report);
            self.lines = for_parts.then_some(lines);
        }
        self.check
            .as_ref()
            .ok_or_else(|| not_run(&self.inputs, "the check"))
    }

    /// The check, once it has run.
    pub fn checked(&self) -> Option<&CheckReport> {
        self.check.as_ref()
    }

    /// The largest lamella section at which every strip passes
    /// (`check --suggest`).
    pub fn suggestion(&mut self) -> Result<&Suggestion> {
        if self.suggestion.is_none() {
            self.analysis()?;
            let (Some(an), Some(profile)) = (&self.analysis, &self.profile) else {
                return Err(not_run(&self.inputs, "the profile"));
            };
            self.suggestion = Some(crate::check::suggest(an, profile));
        }
        self.suggestion
            .as_ref()
            .ok_or_else(|| not_run(&self.inputs, "the suggestion"))
    }

    /// The suggestion, once it has run.
    pub fn suggested(&self) -> Option<&Suggestion> {
        self.suggestion.as_ref()
    }

    /// The flat assembly state: the problem (A×B nodes, strips, stiffness)
    /// and its solution. An error for a two-level profile (no flat state).
    pub fn flat(&mut self) -> Result<(&FlatProblem, &FlatState)> {
        if self.flat.is_none() {
            self.analysis()?;
            let (Some(an), Some(profile)) = (&self.analysis, &self.profile) else {
                return Err(not_run(&self.inputs, "the profile"));
            };
            let problem = crate::flat::problem(an, profile)?;
            let state = crate::flat::solve(&problem);
            self.flat = Some((problem, state));
        }
        self.flat
            .as_ref()
            .map(|(p, s)| (p, s))
            .ok_or_else(|| not_run(&self.inputs, "the flat state"))
    }

    /// The flat state, once solved.
    pub fn flat_state(&self) -> Option<(&FlatProblem, &FlatState)> {
        self.flat.as_ref().map(|(p, s)| (p, s))
    }

    /// Every part to cut: after the flat state when slots are sized from
    /// it, then the check (whose lamella lines the parts are carried onto).
    pub fn kit(&mut self) -> Result<&Kit> {
        if self.kit.is_none() {
            let rotations = if self.inputs.slots_from_flat {
                Some(self.flat()?.1.rotations())
            } else {
                None
            };
            if self.check.is_none() {
                self.check(true)?;
            }
            let lines = self.lines.take().unwrap_or_default();
            let (Some(an), Some(profile)) = (&self.analysis, &self.profile) else {
                return Err(not_run(&self.inputs, "the profile"));
            };
            self.kit = Some(crate::fabricate::fabricate(
                &self.network,
                an,
                profile,
                rotations.as_ref(),
                lines,
            )?);
        }
        self.kit
            .as_ref()
            .ok_or_else(|| not_run(&self.inputs, "the parts"))
    }

    /// The parts, once they are made.
    pub fn made(&self) -> Option<&Kit> {
        self.kit.as_ref()
    }

    /// The erected grid as a frame under the loads file: built from the
    /// analysis and the kit, supported, loaded, analysed and judged
    /// ([`crate::structure::stage::run`]). Runs the parts first.
    pub fn frame(&mut self) -> Result<&FrameReport> {
        if self.frame.is_none() {
            self.kit()?;
            let (Some(an), Some(profile), Some(kit), Some(spec)) =
                (&self.analysis, &self.profile, &self.kit, &self.loads)
            else {
                return Err(not_run(&self.inputs, "the loads file"));
            };
            let report = crate::structure::stage::run(
                &self.network,
                an,
                profile,
                kit,
                spec,
                &FrameOptions::default(),
            )?;
            self.frame = Some(report);
        }
        self.frame
            .as_ref()
            .ok_or_else(|| not_run(&self.inputs, "the frame"))
    }

    /// Add the bracing cables' eye plates to the kit, once the frame is
    /// analysed and braced ([`Kit::add_eye_plates`]): they are cut and
    /// nested with the rest, and their bolts are longer. The frame's
    /// self-weight was taken without them.
    pub fn add_eye_plates(&mut self) -> Result<()> {
        let (Some(report), Some(kit), Some(profile)) =
            (&self.frame, self.kit.as_mut(), &self.profile)
        else {
            return Ok(());
        };
        if let Some(b) = &report.bracing {
            kit.add_eye_plates(profile, &b.design.cable_ends())?;
        }
        Ok(())
    }

    /// The frame's report, once analysed.
    pub fn framed(&self) -> Option<&FrameReport> {
        self.frame.as_ref()
    }

    /// The frame's one-line verdict ([`FrameReport::verdict_line`], strips
    /// by their ids), once analysed.
    pub fn frame_verdict(&self) -> Option<String> {
        let net = &self.network;
        self.frame.as_ref().map(|r| {
            r.verdict_line(|c| {
                net.curves
                    .get(c)
                    .map_or_else(|| format!("strip {c}"), |k| k.id.clone())
            })
        })
    }

    /// plan.json's `structure` of the frame, once analysed.
    pub fn plan_structure(&self) -> Option<PlanStructure> {
        let report = self.frame.as_ref()?;
        let loads = self
            .inputs
            .loads
            .as_ref()
            .and_then(|p| p.file_name())
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let verdict = self.frame_verdict().unwrap_or_default();
        Some(PlanStructure::of(report, &self.network, &loads, &verdict))
    }

    /// The parts nested onto the profile's stock, with `beside` run on the
    /// kit at the same time (the nest is mostly one thread); returns what
    /// `beside` returned.
    pub fn nest_with<R: Send>(&mut self, beside: impl FnOnce(&Kit) -> R + Send) -> Result<R> {
        self.kit()?;
        let (Some(kit), Some(profile)) = (&self.kit, &self.profile) else {
            return Err(not_run(&self.inputs, "the parts"));
        };
        let (nest, r) = rayon::join(|| crate::nest::nest(kit, profile), || beside(kit));
        self.nest = Some(nest?);
        Ok(r)
    }

    /// The nest onto the profile's stock.
    pub fn nest(&mut self) -> Result<&Nest> {
        if self.nest.is_none() {
            self.nest_with(|_| ())?;
        }
        self.nest
            .as_ref()
            .ok_or_else(|| not_run(&self.inputs, "the nest"))
    }

    /// The nest, once it has run.
    pub fn nested(&self) -> Option<&Nest> {
        self.nest.as_ref()
    }

    /// Let the analysis go, and what only the parts needed of it (the
    /// check's report, its lamella lines, the flat state): a big network's
    /// analysis and kit need not both stay. The stages that need it must
    /// have run (the plan of the analysis is made before).
    pub fn release_analysis(&mut self) {
        self.analysis = None;
        self.check = None;
        self.lines = None;
        self.suggestion = None;
        self.flat = None;
    }

    /// The network, the session done with.
    pub fn into_network(self) -> Network {
        self.network
    }

    /// The plan of what has run: strips and nodes always; the profile and
    /// the check once checked (with the suggestion when made); the flat
    /// state when `with_flat` and it has been solved; the parts, their
    /// nest and the takeoff when made.
    pub fn plan(&mut self, with_flat: bool) -> Result<Plan> {
        let mut plan = self.plan_of_analysis()?;
        if with_flat {
            if let Some((p, s)) = &self.flat {
                crate::plan::add_flat(&mut plan, p, s);
            }
        }
        // The structure first: the takeoff lists the bracing.
        plan.structure = self.plan_structure();
        if let (Some(kit), Some(profile)) = (&self.kit, &self.profile) {
            crate::plan::add_parts(&mut plan, kit, profile);
            if let Some(nest) = &self.nest {
                crate::plan::add_nest(&mut plan, kit, nest);
                crate::plan::add_takeoff(&mut plan, kit, nest, profile);
            }
        }
        Ok(plan)
    }

    /// The plan's strips, nodes and check (the analysis must have run).
    fn plan_of_analysis(&mut self) -> Result<Plan> {
        self.analysis()?;
        let Some(an) = &self.analysis else {
            return Err(not_run(&self.inputs, "the analysis"));
        };
        let checked = match (&self.profile, &self.check) {
            (Some(profile), Some(report)) => Some(Checked {
                profile,
                report,
                suggestion: self.suggestion.as_ref(),
                resolved: &self.resolved,
            }),
            _ => None,
        };
        let model = Model::new(&self.network, an, checked);
        Ok(crate::plan::build(&self.network, an, &model))
    }

    /// Add the grid's shape in space to a plan made by this session (for
    /// the 3D model): the analysis must not have been released. The flat
    /// layout's frames come too when the plan holds the flat state.
    pub fn add_shape(&mut self, plan: &mut Plan) -> Result<()> {
        self.analysis()?;
        let Some(an) = &self.analysis else {
            return Err(not_run(&self.inputs, "the analysis"));
        };
        let opts = crate::plan::ShapeOptions::for_nodes(an.topology.nodes.len());
        crate::plan::add_shape(plan, an, self.profile.as_ref(), self.lines.as_ref(), opts);
        Ok(())
    }

    /// The warnings of the analysis and of the parts, one line each.
    pub fn warnings(&self) -> Vec<String> {
        let mut w: Vec<String> = self
            .analysis
            .iter()
            .flat_map(|a| a.warnings().iter().map(|w| w.to_string()))
            .collect();
        if let Some(kit) = &self.kit {
            w.extend(kit.warnings.iter().cloned());
            // Parts and nests of a network the check fails are made (to see
            // what the kit would be), but they are not a kit to cut.
            if let Some(check) = self.check.as_ref().filter(|c| !c.passes()) {
                let (over, bowed, all) = (check.overstressed(), check.bowed(), check.strips.len());
                w.push(if over > 0 {
                    format!(
                        "the check fails ({over} of {all} strips overstressed; see `lamella check`): these parts do not bend into place elastically, and `lamella build` refuses them without --allow-overstress"
                    )
                } else {
                    format!(
                        "the check fails ({bowed} of {all} strips bowed; see `lamella check`): those strips cannot be cut straight"
                    )
                });
            }
        }
        w
    }
}

/// Refuse to write `out` when it is one of the `inputs` (the same file by
/// canonical path, or by device and inode: symlinks and hard links too).
pub fn refuse_inputs(out: &Path, inputs: &[(&str, &Path)]) -> Result<()> {
    if !out.exists() {
        return Ok(());
    }
    for (what, input) in inputs {
        if read::same_file(out, input) {
            return Err(Error::output(
                out,
                format!(
                    "is the {what} ({}): refusing to overwrite an input; choose another output",
                    input.display()
                ),
            ));
        }
    }
    Ok(())
}

/// One output of a command, for [`check_outputs`].
#[derive(Debug, Clone, Copy)]
pub enum Output<'a> {
    /// An output folder (`--out DIR`) and the entries the command writes
    /// in it (`sheets`: the sheets' folder).
    Dir(&'a Path, &'a [&'a str]),
    /// A file the user named, and what the command writes into it
    /// (`instance`, `network`).
    File(&'a str, &'a Path),
}

/// Check every output of a command before anything is written: against
/// the inputs (none may be overwritten, nor removed from a kit's
/// `sheets/`), against one another (no two the same file, no file where a
/// folder goes) and against what is there ([`out::output_dir`],
/// [`out::output_file`]: a link the user named is followed, a folder, a
/// device or a FIFO where a file goes is refused; in an output folder, a
/// file lamella did not write where it writes one is refused,
/// [`out::manifest::check_names`]). What a killed build into an output
/// folder left is finished first ([`out::staging::recover_stale`]).
/// Returns the paths to write, one per output in order, links followed.
pub fn check_outputs(outputs: &[Output], inputs: &[(&str, &Path)]) -> Result<Vec<PathBuf>> {
    let mut real = Vec::with_capacity(outputs.len());
    for o in outputs {
        match *o {
            Output::Dir(dir, names) => {
                for name in names {
                    refuse_inputs(&dir.join(name), inputs)?;
                }
                for folder in out::manifest::FOLDERS.iter().filter(|f| names.contains(f)) {
                    let sheets = dir.join(folder);
                    if std::fs::symlink_metadata(&sheets).is_ok_and(|m| m.is_dir()) {
                        for e in std::fs::read_dir(&sheets)
                            .map_err(|e| Error::io(&sheets, e))?
                            .flatten()
                        {
                            let rel = format!("{folder}/{}", e.file_name().to_string_lossy());
                            if out::manifest::is_lamella_name(&rel) {
                                refuse_inputs(&e.path(), inputs)?;
                            }
                        }
                    }
                }
                real.push(out::output_dir(dir)?);
            }
            Output::File(_, file) => {
                refuse_inputs(file, inputs)?;
                real.push(out::output_file(file)?);
            }
        }
    }
    // A file the user named must not be another output, nor where an
    // output folder or a file in it goes.
    for (i, o) in outputs.iter().enumerate() {
        let Output::File(what, file) = *o else {
            continue;
        };
        let f = normalized(&real[i]);
        let clash = |shown: PathBuf| {
            Err(Error::output(
                file,
                format!(
                    "is also where this command writes {}: choose another path for the {what}",
                    shown.display()
                ),
            ))
        };
        for (j, other) in outputs.iter().enumerate() {
            if i == j {
                continue;
            }
            match *other {
                Output::File(_, g) => {
                    if f == normalized(&real[j]) || read::same_file(&real[i], &real[j]) {
                        return clash(g.to_path_buf());
                    }
                }
                Output::Dir(dir, names) => {
                    let d = normalized(&real[j]);
                    if d.starts_with(&f) {
                        return clash(dir.to_path_buf());
                    }
                    for name in names {
                        let n = d.join(name);
                        let inside = out::manifest::FOLDERS.contains(name) && f.starts_with(&n);
                        if f == n || inside || read::same_file(&real[i], &real[j].join(name)) {
                            return clash(dir.join(name));
                        }
                    }
                }
            }
        }
    }
    for (o, r) in outputs.iter().zip(&real) {
        if let Output::Dir(_, names) = *o {
            out::staging::recover_stale(r)?;
            out::manifest::check_names(r, names)?;
        }
    }
    Ok(real)
}

/// `path` absolute, its longest existing part with links resolved and the
/// rest with `.` and `..` taken as written: two paths to the same place
/// compare equal, whether it exists yet or not.
fn normalized(path: &Path) -> PathBuf {
    let abs = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir()
            .map(|d| d.join(path))
            .unwrap_or_else(|_| path.to_path_buf())
    };
    let mut rest = Vec::new();
    let mut base = abs.as_path();
    loop {
        if let Ok(c) = base.canonicalize() {
            let mut out = c;
            for part in rest.iter().rev() {
                match part {
                    std::path::Component::CurDir => {}
                    std::path::Component::ParentDir => {
                        out.pop();
                    }
                    other => out.push(other.as_os_str()),
                }
            }
            return out;
        }
        match (base.parent(), base.components().next_back()) {
            (Some(parent), Some(last)) => {
                rest.push(last);
                base = parent;
            }
            _ => return abs,
        }
    }
}
