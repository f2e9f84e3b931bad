//! `lamella build`: every stage from a network and a profile to the files a
//! workshop needs — nodes, the elastic check, parts, nest, then
//! `DIR/plan.json`, `DIR/sheets/GROUP-sheet-NNN.dxf` and `.svg` per stock sheet,
//! `DIR/parts/ID.dxf` and `.svg` per distinct part with
//! `DIR/parts/parts.csv`, `DIR/takeoff.csv`, `DIR/takeoff.json` and the assembly sheets
//! `DIR/assembly.pdf` — staged beside DIR and moved
//! into place only once complete ([`crate::formats::out::staging`]).
//!
//! Everything is computed before anything is written; an overstressed
//! strip stops the build before the first file (unless allowed).

use super::{check_outputs, Inputs, Output, Session};
use crate::check::CheckReport;
use crate::error::{Error, Result};
use crate::fabricate::part::PartKind;
use crate::formats::out::staging::Staging;
use crate::formats::write::arcs::DEFAULT_TOLERANCE_MM;
use crate::formats::write::drawing::{part_file_stem, Drawer, Kerf, SheetFileOptions};
use crate::formats::write::{
    assembly, dxf as dxf_out, plan_json, svg as svg_out, takeoff as takeoff_file,
};
use crate::plan::{self, takeoff::Takeoff};
use indicatif::ProgressBar;
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// What `build` is asked to do beyond reading (the session's [`Inputs`]).
#[derive(Debug, Clone, Default)]
pub struct BuildOptions {
    /// Offset outer contours out and inner contours in by half the kerf.
    pub kerf_compensation: bool,
    /// Write the files even when a strip is overstressed.
    pub allow_overstress: bool,
    /// Paper of the assembly sheets.
    pub paper: assembly::Paper,
    /// Write each sheet's outline, on the reference layer `SHEET`.
    pub sheet_outline: bool,
    /// Put screen labels (part ids as text) into the SVGs.
    pub svg_labels: bool,
    /// Fit cut contours by lines and arcs within this, mm: `None` the
    /// default ([`crate::formats::write::arcs::DEFAULT_TOLERANCE_MM`]),
    /// 0 no fitting (plan.json's polygons as they are).
    pub arc_tolerance_mm: Option<f64>,
}

/// The time one stage of a build took.
#[derive(Debug, Clone, PartialEq)]
pub struct StageTime {
    /// The stage.
    pub stage: &'static str,
    /// Wall time, s.
    pub wall_s: f64,
    /// CPU time of the whole process over the stage (all threads, user and
    /// system), s, where the platform tells it.
    pub cpu_s: Option<f64>,
}

/// The governing strip of the elastic check.
#[derive(Debug, Clone, PartialEq)]
pub struct Governing {
    /// Strip id.
    pub strip: String,
    /// Lamella number.
    pub lamella: u32,
    /// Its utilisation.
    pub utilization: f64,
    /// What governs (`bending`, `torsion`, …).
    pub governs: &'static str,
}

/// What a build made, for the summary it prints.
#[derive(Debug, Clone)]
pub struct BuildReport {
    /// Network name.
    pub network: String,
    /// Profile name.
    pub profile: String,
    /// A and B strips.
    pub strips: usize,
    /// Edge strips.
    pub edges: usize,
    /// Nodes.
    pub nodes: usize,
    /// Per kind: distinct parts and pieces.
    pub kinds: Vec<(PartKind, usize, u64)>,
    /// The takeoff (totals, stock, hardware), also written.
    pub takeoff: Takeoff,
    /// Sheets used and the lower bound.
    pub sheets_used: usize,
    /// The nest's lower bound on sheets.
    pub lower_bound_sheets: usize,
    /// Per stock group: its name, sheets (bars) used and lower bound.
    pub sheet_groups: Vec<(String, usize, usize)>,
    /// Part area over used sheet area.
    pub utilization: f64,
    /// Strips overstressed (0 when every strip passes).
    pub overstressed: usize,
    /// The highest-utilised lamella, if any.
    pub governing: Option<Governing>,
    /// The frame's verdict, when built with a loads file.
    pub structure: Option<StructureVerdict>,
    /// Warnings of the analysis and the kit, one line each.
    pub warnings: Vec<String>,
    /// Files written, relative to DIR (empty when the build stopped at the check).
    pub files: Vec<String>,
    /// Where they were written.
    pub out: PathBuf,
    /// Pages of assembly.pdf (0 when not written).
    pub assembly_pages: usize,
    /// Time per stage, in order (for the benchmark; not written
    /// anywhere): `read`, `analyse`, `parts`, `nest`, `plan`, `write`
    /// (the takeoff, then plan.json, the sheets, assembly.pdf and the 3D
    /// model side by side: their own wall times follow as `write:
    /// plan.json`, `write: sheets`, `write: assembly.pdf` and `write:
    /// model.glb and view.html`), `commit`.
    pub stages: Vec<StageTime>,
}

