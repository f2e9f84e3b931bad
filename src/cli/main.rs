//! The `lamella` command line.

use clap::{Parser, Subcommand};
use lamella::formats::read::{self as io, ReadOptions};
use lamella::network::Unit;
use lamella::plan;
use lamella::plan::model::Model;
use lamella::profile::Profile;
use lamella::{analyze, AnalysisOptions};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "lamella",
    version,
    about = "Fabrication CAM for gridshells of flat, straight strips along asymptotic curves",
    long_about = "lamella turns a traced asymptotic curve network into what a workshop needs \
to cut and assemble it. Networks are read from the network file (YAML or JSON, see README), \
OBJ polylines or DXF (POLYLINE, LWPOLYLINE, LINE, SPLINE; layer A, B or edge). \
All outputs are in millimetres."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The whole kit in one command: nodes, elastic check, parts, nest, then
    /// DIR/plan.json, DIR/sheets/sheet-NNN.dxf and .svg per stock sheet,
    /// DIR/takeoff.csv, DIR/takeoff.json and DIR/assembly.pdf (the assembly
    /// sheets). Output is staged beside DIR and
    /// moved into place only when complete. Exit status 3 (nothing written)
    /// when a strip is overstressed, unless --allow-overstress.
    Build {
        /// The network file (.yaml, .yml, .json, .obj, .dxf).
        network: PathBuf,
        /// The material profile (profiles/*.yaml).
        #[arg(long)]
        profile: PathBuf,
        /// Output directory. Created if missing; lamella's files from an
        /// earlier build are replaced, other files are left alone.
        #[arg(long)]
        out: PathBuf,
        /// Offset outer contours out and inner contours in by half the
        /// profile's kerf (for controllers that do not compensate).
        #[arg(long)]
        kerf_compensation: bool,
        /// Write the kit even when a strip is overstressed.
        #[arg(long)]
        allow_overstress: bool,
        /// Size each slot from its node's rotation between the flat state
        /// and the erected one (see `lamella flat`) instead of the profile's
        /// blanket rotation tolerance.
        #[arg(long)]
        slots_from_flat: bool,
        /// Paper of the assembly sheets (assembly.pdf), landscape.
        #[arg(long, default_value = "a3", value_parser = ["a3", "a4"])]
        paper: String,
        /// No progress bar and no summary (errors and warnings still print).
        #[arg(long, short)]
        quiet: bool,
        #[command(flatten)]
        read: ReadArgs,
    },
    /// The flat state of an interlocking grid: the planar layout of least
    /// bending energy with the erected node-to-node lengths, each joint's
    /// rotation from flat to erected, each strip's stress while flat; write
    /// DIR/plan.json (with `flat`) and DIR/flat.svg. Exit status 3 when a
    /// joint turns past the profile's rotation tolerance or a strip is
    /// overstressed while flat; 1 for two-level grids (no flat state).
    Flat {
        /// The network file (.yaml, .yml, .json, .obj, .dxf).
        network: PathBuf,
        /// The material profile (profiles/*.yaml).
        #[arg(long)]
        profile: PathBuf,
        /// Directory for plan.json and flat.svg (created if missing).
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        read: ReadArgs,
    },
    /// Find the nodes of a network and compute node-to-node lengths, curvature
    /// and twist of every strip; write DIR/plan.json and print a summary.
    Nodes {
        /// The network file (.yaml, .yml, .json, .obj, .dxf).
        network: PathBuf,
        /// Output directory (created if missing); plan.json is written there.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        #[command(flatten)]
        read: ReadArgs,
    },
    /// Trace a network on an analytic surface from a spec (surface, scale,
    /// placement, seed, spacing, clip, sampling) and write it as a network
    /// file (YAML, with normals).
    Trace {
        /// The trace spec (YAML).
        spec: PathBuf,
        /// The network file to write (.yaml or .json).
        #[arg(long)]
        out: PathBuf,
    },
    /// Elastic check: the residual stresses of bending and twisting every
    /// flat lamella into place, from geodesic curvature and torsion, against
    /// the profile's design strength. Exit status 0 when every strip passes,
    /// 3 when any strip is overstressed.
    Check {
        /// The network file (.yaml, .yml, .json, .obj, .dxf).
        network: PathBuf,
        /// The material profile (profiles/*.yaml).
        #[arg(long)]
        profile: PathBuf,
        /// Also write DIR/plan.json with the profile and per-strip, per-lamella results.
        #[arg(long)]
        out: Option<PathBuf>,
        /// For a failing network: the largest lamella thickness (and height,
        /// where the trapeze term makes height matter) at which every strip passes.
        #[arg(long)]
        suggest: bool,
        /// Show only the N most utilised strips in the table.
        #[arg(long)]
        top: Option<usize>,
        #[command(flatten)]
        read: ReadArgs,
    },
    /// Nest every part onto the profile's stock: lamellas in lanes, small
    /// parts in the lane tails and shelves; write DIR/plan.json with
    /// everything `parts` writes plus `sheets` and `nesting`, and print the
    /// sheets used against the lower bound.
    Nest {
        /// The network file (.yaml, .yml, .json, .obj, .dxf).
        network: PathBuf,
        /// The material profile (profiles/*.yaml).
        #[arg(long)]
        profile: PathBuf,
        /// Directory for plan.json (created if missing).
        #[arg(long)]
        out: PathBuf,
        /// Also write the part set as a sparrow strip-packing instance
        /// (jagua-rs 0.7 JSON; parts grown by half the kerf plus spacing).
        #[arg(long, value_name = "FILE")]
        export_instance: Option<PathBuf>,
        /// Size each slot from its node's rotation between the flat state
        /// and the erected one (see `lamella flat`).
        #[arg(long)]
        slots_from_flat: bool,
        #[command(flatten)]
        read: ReadArgs,
    },
    /// Turn every A/B strip into flat parts for a profile: lamellas with
    /// swept slots or node holes, shear blocks, splice plates; write
    /// DIR/plan.json with everything `check` writes plus `parts`, and print
    /// a parts summary.
    Parts {
        /// The network file (.yaml, .yml, .json, .obj, .dxf).
        network: PathBuf,
        /// The material profile (profiles/*.yaml).
        #[arg(long)]
        profile: PathBuf,
        /// Directory for plan.json (created if missing).
        #[arg(long)]
        out: PathBuf,
        /// Size each slot from its node's rotation between the flat state
        /// and the erected one (see `lamella flat`).
        #[arg(long)]
        slots_from_flat: bool,
        #[command(flatten)]
        read: ReadArgs,
    },
}

