//! A scratch folder and a runner of the real binary, for the end-to-end tests of the rewriting
//! commands (`fmt`, `renumber`).

use std::fs;
use std::path::PathBuf;
use std::process::Command;

/// A fresh folder per test with an empty `sinumerik.toml` (so no configuration above it applies),
/// removed afterwards.
pub struct Scratch {
    pub path: PathBuf,
}

impl Scratch {
    pub fn new(name: &str) -> Scratch {
        let path = std::env::temp_dir().join(format!(
            "sinumerik-lsp-rewrite-{}-{name}",
            std::process::id()
        ));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).unwrap();
        fs::write(path.join("sinumerik.toml"), "").unwrap();
        Scratch { path }
    }

    pub fn write(&self, name: &str, bytes: &[u8]) -> PathBuf {
        let path = self.path.join(name);
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(&path, bytes).unwrap();
        path
    }

    pub fn read(&self, name: &str) -> Vec<u8> {
        fs::read(self.path.join(name)).unwrap()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.path);
    }
}

/// Runs the binary with `args` in the scratch folder: (exit code, stdout, stderr).
pub fn run_in(scratch: &Scratch, args: &[&str]) -> (i32, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
        .args(args)
        .current_dir(&scratch.path)
        .output()
        .expect("the binary runs");
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}
