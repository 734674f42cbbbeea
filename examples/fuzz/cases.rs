//! Fuzz cases: how each target's inputs are generated from an index (so that a case can be made again
//! from the seed and its number), run, written to a reproducer file and read back.

use super::cli::check_cli;
use super::config::check_config;
use super::document::{self, DocumentCase, Edit};
use super::generate;
use super::random::Random;
use super::seeds::Seed;
use super::targets::{check_analysis, check_parser};
use super::transport::{check_framing, check_publish};
use std::path::Path;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    Parser,
    Analysis,
    Document,
    Cli,
    Config,
    Framing,
    Publish,
}

impl Target {
    pub fn parse(name: &str) -> Option<Target> {
        match name {
            "parser" => Some(Target::Parser),
            "analysis" => Some(Target::Analysis),
            "document" => Some(Target::Document),
            "cli" => Some(Target::Cli),
            "config" => Some(Target::Config),
            "framing" => Some(Target::Framing),
            "publish" => Some(Target::Publish),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Target::Parser => "parser",
            Target::Analysis => "analysis",
            Target::Document => "document",
            Target::Cli => "cli",
            Target::Config => "config",
            Target::Framing => "framing",
            Target::Publish => "publish",
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Case {
    Text(String),
    Document(DocumentCase),
}

impl Case {
    pub fn to_bytes(&self) -> Vec<u8> {
        match self {
            Case::Text(text) => text.clone().into_bytes(),
            Case::Document(case) => case.to_bytes(),
        }
    }

    pub fn extension(&self) -> &'static str {
        match self {
            Case::Text(_) => "mpf",
            Case::Document(_) => "fuzzdoc",
        }
    }

    /// Reads a reproducer: a document case when the file is one, otherwise a program text decoded as
    /// the checker decodes files.
    pub fn from_file(path: &Path) -> std::io::Result<Case> {
        let bytes = std::fs::read(path)?;
        Ok(match DocumentCase::from_bytes(&bytes) {
            Some(case) => Case::Document(case),
            None => Case::Text(sinumerik_lsp::io::source_file::decode_source(&bytes).text),
        })
    }
}

/// Case number `index` of a run with `seed`: each case has its own generator, so it can be made again.
pub fn generate_case(
    target: Target,
    seeds: &[Seed],
    seed: u64,
    index: u64,
    max_bytes: usize,
) -> Case {
    let mut random = Random::new(seed ^ index.wrapping_mul(0xD134_2543_DE82_EF95));
    // The few generated seeds are long incremental programs, where the document model carries
    // shifts across checkpoints: a quarter of the cases start from one of them.
    let generated: Vec<&Seed> = seeds.iter().filter(|seed| seed.generated).collect();
    let donor: &[String] = if !generated.is_empty() && random.one_in(4) {
        &random.pick(&generated).lines
    } else if seeds.is_empty() {
        &[]
    } else {
        &random.pick(seeds).lines
    };
    match target {
        Target::Parser => Case::Text(generate_text(&mut random, donor, 60, max_bytes)),
        Target::Analysis => Case::Text(generate_text(&mut random, donor, 1_500, max_bytes)),
        Target::Cli => Case::Text(generate_text(&mut random, donor, 300, max_bytes / 4)),
        Target::Config => Case::Text(super::config::generate_config(&mut random)),
        Target::Document => Case::Document(document::generate_case(&mut random, donor, 40)),
        Target::Framing => Case::Text(super::transport::generate_stream(&mut random, donor)),
        Target::Publish => Case::Text(generate_text(&mut random, donor, 300, max_bytes / 4)),
    }
}

/// A program text: generated blocks, a window of a seed program changed by lines and characters, raw
/// byte damage, or one long line of repeated pieces.
fn generate_text(
    random: &mut Random,
    donor: &[String],
    max_lines: usize,
    max_bytes: usize,
) -> String {
    let lines = match random.below(5) {
        0 | 1 if !donor.is_empty() => {
            let start = random.below(donor.len());
            let count = random.length(max_lines / 4, max_lines).max(1);
            let mut lines = donor[start..(start + count).min(donor.len())].to_vec();
            generate::mutate_lines(random, &mut lines, donor);
            lines
        }
        2 => {
            let piece = generate::block(random);
            let count = random.length(50, 20_000).max(1);
            vec![piece.repeat(count).chars().take(max_bytes).collect()]
        }
        _ => generate::program(random, max_lines),
    };
    let mut text = generate::join(random, &lines);
    if random.one_in(6) {
        text = generate::mutate_bytes(random, &text);
    }
    let end = generate::char_boundary_at(&text, max_bytes);
    text.truncate(end);
    text
}

/// Runs one case through `target`; `Ok` carries the number of edit steps checked (0 for texts).
pub fn run_case(target: Target, case: &Case) -> Result<usize, String> {
    match (target, case) {
        (Target::Parser, Case::Text(text)) => check_parser(text).map(|()| 0),
        (Target::Analysis, Case::Text(text)) => check_analysis(text).map(|()| 0),
        (Target::Cli, Case::Text(text)) => check_cli(text).map(|()| 0),
        (Target::Cli, Case::Document(case)) => check_cli(&case.final_text()).map(|()| 0),
        // Any text may be read as a configuration: a program is simply an invalid one.
        (Target::Config, Case::Text(text)) => check_config(text).map(|()| 0),
        (Target::Config, Case::Document(case)) => check_config(&case.final_text()).map(|()| 0),
        (Target::Document, Case::Document(case)) => document::check_document(case),
        (Target::Framing, Case::Text(text)) => check_framing(text).map(|()| 0),
        (Target::Framing, Case::Document(case)) => check_framing(&case.final_text()).map(|()| 0),
        (Target::Publish, Case::Text(text)) => check_publish(text).map(|()| 0),
        (Target::Publish, Case::Document(case)) => check_publish(&case.final_text()).map(|()| 0),
        (Target::Document, Case::Text(text)) => document::check_document(&edits_of_text(text)),
        (Target::Parser, Case::Document(case)) => {
            check_parser(&case.join(&case.lines))?;
            check_parser(&case.final_text()).map(|()| 0)
        }
        (Target::Analysis, Case::Document(case)) => {
            check_analysis(&case.join(&case.lines))?;
            check_analysis(&case.final_text()).map(|()| 0)
        }
    }
}

/// A fixed sequence of edits of a program text, for replaying a text reproducer through the document
/// target: remove the first line and put it back, empty the middle line, change the last line, append
/// a block, and remove everything.
pub fn edits_of_text(text: &str) -> DocumentCase {
    let lines = super::seeds::split_lines(text);
    let middle = lines.len() / 2;
    let first_line = lines.first().cloned().unwrap_or_default();
    let last = lines.len().saturating_sub(1);
    let edits = vec![
        Edit {
            first: 0,
            removed: 1,
            inserted: Vec::new(),
        },
        Edit {
            first: 0,
            removed: 0,
            inserted: vec![first_line],
        },
        Edit {
            first: middle,
            removed: 1,
            inserted: vec![String::new()],
        },
        Edit {
            first: last,
            removed: 1,
            inserted: vec![format!("{} X1", lines.last().map_or("", String::as_str))],
        },
        Edit {
            first: usize::MAX,
            removed: 0,
            inserted: vec!["G91 G1 X1 F100".to_string()],
        },
        Edit {
            first: 0,
            removed: usize::MAX,
            inserted: Vec::new(),
        },
    ];
    DocumentCase {
        turn: false,
        subprogram: false,
        terminator: 0,
        lines,
        edits,
    }
}
