//! The run of a document and its machining times as the hover and the inlay hints ask for them:
//! only when the program's flow makes the reading in program order insufficient, since a run costs
//! far more than a reading. The caller decides how runs are made and kept (the server keeps one per
//! revision and library generation; [`RunOnce`] makes one on first use).

use crate::analysis::document::LineSource;
use crate::analysis::library::ProgramLibrary;
use crate::analysis::ProgramKind;
use crate::config::MachineConfig;
use crate::ide::execution::{execute_document, DocumentExecution};
use crate::ide::timing::DocumentTimes;
use std::sync::{Arc, OnceLock};

/// Up to this many lines a feature makes the machining times of a document itself (a few
/// milliseconds); a larger document shows them once something else made them.
pub const TIMES_MADE_UP_TO_LINES: usize = 20_000;

/// Access to the run of one document, made on demand.
pub trait ProgramRun {
    /// The run of the document, made now if nothing asked for it before.
    fn execution(&self) -> Arc<DocumentExecution>;
    /// The machining times of the run, made now if nothing asked for them before.
    fn times(&self) -> Arc<DocumentTimes>;
    /// The machining times if something already made them.
    fn cached_times(&self) -> Option<Arc<DocumentTimes>>;
}

/// A run made on first use and kept, for one document held by a [`LineSource`].
pub struct RunOnce<'a> {
    source: &'a dyn LineSource,
    config: &'a MachineConfig,
    kind: ProgramKind,
    library: &'a dyn ProgramLibrary,
    execution: OnceLock<Arc<DocumentExecution>>,
    times: OnceLock<Arc<DocumentTimes>>,
}

impl<'a> RunOnce<'a> {
    pub fn new(
        source: &'a dyn LineSource,
        config: &'a MachineConfig,
        kind: ProgramKind,
        library: &'a dyn ProgramLibrary,
    ) -> RunOnce<'a> {
        RunOnce {
            source,
            config,
            kind,
            library,
            execution: OnceLock::new(),
            times: OnceLock::new(),
        }
    }
}

impl ProgramRun for RunOnce<'_> {
    fn execution(&self) -> Arc<DocumentExecution> {
        Arc::clone(self.execution.get_or_init(|| {
            Arc::new(execute_document(
                self.source,
                self.config,
                self.kind,
                self.library,
                &self.config.execution,
                None,
            ))
        }))
    }

    fn times(&self) -> Arc<DocumentTimes> {
        let execution = self.execution();
        Arc::clone(self.times.get_or_init(|| {
            Arc::new(DocumentTimes::new(
                self.source,
                &execution,
                self.config,
                self.kind,
            ))
        }))
    }

    fn cached_times(&self) -> Option<Arc<DocumentTimes>> {
        self.times.get().cloned()
    }
}
