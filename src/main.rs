//! The `sinumerik-lsp` binary: everything lives in the library. It chooses between the language
//! server and the command line, passes the arguments in and the exit code out.

#![deny(unsafe_code)]

fn main() -> std::process::ExitCode {
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    let code = if sinumerik_lsp::cli::wants_language_server(&args) {
        sinumerik_lsp::lsp::serve_stdio()
    } else {
        sinumerik_lsp::cli::run(args)
    };
    std::process::ExitCode::from(code)
}