impl BuildReport {
    /// Whether every strip passed the elastic check.
    pub fn passes(&self) -> bool {
        self.overstressed == 0
    }
}

/// The report of a build stopped before anything was written (an
/// overstressed strip, a grid that does not stand).
fn stopped(
    out: &Path,
    (network_name, profile_name): (String, String),
    (strips, edges, nodes): (usize, usize, usize),
    (overstressed, governing): (usize, Option<Governing>),
    warnings: Vec<String>,
    clock: Clock,
) -> BuildReport {
    BuildReport {
        network: network_name.clone(),
        profile: profile_name.clone(),
        strips,
        edges,
        nodes,
        kinds: Vec::new(),
        takeoff: Takeoff {
            project: network_name,
            profile: profile_name,
            ..Default::default()
        },
        sheets_used: 0,
        lower_bound_sheets: 0,
        sheet_groups: Vec::new(),
        utilization: 0.0,
        overstressed,
        governing,
        structure: None,
        warnings,
        files: Vec::new(),
        out: out.to_path_buf(),
        assembly_pages: 0,
        stages: clock.stages,
    }
}

/// The frame's verdict in a build with a loads file.
#[derive(Debug, Clone, PartialEq)]
pub struct StructureVerdict {
    /// Whether the grid stands ([`crate::structure::stage::FrameReport::passes`]).
    pub passes: bool,
    /// The one-line verdict.
    pub verdict: String,
}

/// The files every build writes besides the sheets.
pub const FIXED_FILES: [&str; 7] = [
    "plan.json",
    "takeoff.csv",
    "takeoff.json",
    "setting-out.csv",
    "assembly.pdf",
    "model.glb",
    "view.html",
];

/// What a build writes in DIR: [`FIXED_FILES`], the sheets' and the parts' folders.
const KIT: [&str; 10] = [
    "plan.json",
    "takeoff.csv",
    "takeoff.json",
    "setting-out.csv",
    "assembly.pdf",
    "model.glb",
    "view.html",
    crate::formats::out::manifest::SHEETS,
    crate::formats::out::manifest::PARTS,
    crate::formats::out::manifest::STRUCTURE,
];

