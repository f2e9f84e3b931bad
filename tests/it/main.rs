//! The integration tests, one crate (one link of lamella): a module per
//! area, the shared helpers in `support`.

#![allow(clippy::unwrap_used)] // tests may panic on broken invariants

mod support;

mod assembly;
mod bounds;
mod bracing;
mod build;
mod check;
mod check_cli;
mod cli_errors;
mod closed_forms;
mod edge_joints;
mod equilibrium;
mod exports;
mod film_truth;
mod flat;
mod frame;
mod frame_cli;
mod invariance;
mod layers;
mod loads;
mod mesh;
mod mesh_trace;
mod mesh_truth;
mod minimal;
mod model;
mod nest;
mod nest_stock;
mod nodes;
mod offset;
mod opensees;
mod output_safety;
mod parts;
mod readers;
mod readme;
mod robustness;
mod stock_groups;
mod trace;
mod traced_accuracy;
mod web_ends;
