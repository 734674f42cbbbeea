//! Data-driven tests of the language features: every `.nc` or `.mpf` file under
//! `fixtures/ide/<feature>/` is a small workspace with a cursor marker `$0`, and `<file>.expected`
//! holds what the feature answers there, rendered as text. One helper per feature renders the answer; `UPDATE_EXPECT=1 cargo test --test
//! ide_fixtures` rewrites the expectations (review the diff before committing).
//!
//! Fixture format: lines up to the first `;;; FILE NAME.EXT` belong to `MAIN.MPF`; each such line
//! starts another file of the workspace. Directives: `;;; COMPLETE` marks the index complete,
//! `;;; RENAME NEWNAME` gives the new name for rename fixtures, `;;; MACHINE turn` takes the lathe's
//! default configuration instead of the mill's. The cursor `$0` is removed from the text; its file is
//! the document the feature is asked about (without a cursor: the first file).

use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::library::MemoryLibrary;
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::ide::completion::completion;
use sinumerik_lsp::ide::cross_file_diagnostics::cross_file_diagnostics;
use sinumerik_lsp::ide::documentation::documentation_at;
use sinumerik_lsp::ide::hover::hover_at;
use sinumerik_lsp::ide::inlay::{end_point_hints, HintScope};
use sinumerik_lsp::ide::navigation::{definition, references, rename, workspace_symbols};
use sinumerik_lsp::ide::outline::{
    document_highlights, document_symbols, folding_ranges, OutlineItem,
};
use sinumerik_lsp::ide::program_run::RunOnce;
use sinumerik_lsp::ide::semantic_tokens::semantic_tokens;
use sinumerik_lsp::ide::signature_help::signature_help;
use sinumerik_lsp::ide::{apply_edits, Location, SymbolTable, WorkspaceIndex};
use sinumerik_lsp::syntax::lines::line_ranges;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A parsed fixture: its files, the cursor and the directives.
struct Fixture {
    files: Vec<(String, String)>,
    cursor_file: String,
    cursor_line: usize,
    cursor_byte: usize,
    complete: bool,
    rename_to: Option<String>,
    turn: bool,
}

impl Fixture {
    fn parse(text: &str) -> Fixture {
        let mut files: Vec<(String, String)> = vec![("MAIN.MPF".to_string(), String::new())];
        let mut complete = false;
        let mut rename_to = None;
        let mut turn = false;
        for line in text.lines() {
            if let Some(name) = line.strip_prefix(";;; FILE ") {
                files.push((name.trim().to_string(), String::new()));
            } else if line.trim() == ";;; COMPLETE" {
                complete = true;
            } else if let Some(name) = line.strip_prefix(";;; RENAME ") {
                rename_to = Some(name.trim().to_string());
            } else if line.trim() == ";;; MACHINE turn" {
                turn = true;
            } else {
                let file = &mut files.last_mut().unwrap().1;
                file.push_str(line);
                file.push('\n');
            }
        }
        files.retain(|(name, text)| name != "MAIN.MPF" || !text.trim().is_empty());
        let mut cursor = None;
        for (name, text) in &mut files {
            if let Some(position) = text.find("$0") {
                text.replace_range(position..position + 2, "");
                let line = text[..position].matches('\n').count();
                let line_start = text[..position]
                    .rfind('\n')
                    .map_or(0, |newline| newline + 1);
                cursor = Some((name.clone(), line, position - line_start));
            }
        }
        let (cursor_file, cursor_line, cursor_byte) =
            cursor.unwrap_or_else(|| (files[0].0.clone(), 0, 0));
        Fixture {
            files,
            cursor_file,
            cursor_line,
            cursor_byte,
            complete,
            rename_to,
            turn,
        }
    }

    /// The machine the fixture asks for: the mill unless `;;; MACHINE turn`.
    fn config(&self) -> MachineConfig {
        if self.turn {
            MachineConfig::turn()
        } else {
            MachineConfig::mill()
        }
    }

