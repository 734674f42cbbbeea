//! Semantic tokens (full and range): the protocol's form of `ide::semantic_tokens`, with a legend of
//! the kinds it distinguishes. Standard token types where the protocol has one, own ones for the
//! NC language (`gcode`, `axis`, `address`, `rParameter`, `systemVariable`, `label`, `blockNumber`,
//! `subprogram`); the G group of a G function is a modifier (`motion`, `plane`, ...).
//! Like completion, it reads the document's index entry as it is (possibly a few edits old: only
//! which names are variables, parameters or macros comes from it; the words come from the text).

use crate::analysis::document::LineSource;
use crate::ide::semantic_tokens::{
    semantic_tokens, TokenKind, DECLARATION, MODIFICATION, NON_MODAL,
};
use crate::ide::symbols::SymbolTable;
use crate::lsp::convert::byte_to_character;
use crate::lsp::documents::Analysed;
use crate::lsp::state::DocumentRequest;
use std::sync::Arc;
use tower_lsp_server::ls_types::{
    Range, SemanticToken, SemanticTokenModifier, SemanticTokenType, SemanticTokens,
    SemanticTokensLegend,
};

/// The token types, in the order of their indices in the legend.
const TOKEN_TYPES: [&str; 17] = [
    "comment",
    "string",
    "number",
    "keyword",
    "gcode",
    "axis",
    "address",
    "modifier",
    "variable",
    "parameter",
    "rParameter",
    "systemVariable",
    "label",
    "blockNumber",
    "function",
    "subprogram",
    "macro",
];

/// The modifiers: the first three are the bits of `ide::semantic_tokens`, then one per G group
/// that editors are likely to colour, and `unknownGroup` for a G number that does not exist.
const TOKEN_MODIFIERS: [&str; 11] = [
    "declaration",
    "modification",
    "nonModal",
    "motion",
    "plane",
    "toolRadiusCompensation",
    "workOffset",
    "units",
    "distance",
    "diameter",
    "unknownGroup",
];

/// The G groups with a modifier of their own, with the modifier's bit.
const GROUP_MODIFIERS: [(u8, u32); 7] = [
    (1, 1 << 3),
    (6, 1 << 4),
    (7, 1 << 5),
    (8, 1 << 6),
    (13, 1 << 7),
    (14, 1 << 8),
    (29, 1 << 9),
];
const UNKNOWN_GROUP: u32 = 1 << 10;

pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend {
        token_types: TOKEN_TYPES
            .iter()
            .map(|name| SemanticTokenType::new(name))
            .collect(),
        token_modifiers: TOKEN_MODIFIERS
            .iter()
            .map(|name| SemanticTokenModifier::new(name))
            .collect(),
    }
}

/// The legend index of a kind and the modifier bits its G group adds.
fn encode_kind(kind: TokenKind) -> (u32, u32) {
    match kind {
        TokenKind::Comment => (0, 0),
        TokenKind::String => (1, 0),
        TokenKind::Number => (2, 0),
        TokenKind::Keyword => (3, 0),
        TokenKind::GCode { group } => {
            let bits = match group {
                0 => UNKNOWN_GROUP,
                _ => GROUP_MODIFIERS
                    .iter()
                    .find(|(known, _)| *known == group)
                    .map_or(0, |(_, bit)| *bit),
            };
            (4, bits)
        }
        TokenKind::Axis => (5, 0),
        TokenKind::Address => (6, 0),
        TokenKind::Modifier => (7, 0),
        TokenKind::Variable => (8, 0),
        TokenKind::Parameter => (9, 0),
        TokenKind::RParameter => (10, 0),
        TokenKind::SystemVariable => (11, 0),
        TokenKind::Label => (12, 0),
        TokenKind::BlockNumber => (13, 0),
        TokenKind::Function => (14, 0),
        TokenKind::Subprogram => (15, 0),
        TokenKind::Macro => (16, 0),
    }
}

/// `textDocument/semanticTokens/full` (`range` `None`) and `.../range`.
pub fn tokens(
    request: &DocumentRequest,
    analysed: &Analysed,
    range: Option<Range>,
) -> SemanticTokens {
    let (shared, encoding) = (&request.shared, request.encoding);
    let id = shared.workspace.ensure_present(&request.uri, analysed);
    let table: Arc<SymbolTable> = match shared.workspace.read().index.document(&id) {
        Some(indexed) => Arc::clone(&indexed.symbols),
        None => Arc::new(SymbolTable::build(
            &analysed.lines(),
            analysed.analysis.config(),
        )),
    };
    let lines = analysed.lines();
    let wanted = match range {
        Some(range) => range.start.line as usize..(range.end.line as usize).saturating_add(1),
        None => 0..lines.line_count(),
    };
    let found = semantic_tokens(&lines, &table, analysed.analysis.config(), wanted);
    let all_ascii = analysed.rope.len_bytes() == analysed.rope.len_chars();
    let mut data = Vec::with_capacity(found.len());
    let mut previous = (0u32, 0u32);
    let mut current_line: Option<(usize, String)> = None;
    for token in &found {
        let (start, end) = if all_ascii {
            (token.start as u32, (token.start + token.length) as u32)
        } else {
            if current_line.as_ref().map(|(line, _)| *line) != Some(token.line) {
                current_line = Some((token.line, lines.line(token.line).into_owned()));
            }
            let text = current_line.as_ref().map_or("", |(_, text)| text.as_str());
            (
                byte_to_character(text, token.start, encoding),
                byte_to_character(text, token.start + token.length, encoding),
            )
        };
        let line = u32::try_from(token.line).unwrap_or(u32::MAX);
        let (token_type, group_bits) = encode_kind(token.kind);
        let own_bits = token.modifiers & (DECLARATION | MODIFICATION | NON_MODAL);
        data.push(SemanticToken {
            delta_line: line - previous.0,
            delta_start: if line == previous.0 {
                start - previous.1
            } else {
                start
            },
            length: end.saturating_sub(start),
            token_type,
            token_modifiers_bitset: own_bits | group_bits,
        });
        previous = (line, start);
    }
    SemanticTokens {
        result_id: None,
        data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_legend_has_a_type_for_every_kind_and_the_core_modifier_bits() {
        let kinds = [
            TokenKind::Comment,
            TokenKind::GCode { group: 1 },
            TokenKind::Macro,
            TokenKind::BlockNumber,
        ];
        for kind in kinds {
            let (index, _) = encode_kind(kind);
            assert!((index as usize) < TOKEN_TYPES.len());
        }
        assert_eq!(
            TOKEN_MODIFIERS[DECLARATION.trailing_zeros() as usize],
            "declaration"
        );
        assert_eq!(
            TOKEN_MODIFIERS[MODIFICATION.trailing_zeros() as usize],
            "modification"
        );
        assert_eq!(
            TOKEN_MODIFIERS[NON_MODAL.trailing_zeros() as usize],
            "nonModal"
        );
        assert_eq!(encode_kind(TokenKind::GCode { group: 1 }), (4, 1 << 3));
        assert_eq!(
            TOKEN_MODIFIERS[UNKNOWN_GROUP.trailing_zeros() as usize],
            "unknownGroup"
        );
    }
}
