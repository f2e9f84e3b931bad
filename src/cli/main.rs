//! The `lamella` command line: clap parses, [`lamella::pipeline`] runs the
//! stages and writes, [`report`] prints.

mod report;

use clap::{Parser, Subcommand};
use lamella::formats::read::ReadOptions;
use lamella::network::Unit;
use lamella::pipeline::{self, commands, Inputs};
use std::path::PathBuf;
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
    /// DIR/plan.json, DIR/sheets/sheet-NNN.dxf and .svg per stock sheet
    /// (in cut order: engraving, inner contours, outlines), DIR/parts/ID.dxf
    /// and .svg per distinct part with DIR/parts/parts.csv,
    /// DIR/takeoff.csv, DIR/takeoff.json, DIR/assembly.pdf (the assembly
    /// sheets) and the 3D model DIR/model.glb with its page DIR/view.html
    /// (with --slots-from-flat, the flat state as a morph target). Output is staged beside DIR and
    /// moved into place only when complete. Exit status 3 (nothing written)
    /// when a strip is overstressed, unless --allow-overstress.
    Build {
        #[command(flatten)]
        stage: StageArgs,
        /// Output directory. Created if missing; lamella's files from an
        /// earlier build are replaced, other files are left alone.
        #[arg(long)]
        out: PathBuf,
        /// Offset outer contours out and inner contours in by half the
        /// kerf of each part's stock group (for controllers that do not
        /// compensate).
        #[arg(long)]
        kerf_compensation: bool,
        /// Write the kit even when a strip is overstressed.
        #[arg(long)]
        allow_overstress: bool,
        /// Also write each sheet's outline, on the non-plotting reference
        /// layer SHEET (off by default: CAM software that cuts every closed
        /// contour would cut it).
        #[arg(long)]
        sheet_outline: bool,
        /// Put each part's id as screen text into the SVGs (group LABELS;
        /// off by default: laser software imports text as something to engrave).
        #[arg(long)]
        svg_labels: bool,
        /// Fit cut contours by lines and arcs within this many mm (0: keep
        /// the polygons; at most a quarter of the profile's part spacing).
        #[arg(long, value_name = "MM", default_value_t = lamella::formats::write::arcs::DEFAULT_TOLERANCE_MM)]
        arc_tolerance: f64,
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
        /// Also analyse the erected grid as a frame under this loads file
        /// (see `lamella frame`): plan.json `structure`, DIR/structure/
        /// (opensees.py, model.json) and the structure pages of
        /// assembly.pdf. A grid that does not stand stops the build like
        /// an overstressed strip (exit status 3, nothing written) unless
        /// --allow-overstress.
        #[arg(long, value_name = "LOADS.yaml")]
        loads: Option<PathBuf>,
        #[command(flatten)]
        read: ReadArgs,
    },
    /// Will the erected grid stand? Every lamella a chain of beams on its
    /// own offset line, joints and shear blocks as the profile makes them,
    /// the strips' erection stresses as the initial state; under the loads
    /// file's supports, load cases and EN 1990 combinations: linear
    /// statics, the critical load factor α_cr and its modes, second order
    /// where α_cr < 10, the EN 1993/1995 checks, deflections and
    /// reactions. Prints the verdict; writes DIR/plan.json (with
    /// `structure`), DIR/structure/opensees.py (the model as a runnable
    /// OpenSeesPy script) and DIR/structure/model.json. Exit status 3 when
    /// a ULS utilisation exceeds 1, the grid buckles below the load or a
    /// deflection exceeds its limit.
    Frame {
        #[command(flatten)]
        stage: StageArgs,
        /// The loads file (supports, load cases, combinations; see
        /// samples/loads/pavilion.yaml).
        #[arg(long, value_name = "LOADS.yaml")]
        loads: PathBuf,
        /// Output directory (created if missing).
        #[arg(long)]
        out: PathBuf,
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
        #[command(flatten)]
        stage: StageArgs,
        /// Directory for plan.json and flat.svg (created if missing).
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        read: ReadArgs,
    },
    /// The 3D model of the erected grid: DIR/model.glb (binary glTF: every
    /// lamella a solid on its own offset line with its slots, edge strips,
    /// washers and studs, node markers, coloured by the elastic check's
    /// utilisation) and DIR/view.html (a self-contained page that shows
    /// it: orbit, pan, zoom, pick a strip, toggle families). `build` writes
    /// both too.
    View {
        #[command(flatten)]
        stage: StageArgs,
        /// Directory for model.glb and view.html (created if missing).
        #[arg(long)]
        out: PathBuf,
        /// Also solve the flat state (see `lamella flat`) and put it in
        /// the model as a morph target (a slider in view.html).
        #[arg(long)]
        flat: bool,
        #[command(flatten)]
        read: ReadArgs,
    },
    /// Find the nodes of a network and compute node-to-node lengths, curvature
    /// and twist of every strip; write DIR/plan.json and print a summary.
    Nodes {
        /// The network file (.yaml, .yml, .json, .obj, .dxf).
        network: PathBuf,
        /// Output directory (created if missing); plan.json is written there.
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        read: ReadArgs,
    },
    /// Trace a network from a spec (surface, scale, placement, seed,
    /// spacing, clip, sampling) and write it as a network file (YAML, with
    /// normals). Surfaces: the analytic enneper, catenoid, helicoid, scherk,
    /// schwarz_d and hypar; mesh (a triangle mesh file: OBJ, PLY or STL);
    /// minimal (the soap film form-found on boundaries_mm). Nets: asymptotic
    /// (the strips) or principal.
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
        #[command(flatten)]
        stage: StageArgs,
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
        #[command(flatten)]
        stage: StageArgs,
        /// Directory for plan.json (created if missing).
        #[arg(long)]
        out: PathBuf,
        /// Also write each stock group's parts as a sparrow strip-packing
        /// instance (jagua-rs 0.7 JSON; parts grown by half the group's
        /// kerf plus spacing), named by group beside FILE
        /// (`kit.json` → `kit.lamella-1.5.json`, …; bar groups not).
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
    /// swept slots or node holes, shear blocks, star washers, studs
    /// (two-level grids), splice plates, and edge strips (the boundary
    /// bands, unrolled); write
    /// DIR/plan.json with everything `check` writes plus `parts`, and print
    /// a parts summary.
    Parts {
        #[command(flatten)]
        stage: StageArgs,
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

/// The network file and the material profile a stage reads.
#[derive(clap::Args, Clone)]
struct StageArgs {
    /// The network file (.yaml, .yml, .json, .obj, .dxf).
    network: PathBuf,
    /// The material profile (profiles/*.yaml).
    #[arg(long)]
    profile: PathBuf,
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

/// The session's inputs from the command's arguments.
fn inputs(
    network: PathBuf,
    profile: Option<PathBuf>,
    read: &ReadArgs,
    slots_from_flat: bool,
) -> Inputs {
    Inputs {
        network,
        profile,
        read: read.options(),
        slots_from_flat,
        loads: None,
    }
}

impl StageArgs {
    /// The session's inputs: this network and profile, read as `read` says.
    fn inputs(self, read: &ReadArgs, slots_from_flat: bool) -> Inputs {
        inputs(self.network, Some(self.profile), read, slots_from_flat)
    }
}

fn run(cli: Cli) -> lamella::Result<ExitCode> {
    match cli.command {
        Command::Build {
            stage,
            out,
            kerf_compensation,
            allow_overstress,
            sheet_outline,
            svg_labels,
            arc_tolerance,
            slots_from_flat,
            paper,
            quiet,
            loads,
            read,
        } => {
            let opts = pipeline::build::BuildOptions {
                kerf_compensation,
                allow_overstress,
                sheet_outline,
                svg_labels,
                arc_tolerance_mm: Some(arc_tolerance),
                paper: lamella::formats::write::assembly::Paper::parse(&paper).unwrap_or_default(),
            };
            let progress = report::progress(quiet);
            let mut inputs = stage.inputs(&read, slots_from_flat);
            inputs.loads = loads;
            let r = pipeline::build::build(inputs, &out, &opts, &progress);
            progress.finish_and_clear();
            Ok(report::build(&r?, quiet))
        }
        Command::Frame {
            stage,
            loads,
            out,
            read,
        } => {
            let mut inputs = stage.inputs(&read, false);
            inputs.loads = Some(loads);
            Ok(report::frame(&commands::frame(inputs, &out)?))
        }
        Command::Flat { stage, out, read } => Ok(report::flat(&commands::flat(
            stage.inputs(&read, false),
            &out,
        )?)),
        Command::View {
            stage,
            out,
            flat,
            read,
        } => Ok(report::view(&commands::view(
            stage.inputs(&read, false),
            &out,
            flat,
        )?)),
        Command::Nodes { network, out, read } => Ok(report::nodes(&commands::nodes(
            inputs(network, None, &read, false),
            &out,
        )?)),
        Command::Trace { spec, out } => Ok(report::trace(&commands::trace(&spec, &out)?)),
        Command::Check {
            stage,
            out,
            suggest,
            top,
            read,
        } => Ok(report::check(
            &commands::check(stage.inputs(&read, false), out.as_deref(), suggest)?,
            top,
        )),
        Command::Parts {
            stage,
            out,
            slots_from_flat,
            read,
        } => Ok(report::parts(&commands::parts(
            stage.inputs(&read, slots_from_flat),
            &out,
            &commands::PartsGoal::Parts,
        )?)),
        Command::Nest {
            stage,
            out,
            export_instance,
            slots_from_flat,
            read,
        } => Ok(report::parts(&commands::parts(
            stage.inputs(&read, slots_from_flat),
            &out,
            &commands::PartsGoal::Nest {
                instance: export_instance,
            },
        )?)),
    }
}
