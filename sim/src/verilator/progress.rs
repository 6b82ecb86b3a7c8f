//! What a build that misses the cache shows while it runs. A library is quiet by default; a
//! program whose users wait for builds turns [`show_build_progress`] on. Then a build draws a
//! spinner on stderr (its stage, the C++ files compiled, the time) when stderr is a terminal,
//! and otherwise prints one line when it starts and one when it ends, so a log says why
//! nothing else happened for a minute.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

static SHOW: AtomicBool = AtomicBool::new(false);

/// Whether builds that miss the cache report on stderr (off unless a program turns it on).
pub fn show_build_progress(on: bool) {
    SHOW.store(on, Ordering::Relaxed);
}

/// The report of one build: a spinner, or a start and an end line, or nothing.
pub(crate) struct BuildProgress {
    bar: ProgressBar,
    what: String,
    start: Instant,
    /// Lines instead of a spinner (stderr is not a terminal).
    lines: bool,
}

impl BuildProgress {
    /// Starts reporting the build of `what` (e.g. "the Verilated model model-1a2b3c4d") into
    /// the cache at `root`.
    pub fn start(what: &str, root: &Path) -> Self {
        let show = SHOW.load(Ordering::Relaxed);
        let target = ProgressDrawTarget::stderr();
        let lines = show && target.is_hidden();
        let bar = if show && !lines {
            ProgressBar::with_draw_target(None, target)
        } else {
            ProgressBar::hidden()
        };
        if let Ok(style) = ProgressStyle::with_template("{spinner} {prefix} [{elapsed}] {msg}") {
            bar.set_style(style);
        }
        bar.set_prefix(format!(
            "building {what} (not in the cache {})",
            root.display()
        ));
        bar.enable_steady_tick(Duration::from_millis(120));
        if lines {
            eprintln!(
                "building {what} (not in the cache {}; a minute or more)",
                root.display()
            );
        }
        BuildProgress {
            bar,
            what: what.to_string(),
            start: Instant::now(),
            lines,
        }
    }

    /// The stage the build is in (verilating, compiling, linking).
    pub fn stage(&self, stage: &str) {
        self.bar.set_message(stage.to_string());
    }

    /// One more of `total` C++ files compiled in the current stage.
    pub fn compiled(&self, stage: &str, done: usize, total: usize) {
        self.bar
            .set_message(format!("{stage}: {done}/{total} C++ files"));
    }

    /// The build ended (or failed: `ok` false).
    pub fn finish(self, ok: bool) {
        self.bar.finish_and_clear();
        let secs = self.start.elapsed().as_secs_f64();
        if self.lines {
            let how = if ok { "built" } else { "failed building" };
            eprintln!("{how} {} in {secs:.1} s", self.what);
        }
    }
}
