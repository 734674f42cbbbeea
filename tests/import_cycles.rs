//! No import cycle between the files of `src`. Every file's module paths are read (`use crate::...`,
//! `use super::...`, `use self::...`, a child module's path, and `crate::a::b`, `super::a` or
//! `child::a` paths in code) and resolved to the file that defines the module they name; the files
//! and these edges must form no circle. A `mod x;` declaration is not an edge (it only says where a
//! module lives), a `pub use` re-export is one (the re-exporting file needs the other to compile).
//!
//! The rule that keeps the graph acyclic: a parent `mod.rs` only declares modules and re-exports;
//! shared types live in a file of their own; siblings import each other by their own path, never in a
//! circle.
//!
//! The scanner is a small tokenizer (comments, strings and character literals are skipped), not a
//! Rust parser: it follows the module tree from `lib.rs` as the compiler does (with `#[path]`), and
//! `mod name { ... }` blocks for the meaning of `super` inside them.

use std::collections::{BTreeMap, BTreeSet, HashMap, VecDeque};
use std::path::Path;

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Ident(String),
    Str(String),
    PathSep,
    Punct(char),
}

/// The tokens of a Rust file with their 1-based line numbers, without comments, and with string and
/// character literals reduced to one token (a string keeps its text for `#[path = "..."]`).
fn tokenize(text: &str) -> Vec<(Token, usize)> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let mut line = 1;
    let mut i = 0;
    let count_lines =
        |from: usize, to: usize| chars[from..to].iter().filter(|c| **c == '\n').count();
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            // Block comments nest in Rust.
            let start = i;
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            line += count_lines(start, i.min(chars.len()));
        } else if let Some(end) = raw_string_end(&chars, i) {
            tokens.push((Token::Str(String::new()), line));
            line += count_lines(i, end);
            i = end;
        } else if c == '"' || (c == 'b' && next == Some('"')) {
            let start = i;
            i += if c == 'b' { 2 } else { 1 };
            let mut value = String::new();
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    i += 1;
                } else {
                    value.push(chars[i]);
                }
                i += 1;
            }
            i += 1;
            tokens.push((Token::Str(value), line));
            line += count_lines(start, i.min(chars.len()));
        } else if c == '\'' || (c == 'b' && next == Some('\'')) {
            let quote = if c == 'b' { i + 1 } else { i };
            if chars.get(quote + 1) == Some(&'\\') {
                // An escaped character literal: up to the closing quote.
                i = quote + 2;
                while i < chars.len() && chars[i] != '\'' {
                    i += 1;
                }
                i += 1;
                tokens.push((Token::Str(String::new()), line));
            } else if chars.get(quote + 2) == Some(&'\'') {
                i = quote + 3;
                tokens.push((Token::Str(String::new()), line));
            } else if c == 'b' {
                // `b` followed by a lifetime cannot happen; read `b` as an identifier.
                tokens.push((Token::Ident("b".to_string()), line));
                i += 1;
            } else {
                // A lifetime or label: its name follows as an ordinary identifier.
                i += 1;
            }
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            let mut ident: String = chars[start..i].iter().collect();
            if ident == "r" && chars.get(i) == Some(&'#') {
                // A raw identifier `r#name`.
                let from = i + 1;
                i = from;
                while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
                ident = chars[from..i].iter().collect();
            }
            tokens.push((Token::Ident(ident), line));
        } else if c.is_ascii_digit() {
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
        } else if c == ':' && next == Some(':') {
            tokens.push((Token::PathSep, line));
            i += 2;
        } else {
            tokens.push((Token::Punct(c), line));
            i += 1;
        }
    }
    tokens
}

/// Where a raw string literal starting at `i` (`r"`, `r#"`, `br#"`) ends, if one starts there.
fn raw_string_end(chars: &[char], i: usize) -> Option<usize> {
    let mut j = i;
    if chars.get(j) == Some(&'b') {
        j += 1;
    }
    if chars.get(j) != Some(&'r') || (j > 0 && j == i && is_ident_char(chars, i)) {
        return None;
    }
    j += 1;
    let mut hashes = 0;
    while chars.get(j) == Some(&'#') {
        hashes += 1;
        j += 1;
    }
    if chars.get(j) != Some(&'"') {
        return None;
    }
    j += 1;
    while j < chars.len() {
        if chars[j] == '"' && (0..hashes).all(|k| chars.get(j + 1 + k) == Some(&'#')) {
            return Some(j + 1 + hashes);
        }
        j += 1;
    }
    Some(chars.len())
}

