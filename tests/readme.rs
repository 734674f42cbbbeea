//! The README documents every diagnostic code with its default severity; this keeps it true.

use sinumerik_lsp::diagnostics::Code;

#[test]
fn readme_lists_every_diagnostic_code_with_its_default_severity() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md"))
        .expect("README.md is readable");
    for code in Code::ALL {
        let row_start = format!(
            "| {} | {} |",
            code.as_str(),
            code.default_severity().as_str()
        );
        assert!(
            readme.contains(&row_start),
            "README.md has no row `{row_start} ...` for {code:?}"
        );
    }
}
