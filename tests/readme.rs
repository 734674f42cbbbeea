//! docs/diagnostics.md documents every diagnostic code with its default severity; this keeps it true.
//! (The README links to that page; the table lived in the README before.)

use sinumerik_lsp::diagnostics::Code;

#[test]
fn diagnostics_page_lists_every_diagnostic_code_with_its_default_severity() {
    let page = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/diagnostics.md"))
        .expect("docs/diagnostics.md is readable");
    for code in Code::ALL {
        let row_start = format!(
            "| {} | {} |",
            code.as_str(),
            code.default_severity().as_str()
        );
        assert!(
            page.contains(&row_start),
            "docs/diagnostics.md has no row `{row_start} ...` for {code:?}"
        );
    }
}

#[test]
fn readme_links_to_the_diagnostics_page() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md"))
        .expect("README.md is readable");
    assert!(
        readme.contains("(docs/diagnostics.md)"),
        "README.md does not link to docs/diagnostics.md"
    );
}