/// Whether the character before `i` continues an identifier (so `r` at `i` is not a raw prefix).
fn is_ident_char(chars: &[char], i: usize) -> bool {
    i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_')
}

/// A module path relative to the file's own module: the inline `mod name { }` blocks around it.
type Inline = Vec<String>;

/// What one file says about modules.
#[derive(Default, Debug)]
struct FileScan {
    /// `mod name;` declarations: the inline modules around them, the name, a `#[path]`.
    declarations: Vec<(Inline, String, Option<String>)>,
    /// Inline `mod name { }` blocks, as paths below the file's module.
    inline_modules: Vec<Inline>,
    /// Paths read in `use` declarations and in code: the inline modules around them, the segments,
    /// whether the path came from `use`, the line.
    paths: Vec<(Inline, Vec<String>, bool, usize)>,
}

fn ident(tokens: &[(Token, usize)], i: usize) -> Option<&str> {
    match tokens.get(i) {
        Some((Token::Ident(name), _)) => Some(name),
        _ => None,
    }
}

fn scan(text: &str) -> FileScan {
    let tokens = tokenize(text);
    let mut result = FileScan::default();
    // The inline modules open at each brace depth.
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0usize;
    let mut pending_path: Option<String> = None;
    let mut i = 0;
    while i < tokens.len() {
        let here: Inline = inline.iter().map(|(name, _)| name.clone()).collect();
        match &tokens[i].0 {
            Token::Punct('{') => depth += 1,
            Token::Punct('}') => {
                depth = depth.saturating_sub(1);
                if inline.last().is_some_and(|(_, at)| *at == depth) {
                    inline.pop();
                }
            }
            // `#[path = "file.rs"]` applies to the next `mod` declaration.
            Token::Punct('#') if ident(&tokens, i + 2) == Some("path") => {
                if let Some((Token::Str(value), _)) = tokens.get(i + 4) {
                    pending_path = Some(value.clone());
                }
            }
            Token::Ident(word) if word == "mod" => {
                if let Some(name) = ident(&tokens, i + 1) {
                    match tokens.get(i + 2).map(|t| &t.0) {
                        Some(Token::Punct(';')) => {
                            result.declarations.push((
                                here.clone(),
                                name.to_string(),
                                pending_path.take(),
                            ));
                            i += 3;
                            continue;
                        }
                        Some(Token::Punct('{')) => {
                            let mut path = here.clone();
                            path.push(name.to_string());
                            result.inline_modules.push(path);
                            inline.push((name.to_string(), depth));
                            depth += 1;
                            pending_path = None;
                            i += 3;
                            continue;
                        }
                        _ => {}
                    }
                }
            }
            Token::Ident(word) if word == "use" => {
                let line = tokens[i].1;
                let mut j = i + 1;
                let mut paths = Vec::new();
                use_tree(&tokens, &mut j, Vec::new(), &mut paths);
                for path in paths {
                    result.paths.push((here.clone(), path, true, line));
                }
                // Up to the end of the declaration.
                while j < tokens.len() && tokens[j].0 != Token::Punct(';') {
                    j += 1;
                }
                i = j + 1;
                continue;
            }
            Token::Ident(word)
                if tokens.get(i + 1).map(|t| &t.0) == Some(&Token::PathSep)
                    && !matches!(
                        tokens.get(i.wrapping_sub(1)).map(|t| &t.0),
                        Some(Token::PathSep)
                    )
                    && word != "Self" =>
            {
                // A path in code: the segments as long as `::` follows.
                let line = tokens[i].1;
                let mut segments = vec![word.clone()];
                let mut j = i + 1;
                while tokens.get(j).map(|t| &t.0) == Some(&Token::PathSep) {
                    match ident(&tokens, j + 1) {
                        Some(next) => segments.push(next.to_string()),
                        None => break,
                    }
                    j += 2;
                }
                result.paths.push((here.clone(), segments, false, line));
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    result
}

/// Reads one use tree at `*i` (after `use` or inside braces) and adds its full paths to `out`.
fn use_tree(
    tokens: &[(Token, usize)],
    i: &mut usize,
    prefix: Vec<String>,
    out: &mut Vec<Vec<String>>,
) {
    let mut path = prefix;
    // A leading `::` (an external crate) needs nothing.
    if tokens.get(*i).map(|t| &t.0) == Some(&Token::PathSep) {
        *i += 1;
    }
    loop {
        match tokens.get(*i).map(|t| &t.0) {
            Some(Token::Ident(name)) if name == "self" && !path.is_empty() => {
                *i += 1;
            }
            Some(Token::Ident(name)) => {
                path.push(name.clone());
                *i += 1;
            }
            Some(Token::Punct('*')) => {
                *i += 1;
            }
            Some(Token::Punct('{')) => {
                *i += 1;
                loop {
                    match tokens.get(*i).map(|t| &t.0) {
                        Some(Token::Punct('}')) | None => {
                            *i += 1;
                            return;
                        }
                        Some(Token::Punct(',')) => *i += 1,
                        _ => use_tree(tokens, i, path.clone(), out),
                    }
                }
            }
            _ => break,
        }
        if tokens.get(*i).map(|t| &t.0) == Some(&Token::PathSep) {
            *i += 1;
        } else {
            break;
        }
    }
    // `as name` renames the last segment; the path stays.
    if ident(tokens, *i) == Some("as") {
        *i += 2;
    }
    if !path.is_empty() {
        out.push(path);
    }
}

/// An edge: from a file, at a line, to a file.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Edge {
    from: String,
    line: usize,
    to: String,
}

/// The module tree from `lib.rs` and the edges between files. `files` maps paths relative to `src`
/// (with `/`) to their text.
fn import_graph(files: &BTreeMap<String, String>) -> Vec<Edge> {
    let scans: HashMap<&str, FileScan> = files
        .iter()
        .map(|(path, text)| (path.as_str(), scan(text)))
        .collect();
    // Module path -> file, following the declarations from the crate root.
    let mut modules: BTreeMap<Vec<String>, String> = BTreeMap::new();
    let mut file_module: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut queue = VecDeque::from([(String::from("lib.rs"), Vec::<String>::new())]);
    while let Some((file, module)) = queue.pop_front() {
        let Some(found) = scans.get(file.as_str()) else {
            continue;
        };
        if file_module.contains_key(&file) {
            continue;
        }
        modules.insert(module.clone(), file.clone());
        file_module.insert(file.clone(), module.clone());
        for inline in &found.inline_modules {
            let mut path = module.clone();
            path.extend(inline.iter().cloned());
            modules.insert(path, file.clone());
        }
        let directory = match file.rsplit_once('/') {
            Some((folder, _)) => format!("{folder}/"),
            None => String::new(),
        };
        let name = file.rsplit('/').next().unwrap_or(&file);
        let owns_folder = name == "mod.rs" || name == "lib.rs";
        // Children of a `mod.rs`/`lib.rs` live beside it; those of `a.rs` in `a/`.
        let children_folder = if owns_folder {
            directory.clone()
        } else {
            format!("{directory}{}/", name.trim_end_matches(".rs"))
        };
        for (inline, child, path_attribute) in &found.declarations {
            let mut child_module = module.clone();
            child_module.extend(inline.iter().cloned());
            child_module.push(child.clone());
            let candidates = match path_attribute {
                Some(path) => vec![format!("{directory}{path}")],
                None => {
                    let folder = format!("{children_folder}{}", inline.join("/"));
                    let folder = if inline.is_empty() {
                        folder
                    } else {
                        format!("{folder}/")
                    };
                    vec![
                        format!("{folder}{child}.rs"),
                        format!("{folder}{child}/mod.rs"),
                    ]
                }
            };
            if let Some(child_file) = candidates
                .into_iter()
                .find(|c| scans.contains_key(c.as_str()))
            {
                queue.push_back((child_file, child_module));
            }
        }
    }
    let mut edges = BTreeSet::new();
    for (file, module) in &file_module {
        for (inline, segments, _, line) in &scans[file.as_str()].paths {
            let mut current = module.clone();
            current.extend(inline.iter().cloned());
            let Some(target) = resolve(&modules, &current, segments) else {
                continue;
            };
            if &target != file {
                edges.insert(Edge {
                    from: file.clone(),
                    line: *line,
                    to: target,
                });
            }
        }
    }
    // One edge per pair of files (the first line that makes it).
    let mut seen = BTreeSet::new();
    edges
        .into_iter()
        .filter(|edge| seen.insert((edge.from.clone(), edge.to.clone())))
        .collect()
}

/// The file that defines the module a path names (its longest prefix that is a module), if the path
/// is one of the crate's.
fn resolve(
    modules: &BTreeMap<Vec<String>, String>,
    current: &[String],
    segments: &[String],
) -> Option<String> {
    let mut base: Vec<String>;
    let mut rest = segments;
    match segments.first().map(String::as_str) {
        Some("crate") | Some("$crate") => {
            base = Vec::new();
            rest = &segments[1..];
        }
        Some("self") => {
            base = current.to_vec();
            rest = &segments[1..];
        }
        Some("super") => {
            base = current.to_vec();
            while rest.first().map(String::as_str) == Some("super") {
                base.pop()?;
                rest = &rest[1..];
            }
        }
        Some(first) => {
            // A path relative to the current module names one of its child modules.
            let mut child = current.to_vec();
            child.push(first.to_string());
            if !modules.contains_key(&child) {
                return None;
            }
            base = current.to_vec();
        }
        None => return None,
    }
    let mut full = base;
    full.extend(rest.iter().cloned());
    (0..=full.len())
        .rev()
        .find_map(|n| modules.get(&full[..n]).cloned())
}

/// Every cycle through an edge of a strongly connected group of files, each once: for each edge
/// `a -> b` inside a group, the shortest way back from `b` to `a`.
fn cycles(edges: &[Edge]) -> Vec<Vec<Edge>> {
    let mut out: BTreeMap<&str, Vec<&Edge>> = BTreeMap::new();
    for edge in edges {
        out.entry(edge.from.as_str()).or_default().push(edge);
    }
    let mut found: BTreeSet<Vec<Edge>> = BTreeSet::new();
    for edge in edges {
        // Breadth-first from the edge's target back to its source.
        let mut previous: HashMap<&str, &Edge> = HashMap::new();
        let mut queue = VecDeque::from([edge.to.as_str()]);
        let mut reached = edge.to == edge.from;
        while let Some(node) = queue.pop_front() {
            if node == edge.from {
                reached = true;
                break;
            }
            for next in out.get(node).into_iter().flatten() {
                if next.to != edge.to && !previous.contains_key(next.to.as_str()) {
                    previous.insert(next.to.as_str(), next);
                    queue.push_back(next.to.as_str());
                }
            }
        }
        if !reached {
            continue;
        }
        let mut cycle = vec![edge.clone()];
        let mut node = edge.from.as_str();
        let mut back = Vec::new();
        while node != edge.to {
            let step = previous[node];
            back.push(step.clone());
            node = step.from.as_str();
        }
        back.reverse();
        cycle.extend(back);
        // The same cycle found from another of its edges starts at its smallest file.
        let start = (0..cycle.len())
            .min_by_key(|&k| &cycle[k].from)
            .unwrap_or(0);
        cycle.rotate_left(start);
        found.insert(cycle);
    }
    found.into_iter().collect()
}

fn describe(cycle: &[Edge]) -> String {
    let mut text = String::new();
    for edge in cycle {
        text.push_str(&format!("{}:{} -> ", edge.from, edge.line));
    }
    text.push_str(&cycle[0].from);
    text
}

fn source_files(root: &Path) -> BTreeMap<String, String> {
    let mut files = BTreeMap::new();
    let mut folders = vec![root.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).expect("src is readable") {
            let path = entry.expect("src is readable").path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let relative = path
                    .strip_prefix(root)
                    .unwrap()
                    .to_string_lossy()
                    .replace('\\', "/");
                files.insert(
                    relative,
                    std::fs::read_to_string(&path).expect("a source file"),
                );
            }
        }
    }
    files
}

