//! Tells the viewer's tests whether they can open a window: sets the cfg `rebond_has_xvfb` when
//! `xvfb-run` is on the PATH, so that the tests that need it are reported as ignored, with the
//! reason, rather than passing without looking at anything.

use std::env;
use std::path::Path;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(rebond_has_xvfb)");
    println!("cargo::rerun-if-changed=build.rs");
    // Only the viewer's tests read the cfg; a headless build has nothing to look for.
    if env::var_os("CARGO_FEATURE_VIEWER").is_none() {
        return;
    }
    println!("cargo::rerun-if-env-changed=PATH");
    let directories: Vec<_> = env::var_os("PATH")
        .map(|path| env::split_paths(&path).collect())
        .unwrap_or_default();
    let found = directories
        .iter()
        .map(|directory| directory.join("xvfb-run"))
        .find(|candidate| candidate.is_file());
    match found {
        // Its removal makes cargo run this script again: a watched path that is missing is a
        // change.
        Some(xvfb_run) => {
            println!("cargo::rerun-if-changed={}", xvfb_run.display());
            println!("cargo::rustc-cfg=rebond_has_xvfb");
        }
        // Installing xvfb-run later changes the modification time of the directory it lands in.
        // Watching the missing file itself would do too, but cargo takes a missing path for a
        // change at every build and would recompile this crate each time.
        None => {
            for directory in directories
                .iter()
                .filter(|directory| directory.is_absolute() && Path::is_dir(directory))
            {
                println!("cargo::rerun-if-changed={}", directory.display());
            }
        }
    }
}
