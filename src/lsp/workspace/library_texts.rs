//! The texts of called programs read from disk, kept for the documents' libraries until the index
//! sees their file change, and the generation of the index those libraries compare with.

use crate::ide::DocumentId;
use crate::lsp::locks::lock;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// The texts of files on disk that libraries read, by document id, until the index sees the file
/// change; and the generation of the index, which every change of an entry advances.
#[derive(Default)]
pub struct LibraryTexts {
    state: Mutex<TextsState>,
}

#[derive(Default)]
struct TextsState {
    generation: u64,
    /// `None` for a file that could not be read.
    texts: HashMap<DocumentId, Option<Arc<str>>>,
}

impl LibraryTexts {
    /// Advances with every change of the index: what a library found before may be out of date.
    pub fn generation(&self) -> u64 {
        lock(&self.state).generation
    }

    /// An entry of the index changed (an open document's, whose text libraries do not keep).
    pub fn index_changed(&self) {
        lock(&self.state).generation += 1;
    }

    /// The file of `id` changed on disk or went away: it is read again when asked for.
    pub fn file_changed(&self, id: &str) {
        let mut state = lock(&self.state);
        state.texts.remove(id);
        state.generation += 1;
    }

    /// Every file may have changed (a new indexing run).
    pub fn clear(&self) {
        let mut state = lock(&self.state);
        state.texts.clear();
        state.generation += 1;
    }

    /// The text of `id`, read with `read` unless it is kept. A text read while the file changed is
    /// returned but not kept: the change may have come after the reading.
    pub(crate) fn text(
        &self,
        id: &DocumentId,
        read: impl FnOnce() -> Option<Arc<str>>,
    ) -> Option<Arc<str>> {
        let generation = {
            let state = lock(&self.state);
            if let Some(text) = state.texts.get(id) {
                return text.clone();
            }
            state.generation
        };
        // The lock is not held while the file is read: other lookups go on meanwhile.
        let text = read();
        let mut state = lock(&self.state);
        if state.generation == generation {
            state.texts.insert(Arc::clone(id), text.clone());
        }
        text
    }
}
