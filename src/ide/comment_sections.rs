//! Comment sections: which comment-only lines are rules, framed titles or text, the sections they
//! head, and the documentation comment above a definition.

use crate::ide::names::text_of;
use crate::ide::symbol_types::CommentSection;
use crate::syntax::ast::Block;

/// How a comment-only line may take part in a section header.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum CommentLine {
    /// `;*****`, `;-----`, `;=====`: a rule.
    Rule,
    /// `;--- TITLE ---`: a title framed by rule characters.
    FramedTitle(String),
    /// Plain comment text.
    Text(String),
    /// `;` alone.
    Empty,
}

const RULE_CHARACTERS: &[char] = &['*', '-', '=', '+', '#', '~', '_', '/'];

/// The class of a line that holds only a comment, `None` for other lines.
pub(crate) fn classify_comment_line(line: &str, block: &Block) -> Option<CommentLine> {
    let comment = block.comment?;
    if !block.statements.is_empty()
        || block.number.is_some()
        || block.label.is_some()
        || block.skip.is_some()
    {
        return None;
    }
    if !line[..comment.start()].trim().is_empty() {
        return None;
    }
    let text = text_of(line, comment)[1..].trim();
    if text.is_empty() {
        return Some(CommentLine::Empty);
    }
    let leading_rule = text
        .chars()
        .take_while(|c| RULE_CHARACTERS.contains(c))
        .count();
    let title =
        text.trim_matches(|c: char| RULE_CHARACTERS.contains(&c) || c.is_whitespace() || c == '\'');
    if !title.chars().any(char::is_alphabetic) {
        return (leading_rule >= 5
            || text
                .chars()
                .all(|c| RULE_CHARACTERS.contains(&c) || c.is_whitespace() || c == '\'')
                && leading_rule >= 3)
            .then_some(CommentLine::Rule);
    }
    if leading_rule >= 3 {
        return Some(CommentLine::FramedTitle(title.to_string()));
    }
    Some(CommentLine::Text(text.to_string()))
}

/// Section headers among the comment-only lines: framed titles, a title directly under a rule, or a
/// title directly above a rule that follows no other comment line (an underlined title).
pub(crate) fn find_sections(comment_lines: &[(usize, CommentLine)]) -> Vec<CommentSection> {
    let class_at = |line: usize| -> Option<&CommentLine> {
        comment_lines
            .binary_search_by_key(&line, |(index, _)| *index)
            .ok()
            .map(|position| &comment_lines[position].1)
    };
    let mut sections = Vec::new();
    for (line, class) in comment_lines {
        let line = *line;
        match class {
            CommentLine::FramedTitle(title) => sections.push(CommentSection {
                line: if line > 0 && class_at(line - 1) == Some(&CommentLine::Rule) {
                    line - 1
                } else {
                    line
                },
                title_line: line,
                title: title.clone(),
            }),
            CommentLine::Text(title) => {
                let above = line.checked_sub(1).and_then(class_at);
                let below = class_at(line + 1);
                if above == Some(&CommentLine::Rule) {
                    sections.push(CommentSection {
                        line: line - 1,
                        title_line: line,
                        title: title.clone(),
                    });
                } else if above.is_none() && below == Some(&CommentLine::Rule) {
                    sections.push(CommentSection {
                        line,
                        title_line: line,
                        title: title.clone(),
                    });
                }
            }
            _ => {}
        }
    }
    sections
}

/// The comment text directly above `line`, rule lines left out.
pub(crate) fn documentation_above(
    comment_lines: &[(usize, CommentLine)],
    line: usize,
) -> Option<String> {
    let mut texts = Vec::new();
    let mut expected = line.checked_sub(1)?;
    for (index, class) in comment_lines
        .iter()
        .rev()
        .skip_while(|(index, _)| *index >= line)
    {
        if *index != expected {
            break;
        }
        match class {
            CommentLine::Text(text) | CommentLine::FramedTitle(text) => texts.push(text.clone()),
            CommentLine::Rule | CommentLine::Empty => {}
        }
        if expected == 0 {
            break;
        }
        expected -= 1;
    }
    texts.reverse();
    (!texts.is_empty()).then(|| texts.join("\n"))
}
