//! The open documents: each one's text (changed synchronously, in the order edits arrive) and its
//! analysis (brought up to date on a snapshot, off the async threads), and the worker that publishes
//! the diagnostics of the newest version and never those of a version already replaced.
//!
//! Lock order: a document's `analysis` lock may be taken before its `text` lock, never after it.
//! The `text` lock is only held for short, non-blocking work (applying an edit, taking a snapshot),
//! and once per `didOpen` while the rope is built from the opened string (15-30 ms for 33 MB): an
//! edit that comes then waits for it.

use crate::analysis::document::{
    core_line_count, DocumentAnalysis, FlatLines, LineSource, RopeLines,
};
use crate::analysis::library::ProgramLibrary;
use crate::analysis::ProgramKind;
use crate::config::MachineConfig;
use crate::ide::execution::DocumentExecution;
use crate::ide::program_run::ProgramRun;
use crate::lsp::convert::PositionEncoding;
use crate::lsp::cross_file::{extra_findings, ExtraDiagnostics};
use crate::lsp::execution_job::{CachedExecution, CachedTimes, ExecutionJob};
use crate::lsp::publish::Publisher;
use crate::lsp::text_document::{apply_changes, ChangeError, DocumentText, RopeLineChange};
use crate::lsp::transport::outbox::{Outgoing, OutgoingSender};
use ropey::Rope;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};
use tower_lsp_server::ls_types::{TextDocumentContentChangeEvent, Uri};

/// Kept under this name for the files that take it from here.
pub use crate::lsp::locks::lock;

mod first_analysis;
mod publication;

/// What changed since the analysis last looked at the text.
#[derive(Debug, Clone, Copy)]
enum Pending {
    Nothing,
    Lines(RopeLineChange),
    /// The configuration changed, or the analysis was lost: start from scratch.
    Everything,
}

struct TextState {
    /// The text; its rope is empty while `opened` holds the text instead.
    text: DocumentText,
    /// The text of the `didOpen` until its rope is built (`opened_text.rs`): by the worker after the
    /// first diagnostics, or by whatever needs the rope before.
    opened: Option<Arc<String>>,
    /// Counts every change of text or configuration; results of an older revision are stale.
    revision: u64,
    pending: Pending,
    config: Arc<MachineConfig>,
    worker_running: bool,
    closed: bool,
}

/// What a publication is made of: an analysis, the lines it read, and their version.
struct PublishedText<'a> {
    analysis: &'a DocumentAnalysis,
    lines: &'a dyn LineSource,
    /// Whether the text is ASCII, where byte offsets are the columns in every position encoding.
    all_ascii: bool,
    version: i32,
}

/// An analysis together with the exact text it describes.
pub struct Analysed {
    pub analysis: DocumentAnalysis,
    pub rope: Rope,
    pub version: i32,
    pub revision: u64,
    config: Arc<MachineConfig>,
    /// The run of the document (`ide::execution`), made when a feature first asks for it and kept
    /// for the revision and library generation it ran with. Shared, so that a run can be made
    /// without holding the document's analysis (see [`ExecutionJob`]).
    execution: Arc<Mutex<CachedExecution>>,
    /// The machining times of the run (`ide::timing`), kept like the run.
    times: Arc<Mutex<CachedTimes>>,
}

impl Analysed {
    pub fn lines(&self) -> RopeLines<'_> {
        RopeLines::new(&self.rope)
    }

    /// The run of this revision of the document, made now if no feature asked for it before.
    pub fn execution(&self, library: &dyn ProgramLibrary) -> Arc<DocumentExecution> {
        self.execution_job().run(library)
    }

    /// The machining times of this revision, made now if no feature asked for them before.
    pub fn times(&self, library: &dyn ProgramLibrary) -> Arc<crate::ide::timing::DocumentTimes> {
        self.execution_job().times(library)
    }

    /// Whether a feature at `line` may show the run rather than the reading in program order: the
    /// block there follows a label, a jump or a loop, or the document is a subprogram.
    pub fn may_show_run(&self, line: usize) -> bool {
        if self.analysis.kind() == crate::analysis::ProgramKind::Subprogram {
            return true;
        }
        if line >= self.rope.len_lines() {
            return false;
        }
        // The checkpoints tell it for all but the last interval; replaying the block to know would
        // double the cost of a hover, which replays it anyway.
        self.analysis
            .flow_uncertain_by_checkpoints(line)
            .unwrap_or_else(|| {
                let report = self.analysis.block_report(&self.lines(), line);
                report.before.flow_uncertain || report.after.flow_uncertain
            })
    }

    /// The machining times of this revision if a request already made them (the status bar's, the
    /// toolpath's): the hover shows them without reading a large document again on every edit.
    pub fn cached_times(
        &self,
        library: &dyn ProgramLibrary,
    ) -> Option<Arc<crate::ide::timing::DocumentTimes>> {
        let generation = library.generation();
        lock(&self.times)
            .as_ref()
            .filter(|(revision, run_generation, _)| {
                *revision == self.revision && *run_generation == generation
            })
            .map(|(_, _, times)| Arc::clone(times))
    }

    /// The run and the times of this revision as the hover and the inlay hints ask for them.
    pub fn program_run<'a>(&'a self, library: &'a dyn ProgramLibrary) -> AnalysedRun<'a> {
        AnalysedRun {
            analysed: self,
            library,
        }
    }

    /// What running this revision needs, to run it after letting go of the analysis.
    pub fn execution_job(&self) -> ExecutionJob {
        ExecutionJob {
            rope: self.rope.clone(),
            revision: self.revision,
            config: Arc::clone(&self.config),
            kind: self.analysis.kind(),
            cache: Arc::clone(&self.execution),
            times: Arc::clone(&self.times),
        }
    }
}