/// Run every stage and write the kit into `out`. Returns the report; when
/// a strip is overstressed and `allow_overstress` is off, nothing is
/// written and `report.files` is empty. `progress` shows the stage and the
/// sheets written (pass `ProgressBar::hidden()` for none).
pub fn build(
    inputs: Inputs,
    out: &Path,
    opts: &BuildOptions,
    progress: &ProgressBar,
) -> Result<BuildReport> {
    check_outputs(&[Output::Dir(out, &KIT)], &inputs.files())?;
    let mut clock = Clock::start();
    progress.set_message("reading");
    let profile_path = inputs.profile.clone().unwrap_or_default();
    let mut session = Session::open(inputs)?;
    let tol_mm = arc_tolerance(
        opts.arc_tolerance_mm,
        session.profile()?.cutting.part_spacing_mm,
        &profile_path,
    )?;
    clock.lap("read");
    progress.set_message("finding nodes, frames and curvatures");
    session.analysis()?;
    progress.set_message("checking");
    // The lamella lines the check integrates serve the parts too.
    let report = session.check(true)?;
    let governing = governing(report);
    let overstressed = report.overstressed();
    let mut warnings = session.warnings();
    let (strips, nodes) = match session.analysed() {
        Some(an) => (an.lamella_strips().count(), an.topology.nodes.len()),
        None => (0, 0),
    };
    clock.lap("analyse");
    let edges = session.network().curves.len() - strips;
    let (network_name, profile_name) = (
        session.network().name.clone(),
        session.profile()?.name.clone(),
    );
    if overstressed > 0 && !opts.allow_overstress {
        return Ok(stopped(
            out,
            (network_name, profile_name),
            (strips, edges, nodes),
            (overstressed, governing),
            warnings,
            clock,
        ));
    }
    // The plan's strips and nodes first, so the analysis can go once the
    // parts are made (a big network's analysis and kit need not both stay).
    let mut the_plan = session.plan(false)?;
    progress.set_message("making parts");
    if session.inputs().slots_from_flat {
        progress.set_message("solving the flat state");
        let (problem, state) = session.flat()?;
        plan::add_flat(&mut the_plan, problem, state);
    }
    // The shape in space for the 3D model, while the analysis is there.
    session.add_shape(&mut the_plan)?;
    session.kit()?;
    // The erected grid as a frame, while the analysis is there: it stops
    // the build as an overstressed strip does when it does not stand.
    let mut structure = None;
    if session.inputs().loads.is_some() {
        progress.set_message("analysing the frame");
        let passes = session.frame()?.passes();
        let verdict = session.frame_verdict().unwrap_or_default();
        if !passes && !opts.allow_overstress {
            let mut r = stopped(
                out,
                (network_name, profile_name),
                (strips, edges, nodes),
                (overstressed, governing),
                warnings,
                clock,
            );
            r.structure = Some(StructureVerdict { passes, verdict });
            return Ok(r);
        }
        session.add_eye_plates()?;
        the_plan.structure = session.plan_structure();
        structure = Some((
            StructureVerdict { passes, verdict },
            super::commands::structure_files(&session, out)?,
        ));
    }
    // Checked again (a foreign plan.json or takeoff, a `sheets` link)
    // before the writing: DIR may have changed while the work ran.
    let staging = Staging::begin(out, &KIT)?;
    session.release_analysis();
    clock.lap("parts");
    if let Some(kit) = session.made() {
        warnings.extend(kit.warnings.iter().cloned());
    }
    progress.set_message("nesting");
    // The nest is mostly one thread: the plan's parts are converted and
    // the assembly sheets' strip sheets (which need no nest) drawn beside it.
    let frame = assembly::Frame::of(opts.paper);
    let (plan_parts, strip_pages) = session.nest_with(|kit| {
        let parts = plan::plan_parts(kit);
        let pages = assembly::strips::pages_of(&the_plan, &parts, &frame);
        (parts, pages)
    })?;
    clock.lap("nest");
    let (Some(kit), Some(nest)) = (session.made(), session.nested()) else {
        return Err(Error::output(out, "internal: the kit was not nested"));
    };
    plan::add_takeoff(&mut the_plan, kit, nest, session.profile()?);
    plan::add_nest(&mut the_plan, kit, nest);
    let kinds = kit.summary.kinds.clone();
    plan::set_parts(&mut the_plan, plan_parts, kit, session.profile()?);
    let plan_target = out.join("plan.json");
    if let Some(field) = plan_json::first_non_finite(&mut the_plan) {
        return Err(Error::output(
            &plan_target,
            format!("not written: {field} is not a finite number"),
        ));
    }
    let (sheets_used, lower_bound_sheets, utilization) = (
        nest.summary.sheets_used,
        nest.summary.lower_bound_sheets,
        nest.summary.utilization,
    );
    let sheet_groups: Vec<(String, usize, usize)> = nest
        .groups
        .iter()
        .map(|g| {
            (
                g.name.clone(),
                g.summary.sheets_used,
                g.summary.lower_bound_sheets,
            )
        })
        .collect();
    let kerf = match opts.kerf_compensation {
        true => {
            let profile = session.profile()?;
            Some(Kerf {
                default_mm: profile.cutting.kerf_mm,
                by_group_mm: profile
                    .stock_groups()
                    .into_iter()
                    .map(|g| (g.name, g.cutting.kerf_mm))
                    .collect(),
            })
        }
        false => None,
    };
    // The network's points live on as the overview's curves.
    plan::add_curves(&mut the_plan, session.into_network().curves);
    clock.lap("plan");
    progress.set_message("writing plan, takeoff, sheets and assembly sheets");
    let takeoff = the_plan.takeoff.clone().unwrap_or_default();
    let csv =
        takeoff_file::to_csv(&takeoff).map_err(|e| Error::output(&out.join("takeoff.csv"), e))?;
    staging.write("takeoff.csv", &csv)?;
    staging.write("takeoff.json", takeoff_file::to_json(&takeoff).as_bytes())?;
    let setting = crate::formats::write::setting_out::to_csv(&the_plan)
        .map_err(|e| Error::output(&out.join("setting-out.csv"), e))?;
    staging.write("setting-out.csv", &setting)?;
    let file_opts = SheetFileOptions {
        sheet_outline: opts.sheet_outline,
        labels: opts.svg_labels,
    };
    let drawer = Drawer::new(&the_plan, kerf, &plan_target)?.arc_tolerance(tol_mm);
    let sheet_count = drawer.len();
    progress.set_length(sheet_count as u64);
    progress.set_position(0);
    fn timed<T>(f: impl FnOnce() -> Result<T>) -> (Result<T>, f64) {
        let t = std::time::Instant::now();
        let r = f();
        (r, t.elapsed().as_secs_f64())
    }
    let assembly_input = assembly::AssemblyInput {
        plan: &the_plan,
        paper: opts.paper,
        plan_path: &plan_target,
    };
    // With kerf compensation the cutting files are offset; the nested
    // sheets' pages stay nominal, drawn apart.
    let nominal = match opts.kerf_compensation {
        true => Some(Drawer::new(&the_plan, None, &plan_target)?.arc_tolerance(tol_mm)),
        false => None,
    };
    let sheets_meta = the_plan.sheets.as_deref().unwrap_or_default();
    // plan.json streams out on one thread while the sheets (each drawn once
    // for its DXF, its SVG and its page of the assembly sheets) and the
    // other assembly pages share the others (each deterministic on its own).
    //
    // Big files are written past the page cache (`direct`), and a direct
    // write waits for the disk: one thread more than the cores keeps them
    // busy formatting meanwhile.
    let write_pool = rayon::ThreadPoolBuilder::new()
        .num_threads(rayon::current_num_threads() + 1)
        .build()
        .map_err(|e| Error::output(out, format!("cannot start the writer threads: {e}")))?;
    let (plan_written, (sheets_written, sections)) = write_pool.install(|| {
        rayon::join(
            || timed(|| staging.write_with("plan.json", |w| plan_json::write_json(&the_plan, w))),
            || {
                rayon::join(
                    || {
                        timed(|| {
                            (0..sheet_count)
                                .into_par_iter()
                                // Each worker's text buffers serve sheet after sheet.
                                .map_init(
                                    || (Vec::new(), Vec::new()),
                                    |(dxf, svg), i| -> Result<assembly::SealedPage> {
                                        let sheet = drawer.sheet(i)?;
                                        let stem = sheet.file_stem();
                                        dxf_out::write_dxf(&sheet, file_opts, dxf).map_err(
                                            |e| {
                                                Error::output(
                                                    &out.join(format!("sheets/{stem}.dxf")),
                                                    e,
                                                )
                                            },
                                        )?;
                                        staging.write(&format!("sheets/{stem}.dxf"), dxf)?;
                                        let mut title = format!(
                                            "{} — {}: sheet {} of {} ({}), {} × {} mm",
                                            network_name,
                                            profile_name,
                                            sheet.number,
                                            sheet_count,
                                            sheet.id,
                                            sheet.length_mm,
                                            sheet.width_mm
                                        );
                                        if let Some(note) = &sheet.stock_note {
                                            title += &format!(", {note}");
                                        }
                                        svg_out::write_svg(&sheet, &title, file_opts, svg);
                                        staging.write(&format!("sheets/{stem}.svg"), svg)?;
                                        let page = match &nominal {
                                            Some(d) => assembly::nested::page(
                                                &d.sheet_cuts(i)?,
                                                &sheets_meta[i],
                                                sheet_count,
                                                &frame,
                                            ),
                                            None => assembly::nested::page(
                                                &sheet,
                                                &sheets_meta[i],
                                                sheet_count,
                                                &frame,
                                            ),
                                        };
                                        progress.inc(1);
                                        Ok(page)
                                    },
                                )
                                .collect::<Result<Vec<_>>>()
                        })
                    },
                    || {
                        let sections =
                            timed(|| assembly::sections_with(&assembly_input, Some(strip_pages)));
                        // The 3D model and its page beside the sheets.
                        let model = timed(|| {
                            let glb_path = out.join("model.glb");
                            let [glb, html] = super::commands::model_files(&the_plan, &glb_path)?;
                            staging.write("model.glb", &glb)?;
                            staging.write("view.html", &html)
                        });
                        (sections, model)
                    },
                )
            },
        )
    });
    plan_written.0?;
    let nested = sheets_written.0?;
    let t = std::time::Instant::now();
    let (sections, model) = sections;
    model.0?;
    let (sections, sections_s) = (sections.0?, sections.1);
    let mut assembly_pages = 0;
    staging.write_with("assembly.pdf", |w| {
        assembly_pages = assembly::assemble_into(&assembly_input, sections, nested, w)?;
        Ok(())
    })?;
    let pdf_s = sections_s + t.elapsed().as_secs_f64();
    clock.lap("write");
    clock.part("write: plan.json", plan_written.1);
    clock.part("write: sheets", sheets_written.1);
    // The sections apart from the sheets as nested, then the document.
    clock.part("write: assembly.pdf", pdf_s);
    clock.part("write: model.glb and view.html", model.1);
    // One DXF and SVG per distinct part, at the origin, and parts.csv.
    let parts_clock = std::time::Instant::now();
    let plan_parts = the_plan.parts.as_deref().unwrap_or_default();
    let stems: Vec<String> = plan_parts.iter().map(|p| part_file_stem(&p.id)).collect();
    let mut seen = std::collections::BTreeSet::new();
    if let Some(twice) = stems.iter().find(|s| !seen.insert(s.as_str())) {
        return Err(Error::output(
            &out.join("parts"),
            format!("two parts would share the file parts/{twice}.dxf: their ids differ only in characters a file name cannot hold"),
        ));
    }
    write_pool.install(|| {
        (0..drawer.part_count())
            .into_par_iter()
            .map_init(
                || (Vec::new(), Vec::new()),
                |(dxf, svg), i| -> Result<()> {
                    let part = drawer.part(i)?;
                    let stem = &stems[i];
                    let target = format!("parts/{stem}.dxf");
                    dxf_out::write_dxf(&part, SheetFileOptions::default(), dxf)
                        .map_err(|e| Error::output(&out.join(&target), e))?;
                    staging.write(&target, dxf)?;
                    let title = format!(
                        "{network_name} — {profile_name}: part {}, {} × {} mm",
                        part.id, part.length_mm, part.width_mm
                    );
                    svg_out::write_svg(&part, &title, SheetFileOptions::default(), svg);
                    staging.write(&format!("parts/{stem}.svg"), svg)
                },
            )
            .collect::<Result<Vec<()>>>()
    })?;
    let csv = takeoff_file::parts_csv(plan_parts, &takeoff, part_file_stem)
        .map_err(|e| Error::output(&out.join("parts/parts.csv"), e))?;
    staging.write("parts/parts.csv", &csv)?;
    clock.part("write: parts", parts_clock.elapsed().as_secs_f64());
    drop(drawer);
    let mut files: Vec<String> = FIXED_FILES.iter().map(|s| s.to_string()).collect();
    for (i, s) in sheets_meta.iter().enumerate() {
        let stem = if s.group.is_empty() {
            format!("sheet-{:03}", i + 1)
        } else {
            format!("{}-sheet-{:03}", s.group, i + 1)
        };
        files.push(format!("sheets/{stem}.dxf"));
        files.push(format!("sheets/{stem}.svg"));
    }
    files.push("parts/parts.csv".to_string());
    for stem in &stems {
        files.push(format!("parts/{stem}.dxf"));
        files.push(format!("parts/{stem}.svg"));
    }
    let structure = match structure {
        Some((verdict, frame_files)) => {
            for (name, bytes) in super::commands::STRUCTURE_FILES.iter().zip(&frame_files) {
                staging.write(name, bytes)?;
                files.push(name.to_string());
            }
            Some(verdict)
        }
        None => None,
    };
    progress.set_message("moving into place");
    staging.commit()?;
    clock.lap("commit");
    Ok(BuildReport {
        network: network_name,
        profile: profile_name,
        strips,
        edges,
        nodes,
        kinds,
        takeoff,
        sheets_used,
        lower_bound_sheets,
        sheet_groups,
        utilization,
        overstressed,
        governing,
        structure,
        warnings,
        files,
        out: out.to_path_buf(),
        assembly_pages,
        stages: clock.stages,
    })
}

