//! How the parser reports a finding. Every finding of a line, the block checks' included, goes through
//! [`push_bounded`], which keeps the line's findings bounded and shortens long quotations of program
//! text in their messages.

use crate::diagnostics::{Code, Diagnostic, Fix, Span};
use crate::syntax::parser::cursor::Parser;

/// Most findings reported for one line; the last one says that more were dropped.
pub const MAX_DIAGNOSTICS_PER_LINE: usize = 200;

/// Longest quotation of program text inside a message, in characters.
const MAX_QUOTE_CHARACTERS: usize = 60;

/// Shortens every `quoted` part of a message that is longer than [`MAX_QUOTE_CHARACTERS`] to its start
/// and end around an ellipsis. The span still marks the whole text; a message quoting a megabyte-long
/// name helps nobody in an editor or a terminal.
fn shorten_long_quotes(message: String) -> String {
    if message.len() <= MAX_QUOTE_CHARACTERS * 2 {
        return message;
    }
    let mut out = String::with_capacity(message.len().min(1024));
    for (index, part) in message.split('`').enumerate() {
        if index > 0 {
            out.push('`');
        }
        let is_quote = index % 2 == 1;
        let character_count = if is_quote { part.chars().count() } else { 0 };
        if is_quote && character_count > MAX_QUOTE_CHARACTERS {
            out.extend(part.chars().take(MAX_QUOTE_CHARACTERS - 15));
            out.push('…');
            out.extend(part.chars().skip(character_count - 10));
        } else {
            out.push_str(part);
        }
    }
    // A quoted text that holds a backtick itself ends its quote early, so the rest of it was not
    // shortened above: keep the start and the end of such a message (found by the fuzzer).
    let character_count = out.chars().count();
    if character_count > MAX_MESSAGE_CHARACTERS {
        let tail: String = out.chars().skip(character_count - 80).collect();
        out = out.chars().take(MAX_MESSAGE_CHARACTERS - 81).collect();
        out.push('…');
        out.push_str(&tail);
    }
    out
}

/// Longest message, in characters, even when its quotations could not be found.
const MAX_MESSAGE_CHARACTERS: usize = 300;

impl Parser<'_> {
    pub(super) fn report(&mut self, code: Code, span: Span, message: impl Into<String>) {
        self.push_diagnostic(Diagnostic::new(code, span, message));
    }

    pub(super) fn report_with_fix(
        &mut self,
        code: Code,
        span: Span,
        message: impl Into<String>,
        fix: Fix,
    ) {
        self.push_diagnostic(Diagnostic::new(code, span, message).with_fix(fix));
    }

    pub(super) fn push_diagnostic(&mut self, diagnostic: Diagnostic) {
        push_bounded(self.diagnostics, diagnostic);
    }
}

/// Keeps a line's findings bounded: a line of repeated junk would otherwise give one finding per
/// token, which helps nobody and costs memory. The last kept finding says that more were dropped.
pub(super) fn push_bounded(diagnostics: &mut Vec<Diagnostic>, mut diagnostic: Diagnostic) {
    let count = diagnostics.len();
    if count >= MAX_DIAGNOSTICS_PER_LINE {
        return;
    }
    if count == MAX_DIAGNOSTICS_PER_LINE - 1 {
        diagnostic = Diagnostic::new(
            Code::TooManyDiagnostics,
            diagnostic.span,
            format!(
                "this line has more than {} findings; the rest are not shown",
                MAX_DIAGNOSTICS_PER_LINE - 1
            ),
        );
    }
    diagnostic.message = shorten_long_quotes(diagnostic.message);
    if let Some(fix) = diagnostic.fix.as_mut() {
        fix.title = shorten_long_quotes(std::mem::take(&mut fix.title));
    }
    diagnostics.push(diagnostic);
}