#[derive(clap::Args, Clone)]
struct ReadArgs {
    /// Unit of OBJ files and unitless DXF files (mm, cm, m, in, ft); overrides a DXF's $INSUNITS.
    #[arg(long, value_parser = parse_unit)]
    units: Option<Unit>,
    /// Node tolerance in mm: the largest gap between two curves that is still a node
    /// (default: the file's `tolerance`, else 0.5 mm).
    #[arg(long, value_parser = parse_tolerance)]
    tolerance: Option<f64>,
    /// The grid the coordinates are rounded to, mm (0: exact): curves are
    /// smoothed to it before curvature and twist are taken (default: what
    /// the file's decimals imply, e.g. 0.001 for a Rhino export).
    #[arg(long, value_name = "MM", value_parser = parse_precision)]
    precision: Option<f64>,
}

impl ReadArgs {
    fn options(&self) -> ReadOptions {
        ReadOptions {
            unit: self.units,
            tolerance_mm: self.tolerance,
            precision_mm: self.precision,
        }
    }
}

fn parse_precision(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(p) if p.is_finite() && (0.0..=10.0).contains(&p) => Ok(p),
        _ => Err(format!(
            "'{s}' is not a precision: give the rounding grid in mm, from 0 (exact) to 10"
        )),
    }
}

