//! `lamella build`: every stage from a network and a profile to the files a
//! workshop needs — nodes, the elastic check, parts, nest, then
//! `DIR/plan.json`, `DIR/sheets/sheet-NNN.dxf` and `.svg` per stock sheet,
//! `DIR/takeoff.csv`, `DIR/takeoff.json` and the assembly sheets
//! `DIR/assembly.pdf` — staged beside DIR and moved
//! into place only once complete ([`crate::formats::out::staging`]).
//!
//! Everything is computed before anything is written; an overstressed
//! strip stops the build before the first file (unless allowed).

use crate::check::CheckReport;
use crate::error::{Error, Result};
use crate::fabricate::part::PartKind;
use crate::formats::out::staging::Staging;
use crate::formats::read::{self, ReadOptions};
use crate::formats::write::drawing::Drawer;
use crate::formats::write::{dxf as dxf_out, svg as svg_out};
use crate::plan;
use crate::plan::model::Model;
use crate::plan::takeoff;
use crate::{analyze, AnalysisOptions};
use indicatif::ProgressBar;
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// What `build` is asked to do beyond reading.
#[derive(Debug, Clone, Default)]
pub struct BuildOptions {
    /// Units, tolerance and precision of the network file.
    pub read: ReadOptions,
    /// Offset outer contours out and inner contours in by half the kerf.
    pub kerf_compensation: bool,
    /// Write the files even when a strip is overstressed.
    pub allow_overstress: bool,
    /// Size each slot from its node's rotation between the flat state and
    /// the erected one ([`crate::flat`]) instead of the blanket tolerance.
    pub slots_from_flat: bool,
    /// Paper of the assembly sheets.
    pub paper: crate::formats::write::assembly::Paper,
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
    pub takeoff: takeoff::Takeoff,
    /// Sheets used and the lower bound.
    pub sheets_used: usize,
    /// The nest's lower bound on sheets.
    pub lower_bound_sheets: usize,
    /// Part area over used sheet area.
    pub utilization: f64,
    /// Strips overstressed (0 when every strip passes).
    pub overstressed: usize,
    /// The highest-utilised lamella, if any.
    pub governing: Option<Governing>,
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
    /// (the takeoff, then plan.json, the sheets and assembly.pdf side by
    /// side: their own wall times follow as `write: plan.json`, `write:
    /// sheets` and `write: assembly.pdf`), `commit`.
    pub stages: Vec<StageTime>,
}

impl BuildReport {
    /// Whether every strip passed the elastic check.
    pub fn passes(&self) -> bool {
        self.overstressed == 0
    }
}

/// The files every build writes besides the sheets.
pub const FIXED_FILES: [&str; 4] = ["plan.json", "takeoff.csv", "takeoff.json", "assembly.pdf"];

