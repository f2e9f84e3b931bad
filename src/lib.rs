//! lamella: fabrication CAM for gridshells built from flat, straight strips
//! laid along the asymptotic curves of a minimal surface.
//!
//! Stages (see ARCHITECTURE.md), one folder each:
//! * [`design`]: analytic minimal surfaces, tracing, clips, periodic unfolding
//!   → a network file;
//! * [`io`]: file formats only (network files in, plan.json out, profiles,
//!   trace specs) → [`network::Network`] in mm, validated;
//! * [`geom`]: smooth curves through samples, smoothed to their precision;
//! * [`analysis`]: nodes ([`analysis::topology`]), Darboux frames and
//!   curvatures ([`analysis::strip`], [`analysis::normal_field`]), lamella
//!   lines and the finished model ([`analysis::model`]);
//! * [`check`]: the elastic check of every lamella against a [`profile`];
//! * [`fabricate`]: flat parts per profile; [`nest`]: parts onto stock;
//! * [`emit`]: cutting files, takeoff, safe output; `lamella build`.

#![warn(missing_docs)]

pub mod analysis;
pub mod check;
pub mod design;
pub mod emit;
pub mod error;
pub mod fabricate;
pub mod flat;
pub mod geom;
pub mod io;
pub mod mesh;
pub mod minimal;
pub mod nest;
pub mod network;
pub mod profile;

/// Every program built on lamella (the CLI, the tests and the benchmarks)
/// allocates through mimalloc: writing a big kit's files makes and frees
/// hundreds of thousands of small buffers a second, which glibc's
/// allocator served at about a tenth of the build's CPU time.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// mimalloc's `mi_option_purge_delay` (its index in `mi_option_e` of
/// mimalloc 3; the test `the_purge_delay_index_is_mimallocs` holds it to
/// the library's default).
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

/// Keep memory the program frees for its own reuse instead of handing it
/// back to the kernel a second later (mimalloc's purge delay set to
/// "never", unless `MIMALLOC_PURGE_DELAY` is set in the environment).
///
/// For a short-lived command such as `lamella build`: its working set
/// comes and goes by hundreds of MiB between stages, and every page handed
/// back and faulted in again is zeroed by the kernel once more. On a VM that
/// reports free memory to its host (this project's 2-core machine) those
/// pages also fault on the host, and the 400 × 400 build spent 1.6–4.5 s of
/// system time, against 1.7–1.9 s when freed memory is kept; its peak grows
/// from about 840 to 900 MiB. Call it first thing in `main`, before any
/// other thread starts (mimalloc's option table is not synchronised).
#[allow(unsafe_code)]
pub fn keep_freed_memory() {
    if std::env::var_os("MIMALLOC_PURGE_DELAY").is_some() {
        return;
    }
    // SAFETY: `mi_option_set` stores one value in mimalloc's option table
    // (bounds-checked by mimalloc); it has no other precondition than not
    // racing another thread's allocator calls, and the caller runs before
    // any thread is started.
    unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) }
}

pub use analysis::{analyze, Analysis, AnalysisOptions};
pub use error::{Error, Result};
pub use network::{Family, Network};

#[cfg(test)]
mod allocator_tests {
    /// The index names the purge delay: mimalloc 3's default, 1000 ms, is
    /// what the option reads in a program that has not changed it.
    #[test]
    #[allow(unsafe_code)]
    fn the_purge_delay_index_is_mimallocs() {
        let want = std::env::var("MIMALLOC_PURGE_DELAY")
            .ok()
            .and_then(|v| v.parse::<i64>().ok())
            .unwrap_or(1000);
        // SAFETY: reading an option has no precondition.
        let got = unsafe { libmimalloc_sys::mi_option_get(super::MI_OPTION_PURGE_DELAY) };
        assert_eq!(got as i64, want);
    }
}
