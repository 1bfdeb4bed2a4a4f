//! A stop asked by the user (SIGINT, SIGTERM) during a run.
//!
//! Killing a long study used to lose everything it had computed. The
//! handlers installed here only record which signal arrived; the time loop
//! of DYNA_NON_LINE reads the flag between steps and between Newton
//! iterations and stops cleanly, keeping its archived instants, and the
//! runner skips the commands left and writes what was done
//! (docs/dynamics.md, "Stopping a run"). A second signal, for a user who
//! does not want to wait, ends the process at once.
//!
//! It sits at the bottom of the layers: the engine polls it and must not
//! depend on the runner to do so.

use std::sync::atomic::{AtomicI32, Ordering};

/// The signal received (0: none).
static RECEIVED: AtomicI32 = AtomicI32::new(0);

/// The exit code of a run stopped by `signal`: the shell's convention,
/// 128 + the signal number (130 for SIGINT, 143 for SIGTERM).
pub fn exit_code(signal: i32) -> i32 {
    128 + signal
}

/// The name of a signal handled here.
pub fn name(signal: i32) -> &'static str {
    match signal {
        libc::SIGINT => "SIGINT",
        libc::SIGTERM => "SIGTERM",
        _ => "a signal",
    }
}

/// The signal that asked the run to stop, if one did.
pub fn requested() -> Option<i32> {
    match RECEIVED.load(Ordering::Relaxed) {
        0 => None,
        s => Some(s),
    }
}

/// Records a stop request as if `signal` had been received (what the
/// handler does; for library users and tests that run a study in-process).
pub fn request(signal: i32) {
    RECEIVED.store(signal, Ordering::Relaxed);
}

/// Forgets a stop request (a process that runs several studies).
pub fn clear() {
    RECEIVED.store(0, Ordering::Relaxed);
}

/// Only async-signal-safe work: an atomic swap, and `_exit` on the second
/// signal.
extern "C" fn on_signal(signal: libc::c_int) {
    if RECEIVED.swap(signal, Ordering::Relaxed) != 0 {
        // SAFETY: _exit is async-signal-safe; the user asked twice.
        unsafe { libc::_exit(exit_code(signal)) };
    }
}

/// Installs the handlers of SIGINT and SIGTERM for this process. With
/// SA_RESTART, a file read or write interrupted by the signal resumes, so
/// the outputs written after the stop are complete.
/// Lets a closed output pipe end the process quietly, as Unix tools do.
///
/// Rust starts programs with SIGPIPE ignored, so `aster doc commands |
/// head -1` made the next print fail with EPIPE, and `println!` turned that
/// into a panic (exit 101 and a backtrace). With the default action the
/// process ends by SIGPIPE at that print instead. A run writes its results
/// (.mess, .resu, MED) before it prints its summary to stdout, so nothing
/// computed is lost; its log goes to stderr.
pub fn default_sigpipe() {
    // SAFETY: setting a signal's disposition to SIG_DFL has no memory
    // effects; it is done once, before any thread is started.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

pub fn install() -> Result<(), String> {
    for signal in [libc::SIGINT, libc::SIGTERM] {
        // SAFETY: a zeroed sigaction is valid (empty mask, no flags); the
        // handler only touches an atomic and calls _exit.
        let rc = unsafe {
            let mut action: libc::sigaction = std::mem::zeroed();
            action.sa_sigaction = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
            action.sa_flags = libc::SA_RESTART;
            libc::sigemptyset(&mut action.sa_mask);
            libc::sigaction(signal, &action, std::ptr::null_mut())
        };
        if rc != 0 {
            return Err(format!(
                "cannot install the handler of {}: {}",
                name(signal),
                std::io::Error::last_os_error()
            ));
        }
    }
    Ok(())
}
