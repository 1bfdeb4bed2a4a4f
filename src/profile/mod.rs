//! Phase profiler: the primitives (phases, spans, counters) the engine
//! calls on its hot paths. It sits at the bottom of the layers so that
//! any module may time itself; the harness that turns it on and reports
//! (`aster bench`) is [`crate::bench`], at the top.
//!
//! The profiler is a process-wide set of atomic accumulators: nanoseconds
//! and call counts per [`Phase`] (one set per thread, summed when read),
//! plus event [`Counter`]s. It is off unless
//! the bench turns it on, and the hot paths carry one-line guards
//! (`let _g = profile::span(Phase::FactorSolve);`): when off, a guard costs
//! one relaxed atomic load and no clock read, so normal runs do not pay
//! for the instrumentation.
//!
//! Spans opened inside rayon workers (the law integrations, run per
//! element in parallel) add up the time of every thread: such a phase is
//! CPU time, which can exceed the wall time of the parallel region that
//! contains it. Spans opened on the calling thread around a parallel
//! region (element integration and assembly) measure its wall time.

use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::time::Instant;

/// A part of the computation whose time is accumulated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Element integration and assembly of forces and tangent: the wall
    /// time of `Assembler::compute`, law integration included.
    ElementAssembly,
    /// Constitutive law integration at Gauss points (nested in
    /// [`Phase::ElementAssembly`]; CPU time summed over threads).
    LawIntegration,
    /// Sparse LU factorization and triangular solves.
    FactorSolve,
    /// Contact: pairing and the contact forces and tangent.
    Contact,
    /// Output: IMPR_* commands and the .mess/.resu/unit files.
    Output,
}

impl Phase {
    pub const ALL: [Phase; 5] = [
        Phase::ElementAssembly,
        Phase::LawIntegration,
        Phase::FactorSolve,
        Phase::Contact,
        Phase::Output,
    ];

    /// The key used in the JSON output.
    pub fn key(self) -> &'static str {
        match self {
            Phase::ElementAssembly => "element_assembly",
            Phase::LawIntegration => "law_integration",
            Phase::FactorSolve => "factor_solve",
            Phase::Contact => "contact",
            Phase::Output => "output",
        }
    }
}

/// Events counted while the profiler is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Counter {
    /// Converged time steps.
    Steps,
    /// Steps that were cut (failed or redone by an event) into sub-steps.
    StepCuts,
    /// Newton iterations of the converged steps.
    NewtonIterations,
    /// Contact pairings (geometric updates).
    Pairings,
}

impl Counter {
    pub const ALL: [Counter; 4] = [
        Counter::Steps,
        Counter::StepCuts,
        Counter::NewtonIterations,
        Counter::Pairings,
    ];

    pub fn key(self) -> &'static str {
        match self {
            Counter::Steps => "steps",
            Counter::StepCuts => "step_cuts",
            Counter::NewtonIterations => "newton_iterations",
            Counter::Pairings => "contact_pairings",
        }
    }
}

const NPHASES: usize = Phase::ALL.len();
const NCOUNTERS: usize = Counter::ALL.len();

/// A set of accumulators. The process has one ([`span`], [`count`]...
/// use it); separate instances exist so that tests do not share state
/// with whatever else runs in the test process.
/// Accumulator sets: each thread adds its spans' times to one set
/// ([`shard`]), so that threads timing spans at the same moment (the law
/// integrations of the parallel element loop, one per Gauss point) do not
/// write to the same cache line; a snapshot sums the sets.
const SHARDS: usize = 8;

/// One set of phase accumulators, on cache lines of its own.
#[repr(align(128))]
struct Shard {
    nanos: [AtomicU64; NPHASES],
    calls: [AtomicU64; NPHASES],
}

impl Shard {
    const fn new() -> Shard {
        Shard {
            nanos: [const { AtomicU64::new(0) }; NPHASES],
            calls: [const { AtomicU64::new(0) }; NPHASES],
        }
    }
}

/// The on/off flag, read by every span, away from the written lines.
#[repr(align(128))]
struct Flag(AtomicBool);

/// The accumulator set of the calling thread (threads take the sets in
/// turn as they first time a span).
fn shard() -> usize {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    thread_local! {
        static SHARD: usize = NEXT.fetch_add(1, Ordering::Relaxed) % SHARDS;
    }
    SHARD.with(|s| *s)
}

pub struct Profiler {
    enabled: Flag,
    shards: [Shard; SHARDS],
    counters: [AtomicU64; NCOUNTERS],
}

/// What a profiler accumulated since its last reset.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Profile {
    pub nanos: [u64; NPHASES],
    pub calls: [u64; NPHASES],
    pub counters: [u64; NCOUNTERS],
}

impl Profile {
    pub fn seconds(&self, p: Phase) -> f64 {
        self.nanos[p as usize] as f64 * 1e-9
    }
    pub fn calls(&self, p: Phase) -> u64 {
        self.calls[p as usize]
    }
    pub fn counter(&self, c: Counter) -> u64 {
        self.counters[c as usize]
    }
}

impl Default for Profiler {
    fn default() -> Self {
        Self::new()
    }
}

impl Profiler {
    pub const fn new() -> Profiler {
        Profiler {
            enabled: Flag(AtomicBool::new(false)),
            shards: [const { Shard::new() }; SHARDS],
            counters: [const { AtomicU64::new(0) }; NCOUNTERS],
        }
    }