/// The edges as sorted (from, to) pairs, for comparing with an expected list.
fn sorted_pairs(edges: &[Edge]) -> Vec<(&str, &str)> {
    let mut pairs: Vec<(&str, &str)> = edges
        .iter()
        .map(|e| (e.from.as_str(), e.to.as_str()))
        .collect();
    pairs.sort();
    pairs
}

#[test]
fn no_import_cycle_between_files_of_src() {
    let files = source_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    let edges = import_graph(&files);
    // The scanner must see the crate: a graph without edges would prove nothing.
    assert!(edges.len() > 100, "only {} edges found in src", edges.len());
    let found = cycles(&edges);
    let listing: Vec<String> = found.iter().map(|cycle| describe(cycle)).collect();
    assert!(
        found.is_empty(),
        "{} import cycles between files of src (file:line of the import -> ...):\n{}",
        found.len(),
        listing.join("\n")
    );
}

fn tree(files: &[(&str, &str)]) -> BTreeMap<String, String> {
    files
        .iter()
        .map(|(path, text)| (path.to_string(), text.to_string()))
        .collect()
}

#[test]
fn a_reexport_and_a_use_of_the_parent_make_a_cycle() {
    let files = tree(&[
        ("lib.rs", "pub mod lsp;"),
        (
            "lsp/mod.rs",
            "mod server;\nmod state;\npub use server::Backend;",
        ),
        ("lsp/server.rs", "use super::State;\npub struct Backend;"),
        ("lsp/state.rs", "pub struct State;"),
    ]);
    let found = cycles(&import_graph(&files));
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(
        describe(&found[0]),
        "lsp/mod.rs:3 -> lsp/server.rs:1 -> lsp/mod.rs"
    );
}

