//! The run of one revision of an open document and its machining times, made once per revision and
//! library generation and kept; the job holds a snapshot so that the run does not hold the analysis.

use crate::analysis::library::ProgramLibrary;
use crate::config::MachineConfig;
use crate::ide::execution::{execute_document, DocumentExecution};
use crate::lsp::locks::lock;
use crate::lsp::text_document::RopeLines;
use ropey::Rope;
use std::sync::{Arc, Mutex};

pub type CachedExecution = Option<(u64, u64, Arc<DocumentExecution>)>;
pub type CachedTimes = Option<(u64, u64, Arc<crate::ide::timing::DocumentTimes>)>;

/// What running one revision of a document needs, taken from its analysis so that the run (seconds
/// for a large program with many loops) does not hold the analysis, which every edit needs.
pub struct ExecutionJob {
    pub(crate) rope: Rope,
    pub(crate) revision: u64,
    pub(crate) config: Arc<MachineConfig>,
    pub(crate) kind: crate::analysis::ProgramKind,
    pub(crate) cache: Arc<Mutex<CachedExecution>>,
    pub(crate) times: Arc<Mutex<CachedTimes>>,
}

impl ExecutionJob {
    /// The run of the job's revision: the cached one, or made now (resuming the previous revision's
    /// run where the edit allows it). Runs asked for at once wait for one another.
    pub fn run(&self, library: &dyn ProgramLibrary) -> Arc<DocumentExecution> {
        let mut cached = lock(&self.cache);
        // Another file's change (a callee, a caller, a macro file) advances the library's generation:
        // the run is made again for it.
        let generation = library.generation();
        if let Some((revision, run_generation, execution)) = cached.as_ref() {
            if *revision == self.revision && *run_generation == generation {
                return Arc::clone(execution);
            }
        }
        // The run of an earlier revision is resumed where the edit allows it (`execution/recorded.rs`).
        let earlier = cached
            .as_ref()
            .map(|(_, _, execution)| Arc::clone(execution));
        let execution = Arc::new(execute_document(
            &RopeLines::new(&self.rope),
            &self.config,
            self.kind,
            library,
            &self.config.execution,
            earlier.as_deref(),
        ));
        // A newer revision's run may have been stored meanwhile: it stays.
        let newer = cached
            .as_ref()
            .is_some_and(|(revision, _, _)| *revision > self.revision);
        if !newer {
            *cached = Some((self.revision, generation, Arc::clone(&execution)));
        }
        execution
    }

    /// The machining times of the job's revision: the cached ones, or made now from its run.
    pub fn times(&self, library: &dyn ProgramLibrary) -> Arc<crate::ide::timing::DocumentTimes> {
        let execution = self.run(library);
        let generation = library.generation();
        let mut cached = lock(&self.times);
        if let Some((revision, run_generation, times)) = cached.as_ref() {
            if *revision == self.revision && *run_generation == generation {
                return Arc::clone(times);
            }
        }
        let times = Arc::new(crate::ide::timing::DocumentTimes::new(
            &RopeLines::new(&self.rope),
            &execution,
            &self.config,
            self.kind,
        ));
        let newer = cached
            .as_ref()
            .is_some_and(|(revision, _, _)| *revision > self.revision);
        if !newer {
            *cached = Some((self.revision, generation, Arc::clone(&times)));
        }
        times
    }
}