fn governing(report: &CheckReport) -> Option<Governing> {
    let ranking = report.ranking();
    ranking.first().map(|&i| {
        let s = &report.strips[i];
        let l = s.worst();
        Governing {
            strip: s.id.clone(),
            lamella: l.line.offset.number,
            utilization: l.utilization,
            governs: l.governs.as_str(),
        }
    })
}

/// Wall and CPU time per stage.
struct Clock {
    last: std::time::Instant,
    last_cpu_s: Option<f64>,
    stages: Vec<StageTime>,
}

impl Clock {
    fn start() -> Clock {
        Clock {
            last: std::time::Instant::now(),
            last_cpu_s: process_cpu_s(),
            stages: Vec::new(),
        }
    }

    /// The time since the last lap, as `stage`.
    fn lap(&mut self, stage: &'static str) {
        let now = std::time::Instant::now();
        let cpu = process_cpu_s();
        self.stages.push(StageTime {
            stage,
            wall_s: now.duration_since(self.last).as_secs_f64(),
            cpu_s: cpu.zip(self.last_cpu_s).map(|(b, a)| b - a),
        });
        self.last = now;
        self.last_cpu_s = cpu;
    }

    /// A part of the last stage, timed on its own (wall time only).
    fn part(&mut self, stage: &'static str, wall_s: f64) {
        self.stages.push(StageTime {
            stage,
            wall_s,
            cpu_s: None,
        });
    }
}