#[test]
fn declarations_tests_modules_comments_and_strings_make_no_edge() {
    let files = tree(&[
        ("lib.rs", "pub mod a;\npub mod b;"),
        (
            "a/mod.rs",
            "mod inner;\n// use crate::b::x;\nconst S: &str = \"crate::b::x\";\n\
             const R: &str = r#\"use crate::b\"#;\nfn f<'a>(c: char) -> bool { c == '{' }\n\
             #[cfg(test)]\nmod tests { use super::*; }",
        ),
        (
            "a/inner.rs",
            "use crate::b::thing;\nfn g() { super::f('x'); }",
        ),
        (
            "b.rs",
            "/* crate::a::inner /* nested */ */ pub fn thing() {}",
        ),
    ]);
    let edges = import_graph(&files);
    let pairs = sorted_pairs(&edges);
    assert_eq!(
        pairs,
        vec![("a/inner.rs", "a/mod.rs"), ("a/inner.rs", "b.rs")]
    );
    assert!(cycles(&edges).is_empty());
}

#[test]
fn code_paths_groups_and_path_attributes_are_followed() {
    let files = tree(&[
        ("lib.rs", "pub mod a;\npub mod b;"),
        (
            "a.rs",
            "pub fn f() { crate::b::deep::g(); }\n#[path = \"a_tests.rs\"]\nmod tests;",
        ),
        ("a_tests.rs", "use super::f;"),
        (
            "b/mod.rs",
            "pub mod deep;\nuse {deep::g as h, super::a::{self}};",
        ),
        ("b/deep.rs", "pub fn g() {}"),
    ]);
    let edges = import_graph(&files);
    let pairs = sorted_pairs(&edges);
    assert_eq!(
        pairs,
        vec![
            ("a.rs", "b/deep.rs"),
            ("a_tests.rs", "a.rs"),
            ("b/mod.rs", "a.rs"),
            ("b/mod.rs", "b/deep.rs"),
        ]
    );
}
