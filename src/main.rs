//! The `sinumerik-lsp` binary: everything lives in the library; this only passes the arguments in and
//! the exit code out.

#![deny(unsafe_code)]

fn main() -> std::process::ExitCode {
    std::process::ExitCode::from(sinumerik_lsp::cli::run(std::env::args_os()))
}