/// The run of an analysed revision with the library it calls into ([`Analysed::program_run`]).
pub struct AnalysedRun<'a> {
    analysed: &'a Analysed,
    library: &'a dyn ProgramLibrary,
}

impl ProgramRun for AnalysedRun<'_> {
    fn execution(&self) -> Arc<DocumentExecution> {
        self.analysed.execution(self.library)
    }

    fn times(&self) -> Arc<crate::ide::timing::DocumentTimes> {
        self.analysed.times(self.library)
    }

    fn cached_times(&self) -> Option<Arc<crate::ide::timing::DocumentTimes>> {
        self.analysed.cached_times(self.library)
    }
}

pub struct OpenDocument {
    pub uri: Uri,
    /// The file behind a `file:` URI.
    pub path: Option<PathBuf>,
    pub kind: ProgramKind,
    text: Mutex<TextState>,
    analysis: Mutex<Option<Analysed>>,
    /// The diagnostics last written (in that position encoding), for the worker only.
    published: Mutex<Option<(PositionEncoding, Publisher)>>,
    /// The cross-file findings, published with the analysis's diagnostics (`cross_file.rs`).
    pub extra: Mutex<ExtraDiagnostics>,
}

/// The text of a document as it is now, with what the workspace index needs to read it.
pub struct TextSnapshot {
    pub rope: Rope,
    pub revision: u64,
    pub config: Arc<MachineConfig>,
}

/// What a worker needs besides the document.
#[derive(Clone)]
pub struct WorkerContext {
    pub outgoing: OutgoingSender,
    pub encoding: PositionEncoding,
    /// The `maxDiagnostics` setting (`publish/limit.rs`).
    pub max_diagnostics: Option<usize>,
}

impl OpenDocument {
    /// A document opened with `text`, which its first analysis reads before the rope is built.
    pub fn new(
        uri: Uri,
        path: Option<PathBuf>,
        kind: ProgramKind,
        text: String,
        version: i32,
        config: Arc<MachineConfig>,
    ) -> OpenDocument {
        OpenDocument {
            uri,
            path,
            kind,
            text: Mutex::new(TextState {
                text: DocumentText::from_rope(Rope::new(), version),
                opened: Some(Arc::new(text)),
                revision: 1,
                pending: Pending::Everything,
                config,
                worker_running: false,
                closed: false,
            }),
            analysis: Mutex::new(None),
            published: Mutex::new(None),
            extra: Mutex::new(ExtraDiagnostics::default()),
        }
    }

    /// The current revision; a request remembers it to know whether its answer is still current.
    pub fn revision(&self) -> u64 {
        lock(&self.text).revision
    }

    /// The version of the text as it is now (without building the rope of an opened text).
    pub fn version(&self) -> i32 {
        lock(&self.text).text.version
    }

    /// The rope (a cheap copy), revision and configuration as they are now.
    pub fn text_snapshot(&self) -> TextSnapshot {
        let mut text = lock(&self.text);
        let rope = text.with_rope().rope.clone();
        TextSnapshot {
            rope,
            revision: text.revision,
            config: Arc::clone(&text.config),
        }
    }

    /// Publishes the diagnostics again (the cross-file findings changed); a running worker notices
    /// the change itself.
    pub fn republish(self: &Arc<Self>, context: &WorkerContext) {
        let mut text = lock(&self.text);
        self.schedule(&mut text, context);
    }

