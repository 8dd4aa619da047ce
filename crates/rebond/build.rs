//! Fingerprints the engine's sources for saved states (`src/state/mod.rs`): a state's exact part
//! holds the world's every internal structure, so only a build of the same sources reads that
//! part back; other builds read its portable snapshot. The fingerprint is the FNV-1a hash of
//! every source file's path and bytes, in path order, set as the environment variable
//! `REBOND_SOURCE_FINGERPRINT` for the crate's compilation.

use std::fs;
use std::path::{Path, PathBuf};

fn main() {
    println!("cargo::rerun-if-changed=src");
    let mut files = Vec::new();
    collect(Path::new("src"), &mut files);
    files.sort();
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for file in &files {
        let name = file.to_string_lossy().replace('\\', "/");
        // A file that cannot be read is fingerprinted by its name alone; cargo fails on it anyway.
        let bytes = fs::read(file).unwrap_or_default();
        for byte in name.bytes().chain([0]).chain(bytes) {
            hash = (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
        }
    }
    println!("cargo::rustc-env=REBOND_SOURCE_FINGERPRINT={hash:016x}");
}

/// Every file under `directory`, recursively.
fn collect(directory: &Path, files: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(directory) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect(&path, files);
        } else {
            files.push(path);
        }
    }
}