    #[inline]
    pub fn is_enabled(&self) -> bool {
        self.enabled.0.load(Ordering::Relaxed)
    }

    pub fn set_enabled(&self, on: bool) {
        self.enabled.0.store(on, Ordering::Relaxed);
    }

    /// Zeroes every accumulator (the enabled flag is kept).
    pub fn reset(&self) {
        let phases = self
            .shards
            .iter()
            .flat_map(|s| s.nanos.iter().chain(&s.calls));
        for a in phases.chain(&self.counters) {
            a.store(0, Ordering::Relaxed);
        }
    }

    pub fn snapshot(&self) -> Profile {
        let load = |a: &AtomicU64| a.load(Ordering::Relaxed);
        Profile {
            nanos: std::array::from_fn(|p| self.shards.iter().map(|s| load(&s.nanos[p])).sum()),
            calls: std::array::from_fn(|p| self.shards.iter().map(|s| load(&s.calls[p])).sum()),
            counters: self.counters.each_ref().map(load),
        }
    }

    /// A guard that adds the time until its drop to `phase` (nothing when
    /// the profiler is off at creation).
    #[inline]
    pub fn span(&self, phase: Phase) -> Span<'_> {
        self.span_if(true, phase)
    }

    /// A span that times only when `on` (and the profiler is on).
    #[inline]
    pub fn span_if(&self, on: bool, phase: Phase) -> Span<'_> {
        Span {
            profiler: self,
            phase,
            start: (on && self.is_enabled()).then(Instant::now),
        }
    }

    pub fn add_time(&self, phase: Phase, nanos: u64) {
        let s = &self.shards[shard()];
        s.nanos[phase as usize].fetch_add(nanos, Ordering::Relaxed);
        s.calls[phase as usize].fetch_add(1, Ordering::Relaxed);
    }

    #[inline]
    pub fn count(&self, counter: Counter, n: u64) {
        if self.is_enabled() {
            self.counters[counter as usize].fetch_add(n, Ordering::Relaxed);
        }
    }
}

/// Adds the time from its creation to its drop to a phase.
#[must_use = "the span measures until it is dropped; bind it: `let _g = span(...)`"]
pub struct Span<'a> {
    profiler: &'a Profiler,
    phase: Phase,
    start: Option<Instant>,
}

impl Drop for Span<'_> {
    #[inline]
    fn drop(&mut self) {
        if let Some(s) = self.start {
            // u64 nanoseconds overflow after 584 years.
            let ns = s.elapsed().as_nanos() as u64;
            self.profiler.add_time(self.phase, ns);
        }
    }
}

/// The process-wide profiler.
pub static GLOBAL: Profiler = Profiler::new();

/// Times the rest of the enclosing scope as `phase` (global profiler).
#[inline]
pub fn span(phase: Phase) -> Span<'static> {
    GLOBAL.span(phase)
}

/// Times the rest of the enclosing scope as `phase` when `on`.
#[inline]
pub fn span_if(on: bool, phase: Phase) -> Span<'static> {
    GLOBAL.span_if(on, phase)
}

/// Runs `f`, timing it as `phase` (global profiler).
#[inline]
pub fn timed<T>(phase: Phase, f: impl FnOnce() -> T) -> T {
    let _g = span(phase);
    f()
}

/// Adds `n` to a counter of the global profiler (when on).
#[inline]
pub fn count(counter: Counter, n: usize) {
    GLOBAL.count(counter, n as u64);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn off_records_nothing_on_records_elapsed_time() {
        let p = Profiler::new();
        {
            let _g = p.span(Phase::FactorSolve);
            std::thread::sleep(Duration::from_millis(5));
        }
        p.count(Counter::Steps, 3);
        assert_eq!(p.snapshot(), Profile::default());

        p.set_enabled(true);
        let t0 = Instant::now();
        {
            let _g = p.span(Phase::FactorSolve);
            std::thread::sleep(Duration::from_millis(20));
        }
        let outer = t0.elapsed().as_secs_f64();
        p.count(Counter::Steps, 3);
        let s = p.snapshot();
        assert_eq!(s.calls(Phase::FactorSolve), 1);
        // The span saw at least the sleep, and no more than the outer clock.
        assert!(s.seconds(Phase::FactorSolve) >= 0.020, "{s:?}");
        assert!(s.seconds(Phase::FactorSolve) <= outer, "{s:?}");
        assert_eq!(s.counter(Counter::Steps), 3);
        assert_eq!(s.calls(Phase::Contact), 0);

        p.reset();
        assert_eq!(p.snapshot(), Profile::default());
        assert!(p.is_enabled());
    }

    #[test]
    fn spans_from_several_threads_add_up() {
        let p = Profiler::new();
        p.set_enabled(true);
        std::thread::scope(|s| {
            for _ in 0..4 {
                s.spawn(|| {
                    for _ in 0..250 {
                        let _g = p.span(Phase::LawIntegration);
                    }
                    p.count(Counter::Pairings, 1);
                });
            }
        });
        let s = p.snapshot();
        assert_eq!(s.calls(Phase::LawIntegration), 1000);
        assert_eq!(s.counter(Counter::Pairings), 4);
    }
}