    /// The other files of the workspace as the library a run calls into, by program name.
    fn library(&self) -> MemoryLibrary {
        let mut library = MemoryLibrary::default();
        for (name, text) in &self.files {
            if *name != self.cursor_file {
                let program = name
                    .rsplit_once('.')
                    .map_or(name.as_str(), |(stem, _)| stem);
                library.insert(program, name, text);
            }
        }
        library
    }

    fn index(&self, config: &MachineConfig) -> WorkspaceIndex {
        let mut index = WorkspaceIndex::new();
        for (name, text) in &self.files {
            index.update(
                Arc::from(name.as_str()),
                name,
                &TextLines::new(text),
                config,
            );
        }
        index.set_complete(self.complete);
        index
    }

    fn text_of(&self, file: &str) -> &str {
        &self.files.iter().find(|(name, _)| name == file).unwrap().1
    }

    fn cursor_text(&self) -> &str {
        self.text_of(&self.cursor_file)
    }

    fn cursor_line_text(&self) -> &str {
        line_of(self.cursor_text(), self.cursor_line)
    }
}

fn line_of(text: &str, line: usize) -> &str {
    line_ranges(text)
        .nth(line)
        .map_or("", |(start, end)| &text[start..end])
}

fn show_location(fixture: &Fixture, location: &Location) -> String {
    let line = line_of(fixture.text_of(&location.document), location.line);
    let text = line
        .get(location.span.start()..location.span.end())
        .unwrap_or("");
    format!(
        "{}:{} {:?} {text:?}",
        location.document,
        location.line + 1,
        location.span
    )
}

/// Runs `render` on every fixture of `fixtures/ide/<feature>` and compares with the expectations.
fn check_feature(feature: &str, render: impl Fn(&Fixture, &MachineConfig) -> String) {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/ide")
        .join(feature);
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&folder)
        .unwrap_or_else(|error| panic!("{}: {error}", folder.display()))
        .map(|entry| entry.unwrap().path())
        .filter(|path| {
            path.extension()
                .is_some_and(|extension| extension == "nc" || extension == "mpf")
        })
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "no fixtures in {}", folder.display());
    let update = std::env::var_os("UPDATE_EXPECT").is_some();
    let mut failures = String::new();
    for path in paths {
        let fixture = Fixture::parse(&std::fs::read_to_string(&path).unwrap());
        let actual = render(&fixture, &fixture.config());
        let mut expected_name = path.file_name().unwrap().to_os_string();
        expected_name.push(".expected");
        let expected_path = path.with_file_name(expected_name);
        let expected = std::fs::read_to_string(&expected_path).ok();
        if expected.as_deref() == Some(actual.as_str()) {
            continue;
        }
        if update {
            std::fs::write(&expected_path, &actual).unwrap();
        } else {
            let _ = writeln!(
                failures,
                "{}: expected\n{}\n--- got\n{actual}",
                path.display(),
                expected
                    .as_deref()
                    .unwrap_or("(no .expected file; run with UPDATE_EXPECT=1)")
            );
        }
    }
    assert!(failures.is_empty(), "{failures}");
}

