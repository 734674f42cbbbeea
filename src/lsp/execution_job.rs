//! The run of one revision of an open document and its machining times, made once per revision and
//! library generation and kept; the job holds a snapshot so that the run does not hold the analysis.

use crate::analysis::document::RopeLines;
use crate::analysis::library::ProgramLibrary;
use crate::config::MachineConfig;
use crate::ide::execution::{execute_document, DocumentExecution};
use crate::lsp::locks::lock;
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
        // Another file's change (a callee, a caller, a macro file) advances the library's generation:
        // the run is made again for it.
        self.kept(&self.cache, library.generation(), |earlier| {
            // The run of an earlier revision is resumed where the edit allows it
            // (`execution/recorded.rs`).
            execute_document(
                &RopeLines::new(&self.rope),
                &self.config,
                self.kind,
                library,
                &self.config.execution,
                earlier,
            )
        })
    }

    /// The machining times of the job's revision: the cached ones, or made now from its run.
    pub fn times(&self, library: &dyn ProgramLibrary) -> Arc<crate::ide::timing::DocumentTimes> {
        let execution = self.run(library);
        self.kept(&self.times, library.generation(), |_| {
            crate::ide::timing::DocumentTimes::new(
                &RopeLines::new(&self.rope),
                &execution,
                &self.config,
                self.kind,
            )
        })
    }

    /// The value `cache` keeps for the job's revision and the library's `generation`, or the one
    /// `make` makes now (given the cached value of another revision or generation), kept unless a
    /// newer revision's value was stored meanwhile. The cache stays locked while `make` works, so
    /// that requests asked at once wait for one value.
    fn kept<T>(
        &self,
        cache: &Mutex<Option<(u64, u64, Arc<T>)>>,
        generation: u64,
        make: impl FnOnce(Option<&T>) -> T,
    ) -> Arc<T> {
        let mut cached = lock(cache);
        if let Some((revision, made_for, value)) = cached.as_ref() {
            if *revision == self.revision && *made_for == generation {
                return Arc::clone(value);
            }
        }
        let earlier = cached.as_ref().map(|(_, _, value)| Arc::clone(value));
        let value = Arc::new(make(earlier.as_deref()));
        let newer = cached
            .as_ref()
            .is_some_and(|(revision, _, _)| *revision > self.revision);
        if !newer {
            *cached = Some((self.revision, generation, Arc::clone(&value)));
        }
        value
    }
}
