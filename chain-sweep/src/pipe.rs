//! [`exit_quietly_on_broken_pipe`]: the commands (`phase-diagram`, `paper`, `network`) end
//! without a word when the reader of their output goes away (`paper --list | head -1`).
//!
//! Rust's runtime ignores SIGPIPE, so a write to a closed pipe returns an error, and `println!`
//! and `eprintln!` panic on it ("failed printing to stdout"). Every output path of a command
//! (listings, progress, summaries, error messages) would need its own check; restoring the
//! default action at the start of `main` fixes them all at the root, as `cat` and `ls` behave: the
//! process ends on SIGPIPE (status 141 to a shell, which reports the pipeline's last command).
//! Files are never written through a pipe, so this never interrupts a results file or a figure
//! between its lines or its rename: a sweep killed so resumes, as after any kill.

/// Restore SIGPIPE's default action (end the process quietly). Call it first in `main`.
pub fn exit_quietly_on_broken_pipe() {
    #[cfg(unix)]
    // SAFETY: called at the start of `main`, before any thread is started, to set a signal's
    // disposition to its default; no handler of ours is involved and no memory is touched.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}
