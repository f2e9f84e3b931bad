//! Writers: each formats a finished plan (and nothing else) as bytes.

pub mod arcs;
pub mod assembly;
pub mod drawing;
pub mod dxf;
pub mod finite;
pub mod flat_svg;
pub mod gltf;
pub mod plan_json;
pub mod setting_out;
pub mod sparrow;
pub mod svg;
pub mod takeoff;
pub mod view;
