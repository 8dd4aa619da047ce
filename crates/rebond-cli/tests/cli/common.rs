//! Helpers shared by the integration tests: a scratch directory per test and a way to run the
//! `rebond` binary.

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh, empty directory for one test, under cargo's scratch directory for integration tests.
pub struct TestDir {
    path: PathBuf,
}

impl TestDir {
    /// Creates (emptying it first) the directory named after `test_name`.
    pub fn new(test_name: &str) -> Self {
        let path = Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join("rebond-cli")
            .join(test_name);
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).expect("create the test directory");
        Self { path }
    }

    /// The path of `name` in the directory.
    pub fn path(&self, name: &str) -> PathBuf {
        self.path.join(name)
    }

    /// The directory itself.
    pub fn root(&self) -> &Path {
        &self.path
    }

    /// Writes `contents` to `name` and returns its path.
    pub fn write(&self, name: &str, contents: &str) -> PathBuf {
        let path = self.path(name);
        fs::write(&path, contents).expect("write a test file");
        path
    }
}

/// What a run of the binary gave.
pub struct Outcome {
    /// Exit status code.
    pub status: i32,
    /// Everything written to stdout.
    pub stdout: String,
    /// Everything written to stderr.
    pub stderr: String,
}

impl From<Output> for Outcome {
    fn from(output: Output) -> Self {
        Self {
            status: output.status.code().expect("the binary exited normally"),
            stdout: String::from_utf8(output.stdout).expect("stdout is UTF-8"),
            stderr: String::from_utf8(output.stderr).expect("stderr is UTF-8"),
        }
    }
}

/// Runs `rebond` with `arguments`.
pub fn rebond<I, S>(arguments: I) -> Outcome
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    rebond_in(None, arguments)
}

/// Runs `rebond` with `arguments` in the working directory `directory` (or the current one).
pub fn rebond_in<I, S>(directory: Option<&Path>, arguments: I) -> Outcome
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let mut command = Command::new(env!("CARGO_BIN_EXE_rebond"));
    command.args(arguments);
    if let Some(directory) = directory {
        command.current_dir(directory);
    }
    command.output().expect("run the rebond binary").into()
}

/// Asserts a failure the contract's way: the exit status, nothing on stdout, exactly one stderr
/// line starting `error:` and naming `file`, and no panic.
pub fn assert_one_error_line(outcome: &Outcome, status: i32, file: &Path) -> String {
    let context = format!("stderr: {:?}", outcome.stderr);
    assert_eq!(outcome.status, status, "{context}");
    assert_eq!(outcome.stdout, "", "{context}");
    assert!(!outcome.stderr.contains("panicked"), "{context}");
    let lines: Vec<&str> = outcome.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "{context}");
    let line = lines[0];
    assert!(line.starts_with("error: "), "{context}");
    assert!(
        line.contains(&file.display().to_string()),
        "the error names the file: {context}"
    );
    line.to_owned()
}
