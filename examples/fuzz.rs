//! A coverage-free mutation fuzzer for the stable toolchain: the block parser, the full analysis, the
//! document model under random edits, the command line's output formats and the configuration
//! reader, the server's framing parser and its encoding of diagnostics, each checked against the
//! properties the product promises.
//!
//! ```text
//! cargo run --release --example fuzz -- --target parser|analysis|document|cli|config|framing|publish [--seconds N] [--steps N]
//!     [--seed S] [--timeout-ms T] [--max-input-bytes B] [--memory-mb M]
//! cargo run --release --example fuzz -- --target document --replay FILE...
//! ```
//!
//! The process that is started supervises a worker process (the same program with `--worker`): the
//! worker tells it the number of each case before running it, so a case that aborts the worker (a
//! stack overflow, an allocation over the memory limit) or runs past the timeout (a hang) is made again
//! from the seed and its number and saved. Panics and broken properties are caught inside the worker,
//! minimised (lines, then characters) and written to `fixtures/fuzz/`. Any failure exits with 1.

#[path = "fuzz/approx.rs"]
mod approx;
#[path = "fuzz/cases.rs"]
mod cases;
#[path = "fuzz/cli.rs"]
mod cli;
#[path = "fuzz/config.rs"]
mod config;
#[path = "fuzz/document.rs"]
mod document;
#[path = "fuzz/generate.rs"]
mod generate;
#[path = "fuzz/minimise.rs"]
mod minimise;
#[path = "fuzz/random.rs"]
mod random;
#[path = "fuzz/seeds.rs"]
mod seeds;
#[path = "fuzz/spans.rs"]
mod spans;
#[path = "fuzz/targets.rs"]
mod targets;
#[path = "fuzz/transport.rs"]
mod transport;

use cases::{generate_case, run_case, Case, Target};
use std::alloc::{GlobalAlloc, Layout, System};
use std::io::{Read, Write};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::sync::Mutex;
use std::time::{Duration, Instant};

// ----- memory: a counting allocator with a hard limit --------------------------------------------

/// Counts the bytes in use and refuses allocations beyond the limit, which aborts the worker with
/// "memory allocation failed": the supervisor then saves the case as one that needs too much memory.
struct CountingAllocator;