#[test]
fn symbols() {
    check_feature("symbols", |fixture, config| {
        let table = SymbolTable::of_text(fixture.cursor_text(), config);
        let mut out = String::new();
        for label in &table.labels {
            let _ = writeln!(out, "label {} @{}", label.name, label.line + 1);
        }
        for number in &table.block_numbers {
            let _ = writeln!(
                out,
                "block {}{} @{}",
                if number.main { ":" } else { "N" },
                number.value,
                number.line + 1
            );
        }
        for variable in &table.variables {
            let _ = writeln!(
                out,
                "def {} {}{} {} @{}",
                variable.type_name,
                variable.name,
                variable.dimensions.as_deref().unwrap_or(""),
                variable.global_attribute.as_deref().unwrap_or("local"),
                variable.line + 1
            );
        }
        for parameter in &table.r_parameters {
            let _ = writeln!(
                out,
                "r {:?} {} @{}",
                parameter.number,
                if parameter.write { "write" } else { "read" },
                parameter.line + 1
            );
        }
        if let Some(procedure) = &table.procedure {
            let _ = writeln!(
                out,
                "proc {} @{} doc={:?}",
                procedure.name,
                procedure.line + 1,
                procedure.documentation
            );
            for parameter in &procedure.parameters {
                let _ = writeln!(
                    out,
                    "  param {}{} {}{}",
                    if parameter.by_reference { "VAR " } else { "" },
                    parameter.type_name,
                    parameter.name,
                    parameter.dimensions.as_deref().unwrap_or("")
                );
            }
        }
        for definition in &table.macros {
            let _ = writeln!(
                out,
                "define {} AS {} @{}",
                definition.name,
                definition.body,
                definition.line + 1
            );
        }
        for declaration in &table.externs {
            let _ = writeln!(
                out,
                "extern {} {:?} @{}",
                declaration.name,
                declaration.parameter_types,
                declaration.line + 1
            );
        }
        for call in &table.calls {
            let _ = writeln!(
                out,
                "call {} {:?} args={:?} @{}",
                call.name,
                call.style,
                call.argument_count,
                call.line + 1
            );
        }
        for jump in &table.jumps {
            let _ = writeln!(
                out,
                "jump {:?} {:?} case={} @{}",
                jump.kind,
                jump.destination,
                jump.in_case,
                jump.line + 1
            );
        }
        for change in &table.tool_changes {
            let _ = writeln!(out, "tool {} @{}", change.text, change.line + 1);
        }
        for section in &table.sections {
            let _ = writeln!(out, "section {:?} @{}", section.title, section.line + 1);
        }
        for name_use in &table.name_uses {
            let _ = writeln!(
                out,
                "name {} {} @{}",
                name_use.name,
                if name_use.write { "write" } else { "read" },
                name_use.line + 1
            );
        }
        let _ = writeln!(
            out,
            "first executable @{:?}",
            table.first_executable_line.map(|line| line + 1)
        );
        out
    });
}

#[test]
fn goto_definition() {
    check_feature("definition", |fixture, config| {
        let index = fixture.index(config);
        let found = definition(
            &index,
            &fixture.cursor_file,
            fixture.cursor_line,
            fixture.cursor_byte,
        );
        let mut out = String::new();
        for location in &found {
            let _ = writeln!(out, "{}", show_location(fixture, location));
        }
        if found.is_empty() {
            out.push_str("(none)\n");
        }
        out
    });
}

#[test]
fn find_references() {
    check_feature("references", |fixture, config| {
        let index = fixture.index(config);
        let found = references(
            &index,
            &fixture.cursor_file,
            fixture.cursor_line,
            fixture.cursor_byte,
            true,
        );
        let mut out = String::new();
        for location in &found {
            let _ = writeln!(out, "{}", show_location(fixture, location));
        }
        if found.is_empty() {
            out.push_str("(none)\n");
        }
        out
    });
}

#[test]
fn rename_symbols() {
    check_feature("rename", |fixture, config| {
        let index = fixture.index(config);
        let new_name = fixture
            .rename_to
            .as_deref()
            .expect("rename fixtures need `;;; RENAME NAME`");
        match rename(
            &index,
            config,
            &fixture.cursor_file,
            fixture.cursor_line,
            fixture.cursor_byte,
            new_name,
        ) {
            Err(error) => format!("{error:?}\n"),
            Ok(edit) => {
                let mut out = String::new();
                for (document, edits) in &edit.changes {
                    let _ = write!(
                        out,
                        "--- {document}\n{}",
                        apply_edits(fixture.text_of(document), edits)
                    );
                }
                for (document, name) in &edit.renamed_programs {
                    let _ = writeln!(out, "rename file {document} -> program {name}");
                }
                out
            }
        }
    });
}

#[test]
fn completions() {
    check_feature("completion", |fixture, config| {
        let index = fixture.index(config);
        let items = completion(
            &index,
            &fixture.cursor_file,
            fixture.cursor_line_text(),
            fixture.cursor_line,
            fixture.cursor_byte,
            config,
        );
        let mut out = String::new();
        for item in &items {
            let _ = writeln!(
                out,
                "{:?} {} | {} | {}",
                item.kind,
                item.label,
                item.detail,
                item.snippet.as_deref().unwrap_or("")
            );
        }
        if items.is_empty() {
            out.push_str("(none)\n");
        }
        out
    });
}