    /// The version and the whole text as they are now.
    pub fn text_now(&self) -> (i32, String) {
        let text = lock(&self.text);
        match &text.opened {
            Some(opened) => (text.text.version, String::clone(opened)),
            None => (text.text.version, text.text.rope.to_string()),
        }
    }

    /// The number of lines as the core counts them, without building the rope.
    pub fn line_count(&self) -> usize {
        let opened = {
            let text = lock(&self.text);
            match &text.opened {
                Some(opened) => Arc::clone(opened),
                None => return text.text.line_count(),
            }
        };
        FlatLines::new(&opened).line_count()
    }

    /// Applies a `didChange` synchronously and starts the analysis. Called before any `.await` of
    /// the handler, so edits are applied in the order they arrive.
    pub fn change(
        self: &Arc<Self>,
        changes: &[TextDocumentContentChangeEvent],
        version: i32,
        context: &WorkerContext,
    ) -> Result<(), ChangeError> {
        let mut text = lock(&self.text);
        let changed = apply_changes(text.with_rope(), changes, version, context.encoding)?;
        if let Some(line_change) = changed {
            text.pending = match text.pending {
                Pending::Nothing => Pending::Lines(line_change),
                Pending::Lines(earlier) => Pending::Lines(earlier.then(line_change)),
                Pending::Everything => Pending::Everything,
            };
        }
        text.revision += 1;
        lock(&self.extra).on_edit(changed, text.revision);
        self.schedule(&mut text, context);
        Ok(())
    }

    /// Replaces the configuration (it changed on disk or in the settings) and re-analyses.
    pub fn set_config(self: &Arc<Self>, config: Arc<MachineConfig>, context: &WorkerContext) {
        let mut text = lock(&self.text);
        if *text.config == *config {
            return;
        }
        text.config = config;
        text.pending = Pending::Everything;
        text.revision += 1;
        self.schedule(&mut text, context);
    }

    /// Starts the first analysis after `didOpen`.
    pub fn start(self: &Arc<Self>, context: &WorkerContext) {
        let mut text = lock(&self.text);
        self.schedule(&mut text, context);
    }

    /// Marks the document closed and clears its diagnostics; a running worker publishes nothing more.
    pub fn close(&self, context: &WorkerContext) {
        let mut text = lock(&self.text);
        text.closed = true;
        text.revision += 1;
        // Sent under the lock, so no publication of a worker can come after it.
        context.outgoing.send(Outgoing::Diagnostics {
            uri: self.uri.clone(),
            version: None,
            diagnostics: Vec::new(),
        });
    }

    fn schedule(self: &Arc<Self>, text: &mut TextState, context: &WorkerContext) {
        if text.worker_running || text.closed {
            return;
        }
        text.worker_running = true;
        let document = Arc::clone(self);
        let context = context.clone();
        tokio::task::spawn_blocking(move || document.run_worker(&context));
    }

