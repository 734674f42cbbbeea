//! Bytes that are never changed after they are made, large ones in pages mapped for them alone. The
//! output may hand such pages to a pipe itself (`vmsplice`, `stdout.rs`) instead of copying them in.
//! That is only safe because the pages are never written again and, when the bytes are dropped, are
//! unmapped rather than given back to the allocator: the kernel keeps a page alive for as long as a
//! pipe still refers to it, and no later allocation of the server can reuse it.

/// From this size on the bytes get pages of their own. Below it the unused rest of the last page
/// would cost more than the copy into the pipe.
#[cfg(target_os = "linux")]
const OWN_PAGES_MIN_BYTES: usize = 16 * 1024;

pub struct FrozenBytes(Storage);

enum Storage {
    Heap(Vec<u8>),
    #[cfg(target_os = "linux")]
    Pages {
        start: std::ptr::NonNull<u8>,
        length: usize,
        mapped: usize,
    },
}

// SAFETY: the mapped pages are written once, before the value exists, and only read afterwards; the
// value owns the mapping alone, so sharing and sending it is as safe as for a `Vec<u8>`.
unsafe impl Send for FrozenBytes {}
unsafe impl Sync for FrozenBytes {}

impl FrozenBytes {
    /// Freezes `bytes`; large ones are copied into pages of their own when the system gives them.
    pub fn new(bytes: Vec<u8>) -> FrozenBytes {
        #[cfg(target_os = "linux")]
        if bytes.len() >= OWN_PAGES_MIN_BYTES
            && !crate::lsp::transport::measure::measured_without("vmsplice")
        {
            if let Some(storage) = map_copy(&bytes) {
                return FrozenBytes(storage);
            }
        }
        FrozenBytes(Storage::Heap(bytes))
    }

    pub fn as_slice(&self) -> &[u8] {
        match &self.0 {
            Storage::Heap(bytes) => bytes,
            // SAFETY: `start` points at `mapped >= length` bytes mapped readable for as long as
            // `self` lives, all of them written before the value was made.
            #[cfg(target_os = "linux")]
            Storage::Pages { start, length, .. } => unsafe {
                std::slice::from_raw_parts(start.as_ptr(), *length)
            },
        }
    }

    /// Whether the bytes lie in pages that nothing else uses and that are never written or reused:
    /// only then may the pages themselves be given to a pipe.
    pub fn has_own_pages(&self) -> bool {
        match self.0 {
            Storage::Heap(_) => false,
            #[cfg(target_os = "linux")]
            Storage::Pages { .. } => true,
        }
    }
}

impl Drop for FrozenBytes {
    fn drop(&mut self) {
        #[cfg(target_os = "linux")]
        if let Storage::Pages { start, mapped, .. } = self.0 {
            // SAFETY: the mapping was made by `map_copy` with exactly this start and size, and
            // nothing refers to it any more. A pipe that still holds some of its pages keeps them
            // alive by itself.
            unsafe {
                libc::munmap(start.as_ptr().cast(), mapped);
            }
        }
    }
}

/// `bytes` copied into a private anonymous mapping of their own; `None` when the system refuses one.
#[cfg(target_os = "linux")]
fn map_copy(bytes: &[u8]) -> Option<Storage> {
    // SAFETY: sysconf has no preconditions.
    let page = usize::try_from(unsafe { libc::sysconf(libc::_SC_PAGESIZE) })
        .ok()
        .filter(|&page| page > 0)?;
    let mapped = bytes.len().div_ceil(page) * page;
    // SAFETY: a new private anonymous mapping touches no existing memory; the result is checked.
    let address = unsafe {
        libc::mmap(
            std::ptr::null_mut(),
            mapped,
            libc::PROT_READ | libc::PROT_WRITE,
            libc::MAP_PRIVATE | libc::MAP_ANONYMOUS | libc::MAP_POPULATE,
            -1,
            0,
        )
    };
    if address == libc::MAP_FAILED {
        return None;
    }
    let start = std::ptr::NonNull::new(address.cast::<u8>())?;
    // SAFETY: the mapping is `mapped >= bytes.len()` bytes long, writable, and overlaps nothing.
    unsafe {
        std::ptr::copy_nonoverlapping(bytes.as_ptr(), start.as_ptr(), bytes.len());
    }
    Some(Storage::Pages {
        start,
        length: bytes.len(),
        mapped,
    })
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    pub(crate) fn pattern(length: usize, seed: u8) -> Vec<u8> {
        (0..length)
            .map(|index| (index % 251) as u8 ^ seed)
            .collect()
    }

    #[test]
    fn frozen_bytes_read_back_as_written_whatever_their_size() {
        for length in [0, 1, 4095, 4096, 16 * 1024 - 1, 16 * 1024, 70_001] {
            let frozen = FrozenBytes::new(pattern(length, 0));
            assert_eq!(frozen.as_slice(), pattern(length, 0).as_slice(), "{length}");
        }
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn only_large_bytes_get_pages_of_their_own() {
        assert!(!FrozenBytes::new(pattern(100, 0)).has_own_pages());
        assert!(FrozenBytes::new(pattern(70_001, 0)).has_own_pages());
    }
}
