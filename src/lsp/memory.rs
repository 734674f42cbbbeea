//! How the server asks the allocator to keep its resident memory close to what it uses. Every
//! publication of a large program's diagnostics writes megabytes of JSON, and analyses run on several
//! threads of the blocking pool. glibc's allocator raises its threshold for serving blocks by `mmap`
//! each time such a block is freed, after which these buffers come from its heaps and stay resident
//! when freed, and it gives each thread a heap of its own: resident memory then grows with every
//! edit. A fixed threshold and two heaps keep it flat (measured with `benches/lsp_latency.rs`).

/// Blocks from this size on are mapped and unmapped on their own, so freeing them returns the memory.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD_BYTES: libc::c_int = 256 * 1024;

/// The allocator's heaps: one per core of the machines the server is measured on.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const ARENAS: libc::c_int = 2;

/// Sets the allocator's options; called once, before the server starts its threads. Settings made by
/// the user through glibc's environment variables (`MALLOC_MMAP_THRESHOLD_`, `MALLOC_ARENA_MAX`)
/// are kept.
pub fn configure_allocator() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        let unset = |name: &str| std::env::var_os(name).is_none();
        // SAFETY: mallopt only changes the allocator's parameters; it is called before any other
        // thread of the server exists.
        unsafe {
            if unset("MALLOC_MMAP_THRESHOLD_") {
                libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD_BYTES);
            }
            if unset("MALLOC_ARENA_MAX") {
                libc::mallopt(libc::M_ARENA_MAX, ARENAS);
            }
        }
    }
}