#[test]
fn signature_helps() {
    check_feature("signature", |fixture, config| {
        let index = fixture.index(config);
        match signature_help(
            &index,
            &fixture.cursor_file,
            fixture.cursor_line_text(),
            fixture.cursor_byte,
        ) {
            None => "(none)\n".to_string(),
            Some(help) => {
                let (start, end) = help
                    .parameters
                    .get(help.active_parameter)
                    .copied()
                    .unwrap_or((0, 0));
                format!(
                    "{}\nactive {} {:?}\ndoc {:?}\nparameter doc {:?}\n",
                    help.label,
                    help.active_parameter,
                    &help.label[start..end],
                    help.documentation,
                    help.parameter_documentation
                        .get(help.active_parameter)
                        .cloned()
                        .flatten()
                )
            }
        }
    });
}

fn render_outline(items: &[OutlineItem], depth: usize, out: &mut String) {
    for item in items {
        let _ = writeln!(
            out,
            "{}{:?} {} ({}) lines {}-{}",
            "  ".repeat(depth),
            item.kind,
            item.name,
            item.detail,
            item.lines.0 + 1,
            item.lines.1 + 1
        );
        render_outline(&item.children, depth + 1, out);
    }
}

#[test]
fn outline_and_folding() {
    check_feature("outline", |fixture, config| {
        let table = SymbolTable::of_text(fixture.cursor_text(), config);
        let mut out = String::new();
        render_outline(&document_symbols(&table), 0, &mut out);
        for range in folding_ranges(&table) {
            let _ = writeln!(
                out,
                "fold {:?} {}-{}",
                range.kind,
                range.start_line + 1,
                range.end_line + 1
            );
        }
        out
    });
}

#[test]
fn highlights() {
    check_feature("highlights", |fixture, config| {
        let index = fixture.index(config);
        let mut out = String::new();
        for (line, span, role) in document_highlights(
            &index,
            &fixture.cursor_file,
            fixture.cursor_line,
            fixture.cursor_byte,
        ) {
            let text = &line_of(fixture.cursor_text(), line)[span.start()..span.end()];
            let _ = writeln!(out, "{} {text:?} {role:?}", line + 1);
        }
        if out.is_empty() {
            out.push_str("(none)\n");
        }
        out
    });
}

#[test]
fn semantic_token_kinds() {
    check_feature("semantic_tokens", |fixture, config| {
        let text = fixture.cursor_text();
        let lines = TextLines::new(text);
        let table = SymbolTable::of_text(text, config);
        let mut out = String::new();
        for token in semantic_tokens(&lines, &table, config, 0..usize::MAX) {
            let line = line_of(text, token.line);
            let _ = writeln!(
                out,
                "{}:{} {:?} {:?} m{}",
                token.line + 1,
                token.start,
                &line[token.start..token.start + token.length],
                token.kind,
                token.modifiers
            );
        }
        out
    });
}

#[test]
fn workspace_diagnostics() {
    check_feature("diagnostics", |fixture, config| {
        let index = fixture.index(config);
        let mut out = String::new();
        for (name, text) in &fixture.files {
            for item in cross_file_diagnostics(&index, name, config) {
                let line = line_of(text, item.line);
                // The fix with the text each edit replaces, so that the edited span is checked too.
                let fix = item
                    .diagnostic
                    .fix
                    .as_ref()
                    .map(|fix| {
                        let replaced: Vec<&str> = fix
                            .edits
                            .iter()
                            .map(|edit| &line[edit.span.start()..edit.span.end()])
                            .collect();
                        format!(" [fix: {} replacing {replaced:?}]", fix.title)
                    })
                    .unwrap_or_default();
                let _ = writeln!(
                    out,
                    "{name}:{} {} {} {:?}: {}{fix}",
                    item.line + 1,
                    item.diagnostic.code,
                    item.diagnostic.severity,
                    &line[item.diagnostic.span.start()..item.diagnostic.span.end()],
                    item.diagnostic.message
                );
            }
        }
        if out.is_empty() {
            out.push_str("(none)\n");
        }
        out
    });
}

