//! Findings that depend on the configured machine or on what the evaluator can compute: diameter
//! programming and G96 without a transverse axis (alarms 16510, 10870), R parameters beyond the
//! configured count (alarm 17020), modulo rotary axes programmed outside 0..360 (MD30455 bit 0), and
//! calls of predefined functions the checker does not compute.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::eval::is_evaluated_function;
use crate::config::AxisKind;
use crate::diagnostics::{Code, Diagnostic, Span};
use crate::syntax::ast::{AssignTarget, Block, ExprKind, Modifier, Statement, ValueExpr};
use crate::syntax::keywords::is_function;

/// How to configure a lathe, said by the findings about a missing transverse axis.
const CONFIGURE_LATHE: &str = "if this program is for a lathe, put `[machine]` with `kind = \"turn\"` in a `sinumerik.toml` next to it (see docs/configuration.md)";

impl Engine<'_> {
    /// The findings of this file for one block (after its words have been applied).
    pub(super) fn check_machine_words(
        &mut self,
        line: &str,
        block: &Block,
        statements: &[Statement],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        self.check_transverse_functions(statements, diagnostics);
        self.check_r_parameter_numbers(block, statements, diagnostics);
        self.check_modulo_positions(line, block, statements, diagnostics);
        check_functions_not_evaluated(line, block, diagnostics);
    }

    /// DIAMON, DIAM90, DIAMCYCOF and G96 need a transverse axis (MD20100). Without a configuration
    /// file the machine is an assumed mill, so the finding is a warning that says how to configure a
    /// lathe, once per program.
    fn check_transverse_functions(
        &mut self,
        statements: &[Statement],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        if self.memory.transverse_reported
            || self
                .config
                .axes
                .iter()
                .any(|axis| axis.kind == AxisKind::Transverse)
        {
            return;
        }
        for statement in statements {
            let Statement::GCode { code, span } = statement else {
                continue;
            };
            let name = code.name();
            let (finding, alarm, what, consequence) = match name.as_ref() {
                "DIAMON" | "DIAM90" | "DIAMCYCOF" => (
                    Code::DiameterWithoutTransverseAxis,
                    16510,
                    "diameter programming",
                    ": until then diameters are read as radii",
                ),
                "G96" => (
                    Code::CuttingSpeedWithoutTransverseAxis,
                    10870,
                    "constant cutting speed",
                    "",
                ),
                _ => continue,
            };
            self.memory.transverse_reported = true;
            diagnostics.push(Diagnostic::new(
                finding,
                *span,
                format!("{name} ({what}) needs a transverse axis, and the configured machine has none (alarm {alarm}); {CONFIGURE_LATHE}{consequence}"),
            ));
            return;
        }
    }

    /// `R200=5` or `X=R200` with fewer R parameters configured (MD28050, `r_parameters`); without a
    /// configured count the machine's is not known.
    fn check_r_parameter_numbers(
        &self,
        block: &Block,
        statements: &[Statement],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        if !self.config.r_parameters_configured {
            return;
        }
        let count = self.config.r_parameter_count;
        let mut report = |number: u32, span: Span| {
            if number >= count {
                diagnostics.push(Diagnostic::new(
                    Code::IndexOutOfRange,
                    span,
                    format!("R{number} does not exist: the machine has {count} R parameters, R0 to R{} (`r_parameters`, MD28050; alarm 17020)", count.saturating_sub(1)),
                ));
            }
        };
        for statement in statements {
            if let Statement::Assignment {
                target: AssignTarget::RParameter(number),
                target_span,
                ..
            } = statement
            {
                report(*number, *target_span);
            }
        }
        for expr in &block.exprs {
            if let ExprKind::RParameter(number) = expr.kind {
                report(number, expr.span);
            }
        }
    }

    /// An absolute position of a modulo rotary axis outside 0..360: MD30455 bit 0 = 0 makes it an
    /// error (reference §3.5); checked only where the configuration says so (`modulo_range_error`).
    fn check_modulo_positions(
        &self,
        line: &str,
        block: &Block,
        statements: &[Statement],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        if !self.config.modulo_range_error {
            return;
        }
        for (index, word) in self.configured_axis_words(line, statements) {
            if self.config.axes[index].kind != AxisKind::Modulo {
                continue;
            }
            let absolute = match word.value.modifier {
                Some((Modifier::Ac | Modifier::Dc | Modifier::Acp | Modifier::Acn, _)) => true,
                Some(_) => false,
                None => self.state.is_incremental() == Some(false),
            };
            if !absolute {
                continue;
            }
            let value = match word.value.expr {
                ValueExpr::Constant { value, .. } => Some(value),
                ValueExpr::Expr(id) => {
                    crate::analysis::eval::evaluate(block, line, id, &self.state.variables)
                        .ok()
                        .flatten()
                }
                ValueExpr::Missing => None,
            };
            if let Some(value) = value.filter(|value| !(0.0..360.0).contains(value)) {
                diagnostics.push(Diagnostic::new(
                    Code::ModuloPositionOutOfRange,
                    word.span,
                    format!(
                        "{} is a modulo rotary axis: an absolute position must lie in 0 to 360 degrees, not {value} (MD30455 bit 0 = 0); write the position within the range, or use `=IC(..)` for a travel",
                        self.config.axes[index].name
                    ),
                ));
            }
        }
    }
}

/// The frame functions: their frames are computed where frame variables are assigned
/// (`frame_variables.rs`), not by the evaluator of numbers.
const FRAME_FUNCTIONS: &[&str] = &[
    "CTRANS", "CROT", "CROTS", "CSCALE", "CMIRROR", "CFINE", "INVFRAME", "ADDFRAME", "MEAFRAME",
];

/// A call of a predefined function the evaluator does not compute gets an information finding, once
/// per name and block, so that an unknown value is explained instead of silent.
fn check_functions_not_evaluated(line: &str, block: &Block, diagnostics: &mut Vec<Diagnostic>) {
    let mut reported: Vec<String> = Vec::new();
    for expr in &block.exprs {
        let ExprKind::Call { name, .. } = &expr.kind else {
            continue;
        };
        let Some(text) = line.get(name.start()..name.end()) else {
            continue;
        };
        let upper = text.to_ascii_uppercase();
        if !is_function(&upper)
            || is_evaluated_function(&upper)
            || FRAME_FUNCTIONS.contains(&upper.as_str())
            || reported.contains(&upper)
        {
            continue;
        }
        diagnostics.push(Diagnostic::new(
            Code::FunctionNotEvaluated,
            *name,
            format!("the checker does not compute {upper}: its result, and what depends on it, is unknown here"),
        ));
        reported.push(upper);
    }
}