fn parse_unit(s: &str) -> Result<Unit, String> {
    Unit::parse(s).ok_or_else(|| format!("unknown unit '{s}' (use mm, cm, m, in or ft)"))
}

fn parse_tolerance(s: &str) -> Result<f64, String> {
    let max = lamella::network::MAX_TOLERANCE_MM;
    match s.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 && t <= max => Ok(t),
        Ok(_) => Err(format!(
            "the node tolerance must be a length in mm above 0 and at most {max}"
        )),
        Err(_) => Err(format!("'{s}' is not a number (a length in mm)")),
    }
}

/// Refuse to write `out` when it is one of the `inputs` (the same file by
/// canonical path, or by device and inode: symlinks and hard links too).
fn refuse_overwriting_input(out: &Path, inputs: &[(&str, &Path)]) -> lamella::Result<()> {
    if !out.exists() {
        return Ok(());
    }
    for (what, input) in inputs {
        if io::same_file(out, input) {
            return Err(lamella::Error::input(
                out,
                lamella::error::Location::File,
                format!(
                    "is the {what} ({}): refusing to overwrite an input; choose another output",
                    input.display()
                ),
            ));
        }
    }
    Ok(())
}

/// Serialise a plan, refusing one with a NaN or infinite number (JSON would
/// write it as null).
fn plan_json(plan: &plan::Plan, target: &Path) -> lamella::Result<String> {
    if let Some(field) = lamella::formats::write::finite::first_non_finite(plan) {
        return Err(lamella::Error::network(
            target,
            format!("not written: {field} is not a finite number"),
        ));
    }
    Ok(plan::to_json(plan))
}