/// User and system CPU time of this process, all threads, s: from
/// `/proc/self/stat` (Linux; clock ticks of 1/100 s), `None` elsewhere.
fn process_cpu_s() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The fields after the command name (in parentheses, may hold spaces):
    // utime and stime are the 12th and 13th.
    let mut f = stat.rsplit_once(')')?.1.split_whitespace().skip(11);
    let utime: f64 = f.next()?.parse().ok()?;
    let stime: f64 = f.next()?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

/// The arc fit's tolerance, mm (`None`: no fit): at most a quarter of the
/// profile's part spacing, so two fitted outlines the nest kept `spacing`
/// apart stay at least `spacing − 2·tol` ≥ half of it apart.
fn arc_tolerance(asked_mm: Option<f64>, spacing_mm: f64, profile: &Path) -> Result<Option<f64>> {
    let tol = asked_mm.unwrap_or(DEFAULT_TOLERANCE_MM);
    let field = || crate::error::Location::Field("cutting.part_spacing_mm".into());
    if !tol.is_finite() || tol < 0.0 {
        return Err(Error::input(
            profile,
            field(),
            format!("--arc-tolerance {tol}: a tolerance is a length ≥ 0 mm (0: no arcs)"),
        ));
    }
    if tol > 0.25 * spacing_mm {
        return Err(Error::input(profile, field(), format!(
            "--arc-tolerance {tol}: more than a quarter of the profile's part spacing ({spacing_mm} mm) \
             would let fitted outlines come closer than the nest keeps them"
        ),
        ));
    }
    Ok((tol > 0.0).then_some(tol))
}
