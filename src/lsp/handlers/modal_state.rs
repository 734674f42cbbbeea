//! `sinumerik/modalState` for a status bar: the modal state after the block on a line. For a block
//! whose state depends on the way the control runs the program (after a label, a jump or a loop, or in
//! a subprogram), it is the state of the block's first execution in the program's run, with how often
//! the block runs; elsewhere the state of the analysis in program order, which is the same.

use crate::analysis::library::ProgramLibrary;
use crate::analysis::ProgramKind;
use crate::config::AxisKind;
use crate::lsp::documents::Analysed;
use crate::lsp::ext::{ModalStateResult, ProgramTime};

/// The modal state after the block on `line` of `analysed`.
pub fn modal_state_at(
    analysed: &Analysed,
    library: &dyn ProgramLibrary,
    line: usize,
) -> ModalStateResult {
    let after = analysed
        .analysis
        .block_report(&analysed.lines(), line)
        .after;
    let totals = analysed.times(library).totals();
    let time = ProgramTime {
        total_s: totals.total_s,
        feed_s: totals.feed_s,
        rapid_s: totals.rapid_s,
        dwell_s: totals.dwell_s,
        unknown_moves: totals.unknown_moves,
    };
    // DIAMOF is the reset state of every machine, also of a mill, where diameter programming has no
    // axis to act on; the client hides it there.
    let diameter_axis = analysed
        .analysis
        .config()
        .axes
        .iter()
        .any(|axis| axis.kind == AxisKind::Transverse);
    let needs_run = after.flow_uncertain || analysed.analysis.kind() == ProgramKind::Subprogram;
    if needs_run {
        let execution = analysed.execution(library);
        if let Some((first, passes)) = execution.first_pass(line) {
            return ModalStateResult {
                motion: first.motion(),
                plane: first.plane(),
                units: first.units(),
                distance: first.distance(),
                diameter: first.diameter(),
                diameter_axis,
                settable_offset: first.settable_offset(),
                feed: first.feed,
                // The run follows the control's way: its first pass is not uncertain for flow.
                flow_uncertain: false,
                passes: Some(passes),
                time,
            };
        }
    }
    ModalStateResult {
        motion: after.motion,
        plane: after.plane,
        units: after.units,
        distance: after.distance,
        diameter: after.diameter,
        diameter_axis,
        settable_offset: after.settable_offset,
        feed: after.feed,
        flow_uncertain: after.flow_uncertain,
        passes: None,
        time,
    }
}