    /// The analysis, locked, when it is of `revision` and nobody holds it: a request answered on it
    /// right away needs neither to wait nor to move to another thread.
    pub fn try_current(&self, revision: u64) -> Option<MutexGuard<'_, Option<Analysed>>> {
        let slot = self.analysis.try_lock().ok()?;
        slot.as_ref()
            .is_some_and(|analysed| analysed.revision == revision)
            .then_some(slot)
    }

    /// Brings the analysis up to date with the newest text and returns it, locked. Waits for a
    /// worker that is analysing, and may itself do the work a worker would have done.
    pub fn catch_up(&self) -> MutexGuard<'_, Option<Analysed>> {
        let mut slot = lock(&self.analysis);
        loop {
            let (rope, version, revision, pending, config) = {
                let mut text = lock(&self.text);
                // A closed document is not brought up to date: nothing of it is published any more.
                if text.closed
                    || slot
                        .as_ref()
                        .is_some_and(|analysed| analysed.revision == text.revision)
                {
                    return slot;
                }
                let pending = std::mem::replace(&mut text.pending, Pending::Nothing);
                (
                    text.with_rope().rope.clone(),
                    text.text.version,
                    text.revision,
                    pending,
                    text.config.clone(),
                )
            };
            // A long update stops when a newer edit has come: it goes on with that edit's text.
            let newer_edit = || lock(&self.text).revision != revision;
            let updated = match (slot.as_mut(), pending) {
                (Some(analysed), pending) if Arc::ptr_eq(&analysed.config, &config) => {
                    let source = RopeLines::new(&rope);
                    match pending {
                        Pending::Lines(change) => {
                            let line_change = change
                                .to_core(core_line_count(&analysed.rope), source.line_count());
                            Some(analysed.analysis.update_interruptible(
                                &source,
                                line_change.first,
                                line_change.removed,
                                line_change.inserted,
                                &newer_edit,
                            ))
                        }
                        // The text did not change (or the document was closed): only what an
                        // interrupted update left is read.
                        Pending::Nothing if analysed.analysis.is_complete() => Some(true),
                        Pending::Nothing => Some(analysed.analysis.update_interruptible(
                            &source,
                            0,
                            0,
                            0,
                            &newer_edit,
                        )),
                        Pending::Everything => None,
                    }
                }
                _ => None,
            };
            match (updated, slot.as_mut()) {
                (Some(finished), Some(analysed)) => {
                    // The analysis now describes this text, up to what an interruption left.
                    analysed.rope = rope;
                    if finished {
                        analysed.version = version;
                        analysed.revision = revision;
                        return slot;
                    }
                }
                _ => {
                    // The whole document is read on two threads: the first analysis of a large
                    // program is what the user waits for after opening it.
                    let analysis = DocumentAnalysis::new_in_parallel(
                        &RopeLines::new(&rope),
                        &mut RopeLines::new(&rope),
                        config.clone(),
                        self.kind,
                    );
                    *slot = Some(Analysed {
                        analysis,
                        rope,
                        version,
                        revision,
                        config,
                        execution: Arc::new(Mutex::new(None)),
                        times: Arc::new(Mutex::new(None)),
                    });
                    return slot;
                }
            }
        }
    }

    /// Analyses until the analysis matches the newest revision, then publishes its diagnostics.
    fn run_worker(&self, context: &WorkerContext) {
        let opened = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            self.publish_opened_text(context)
        }));
        // After a failure the loop starts from scratch, as after any failed analysis.
        if opened.unwrap_or(false) {
            return;
        }
        loop {
            let started = std::time::Instant::now();
            let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                let slot = self.catch_up();
                let analysed_in = started.elapsed();
                slot.as_ref().map(|analysed| {
                    let lines = analysed.lines();
                    let (extra, extra_generation) =
                        extra_findings(&self.extra, LineSource::line_count(&lines));
                    let published = PublishedText {
                        analysis: &analysed.analysis,
                        lines: &lines,
                        all_ascii: analysed.rope.len_bytes() == analysed.rope.len_chars(),
                        version: analysed.version,
                    };
                    let message = self.publication(
                        published,
                        context.encoding,
                        context.max_diagnostics,
                        &extra,
                    );
                    let count = analysed.analysis.diagnostics().len();
                    (
                        (analysed.revision, extra_generation),
                        message,
                        count,
                        analysed_in,
                    )
                })
            }));
            if let Ok(Some((_, _, count, analysed_in))) = &result {
                context.log_slow_publication(*analysed_in, *count, started);
            }
            match result {
                Ok(Some(((revision, extra_generation), message, _, _))) => {
                    let mut text = lock(&self.text);
                    if text.closed {
                        text.worker_running = false;
                        return;
                    }
                    if self.is_current(&text, revision, extra_generation) {
                        // Sent under the lock: a newer revision's publication cannot overtake it.
                        context.outgoing.send_parts(message);
                        text.worker_running = false;
                        return;
                    }
                    // The text or the cross-file findings changed meanwhile: write again.
                }
                Ok(None) => {
                    lock(&self.text).worker_running = false;
                    return;
                }
                Err(_) => {
                    *lock(&self.analysis) = None;
                    let mut text = lock(&self.text);
                    text.pending = Pending::Everything;
                    text.worker_running = false;
                    context.outgoing.log_error(format!(
                        "the analysis of {} failed; it is retried at the next edit",
                        self.uri.as_str()
                    ));
                    return;
                }
            }
        }
    }
}

/// The open documents by URI.
#[derive(Default)]
pub struct Documents {
    map: Mutex<HashMap<Uri, Arc<OpenDocument>>>,
}

impl Documents {
    pub fn get(&self, uri: &Uri) -> Option<Arc<OpenDocument>> {
        lock(&self.map).get(uri).cloned()
    }

    /// Adds a document; returns the one it replaced (a second `didOpen` without `didClose`).
    pub fn insert(&self, document: Arc<OpenDocument>) -> Option<Arc<OpenDocument>> {
        lock(&self.map).insert(document.uri.clone(), document)
    }

    pub fn remove(&self, uri: &Uri) -> Option<Arc<OpenDocument>> {
        lock(&self.map).remove(uri)
    }

    pub fn all(&self) -> Vec<Arc<OpenDocument>> {
        lock(&self.map).values().cloned().collect()
    }
}
