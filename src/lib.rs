//! lamella: fabrication CAM for gridshells built from flat, straight strips
//! laid along the asymptotic curves of a minimal surface.
//!
//! Stages (see ARCHITECTURE.md), one folder each, over plain models
//! ([`network`], [`profile`], [`spec`], [`loads`]) and shared geometry
//! ([`geom`]):
//! * [`design`]: analytic minimal surfaces, meshes and soap films, tracing,
//!   clips, periodic unfolding → a network;
//! * [`analysis`]: nodes ([`analysis::topology`]), Darboux frames and
//!   curvatures ([`analysis::strip`], [`analysis::normal_field`]), each
//!   lamella on its own line ([`analysis::lines`]);
//! * [`check`]: the elastic check of every lamella against a [`profile`];
//! * [`flat`]: the flat assembly state;
//! * [`fabricate`]: flat parts per profile; [`nest`]: parts onto stock;
//! * [`structure`]: the erected grid as a frame (statics, buckling);
//! * [`plan`]: what every writer formats; [`formats`]: file readers and
//!   writers, safe output; [`pipeline`]: the commands and `lamella build`.

#![warn(missing_docs)]

pub mod analysis;
pub mod check;
pub mod design;
pub mod error;
pub mod fabricate;
pub mod flat;
pub mod formats;
pub mod geom;
pub mod loads;
pub mod nest;
pub mod network;
pub mod pipeline;
pub mod plan;
pub mod profile;
pub mod spec;
pub mod structure;

/// Every program built on lamella (the CLI, the tests and the benchmarks)
/// allocates through mimalloc: writing a big kit's files makes and frees
/// hundreds of thousands of small buffers a second, which glibc's
/// allocator served at about a tenth of the build's CPU time.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// mimalloc's `mi_option_purge_delay` and `mi_option_allow_thp` (their
/// indices in `mi_option_e` of mimalloc 3; the test
/// `the_option_indices_are_mimallocs` holds them to the library's
/// defaults).
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;
const MI_OPTION_ALLOW_THP: libmimalloc_sys::mi_option_t = 43;

/// Set the memory policy of a short-lived command such as `lamella build`
/// (the CLI and the benchmarks' children call it first thing in `main`,
/// before any other thread starts: mimalloc's option table is not
/// synchronised). Either part is left alone when its mimalloc variable is
/// set in the environment (`MIMALLOC_PURGE_DELAY`, `MIMALLOC_ALLOW_THP`).
///
/// * Memory the program frees is kept for its own reuse instead of being
///   handed back to the kernel a second later (purge delay "never"): the
///   working set comes and goes by hundreds of MiB between stages, and a
///   page handed back and faulted in again is zeroed once more.
/// * No transparent huge pages (mimalloc's `allow_thp` off and the
///   process's THP disabled, `PR_SET_THP_DISABLE`): a huge page is 2 MiB
///   zeroed at once, taken from large free blocks of memory.
///
/// Both matter most on a VM that reports free memory to its host (this
/// project's 2-core machine, `page_reporting`): reported pages fault on the
/// host again, and large free blocks are the ones reported. At 400 × 400,
/// alternating runs: keeping freed memory took system time from 1.6–4.5 s
/// to 1.7–1.9 s; disabling THP then from 3.1 s to 1.05 s (9.7 → 7.9–8.6 s
/// wall), with 200,000 small page faults instead of 900 huge ones and a
/// peak as low or lower.
#[allow(unsafe_code)]
pub fn tune_allocator() {
    if std::env::var_os("MIMALLOC_PURGE_DELAY").is_none() {
        // SAFETY: `mi_option_set` stores one value in mimalloc's option
        // table (bounds-checked by mimalloc); it has no other precondition
        // than not racing another thread's allocator calls, and the caller
        // runs before any thread is started.
        unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, -1) }
    }
    if std::env::var_os("MIMALLOC_ALLOW_THP").is_none() {
        // SAFETY: as above; and `prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0)`
        // only sets a flag of this process (its result is not needed:
        // where the kernel refuses, huge pages stay allowed).
        unsafe {
            libmimalloc_sys::mi_option_set(MI_OPTION_ALLOW_THP, 0);
            libc::prctl(libc::PR_SET_THP_DISABLE, 1, 0, 0, 0);
        }
    }
}

pub use analysis::{analyze, Analysis, AnalysisOptions};
pub use error::{Error, Result};
pub use network::{Family, Network};

#[cfg(test)]
mod allocator_tests {
    /// The indices name the purge delay and THP: mimalloc 3's defaults,
    /// 1000 ms and allowed (1), are what the options read in a program that
    /// has not changed them.
    #[test]
    #[allow(unsafe_code)]
    fn the_option_indices_are_mimallocs() {
        for (option, var, default) in [
            (super::MI_OPTION_PURGE_DELAY, "MIMALLOC_PURGE_DELAY", 1000),
            (super::MI_OPTION_ALLOW_THP, "MIMALLOC_ALLOW_THP", 1),
        ] {
            let want = std::env::var(var)
                .ok()
                .and_then(|v| v.parse::<i64>().ok())
                .unwrap_or(default);
            // SAFETY: reading an option has no precondition.
            let got = unsafe { libmimalloc_sys::mi_option_get(option) };
            assert_eq!(got as i64, want, "{var}");
        }
    }
}