fn main() -> ExitCode {
    lamella::tune_allocator();
    let cli = Cli::parse();
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

fn run(cli: Cli) -> lamella::Result<ExitCode> {
    match cli.command {
        Command::Flat {
            network,
            profile,
            out,
            read,
        } => flat(&network, &profile, &out, &read),
        Command::Build {
            network,
            profile,
            out,
            kerf_compensation,
            allow_overstress,
            slots_from_flat,
            paper,
            quiet,
            read,
        } => build(
            &network,
            &profile,
            &out,
            &lamella::pipeline::build::BuildOptions {
                read: read.options(),
                kerf_compensation,
                allow_overstress,
                slots_from_flat,
                paper: lamella::formats::write::assembly::Paper::parse(&paper).unwrap_or_default(),
            },
            quiet,
        ),
        Command::Nodes { network, out, read } => nodes(&network, &out, &read),
        Command::Trace { spec, out } => trace(&spec, &out),
        Command::Check {
            network,
            profile,
            out,
            suggest,
            top,
            read,
        } => check(&network, &profile, out.as_deref(), suggest, top, &read),
        Command::Parts {
            network,
            profile,
            out,
            slots_from_flat,
            read,
        } => parts(&network, &profile, &out, &read, None, slots_from_flat),
        Command::Nest {
            network,
            profile,
            out,
            export_instance,
            slots_from_flat,
            read,
        } => parts(
            &network,
            &profile,
            &out,
            &read,
            Some(export_instance),
            slots_from_flat,
        ),
    }
}

fn flat(
    path: &Path,
    profile_path: &Path,
    out: &Path,
    read: &ReadArgs,
) -> lamella::Result<ExitCode> {
    let target = out.join("plan.json");
    let svg_target = out.join("flat.svg");
    for t in [&target, &svg_target] {
        refuse_overwriting_input(t, &[("network", path), ("profile", profile_path)])?;
    }
    let profile = io::profile_file::load(profile_path)?;
    let net = io::read_network(path, read.options())?;
    let an = analyze(&net, AnalysisOptions::for_network(&net))?;
    let problem = lamella::flat::problem(&an, &profile)?;
    let st = lamella::flat::solve(&problem);
    let report = lamella::check::check(&an, &profile);
    let model = Model::checked(&net, &an, profile.clone(), report, None);
    let mut plan = plan::build(&net, &an, &model);
    plan::add_flat(&mut plan, &st);
    let svg = lamella::formats::write::flat_svg::to_svg(
        &problem,
        &st,
        &format!("{} — flat assembly layout ({}), mm", net.name, profile.name),
    );
    plan::write_atomic(&target, plan_json(&plan, &target)?.as_bytes())?;
    plan::write_atomic(&svg_target, svg.as_bytes())?;
    for w in an.warnings() {
        eprintln!("warning: {w}");
    }
    println!(
        "{} flat ({}): {} nodes, {} strips; footprint {:.0} × {:.0} mm; energy {:.1} N·mm (start {:.1}); {} iterations, {}",
        net.name,
        profile.name,
        st.nodes.len(),
        st.strips.len(),
        st.footprint_mm[0],
        st.footprint_mm[1],
        st.energy_nmm,
        st.start_energy_nmm,
        st.iterations,
        if st.converged {
            format!("converged (projected gradient {:.1e}, lengths to {:.1e})", st.gradient_norm, st.max_length_error)
        } else {
            format!("NOT converged (projected gradient {:.1e}, lengths to {:.1e})", st.gradient_norm, st.max_length_error)
        }
    );
    let tolerance = profile.joint.rotation_tolerance_deg;
    let mut fails = Vec::new();
    if let Some(i) = st.max_rotation() {
        let n = &st.nodes[i];
        println!(
            "largest rotation: {:+.2}° at node {} (flat {:.2}°, erected {:.2}°); the slots allow ±{tolerance}°",
            n.rotation_deg, n.node, n.angle_deg, n.erected_angle_deg
        );
        if n.rotation_deg.abs() > tolerance {
            fails.push(format!(
                "node {} turns {:.2}° on erection, past the rotation tolerance {tolerance}°",
                n.node,
                n.rotation_deg.abs()
            ));
        }
    }
    if let Some(s) = st
        .strips
        .iter()
        .max_by(|a, b| a.utilization.total_cmp(&b.utilization))
    {
        println!(
            "largest stress while flat: {:.1} MPa in {} (utilisation {:.2})",
            s.max_bending_stress_mpa, s.strip, s.utilization
        );
        if s.utilization > 1.0 {
            fails.push(format!(
                "strip {} is overstressed while flat ({:.2} × the design strength)",
                s.strip, s.utilization
            ));
        }
    }
    if !st.converged {
        fails.push("the flat state did not converge".into());
    }
    println!("wrote {} and {}", target.display(), svg_target.display());
    if fails.is_empty() {
        println!("PASS: the grid assembles flat and erects within the slots and the strength");
        Ok(ExitCode::SUCCESS)
    } else {
        println!("FAIL: {}", fails.join("; "));
        Ok(ExitCode::from(3))
    }
}

fn build(
    network: &Path,
    profile: &Path,
    out: &Path,
    opts: &lamella::pipeline::build::BuildOptions,
    quiet: bool,
) -> lamella::Result<ExitCode> {
    // Hidden when stderr is not a terminal (indicatif's default target).
    let pb = if quiet {
        indicatif::ProgressBar::hidden()
    } else {
        indicatif::ProgressBar::new_spinner()
    };
    pb.set_style(
        indicatif::ProgressStyle::with_template("{spinner} {msg} {bar:30} {pos}/{len} [{elapsed}]")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
    );
    pb.enable_steady_tick(std::time::Duration::from_millis(120));
    let r = lamella::pipeline::build::build(network, profile, out, opts, &pb);
    pb.finish_and_clear();
    let r = r?;
    for w in &r.warnings {
        eprintln!("warning: {w}");
    }
    if r.files.is_empty() {
        if let Some(g) = &r.governing {
            eprintln!(
                "error: {} of {} strips overstressed (worst {} lamella {} at {:.2} × the design strength, {} governs): nothing written; see `lamella check`, or pass --allow-overstress",
                r.overstressed, r.strips, g.strip, g.lamella, g.utilization, g.governs
            );
        }
        return Ok(ExitCode::from(3));
    }
    if !quiet {
        print_build_summary(&r);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_build_summary(r: &lamella::pipeline::build::BuildReport) {
    let t = &r.takeoff;
    println!(
        "{} with {}: {} strips, {} edge strips, {} nodes",
        r.network, r.profile, r.strips, r.edges, r.nodes
    );
    for (kind, distinct, count) in &r.kinds {
        println!("  {:<13} {count:>8} ({distinct} distinct)", kind.as_str());
    }
    println!(
        "sheets: {} (lower bound {}), utilisation {:.1} %",
        r.sheets_used,
        r.lower_bound_sheets,
        100.0 * r.utilization
    );
    println!(
        "lamellas: {:.1} m of strip; mass {:.1} kg",
        t.totals.lamella_length_m, t.totals.mass_kg
    );
    if let (Some(cost), Some(cur)) = (t.totals.stock_cost, &t.currency) {
        println!("stock cost: {cost:.2} {cur}");
    }
    for h in t.hardware.iter().filter(|h| !h.made) {
        println!("  {:<17} {:>8}  {}", h.item, h.count, h.designation);
    }
    match &r.governing {
        Some(g) if r.passes() => println!(
            "elastic check: PASS, highest utilisation {:.2} ({} lamella {}, {} governs)",
            g.utilization, g.strip, g.lamella, g.governs
        ),
        Some(g) => println!(
            "elastic check: FAIL (--allow-overstress): {} strips overstressed, worst {} lamella {} at {:.2}",
            r.overstressed, g.strip, g.lamella, g.utilization
        ),
        None => println!("elastic check: no strips"),
    }
    println!(
        "wrote {} files into {} (plan.json, takeoff.csv, takeoff.json, assembly.pdf, sheets/)",
        r.files.len(),
        r.out.display()
    );
}

fn parts(
    path: &Path,
    profile_path: &Path,
    out: &Path,
    read: &ReadArgs,
    nest: Option<Option<PathBuf>>,
    slots_from_flat: bool,
) -> lamella::Result<ExitCode> {
    let target = out.join("plan.json");
    refuse_overwriting_input(&target, &[("network", path), ("profile", profile_path)])?;
    if let Some(Some(instance)) = &nest {
        refuse_overwriting_input(instance, &[("network", path), ("profile", profile_path)])?;
    }
    let profile = io::profile_file::load(profile_path)?;
    let net = io::read_network(path, read.options())?;
    let an = analyze(&net, AnalysisOptions::for_network(&net))?;
    let rotations = if slots_from_flat {
        let pr = lamella::flat::problem(&an, &profile)?;
        Some(lamella::flat::solve(&pr).rotations())
    } else {
        None
    };
    // The lamella lines the check integrates serve fabrication too.
    let (report, lines) = lamella::check::check_with_lines(&an, &profile);
    let kit =
        lamella::fabricate::fabricate_with_lines(&net, &an, &profile, rotations.as_ref(), lines)?;
    let model = Model::checked(&net, &an, profile.clone(), report, None);
    let mut plan = plan::build(&net, &an, &model);
    plan::add_parts(&mut plan, &kit);
    // Everything is computed before anything is written.
    let mut instance_text: Option<(PathBuf, String)> = None;
    let nested = match &nest {
        Some(instance) => {
            let n = lamella::nest::nest(&kit, &profile)?;
            plan::add_nest(&mut plan, &kit, &n);
            if let Some(file) = instance {
                let inst = lamella::plan::sparrow::instance(&net.name, &kit, &profile);
                let text = serde_json::to_string_pretty(&inst).map_err(|e| {
                    lamella::Error::input(file, lamella::error::Location::File, e.to_string())
                })?;
                instance_text = Some((file.clone(), text));
            }
            Some(n)
        }
        None => None,
    };
    plan::write_atomic(&target, plan_json(&plan, &target)?.as_bytes())?;
    if let Some((file, text)) = &instance_text {
        plan::write_atomic(file, text.as_bytes())?;
        println!("wrote {}", file.display());
    }
    for w in an.warnings() {
        eprintln!("warning: {w}");
    }
    for w in &kit.warnings {
        eprintln!("warning: {w}");
    }
    let s = &kit.summary;
    println!(
        "{} on {}: {} parts to make",
        profile.name,
        net.name,
        s.kinds.iter().map(|k| k.2).sum::<u64>()
    );
    for (kind, distinct, count) in &s.kinds {
        println!("  {:<13} {count:>8} ({distinct} distinct)", kind.as_str());
    }
    println!(
        "lamellas: {:.1} m of strip; mass {:.1} kg",
        s.lamella_length_mm / 1000.0,
        s.mass_kg
    );
    if s.stud_bars > 0 {
        println!("studs: {} bars of stud stock", s.stud_bars);
    }
    if let Some(n) = nested {
        println!("nest: {}", nest_line(&profile, &n));
    }
    println!("wrote {}", target.display());
    Ok(ExitCode::SUCCESS)
}

/// The nest's line: sheets (or coil length) per stock size, the bounds,
/// utilisation, cost where priced, time.
fn nest_line(profile: &Profile, n: &lamella::nest::Nest) -> String {
    let ns = &n.summary;
    let stock = &profile.stock;
    let size = |u: &lamella::nest::StockUse| {
        if stock.sizes[u.size].name.is_some() {
            u.stock.clone()
        } else {
            format!("{} mm", u.stock)
        }
    };
    let mut line = if let (true, Some(used), Some(bound)) =
        (stock.is_coil(), ns.length_used_mm, ns.length_bound_mm)
    {
        format!(
            "{:.3} m of {} mm coil in {} piece(s) (lower bound {:.3} m)",
            used / 1000.0,
            stock.sizes[0].width_mm,
            ns.sheets_used,
            bound / 1000.0
        )
    } else {
        let sizes: Vec<String> = n
            .stock_used
            .iter()
            .map(|u| format!("{} of {}", u.sheets, size(u)))
            .collect();
        let what = if n.stock_used.len() == 1 {
            format!("{} sheets of {}", ns.sheets_used, size(&n.stock_used[0]))
        } else {
            format!("{} sheets ({})", ns.sheets_used, sizes.join(" + "))
        };
        format!(
            "{what} (lower bound {}: area {}, lanes {})",
            ns.lower_bound_sheets, ns.area_bound_sheets, ns.lane_bound_sheets
        )
    };
    line += &format!("; utilisation {:.1} %", 100.0 * ns.utilization);
    if let Some(cost) = ns.cost {
        let currency = n.currency.as_deref().unwrap_or("");
        line += &format!(
            "; cost {cost:.2} {currency} (lower bound {:.2})",
            ns.cost_bound.unwrap_or(0.0)
        );
    }
    line + &format!("; {:.3} s", ns.seconds)
}

fn check(
    path: &Path,
    profile_path: &Path,
    out: Option<&Path>,
    want_suggestion: bool,
    top: Option<usize>,
    read: &ReadArgs,
) -> lamella::Result<ExitCode> {
    if let Some(dir) = out {
        let target = dir.join("plan.json");
        refuse_overwriting_input(&target, &[("network", path), ("profile", profile_path)])?;
    }
    let profile = io::profile_file::load(profile_path)?;
    let net = io::read_network(path, read.options())?;
    let an = analyze(&net, AnalysisOptions::for_network(&net))?;
    let report = lamella::check::check(&an, &profile);
    let suggestion = want_suggestion.then(|| lamella::check::suggest(&an, &profile));
    if let Some(dir) = out {
        let model = Model::checked(
            &net,
            &an,
            profile.clone(),
            report.clone(),
            suggestion.clone(),
        );
        let plan = plan::build(&net, &an, &model);
        let target = dir.join("plan.json");
        plan::write_atomic(&target, plan_json(&plan, &target)?.as_bytes())?;
    }
    for w in an.warnings() {
        eprintln!("warning: {w}");
    }
    println!(
        "{} on {}: {} × {} mm, {} per strip; f_d = {:.1} MPa; limits: R ≥ {:.0} mm in pure bending, twist ≤ {:.1} °/m in pure twist",
        profile.name,
        net.name,
        profile.section.thickness_mm,
        profile.section.height_mm,
        profile.section.per_strip,
        report.design_strength_mpa,
        report.limit_bending_radius_mm,
        report.limit_twist_deg_per_m
    );
    println!(
        "{:<12} {:>7} {:>11} {:>11} {:>13} {:>10}  governs",
        "strip", "lamella", "utilisation", "station mm", "min radius mm", "twist °/m"
    );
    let ranking = report.ranking();
    for &i in ranking.iter().take(top.unwrap_or(usize::MAX)) {
        let s = &report.strips[i];
        let l = s.worst();
        println!(
            "{:<12} {:>7} {:>11.3} {:>11.1} {:>13} {:>10.2}  {}{}",
            s.id,
            l.line.offset.number,
            l.utilization,
            l.governing_station_mm,
            l.min_bending_radius_mm
                .map_or("straight".to_string(), |r| format!("{r:.0}")),
            l.max_twist_deg_per_m,
            l.governs.as_str(),
            if l.utilization > 1.0 {
                "  OVERSTRESSED"
            } else {
                ""
            }
        );
    }
    if let Some(n) = top.filter(|n| *n < ranking.len()) {
        println!("… {} more strips", ranking.len() - n);
    }
    let worst = ranking.first().map(|&i| &report.strips[i]);
    let passes = report.passes();
    match worst {
        Some(w) if passes => println!(
            "PASS: all {} strips bend and twist into place elastically; highest utilisation {:.2} ({} lamella {}, {} governs)",
            report.strips.len(),
            w.worst().utilization,
            w.id,
            w.worst().line.offset.number,
            w.worst().governs.as_str()
        ),
        Some(w) => println!(
            "FAIL: {} of {} strips overstressed; worst {} lamella {} at {:.2} × the design strength ({} governs)",
            report.overstressed(),
            report.strips.len(),
            w.id,
            w.worst().line.offset.number,
            w.worst().utilization,
            w.worst().governs.as_str()
        ),
        None => println!("no strips"),
    }
    if let Some(s) = &suggestion {
        print_suggestion(s, &profile, passes);
    }
    if let Some(dir) = out {
        println!("wrote {}", dir.join("plan.json").display());
    }
    Ok(if passes {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(3)
    })
}

fn nodes(path: &Path, out: &Path, read: &ReadArgs) -> lamella::Result<ExitCode> {
    let target = out.join("plan.json");
    refuse_overwriting_input(&target, &[("network", path)])?;
    let net = io::read_network(path, read.options())?;
    let an = analyze(&net, AnalysisOptions::for_network(&net))?;
    let model = Model::new(&net, &an);
    let plan = plan::build(&net, &an, &model);
    plan::write_atomic(&target, plan_json(&plan, &target)?.as_bytes())?;
    for w in an.warnings() {
        eprintln!("warning: {w}");
    }
    let s = &plan.summary;
    println!(
        "{}: {} curves ({} points), {} nodes, {:.1} m of strip",
        net.name,
        s.curves,
        net.point_count(),
        s.nodes,
        s.total_length_mm / 1000.0
    );
    if let (Some(lo), Some(hi)) = (s.shortest_node_to_node_mm, s.longest_node_to_node_mm) {
        println!("node-to-node length: shortest {lo:.2} mm, longest {hi:.2} mm");
    }
    if let (Some(lo), Some(hi)) = (s.min_angle_deg, s.max_angle_deg) {
        println!("crossing angle: {lo:.3}° to {hi:.3}°");
    }
    println!(
        "largest normal-curvature residual kn: {:.6} 1/m",
        s.max_normal_curvature_per_m
    );
    println!("wrote {}", target.display());
    Ok(ExitCode::SUCCESS)
}

/// The `--suggest` lines: what to change when failing, the headroom when passing.
fn print_suggestion(s: &lamella::check::Suggestion, profile: &Profile, passes: bool) {
    let (t0, h0) = (profile.thickness_mm(), profile.height_mm());
    // The searches stop at 4 × the profile's value.
    let bound = |x: f64, cap: f64| {
        if x >= cap - 1e-9 {
            format!("{x:.4} mm or more")
        } else {
            format!("{x:.4} mm")
        }
    };
    if passes {
        if let Some(t) = s.max_thickness_mm {
            println!(
                "headroom: every strip still passes with lamellas {} thick (now {t0} mm)",
                bound(t, 4.0 * t0)
            );
        }
        if let Some(h) = s.max_height_mm {
            println!(
                "headroom: or {} high at {t0} mm thick (now {h0} mm)",
                bound(h, 4.0 * h0)
            );
        }
        return;
    }
    match s.max_thickness_mm {
        Some(t) => println!("suggest: every strip passes with lamellas at most {t:.4} mm thick (now {t0} mm)"),
        None => println!(
            "suggest: no thickness passes at {h0} mm height: the trapeze stress of the twist alone exceeds f_d"
        ),
    }
    if let Some(h) = s.max_height_mm {
        println!(
            "suggest: or keep {t0} mm and make the lamellas at most {h:.4} mm high (now {h0} mm)"
        );
    }
    if let Some((h, t)) = s.height_and_thickness_mm {
        println!(
            "suggest: or lower the lamellas to {h:.4} mm and make them at most {t:.4} mm thick"
        );
    }
}

/// Decimals of a traced network's coordinates (mm): 1e-6 mm, so rounding
/// (±5e-7 mm) stays far below what curvature between samples 25 mm apart
/// can resolve (4·5e-7 / 25² ≈ 3e-9 1/mm).
const COORDINATE_DECIMALS: usize = 6;

fn trace(spec_path: &Path, out: &Path) -> lamella::Result<ExitCode> {
    refuse_overwriting_input(out, &[("trace spec", spec_path)])?;
    let spec = io::trace_spec::load(spec_path)?;
    if let Some(mesh) = lamella::design::mesh_source::mesh_path(&spec, spec_path) {
        refuse_overwriting_input(out, &[("mesh", &mesh)])?;
    }
    let (net, report) = lamella::design::design(&spec, spec_path)?;
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
        Some("json") => io::network_file::to_json(&net, COORDINATE_DECIMALS),
        _ => io::network_file::to_yaml(&net, COORDINATE_DECIMALS, &comment),
    };
    plan::write_atomic(out, text.as_bytes())?;
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    let length_m: f64 = net
        .curves
        .iter()
        .map(|c| {
            c.points
                .windows(2)
                .map(|w| w[1].distance(w[0]))
                .sum::<f64>()
        })
        .sum::<f64>()
        / 1000.0;
    println!(
        "{}: {} A, {} B and {} edge curves, {} points, {:.1} m of curve",
        net.name,
        report.a_curves,
        report.b_curves,
        report.edges,
        net.curves.iter().map(|c| c.points.len()).sum::<usize>(),
        length_m
    );
    for note in &report.notes {
        println!("{note}");
    }
    let unusual: Vec<String> = report
        .stops
        .iter()
        .filter(|(_, a, b)| {
            *a != lamella::design::trace::Stop::Clip || *b != lamella::design::trace::Stop::Clip
        })
        .map(|(id, a, b)| format!("{id} ({}, {})", a.as_str(), b.as_str()))
        .collect();
    if !unusual.is_empty() {
        const SHOWN: usize = 8;
        let more = unusual.len().saturating_sub(SHOWN);
        println!(
            "curves ending elsewhere than the clip: {}{}",
            unusual[..unusual.len().min(SHOWN)].join(", "),
            if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            }
        );
    }
    println!("wrote {}", out.display());
    Ok(ExitCode::SUCCESS)
}
