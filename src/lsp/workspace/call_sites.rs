//! The entry state of a subprogram opened on its own, from the places the workspace calls it: the
//! index lists the calls of its program name; the modal state at each is what the calling program's
//! analysis in program order has after the calling block (its text as the editor has it when open,
//! else the file read as the library reads it). When every call site has the same units, distance
//! mode and plane, the run starts from that state (`analysis::execution::entry`).

use crate::analysis::document::{DocumentAnalysis, TextLines};
use crate::analysis::execution::entry::{CallSiteState, CallerEntry};
use crate::analysis::ProgramKind;
use crate::ide::workspace::{program_name_and_kind, FileKind};
use crate::io::source_file::read_source_file;
use crate::lsp::state::Shared;
use std::path::Path;
use std::sync::Arc;

/// Callers longer than this are not analysed for the state at their calls: the reset state is
/// assumed instead, so that a hover never waits for a huge program's analysis.
const MAX_CALLER_BYTES: usize = 4 << 20;

/// The call sites of the program at `path` and the entry state they agree on.
pub fn caller_entry(shared: &Shared, path: &Path) -> Option<Arc<CallerEntry>> {
    let (name, kind) = program_name_and_kind(path.file_name()?.to_str()?);
    if kind != FileKind::Subprogram {
        return None;
    }
    let own = path.to_string_lossy();
    // (document id, URI when open, kind, call lines), read under the index's lock and used after it.
    let callers: Vec<_> = {
        let state = shared.workspace.read();
        state
            .index
            .documents()
            .filter(|document| document.id.as_ref() != own.as_ref())
            .filter(|document| {
                matches!(document.kind, FileKind::MainProgram | FileKind::Subprogram)
            })
            .filter_map(|document| {
                let lines: Vec<usize> = document
                    .symbols
                    .calls
                    .iter()
                    .filter(|call| call.name == name)
                    .map(|call| call.line)
                    .collect();
                (!lines.is_empty()).then(|| {
                    (
                        Arc::clone(&document.id),
                        state.uri(&document.id).cloned(),
                        document.kind,
                        lines,
                    )
                })
            })
            .collect()
    };
    let mut sites = Vec::new();
    for (id, uri, file_kind, lines) in callers {
        let open = uri.as_ref().and_then(|uri| shared.documents.get(uri));
        let text: String = match &open {
            Some(document) => document.text_snapshot().rope.to_string(),
            None => read_source_file(Path::new(id.as_ref())).ok()?.text,
        };
        // A caller that cannot be analysed here leaves its call sites unknown: no agreement.
        if text.len() > MAX_CALLER_BYTES {
            return None;
        }
        let caller_path = Path::new(id.as_ref());
        let config = shared.machine_config(Some(caller_path));
        let program_kind = match file_kind {
            FileKind::Subprogram => ProgramKind::Subprogram,
            _ => ProgramKind::Main,
        };
        let source = TextLines::new(&text);
        let analysis = DocumentAnalysis::new(&source, config, program_kind);
        let file = caller_path.file_name().map_or_else(
            || id.to_string(),
            |name| name.to_string_lossy().into_owned(),
        );
        for line in lines {
            let after = analysis.block_report(&source, line).after;
            sites.push(CallSiteState {
                file: file.clone(),
                motion: after.motion,
                plane: after.plane,
                units: after.units,
                distance: after.distance,
                diameter: after.diameter,
            });
        }
    }
    CallerEntry::agreed(&sites).map(Arc::new)
}
