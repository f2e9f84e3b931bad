//! What each command prints, and its exit status: 0 when done and
//! passing, 3 when the check or the flat state fails (warnings and errors
//! go to stderr, one line each).

use lamella::pipeline::build::BuildReport;
use lamella::pipeline::commands::{Done, Traced};
use lamella::profile::Profile;
use std::process::ExitCode;

/// Exit status of a failed verdict (overstressed, or a flat state that does
/// not erect).
const FAIL: u8 = 3;

fn warn(warnings: &[String]) {
    for w in warnings {
        eprintln!("warning: {w}");
    }
}

/// The build's progress bar (hidden when `quiet`, or when stderr is not a
/// terminal: indicatif's default target).
pub fn progress(quiet: bool) -> indicatif::ProgressBar {
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
    pb
}

/// `lamella build`: the summary, or why nothing was written.
pub fn build(r: &BuildReport, quiet: bool) -> ExitCode {
    warn(&r.warnings);
    if r.files.is_empty() {
        if let Some(st) = r.structure.as_ref().filter(|s| !s.passes) {
            eprintln!(
                "error: the grid does not stand: {}: nothing written; see `lamella frame`, or pass --allow-overstress",
                st.verdict
            );
        } else if let Some(g) = &r.governing {
            eprintln!(
                "error: {} of {} strips overstressed (worst {} lamella {} at {:.2} × the design strength, {} governs): nothing written; see `lamella check`, or pass --allow-overstress",
                r.overstressed, r.strips, g.strip, g.lamella, g.utilization, g.governs
            );
        }
        return ExitCode::from(FAIL);
    }
    if quiet {
        return ExitCode::SUCCESS;
    }
    let t = &r.takeoff;
    println!(
        "{} with {}: {} strips, {} edge strips, {} nodes",
        r.network, r.profile, r.strips, r.edges, r.nodes
    );
    for (kind, distinct, count) in &r.kinds {
        println!("  {:<13} {count:>8} ({distinct} distinct)", kind.as_str());
    }
    let by_group = if r.sheet_groups.len() > 1 {
        let list: Vec<String> = r
            .sheet_groups
            .iter()
            .map(|(name, used, _)| format!("{name} {used}"))
            .collect();
        format!("; by stock group: {}", list.join(", "))
    } else {
        String::new()
    };
    println!(
        "sheets: {} (lower bound {}), utilisation {:.1} %{by_group}",
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
    let item_w = t
        .hardware
        .iter()
        .map(|h| h.item.chars().count())
        .fold(17, usize::max);
    for h in &t.hardware {
        println!("  {:<item_w$} {:>8}  {}", h.item, h.count, h.designation);
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
    if let Some(st) = &r.structure {
        match st.passes {
            true => println!("{}", st.verdict),
            false => println!("{} (--allow-overstress)", st.verdict),
        }
    }
    println!(
        "wrote {} files into {} (plan.json, takeoff.csv, takeoff.json, setting-out.csv, assembly.pdf, model.glb, view.html, sheets/, parts/)",
        r.files.len(),
        r.out.display()
    );
    ExitCode::SUCCESS
}

/// `lamella frame`: the model's size, a line per combination, the
/// governing items and the verdict; exit status 3 when the grid does not
/// stand.
pub fn frame(done: &Done) -> ExitCode {
    let s = &done.session;
    warn(&s.warnings());
    let Some(st) = done.plan.as_ref().and_then(|p| p.structure.as_ref()) else {
        return ExitCode::from(1);
    };
    let m = &st.model;
    println!(
        "{} under {}: {} model nodes, {} beam elements ({} per node-to-node span), {} links, {} supports; span {:.0} mm",
        s.network().name,
        st.loads,
        m.nodes,
        m.beams,
        m.elements_per_span,
        m.links,
        m.supports,
        st.span_mm
    );
    println!(
        "{:<28} {:>10} {:>11} {:>14}  {:<10} {:>10}",
        "combination", "α_cr", "utilisation", "max. disp. mm", "at node", "load z kN"
    );
    for c in &st.combinations {
        println!(
            "{:<28} {:>10} {:>11} {:>14.2}  {:<10} {:>10.2}",
            c.name,
            c.alpha_cr
                .first()
                .map_or("–".to_string(), |a| format!("{a:.2}")),
            c.max_utilisation
                .map_or("–".to_string(), |u| format!("{u:.3}")),
            c.max_translation_mm,
            c.max_translation_node,
            c.load_sum_n[2] / 1000.0
        );
    }
    if let Some(g) = &st.governing {
        println!(
            "governing: {} lamella {} at {:.0} mm, {} check, utilisation {:.2} ({})",
            g.strip, g.lamella, g.station_mm, g.check, g.utilisation, g.combination
        );
    }
    if let Some(b) = &st.bracing {
        bracing(b);
    }
    println!("{}", st.verdict);
    wrote(done);
    if st.passes {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(FAIL)
    }
}

/// The bracing's lines: what was chosen, how each figure moved, the cable.
fn bracing(b: &lamella::plan::structure::PlanBracing) {
    println!(
        "bracing ({} layout, {} diagonals): {} cables of {} candidates, {} ⌀{} mm, pretension {:.2} kN, {:.1} m pin to pin ({:.1} m of wire)",
        b.layout,
        b.diagonals,
        b.cables.len(),
        b.candidates,
        b.designation,
        b.diameter_mm,
        b.pretension_kn,
        b.total_length_m,
        b.total_wire_m
    );
    if b.too_short > 0 {
        println!(
            "  {} diagonals left out: pin to pin no longer than the fittings ({} mm terminal + {} mm turnbuckle)",
            b.too_short, b.fittings.terminal_mm, b.fittings.turnbuckle_mid_mm
        );
    }
    if b.no_bolt > 0 {
        println!(
            "  {} diagonals left out: they end at an edge joint without a bolt for the eye plate",
            b.no_bolt
        );
    }
    let show = |x: Option<f64>, d: usize| x.map_or("–".to_string(), |v| format!("{v:.d$}"));
    let goal = |x: Option<f64>, sign: &str, d: usize| {
        x.map_or("no target".to_string(), |v| {
            format!("target {sign} {v:.d$}")
        })
    };
    println!(
        "  α_cr {} → {} ({}); deflection {} → {} mm ({}); utilisation {} → {} ({})",
        show(b.before.alpha_cr, 2),
        show(b.after.alpha_cr, 2),
        goal(b.targets.alpha_cr, "≥", 2),
        show(b.before.deflection_mm, 1),
        show(b.after.deflection_mm, 1),
        goal(b.targets.deflection_mm, "≤", 1),
        show(b.before.utilisation, 2),
        show(b.after.utilisation, 2),
        goal(b.targets.utilisation, "≤", 2),
    );
    println!(
        "  largest cable force {:.2} kN, F_Rd {:.2} kN; eye plate F_Rd {:.2} kN",
        b.max_force_kn, b.design_resistance_kn, b.fittings.eye_plate_resistance_kn
    );
}

/// `lamella nodes`.
pub fn nodes(done: &Done) -> ExitCode {
    let s = &done.session;
    warn(&s.warnings());
    let net = s.network();
    if let Some(plan) = &done.plan {
        let sm = &plan.summary;
        println!(
            "{}: {} curves ({} points), {} nodes, {:.1} m of strip",
            net.name,
            sm.curves,
            net.point_count(),
            sm.nodes,
            sm.total_length_mm / 1000.0
        );
        if let (Some(lo), Some(hi)) = (sm.shortest_node_to_node_mm, sm.longest_node_to_node_mm) {
            println!("node-to-node length: shortest {lo:.2} mm, longest {hi:.2} mm");
        }
        if let (Some(lo), Some(hi)) = (sm.min_angle_deg, sm.max_angle_deg) {
            println!("crossing angle: {lo:.3}° to {hi:.3}°");
        }
        println!(
            "largest normal-curvature residual kn: {:.6} 1/m",
            sm.max_normal_curvature_per_m
        );
    }
    wrote(done);
    ExitCode::SUCCESS
}

fn wrote(done: &Done) {
    for f in &done.written {
        println!("wrote {}", f.display());
    }
}

/// `lamella check`: the table of strips by utilisation, the verdict, the
/// suggestion.
pub fn check(done: &Done, top: Option<usize>) -> ExitCode {
    let s = &done.session;
    warn(&s.warnings());
    let (Some(report), Ok(profile)) = (s.checked(), s.profile()) else {
        return ExitCode::from(1);
    };
    println!(
        "{} on {}: {} × {} mm, {} per strip; f_d = {:.1} MPa; limits: R ≥ {:.0} mm in pure bending, twist ≤ {:.1} °/m in pure twist, sagitta ≤ {:.2} mm",
        profile.name,
        s.network().name,
        profile.section.thickness_mm,
        profile.section.height_mm,
        profile.section.per_strip,
        report.design_strength_mpa,
        report.limit_bending_radius_mm,
        report.limit_twist_deg_per_m,
        report.limit_sagitta_mm
    );
    println!(
        "{:<12} {:>7} {:>11} {:>11} {:>13} {:>10} {:>10}  governs",
        "strip", "lamella", "utilisation", "station mm", "min radius mm", "twist °/m", "sagitta mm"
    );
    let ranking = report.ranking();
    for &i in ranking.iter().take(top.unwrap_or(usize::MAX)) {
        let s = &report.strips[i];
        let l = s.worst();
        println!(
            "{:<12} {:>7} {:>11.3} {:>11.1} {:>13} {:>10.2} {:>10.3}  {}{}{}",
            s.id,
            l.line.offset.number,
            l.utilization,
            l.governing_station_mm,
            l.min_bending_radius_mm
                .map_or("straight".to_string(), |r| format!("{r:.0}")),
            l.max_twist_deg_per_m,
            s.sagitta_mm(),
            l.governs.as_str(),
            if l.utilization > 1.0 {
                "  OVERSTRESSED"
            } else {
                ""
            },
            if report.straight_enough(s) {
                ""
            } else {
                "  BOWED"
            }
        );
    }
    if let Some(n) = top.filter(|n| *n < ranking.len()) {
        println!("… {} more strips", ranking.len() - n);
    }
    let worst = ranking.first().map(|&i| &report.strips[i]);
    let passes = report.passes();
    let stressed_ok = report.overstressed() == 0;
    match worst {
        Some(w) if passes => println!(
            "PASS: all {} strips bend and twist into place elastically; highest utilisation {:.2} ({} lamella {}, {} governs); largest sagitta {:.3} mm",
            report.strips.len(),
            w.worst().utilization,
            w.id,
            w.worst().line.offset.number,
            w.worst().governs.as_str(),
            report.most_bowed().map_or(0.0, |b| b.sagitta_mm())
        ),
        Some(_) if stressed_ok => {}
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
    if let Some(b) = report.most_bowed().filter(|b| !report.straight_enough(b)) {
        let l = b.most_bowed();
        println!(
            "FAIL: {} of {} strips bowed; {} lamella {} bows {:.3} mm off its chord, unrolled in its own plane (normal curvature kn: strong-axis bending), over the {:.3} mm limit (check.max_sagitta_mm)",
            report.bowed(),
            report.strips.len(),
            b.id,
            l.line.offset.number,
            l.sagitta_mm,
            report.limit_sagitta_mm
        );
    }
    if let Some(suggestion) = s.suggested() {
        // The section changes the stresses only, never the bow.
        print_suggestion(suggestion, profile, stressed_ok);
    }
    wrote(done);
    if passes {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(FAIL)
    }
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

/// `lamella parts` and `lamella nest`: the parts by kind, the nest's line.
pub fn parts(done: &Done) -> ExitCode {
    let s = &done.session;
    // The sparrow instance is written after plan.json.
    for f in done.written.iter().skip(1) {
        println!("wrote {}", f.display());
    }
    warn(&s.warnings());
    let (Some(kit), Ok(profile)) = (s.made(), s.profile()) else {
        return ExitCode::from(1);
    };
    let k = &kit.summary;
    println!(
        "{} on {}: {} parts to make",
        profile.name,
        s.network().name,
        k.kinds.iter().map(|k| k.2).sum::<u64>()
    );
    for (kind, distinct, count) in &k.kinds {
        println!("  {:<13} {count:>8} ({distinct} distinct)", kind.as_str());
    }
    println!(
        "lamellas: {:.1} m of strip; mass {:.1} kg",
        k.lamella_length_mm / 1000.0,
        k.mass_kg
    );
    match s.nested() {
        Some(n) => {
            for (k, line) in nest_lines(profile, n).into_iter().enumerate() {
                if k == 0 {
                    println!("nest: {line}");
                } else {
                    println!("{line}");
                }
            }
        }
        None if k.stud_bars > 0 => println!("studs: {} bars of stud stock", k.stud_bars),
        None => {}
    }
    if let Some(f) = done.written.first() {
        println!("wrote {}", f.display());
    }
    ExitCode::SUCCESS
}

/// The nest's lines: with one stock group its line; with several, the
/// sums, then each group's line.
fn nest_lines(profile: &Profile, n: &lamella::nest::Nest) -> Vec<String> {
    let groups = profile.stock_groups();
    let line_of = |g: &lamella::nest::GroupNest| {
        let stock = groups
            .iter()
            .find(|s| s.name == g.name)
            .map_or(&profile.stock, |s| &s.stock);
        format!(
            "{} ({}, {} mm): {}",
            g.name,
            g.material,
            lamella::profile::groups::trim_mm(g.thickness_mm),
            nest_line(
                stock,
                &g.summary,
                &g.stock_used,
                n.currency.as_deref(),
                g.form
            )
        )
    };
    if n.groups.len() == 1 {
        return vec![line_of(&n.groups[0])];
    }
    let ns = &n.summary;
    let mut total = format!(
        "{} pieces of stock in {} groups (lower bound {}); utilisation {:.1} %",
        ns.sheets_used,
        n.groups.len(),
        ns.lower_bound_sheets,
        100.0 * ns.utilization
    );
    if let Some(cost) = ns.cost {
        let currency = n.currency.as_deref().unwrap_or("");
        total += &format!(
            "; cost {cost:.2} {currency} (lower bound {:.2})",
            ns.cost_bound.unwrap_or(0.0)
        );
    }
    total += &format!("; {:.3} s", ns.seconds);
    std::iter::once(total)
        .chain(n.groups.iter().map(|g| format!("  {}", line_of(g))))
        .collect()
}

/// One group's line: sheets (or coil length, or bars) per stock size, the
/// bounds, utilisation, cost where priced, time.
fn nest_line(
    stock: &lamella::profile::Stock,
    ns: &lamella::nest::NestSummary,
    stock_used: &[lamella::nest::StockUse],
    currency: Option<&str>,
    form: lamella::profile::StockForm,
) -> String {
    let size = |u: &lamella::nest::StockUse| {
        if stock.sizes.get(u.size).is_some_and(|z| z.name.is_some()) {
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
    } else if form == lamella::profile::StockForm::Bar {
        format!(
            "{} bars of {} mm (lower bound {})",
            ns.sheets_used,
            stock_used
                .first()
                .map_or(String::new(), |u| u.stock.clone()),
            ns.lower_bound_sheets
        )
    } else {
        let sizes: Vec<String> = stock_used
            .iter()
            .map(|u| format!("{} of {}", u.sheets, size(u)))
            .collect();
        let what = if stock_used.len() == 1 {
            format!("{} sheets of {}", ns.sheets_used, size(&stock_used[0]))
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
        let currency = currency.unwrap_or("");
        line += &format!(
            "; cost {cost:.2} {currency} (lower bound {:.2})",
            ns.cost_bound.unwrap_or(0.0)
        );
    }
    line + &format!("; {:.3} s", ns.seconds)
}

/// `lamella flat`: the flat state's figures and its verdict.
/// `lamella view`: what the model holds and where it went.
pub fn view(done: &Done) -> ExitCode {
    let s = &done.session;
    warn(&s.warnings());
    warn(&done.notes);
    let Some(plan) = &done.plan else {
        return ExitCode::from(1);
    };
    let strips = plan.strips.len();
    let detail = if !lamella::formats::write::gltf::full_detail(plan) {
        "ribbons (a big grid: no slots, washers or studs)"
    } else if plan.parts.is_some() {
        "solids with slots and hardware"
    } else {
        "solids (no parts: no slots or hardware)"
    };
    let flat = if plan.flat.is_some() {
        ", the flat state as a morph target"
    } else {
        ""
    };
    println!(
        "{}: {strips} strips, {} nodes as {detail}{flat}",
        plan.network.name,
        plan.nodes.len()
    );
    for f in &done.written {
        println!("wrote {}", f.display());
    }
    ExitCode::SUCCESS
}

pub fn flat(done: &Done) -> ExitCode {
    let s = &done.session;
    warn(&s.warnings());
    let (Some((_, st)), Ok(profile)) = (s.flat_state(), s.profile()) else {
        return ExitCode::from(1);
    };
    let converged = match (st.least_rotation_deg, st.converged) {
        (Some(_), _) => "no least-bending state found; laid out for least rotation",
        (None, true) => "converged",
        (None, false) => "NOT converged",
    };
    println!(
        "{} flat ({}): {} nodes, {} strips; footprint {:.0} × {:.0} mm; energy {:.1} N·mm (start {:.1}); {} iterations, {converged} (projected gradient {:.1e}, lengths to {:.1e})",
        s.network().name,
        profile.name,
        st.nodes.len(),
        st.strips.len(),
        st.footprint_mm[0],
        st.footprint_mm[1],
        st.energy_nmm,
        st.start_energy_nmm,
        st.iterations,
        st.gradient_norm,
        st.max_length_error
    );
    let tolerance = profile.joint.rotation_tolerance_deg;
    let mut fails = Vec::new();
    // A layout of least rotation that misses the slots or the lengths is
    // stated as the best found; one within them that is not stationary is
    // no state the grid rests in (it would have to be held there), so it
    // fails too, saying so.
    let beyond = st
        .least_rotation_deg
        .filter(|&best| best > tolerance || st.max_length_error > lamella::flat::LENGTH_TOLERANCE);
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
    if let Some(strip) = st
        .strips
        .iter()
        .max_by(|a, b| a.utilization.total_cmp(&b.utilization))
    {
        println!(
            "largest stress while flat: {:.1} MPa in {} (utilisation {:.2})",
            strip.max_bending_stress_mpa, strip.strip, strip.utilization
        );
        if strip.utilization > 1.0 {
            fails.push(format!(
                "strip {} is overstressed while flat ({:.2} × the design strength)",
                strip.strip, strip.utilization
            ));
        }
    }
    if let Some(best) = beyond {
        // One statement instead of the figures of a layout that misses.
        fails = vec![format!(
            "no flat state within ±{tolerance}° found; the best needs ±{best:.2}°"
        )];
    } else if let (Some(best), false) = (st.least_rotation_deg, st.converged) {
        fails.push(format!(
            "no flat state at rest found: a layout within ±{best:.2}° holds the lengths but is not stationary (projected gradient {:.1e}), so the grid would have to be held in it",
            st.gradient_norm
        ));
    } else if !st.converged {
        fails.push("the flat state did not converge".into());
    }
    let names: Vec<String> = done
        .written
        .iter()
        .map(|f| f.display().to_string())
        .collect();
    println!("wrote {}", names.join(" and "));
    if fails.is_empty() {
        println!("PASS: the grid assembles flat and erects within the slots and the strength");
        ExitCode::SUCCESS
    } else {
        println!("FAIL: {}", fails.join("; "));
        ExitCode::from(FAIL)
    }
}

/// `lamella trace`: counts, notes, curves that end elsewhere than the clip.
pub fn trace(t: &Traced) -> ExitCode {
    warn(&t.report.warnings);
    let net = &t.network;
    let report = &t.report;
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
    println!("wrote {}", t.written.display());
    ExitCode::SUCCESS
}
