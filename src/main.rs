//! The `lamella` command line.

use clap::{Parser, Subcommand};
use lamella::io::{self, plan, ReadOptions};
use lamella::network::Unit;
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
}

#[derive(clap::Args, Clone)]
struct ReadArgs {
    /// Unit of OBJ files and unitless DXF files (mm, cm, m, in, ft); overrides a DXF's $INSUNITS.
    #[arg(long, value_parser = parse_unit)]
    units: Option<Unit>,
    /// Node tolerance in mm: the largest gap between two curves that is still a node
    /// (default: the file's `tolerance`, else 0.5 mm).
    #[arg(long)]
    tolerance: Option<f64>,
}

impl ReadArgs {
    fn options(&self) -> ReadOptions {
        ReadOptions {
            unit: self.units,
            tolerance_mm: self.tolerance,
        }
    }
}

fn parse_unit(s: &str) -> Result<Unit, String> {
    Unit::parse(s).ok_or_else(|| format!("unknown unit '{s}' (use mm, cm, m, in or ft)"))
}

fn main() -> ExitCode {
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
        Command::Nodes { network, out, read } => nodes(&network, &out, &read),
    }
}

fn nodes(path: &Path, out: &Path, read: &ReadArgs) -> lamella::Result<ExitCode> {
    let net = io::read_network(path, read.options())?;
    let an = analyze(&net, AnalysisOptions::for_network(&net))?;
    let plan = plan::build(&net, &an);
    let target = out.join("plan.json");
    plan::write_atomic(&target, plan::to_json(&plan).as_bytes())?;
    for w in &plan.warnings {
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