static ALLOCATED: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static LIMIT: AtomicUsize = AtomicUsize::new(usize::MAX);

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let now = ALLOCATED.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        if now > LIMIT.load(Ordering::Relaxed) {
            ALLOCATED.fetch_sub(layout.size(), Ordering::Relaxed);
            return std::ptr::null_mut();
        }
        PEAK.fetch_max(now, Ordering::Relaxed);
        // SAFETY: the layout is passed on unchanged to the system allocator.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, pointer: *mut u8, layout: Layout) {
        ALLOCATED.fetch_sub(layout.size(), Ordering::Relaxed);
        // SAFETY: the pointer came from `alloc` above with this layout.
        unsafe { System.dealloc(pointer, layout) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

// ----- options --------------------------------------------------------------------------------------

struct Options {
    target: Target,
    seconds: Option<u64>,
    steps: Option<usize>,
    seed: u64,
    timeout: Duration,
    max_input_bytes: usize,
    memory_mb: usize,
    replay: Vec<PathBuf>,
    worker: bool,
    /// Where reproducers are written.
    out: PathBuf,
    /// Makes case 3 fail on purpose (panic, abort, hang, memory, overflow), to see the failure
    /// handling work.
    self_test: Option<String>,
    /// Where the slowest case of the run is written at its end, for profiling.
    save_slowest: Option<PathBuf>,
    /// Where the case that needed the most memory is written at the end of the run.
    save_hungriest: Option<PathBuf>,
}

const USAGE: &str =
    "usage: fuzz --target parser|analysis|document|cli|config|framing|publish [--seconds N] [--steps N] [--seed S] \
[--timeout-ms T] [--max-input-bytes B] [--memory-mb M] [--out DIR] [--save-slowest FILE] [--save-hungriest FILE] [--self-test panic|abort|hang|memory|overflow] \
[--replay FILE...]";

fn parse_options(args: &[String]) -> Result<Options, String> {
    let mut options = Options {
        target: Target::Parser,
        seconds: None,
        steps: None,
        seed: 1,
        timeout: Duration::from_secs(10),
        max_input_bytes: 1 << 20,
        memory_mb: 1024,
        replay: Vec::new(),
        worker: false,
        out: Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/fuzz"),
        self_test: None,
        save_slowest: None,
        save_hungriest: None,
    };
    let mut target = None;
    let mut index = 0;
    while index < args.len() {
        let flag = args[index].as_str();
        let mut value = || -> Result<&String, String> {
            index += 1;
            args.get(index).ok_or(format!("{flag} needs a value"))
        };
        let number = |text: &String| -> Result<u64, String> {
            text.parse()
                .map_err(|_| format!("{flag}: `{text}` is not a number"))
        };
        match flag {
            "--target" => {
                let name = value()?;
                target = Some(Target::parse(name).ok_or(format!("unknown target `{name}`"))?);
            }
            "--seconds" => options.seconds = Some(number(value()?)?),
            "--steps" => options.steps = Some(number(value()?)? as usize),
            "--seed" => options.seed = number(value()?)?,
            "--timeout-ms" => options.timeout = Duration::from_millis(number(value()?)?),
            "--max-input-bytes" => options.max_input_bytes = number(value()?)? as usize,
            "--memory-mb" => options.memory_mb = number(value()?)? as usize,
            "--replay" => {
                options
                    .replay
                    .extend(args[index + 1..].iter().map(PathBuf::from));
                index = args.len();
            }
            "--worker" => options.worker = true,
            "--out" => options.out = PathBuf::from(value()?),
            "--self-test" => options.self_test = Some(value()?.clone()),
            "--save-slowest" => options.save_slowest = Some(PathBuf::from(value()?)),
            "--save-hungriest" => options.save_hungriest = Some(PathBuf::from(value()?)),
            _ => return Err(format!("unknown argument `{flag}`")),
        }
        index += 1;
    }
    options.target = target.ok_or("--target is needed")?;
    if options.seconds.is_none() && options.steps.is_none() {
        options.seconds = Some(60);
    }
    Ok(options)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let options = match parse_options(&args) {
        Ok(options) => options,
        Err(problem) => {
            eprintln!("fuzz: {problem}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    install_quiet_panic_hook();
    let code = if !options.replay.is_empty() {
        replay(&options)
    } else if options.worker {
        LIMIT.store(options.memory_mb << 20, Ordering::Relaxed);
        // Cases run on a thread with the stack a language-server worker thread gets (2 MiB), not on
        // the main thread's 8 MiB: recursion that fits only in the larger stack is a crash to find.
        match std::thread::Builder::new()
            .stack_size(WORKER_STACK_BYTES)
            .spawn(move || work(&options))
            .map(|worker| worker.join())
        {
            Ok(Ok(code)) => code,
            _ => 2,
        }
    } else {
        supervise(&args, &options)
    };
    ExitCode::from(code)
}

/// The stack of the thread that runs the cases.
const WORKER_STACK_BYTES: usize = 2 << 20;

// ----- panics ---------------------------------------------------------------------------------------

/// The message of the last panic, kept instead of printed: minimising runs a failing case many times.
static LAST_PANIC: Mutex<String> = Mutex::new(String::new());

fn install_quiet_panic_hook() {
    std::panic::set_hook(Box::new(|info| {
        let location = info
            .location()
            .map(|location| format!(" at {}:{}", location.file(), location.line()))
            .unwrap_or_default();
        let payload = info
            .payload()
            .downcast_ref::<&str>()
            .map(|text| text.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        if let Ok(mut last) = LAST_PANIC.lock() {
            *last = format!("panic{location}: {payload}");
        }
    }));
}

/// How a case failed. Minimising keeps a candidate only when it fails the same way.
#[derive(Debug, Clone, PartialEq)]
enum Failure {
    Panic(String),
    Property(String),
}

impl Failure {
    /// Whether `other` is the same failure: the same kind with the same message once numbers (lines,
    /// counts, values) are left out, so that a shrunk input keeps the bug it was found with.
    fn same_kind(&self, other: &Failure) -> bool {
        let signature = |failure: &Failure| -> (bool, String) {
            let (panic, message) = match failure {
                Failure::Panic(message) => (true, message),
                Failure::Property(message) => (false, message),
            };
            let words: String = message
                .chars()
                .filter(|character| !character.is_ascii_digit())
                .take(60)
                .collect();
            (panic, words)
        };
        signature(self) == signature(other)
    }

    fn describe(&self) -> &str {
        match self {
            Failure::Panic(message) | Failure::Property(message) => message,
        }
    }
}

fn run_caught(target: Target, case: &Case) -> Result<usize, Failure> {
    run_caught_with(|| run_case(target, case))
}

fn run_caught_with(work: impl FnOnce() -> Result<usize, String>) -> Result<usize, Failure> {
    match catch_unwind(AssertUnwindSafe(work)) {
        Ok(Ok(steps)) => Ok(steps),
        Ok(Err(problem)) => Err(Failure::Property(problem)),
        Err(_) => Err(Failure::Panic(
            LAST_PANIC
                .lock()
                .map(|last| last.clone())
                .unwrap_or_default(),
        )),
    }
}

// ----- the worker -----------------------------------------------------------------------------------

/// Tells the supervisor which case runs next (or that a minimisation attempt runs), so that it can
/// make the case again when the worker dies or hangs.
fn announce(index: u64) {
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(&index.to_le_bytes());
    let _ = out.flush();
}

/// Announced while minimising: the supervisor resets its timer but keeps the case.
const MINIMISING: u64 = u64::MAX;

fn work(options: &Options) -> u8 {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let (seeds, corpus_count, generated_count) = seeds::load_seeds(crate_dir);
    eprintln!(
        "fuzz {}: seed {}, {} seed programs ({} from fixtures, {} from the corpus{}, {} generated), timeout {:?} and {} MiB per case",
        options.target.name(),
        options.seed,
        seeds.len(),
        seeds.len() - corpus_count - generated_count,
        corpus_count,
        if corpus_count == 0 { ": not found" } else { "" },
        generated_count,
        options.timeout,
        options.memory_mb
    );
    let mut totals = Totals {
        started: Instant::now(),
        executions: 0,
        steps: 0,
        bytes: 0,
        peak: 0,
        slowest: Duration::ZERO,
    };
    let deadline = options
        .seconds
        .map(|seconds| totals.started + Duration::from_secs(seconds));
    let mut last_report = totals.started;
    let mut slowest_case = None;
    let mut hungriest_case = None;
    loop {
        if deadline.is_some_and(|deadline| Instant::now() >= deadline)
            || options.steps.is_some_and(|wanted| totals.steps >= wanted)
        {
            break;
        }
        let index = totals.executions;
        let case = case_number(options, &seeds, index);
        totals.bytes += case.to_bytes().len();
        announce(index);
        let base = ALLOCATED.load(Ordering::Relaxed);
        PEAK.store(base, Ordering::Relaxed);
        let case_started = Instant::now();
        let result = match &options.self_test {
            Some(kind) if index == 3 => induce_failure(kind),
            _ => run_caught(options.target, &case),
        };
        let elapsed = case_started.elapsed();
        if elapsed > totals.slowest {
            totals.slowest = elapsed;
            if options.save_slowest.is_some() {
                slowest_case = Some(case.clone());
            }
        }
        let memory = PEAK.load(Ordering::Relaxed).saturating_sub(base);
        if memory > totals.peak {
            totals.peak = memory;
            if options.save_hungriest.is_some() {
                hungriest_case = Some(case.clone());
            }
        }
        totals.executions += 1;
        match result {
            Ok(case_steps) => totals.steps += case_steps,
            Err(failure) => {
                eprintln!("fuzz: case {index} failed: {}", failure.describe());
                let minimal = minimise_case(options.target, &case, &failure);
                let path = save_reproducer(options, &minimal);
                eprintln!(
                    "fuzz: minimised reproducer written to {}\n      ({})",
                    path.display(),
                    run_caught(options.target, &minimal)
                        .err()
                        .as_ref()
                        .map_or("the minimised case passes on its own", Failure::describe)
                );
                return 1;
            }
        }
        if last_report.elapsed() >= Duration::from_secs(10) {
            last_report = Instant::now();
            totals.report(options, false);
        }
    }
    totals.report(options, true);
    for (path, case, what) in [
        (&options.save_slowest, slowest_case, "slowest case"),
        (
            &options.save_hungriest,
            hungriest_case,
            "case that needed the most memory",
        ),
    ] {
        if let (Some(path), Some(case)) = (path, case) {
            match std::fs::write(path, case.to_bytes()) {
                Ok(()) => eprintln!("fuzz: the {what} is in {}", path.display()),
                Err(problem) => eprintln!("fuzz: cannot write {}: {problem}", path.display()),
            }
        }
    }
    0
}

/// What a run has done so far, for the progress lines and the final figures.
struct Totals {
    started: Instant,
    executions: u64,
    /// Edit steps compared (document target).
    steps: usize,
    /// Bytes of input generated.
    bytes: usize,
    /// The most memory one case allocated beyond what was in use before it.
    peak: usize,
    slowest: Duration,
}

impl Totals {
    fn report(&self, options: &Options, last: bool) {
        let seconds = self.started.elapsed().as_secs_f64().max(1e-9);
        let steps_text = if options.target == Target::Document {
            format!(
                ", {} edit steps compared ({:.0}/s)",
                self.steps,
                self.steps as f64 / seconds
            )
        } else {
            String::new()
        };
        eprintln!(
            "fuzz {}{}: {} executions in {seconds:.1} s ({:.0}/s){steps_text}, {:.1} MB of input, slowest case {:.1} ms, peak memory per case {:.1} MB{}",
            options.target.name(),
            if last { " done" } else { "" },
            self.executions,
            self.executions as f64 / seconds,
            self.bytes as f64 / 1e6,
            self.slowest.as_secs_f64() * 1e3,
            self.peak as f64 / 1e6,
            if last { ", no failure" } else { "" },
        );
    }
}

fn minimise_case(target: Target, case: &Case, failure: &Failure) -> Case {
    let fails = |candidate: &Case| {
        announce(MINIMISING);
        run_caught(target, candidate)
            .err()
            .is_some_and(|found| found.same_kind(failure))
    };
    match case {
        Case::Text(text) => Case::Text(minimise::minimise_text(text, &mut |candidate| {
            fails(&Case::Text(candidate.to_string()))
        })),
        Case::Document(document) => {
            Case::Document(minimise::minimise_document(document, &mut |candidate| {
                fails(&Case::Document(candidate.clone()))
            }))
        }
    }
}

/// Fails on purpose the way `kind` says, to show that each kind of failure is caught and saved.
fn induce_failure(kind: &str) -> Result<usize, Failure> {
    fn recurse(depth: u64) -> u64 {
        // The stop condition is never met (the depth never reaches it): the stack overflows first.
        // The addition after the call keeps the recursion from becoming a loop.
        if std::hint::black_box(depth) == u64::MAX {
            return depth;
        }
        let buffer = std::hint::black_box([depth; 64]);
        recurse(depth + 1) + buffer[7]
    }
    match kind {
        "panic" => run_caught_with(|| panic!("a panic on purpose")),
        "abort" => std::process::abort(),
        "hang" => loop {
            std::thread::sleep(Duration::from_secs(1));
        },
        "memory" => {
            let mut blocks = Vec::new();
            loop {
                blocks.push(vec![1u8; 64 << 20]);
                std::hint::black_box(&blocks);
            }
        }
        "overflow" => Ok(recurse(0) as usize),
        _ => Err(Failure::Property(format!("unknown self test `{kind}`"))),
    }
}

/// Writes `case` to `OUT/TARGET-HASH.EXT` (`fixtures/fuzz/` unless `--out` says otherwise) and
/// returns the path.
fn save_reproducer(options: &Options, case: &Case) -> PathBuf {
    let target = options.target;
    let bytes = case.to_bytes();
    // FNV-1a: a stable name for the same input.
    let hash = bytes.iter().fold(0xCBF2_9CE4_8422_2325u64, |hash, byte| {
        (hash ^ u64::from(*byte)).wrapping_mul(0x0100_0000_01B3)
    });
    let folder = &options.out;
    let _ = std::fs::create_dir_all(folder);
    let path = folder.join(format!(
        "{}-{hash:016x}.{}",
        target.name(),
        case.extension()
    ));
    if let Err(problem) = std::fs::write(&path, &bytes) {
        eprintln!("fuzz: cannot write {}: {problem}", path.display());
    }
    path
}

// ----- replaying reproducers ------------------------------------------------------------------------

fn replay(options: &Options) -> u8 {
    let mut failed = false;
    for path in &options.replay {
        let case = match Case::from_file(path) {
            Ok(case) => case,
            Err(problem) => {
                eprintln!("fuzz: cannot read {}: {problem}", path.display());
                failed = true;
                continue;
            }
        };
        if let Err(failure) = run_caught(options.target, &case) {
            eprintln!("fuzz: {} fails: {}", path.display(), failure.describe());
            failed = true;
        }
    }
    u8::from(failed)
}

// ----- the supervisor -------------------------------------------------------------------------------

fn supervise(args: &[String], options: &Options) -> u8 {
    let executable = match std::env::current_exe() {
        Ok(executable) => executable,
        Err(problem) => {
            eprintln!("fuzz: cannot find my own executable: {problem}");
            return 2;
        }
    };
    let mut child = match Command::new(&executable)
        .args(args)
        .arg("--worker")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
    {
        Ok(child) => child,
        Err(problem) => {
            eprintln!("fuzz: cannot start the worker: {problem}");
            return 2;
        }
    };
    let mut announcements = child.stdout.take().expect("the worker's stdout is piped");
    let (sender, receiver) = mpsc::channel::<u64>();
    std::thread::spawn(move || {
        let mut frame = [0u8; 8];
        while announcements.read_exact(&mut frame).is_ok() {
            if sender.send(u64::from_le_bytes(frame)).is_err() {
                return;
            }
        }
    });
    let mut current: Option<u64> = None;
    let mut since = Instant::now();
    loop {
        match receiver.recv_timeout(Duration::from_millis(100)) {
            Ok(MINIMISING) => since = Instant::now(),
            Ok(index) => {
                current = Some(index);
                since = Instant::now();
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {
                if current.is_some() && since.elapsed() > options.timeout {
                    let _ = child.kill();
                    let _ = child.wait();
                    eprintln!(
                        "fuzz: case {} ran longer than {:?}: a hang",
                        current.unwrap_or_default(),
                        options.timeout
                    );
                    save_lost_case(options, current);
                    return 1;
                }
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
        }
    }
    let status = match child.wait() {
        Ok(status) => status,
        Err(problem) => {
            eprintln!("fuzz: cannot wait for the worker: {problem}");
            return 2;
        }
    };
    match status.code() {
        Some(0) => 0,
        // The worker found, minimised and saved a failure itself.
        Some(1) => 1,
        _ => {
            eprintln!("fuzz: the worker died ({status}) while running a case");
            save_lost_case(options, current);
            1
        }
    }
}

/// Case `index` of this run: the worker and the supervisor make the same case from the same number.
fn case_number(options: &Options, seeds: &[seeds::Seed], index: u64) -> Case {
    generate_case(
        options.target,
        seeds,
        options.seed,
        index,
        options.max_input_bytes,
    )
}

/// Makes the case the worker was running again from the seed and its number, and saves it. It is not
/// minimised: each attempt with a case that kills the process would need a process of its own.
fn save_lost_case(options: &Options, index: Option<u64>) {
    let Some(index) = index else {
        eprintln!("fuzz: the worker failed before its first case");
        return;
    };
    let (seeds, _, _) = seeds::load_seeds(Path::new(env!("CARGO_MANIFEST_DIR")));
    let case = case_number(options, &seeds, index);
    let path = save_reproducer(options, &case);
    eprintln!(
        "fuzz: reproducer (case {index} of seed {}) written to {}\n      replay it with: cargo run --release --example fuzz -- --target {} --replay {}",
        options.seed,
        path.display(),
        options.target.name(),
        path.display()
    );
}