#[test]
fn hover_documentation() {
    check_feature("documentation", |fixture, config| {
        let index = fixture.index(config);
        match documentation_at(
            &index,
            &fixture.cursor_file,
            fixture.cursor_line_text(),
            fixture.cursor_line,
            fixture.cursor_byte,
        ) {
            None => "(none)\n".to_string(),
            Some(doc) => format!(
                "{:?}\n{}\n{}\n",
                &fixture.cursor_line_text()[doc.span.start()..doc.span.end()],
                doc.title,
                doc.text
            ),
        }
    });
}

#[test]
fn workspace_symbol_search() {
    check_feature("workspace_symbols", |fixture, config| {
        let index = fixture.index(config);
        // The query is the word under the cursor's line, after `;;; QUERY` is not needed: the cursor
        // line holds it as a comment `; query: TEXT`.
        let query = fixture
            .cursor_line_text()
            .split("query:")
            .nth(1)
            .unwrap_or("")
            .trim()
            .to_string();
        let mut found = workspace_symbols(&index, &query);
        found.sort_by(|left, right| {
            (&left.2.document, left.2.line, &left.0).cmp(&(
                &right.2.document,
                right.2.line,
                &right.0,
            ))
        });
        let mut out = format!("query {query:?}\n");
        for (name, kind, location) in &found {
            let _ = writeln!(out, "{kind:?} {name} {}", show_location(fixture, location));
        }
        out
    });
}

#[test]
fn semantic_tokens_of_a_line_range_equal_those_of_the_whole_document() {
    let text = "N10 G0 X10 ; start\nDEF REAL DEPTH=5\nIF DEPTH > 2 GOTOF LBL\nLBL: Z=-DEPTH\n";
    let config = MachineConfig::mill();
    let lines = TextLines::new(text);
    let table = SymbolTable::of_text(text, &config);
    let all = semantic_tokens(&lines, &table, &config, 0..4);
    let middle = semantic_tokens(&lines, &table, &config, 1..3);
    let expected: Vec<_> = all
        .iter()
        .filter(|token| (1..3).contains(&token.line))
        .copied()
        .collect();
    assert!(!middle.is_empty());
    assert_eq!(middle, expected);
}

#[test]
fn hovers() {
    check_feature("hover", |fixture, config| {
        let lines = TextLines::new(fixture.cursor_text());
        let kind = ProgramKind::from_file_name(&fixture.cursor_file);
        let analysis = DocumentAnalysis::new(&lines, Arc::new(config.clone()), kind);
        let library = fixture.library();
        let run = RunOnce::new(&lines, config, kind, &library);
        let index = fixture.index(config);
        let found = hover_at(
            &lines,
            &analysis,
            &run,
            fixture.cursor_line,
            fixture.cursor_byte,
            |line_text, line, byte| {
                documentation_at(&index, &fixture.cursor_file, line_text, line, byte)
            },
        );
        match found {
            None => "(none)\n".to_string(),
            Some(hover) => {
                let about = hover.span.map_or_else(
                    || "the block".to_string(),
                    |span| {
                        format!(
                            "{:?}",
                            &fixture.cursor_line_text()[span.start()..span.end()]
                        )
                    },
                );
                format!("hover on {about}\n\n{}\n", hover.markdown)
            }
        }
    });
}

#[test]
fn inlay_hints() {
    check_feature("inlay", |fixture, config| {
        let lines = TextLines::new(fixture.cursor_text());
        let kind = ProgramKind::from_file_name(&fixture.cursor_file);
        let analysis = DocumentAnalysis::new(&lines, Arc::new(config.clone()), kind);
        let library = fixture.library();
        let run = RunOnce::new(&lines, config, kind, &library);
        let mut out = String::new();
        for (title, scope) in [
            ("not plain (the default)", HintScope::NotPlain),
            ("all", HintScope::All),
        ] {
            let _ = writeln!(out, "{title}:");
            for hint in end_point_hints(&lines, &analysis, &run, 0..usize::MAX, scope) {
                let _ = writeln!(
                    out,
                    "  {}: {} [{}]",
                    hint.line + 1,
                    hint.label,
                    hint.tooltip
                );
            }
        }
        out
    });
}