/// Run every stage and write the kit into `out`. Returns the report; when
/// a strip is overstressed and `allow_overstress` is off, nothing is
/// written and `report.files` is empty. `progress` shows the stage and the
/// sheets written (pass `ProgressBar::hidden()` for none).
pub fn build(
    network: &Path,
    profile_path: &Path,
    out: &Path,
    opts: &BuildOptions,
    progress: &ProgressBar,
) -> Result<BuildReport> {
    for name in FIXED_FILES {
        let target = out.join(name);
        for (what, input) in [("network", network), ("profile", profile_path)] {
            if target.exists() && read::same_file(&target, input) {
                return Err(Error::output(
                    &target,
                    format!(
                        "is the {what} ({}): refusing to overwrite an input; choose another output",
                        input.display()
                    ),
                ));
            }
        }
    }
    let mut clock = Clock::start();
    progress.set_message("reading");
    let profile = read::profile_file::load(profile_path)?;
    let net = read::read_network(network, opts.read)?;
    clock.lap("read");
    progress.set_message("finding nodes, frames and curvatures");
    let an = analyze(&net, AnalysisOptions::for_network(&net))?;
    progress.set_message("checking");
    // The lamella lines the check integrates serve fabrication too.
    let (report, lines) = crate::check::check_with_lines(&an, &profile);
    let mut warnings: Vec<String> = an.warnings().iter().map(|w| w.to_string()).collect();
    let governing = governing(&report);
    let overstressed = report.overstressed();
    let strips = an.lamella_strips().count();
    clock.lap("analyse");
    let edges = net.curves.len() - strips;
    if overstressed > 0 && !opts.allow_overstress {
        return Ok(BuildReport {
            network: net.name.clone(),
            profile: profile.name.clone(),
            strips,
            edges,
            nodes: an.topology.nodes.len(),
            kinds: Vec::new(),
            takeoff: takeoff::Takeoff {
                project: net.name.clone(),
                profile: profile.name.clone(),
                ..Default::default()
            },
            sheets_used: 0,
            lower_bound_sheets: 0,
            utilization: 0.0,
            overstressed,
            governing,
            warnings,
            files: Vec::new(),
            out: out.to_path_buf(),
            assembly_pages: 0,
            stages: clock.stages,
        });
    }
    // Refuse a foreign plan.json or takeoff before the long work.
    let staging = Staging::begin(out, &FIXED_FILES)?;
    // The plan's strips and nodes first, so the analysis can go once the
    // parts are made (a big network's analysis and kit need not both stay).
    let model = Model::checked(&net, &an, profile.clone(), report, None);
    let mut the_plan = plan::build(&net, &an, &model);
    drop(model);
    progress.set_message("making parts");
    let flat = if opts.slots_from_flat {
        progress.set_message("solving the flat state");
        let pr = crate::flat::problem(&an, &profile)?;
        Some(crate::flat::solve(&pr))
    } else {
        None
    };
    let rotations = flat.as_ref().map(|f| f.rotations());
    if let Some(f) = &flat {
        plan::add_flat(&mut the_plan, f);
    }
    let kit =
        crate::fabricate::fabricate_with_lines(&net, &an, &profile, rotations.as_ref(), lines)?;
    let nodes = an.topology.nodes.len();
    drop(an);
    clock.lap("parts");
    warnings.extend(kit.warnings.iter().cloned());
    progress.set_message("nesting");
    // The nest is mostly one thread: the plan's parts are converted and
    // the assembly sheets' strip sheets (which need no nest) drawn beside it.
    let frame = crate::formats::write::assembly::Frame::of(opts.paper);
    let (nest, (plan_parts, strip_pages)) = rayon::join(
        || crate::nest::nest(&kit, &profile),
        || {
            let parts = plan::plan_parts(&kit);
            let pages =
                crate::formats::write::assembly::strips::pages_of(&the_plan, &parts, &frame);
            (parts, pages)
        },
    );
    let nest = nest?;
    clock.lap("nest");
    let takeoff = takeoff::takeoff(&net.name, &kit, &nest, &profile);
    plan::add_nest(&mut the_plan, &kit, &nest);
    let kinds = kit.summary.kinds.clone();
    plan::set_parts(&mut the_plan, plan_parts, &kit);
    let plan_target = out.join("plan.json");
    if let Some(field) = plan::first_non_finite(&mut the_plan) {
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
    drop(nest);
    drop(kit);
    clock.lap("plan");
    progress.set_message("writing plan, takeoff, sheets and assembly sheets");
    let csv = takeoff::to_csv(&takeoff).map_err(|e| Error::output(&out.join("takeoff.csv"), e))?;
    staging.write("takeoff.csv", &csv)?;
    staging.write("takeoff.json", takeoff::to_json(&takeoff).as_bytes())?;
    let kerf = opts.kerf_compensation.then_some(profile.cutting.kerf_mm);
    let drawer = Drawer::new(&the_plan, kerf, &plan_target)?;
    let sheet_count = drawer.len();
    progress.set_length(sheet_count as u64);
    progress.set_position(0);
    // The network's points live on as the overview's curves.
    let network_name = net.name.clone();
    let curves: Vec<crate::formats::write::assembly::CurvePoints> = net
        .curves
        .into_iter()
        .map(|c| crate::formats::write::assembly::CurvePoints {
            id: c.id,
            points_mm: c.points_world_mm.iter().map(|p| [p.x, p.y, p.z]).collect(),
        })
        .collect();
    fn timed<T>(f: impl FnOnce() -> Result<T>) -> (Result<T>, f64) {
        let t = std::time::Instant::now();
        let r = f();
        (r, t.elapsed().as_secs_f64())
    }
    let assembly_input = crate::formats::write::assembly::AssemblyInput {
        plan: &the_plan,
        takeoff: &takeoff,
        curves: &curves,
        paper: opts.paper,
        plan_path: &plan_target,
    };
    // With kerf compensation the cutting files are offset; the nested
    // sheets' pages stay nominal, drawn apart.
    let nominal = match kerf {
        Some(_) => Some(Drawer::new(&the_plan, None, &plan_target)?),
        None => None,
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
            || timed(|| staging.write_with("plan.json", |w| plan::write_json(&the_plan, w))),
            || {
                rayon::join(
                    || {
                        timed(|| {
                            (0..sheet_count)
                                .into_par_iter()
                                // Each worker's text buffers serve sheet after sheet.
                                .map_init(
                                    || (Vec::new(), Vec::new()),
                                    |(dxf, svg), i| -> Result<crate::formats::write::assembly::SealedPage> {
                                        let sheet = drawer.sheet(i)?;
                                        let stem = sheet.file_stem();
                                        dxf_out::write_dxf(&sheet, dxf).map_err(|e| {
                                            Error::output(
                                                &out.join(format!("sheets/{stem}.dxf")),
                                                e,
                                            )
                                        })?;
                                        staging.write(&format!("sheets/{stem}.dxf"), dxf)?;
                                        let title = format!(
                                            "{} — {}: sheet {} of {} ({}), {} × {} mm",
                                            network_name,
                                            profile.name,
                                            sheet.number,
                                            sheet_count,
                                            sheet.id,
                                            sheet.length_mm,
                                            sheet.width_mm
                                        );
                                        svg_out::write_svg(&sheet, &title, svg);
                                        staging.write(&format!("sheets/{stem}.svg"), svg)?;
                                        let page = match &nominal {
                                            Some(d) => crate::formats::write::assembly::nested::page(
                                                &d.sheet_cuts(i)?,
                                                &sheets_meta[i],
                                                sheet_count,
                                                &frame,
                                            ),
                                            None => crate::formats::write::assembly::nested::page(
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
                    || timed(|| crate::formats::write::assembly::sections_with(&assembly_input, Some(strip_pages))),
                )
            },
        )
    });
    plan_written.0?;
    let nested = sheets_written.0?;
    let t = std::time::Instant::now();
    let (sections, sections_s) = (sections.0?, sections.1);
    let mut assembly_pages = 0;
    staging.write_with("assembly.pdf", |w| {
        assembly_pages =
            crate::formats::write::assembly::assemble_into(&assembly_input, sections, nested, w)?;
        Ok(())
    })?;
    let pdf_s = sections_s + t.elapsed().as_secs_f64();
    clock.lap("write");
    clock.part("write: plan.json", plan_written.1);
    clock.part("write: sheets", sheets_written.1);
    // The sections apart from the sheets as nested, then the document.
    clock.part("write: assembly.pdf", pdf_s);
    drop(drawer);
    drop(curves);
    let mut files: Vec<String> = FIXED_FILES.iter().map(|s| s.to_string()).collect();
    for i in 1..=sheet_count {
        files.push(format!("sheets/sheet-{i:03}.dxf"));
        files.push(format!("sheets/sheet-{i:03}.svg"));
    }
    progress.set_message("moving into place");
    staging.commit()?;
    clock.lap("commit");
    Ok(BuildReport {
        network: network_name,
        profile: profile.name.clone(),
        strips,
        edges,
        nodes,
        kinds,
        takeoff,
        sheets_used,
        lower_bound_sheets,
        utilization,
        overstressed,
        governing,
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
