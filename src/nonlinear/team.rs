//! A team of threads kept for the whole explicit time loop.
//!
//! An explicit step is short (tens to hundreds of microseconds) and has two
//! parallel phases (the element loop, then the assembly of the forces and
//! the velocity update over dof ranges) between serial parts (contact,
//! energy balance). Rayon's idle threads go to sleep after a few yields:
//! at every step the element loop had to wake the other thread (a futex
//! call and its latency, about a tenth of the step), and the serial parts
//! ran alone. The team's members wait for the next phase spinning for
//! [`SPIN`] (longer than the serial part of a step), then park; the leader
//! (the thread running the time loop) unparks a parked member when it
//! publishes a phase. ("Spinning" is a loop of `sched_yield`: immediate on
//! an idle core, and it leaves a loaded core to the other programs.)
//!
//! A phase is a list of pieces claimed one at a time through an atomic
//! counter, by the leader as well as the members: a member that is late
//! (descheduled on a loaded machine) takes what is left or nothing, and
//! the leader withdraws the phase from a member that has not started it,
//! so it never waits for a thread that is not working. Which thread
//! computes a piece never changes what it computes: the results are the
//! same to the bit whatever the team size.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::thread::{self, Thread};
use std::time::{Duration, Instant};

/// How long an idle member spins (yields) for the next phase before it
/// parks: the serial part of an explicit step is tens of microseconds on
/// the meshes of the studies; a member waiting longer (a step estimate,
/// archiving) sleeps instead of burning its core.
const SPIN: Duration = Duration::from_micros(300);

/// A phase with its lifetime erased (see [`Team::run`] for why a member
/// never calls it after the phase is over).
#[derive(Clone, Copy)]
struct Job(*const (dyn Fn(bool) + Sync + 'static));

// SAFETY: the pointee is `Sync` (called from several threads at once);
// the pointer is only dereferenced while the leader waits in `Team::run`.
unsafe impl Send for Job {}

/// One member's hand-over state.
struct Member {
    /// The last phase number taken, by the member (which then runs it) or
    /// by the leader (which withdrew it).
    taken: AtomicUsize,
    /// The last phase number the member finished.
    done: AtomicUsize,
    /// The member is parked or about to park.
    parked: AtomicBool,
    thread: Mutex<Option<Thread>>,
}

struct Shared {
    /// The number of the last phase published.
    epoch: AtomicUsize,
    job: Mutex<Option<Job>>,
    stop: AtomicBool,
    panicked: AtomicBool,
    members: Vec<Member>,
}

/// The leader's handle: [`Team::for_each`] runs a phase on all the team.
pub struct Team<'s> {
    shared: &'s Shared,
}

/// Runs `f` with a team of `threads` threads (the calling thread and
/// `threads − 1` members, which exist while `f` runs). One thread: no
/// member, every phase runs on the caller.
pub fn with_team<R>(threads: usize, f: impl FnOnce(&Team) -> R) -> R {
    let shared = Shared {
        epoch: AtomicUsize::new(0),
        job: Mutex::new(None),
        stop: AtomicBool::new(false),
        panicked: AtomicBool::new(false),
        members: (1..threads.max(1))
            .map(|_| Member {
                taken: AtomicUsize::new(0),
                done: AtomicUsize::new(0),
                parked: AtomicBool::new(false),
                thread: Mutex::new(None),
            })
            .collect(),
    };
    thread::scope(|s| {
        for (k, _) in shared.members.iter().enumerate() {
            let shared = &shared;
            s.spawn(move || work(shared, k));
        }
        // Stops the members however `f` ends (a panic too), so that the
        // scope's join returns.
        struct Stop<'a>(&'a Shared);
        impl Drop for Stop<'_> {
            fn drop(&mut self) {
                self.0.stop.store(true, Ordering::SeqCst);
                for m in &self.0.members {
                    if let Some(t) = m.thread.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
                        t.unpark();
                    }
                }
            }
        }
        let _stop = Stop(&shared);
        f(&Team { shared: &shared })
    })
}

impl Team<'_> {
    /// Threads of the team, the caller included.
    pub fn threads(&self) -> usize {
        self.shared.members.len() + 1
    }

    /// Calls `f(i)` once for every `i` in `0..n`, the pieces spread over
    /// the team; returns when all are done.
    pub fn for_each(&self, n: usize, f: &(dyn Fn(usize) + Sync)) {
        if self.shared.members.is_empty() || n <= 1 {
            (0..n).for_each(f);
            return;
        }
        // The leader takes the pieces from the front, the members from the
        // back, until the two ends meet: from one step to the next a
        // thread takes mostly the same pieces, whose data (an element's
        // states, kept gradients, geometry) are still in its core's cache.
        // The two ends in one word (front << 32 | back).
        let n32 = u32::try_from(n).expect("fewer than 2^32 pieces");
        let ends = AtomicU64::new(u64::from(n32));
        let job = |leader: bool| loop {
            let cur = ends.load(Ordering::Relaxed);
            let (front, back) = (cur >> 32, cur & 0xffff_ffff);
            if front >= back {
                break;
            }
            let (new, i) = if leader {
                (cur + (1 << 32), front)
            } else {
                (cur - 1, back - 1)
            };
            if ends
                .compare_exchange_weak(cur, new, Ordering::Relaxed, Ordering::Relaxed)
                .is_ok()
            {
                f(i as usize);
            }
        };
        self.run(&job);
    }

    /// Publishes `job`, runs it on the caller, then waits for the members
    /// that took it.
    fn run(&self, job: &(dyn Fn(bool) + Sync)) {
        let sh = self.shared;
        let ptr: *const (dyn Fn(bool) + Sync + '_) = job;
        // SAFETY: only the lifetime is erased. A member calls the job only
        // after taking this phase's number (`taken` from e − 1 to e), and
        // this function returns only once every member has either finished
        // it (`done` = e) or can no longer take it (the leader set `taken`
        // to e itself): no call outlives `job`.
        let ptr: *const (dyn Fn(bool) + Sync + 'static) = unsafe { std::mem::transmute(ptr) };
        *sh.job.lock().unwrap_or_else(|e| e.into_inner()) = Some(Job(ptr));
        let e = sh.epoch.fetch_add(1, Ordering::SeqCst) + 1;
        for m in &sh.members {
            if m.parked.swap(false, Ordering::SeqCst) {
                if let Some(t) = m.thread.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
                    t.unpark();
                }
            }
        }
        // A panic of the leader's share is resumed only once no member
        // can still be in the job.
        let mine = catch_unwind(AssertUnwindSafe(|| job(true)));
        for m in &sh.members {
            if m.taken
                .compare_exchange(e - 1, e, Ordering::SeqCst, Ordering::SeqCst)
                .is_ok()
            {
                continue; // withdrawn: the member never started it
            }
            // The member is finishing its last piece (an element block,
            // a few microseconds): spin, then yield.
            let mut spins = 0u32;
            while m.done.load(Ordering::Acquire) != e {
                if spins < 256 {
                    spins += 1;
                    std::hint::spin_loop();
                } else {
                    thread::yield_now();
                }
            }
        }
        if let Err(p) = mine {
            std::panic::resume_unwind(p);
        }
        if sh.panicked.load(Ordering::SeqCst) {
            panic!("a thread of the explicit loop's team panicked");
        }
    }
}

/// A member's loop: wait for a phase (spin, then park), take it, run it.
fn work(sh: &Shared, k: usize) {
    let me = &sh.members[k];
    *me.thread.lock().unwrap_or_else(|e| e.into_inner()) = Some(thread::current());
    let mut seen = 0usize;
    // The spin budget adapts: a member that spun and still came too late
    // for a phase (the leader withdrew it: the member was not running,
    // the machine is loaded) spins four times shorter next time, down to
    // parking at once, so that it does not take CPU from the leader; each
    // phase it takes doubles the budget back up to SPIN. (A parked member is often late for a short phase:
    // that is the wake-up's latency, not a loaded machine.)
    let mut spin = SPIN;
    loop {
        let mut since = Instant::now();
        let mut parked = false;
        let e = loop {
            if sh.stop.load(Ordering::SeqCst) {
                return;
            }
            let e = sh.epoch.load(Ordering::SeqCst);
            if e != seen {
                break e;
            }
            if since.elapsed() < spin {
                // Yielding rather than spinning: on an idle core it
                // returns at once; on a loaded machine it gives the core
                // to the other programs instead of taking CPU time from
                // them and from the leader (measured, docs/performance.md).
                thread::yield_now();
                continue;
            }
            // Park: the flag first, then the check, so that a leader that
            // publishes in between sees the flag and unparks.
            me.parked.store(true, Ordering::SeqCst);
            if sh.epoch.load(Ordering::SeqCst) == seen && !sh.stop.load(Ordering::SeqCst) {
                thread::park();
            }
            parked = true;
            me.parked.store(false, Ordering::SeqCst);
            since = Instant::now();
        };
        seen = e;
        if me
            .taken
            .compare_exchange(e - 1, e, Ordering::SeqCst, Ordering::SeqCst)
            .is_err()
        {
            // Withdrawn by the leader, which did the work.
            if !parked {
                spin /= 4;
            }
            continue;
        }
        spin = (spin * 2).clamp(SPIN / 64, SPIN);
        let job = *sh.job.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(Job(ptr)) = job {
            // SAFETY: phase e is taken, so the leader waits in `run` for
            // `done` = e before the job goes out of scope.
            let f = unsafe { &*ptr };
            if catch_unwind(AssertUnwindSafe(|| f(false))).is_err() {
                sh.panicked.store(true, Ordering::SeqCst);
            }
        }
        me.done.store(e, Ordering::Release);
    }
}

/// Pieces of mutable data handed out once each to the team's threads.
pub struct Parts<P>(Vec<Mutex<Option<P>>>);

impl<P: Send> Parts<P> {
    pub fn new(parts: impl IntoIterator<Item = P>) -> Parts<P> {
        Parts(parts.into_iter().map(|p| Mutex::new(Some(p))).collect())
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Piece `i` (each is taken once).
    pub fn take(&self, i: usize) -> P {
        self.0[i]
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
            .expect("each piece is taken once")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_piece_once_whatever_the_team() {
        for threads in 1..4 {
            with_team(threads, |team| {
                assert_eq!(team.threads(), threads);
                for n in [0, 1, 2, 7, 100] {
                    let hits: Vec<AtomicUsize> = (0..n).map(|_| AtomicUsize::new(0)).collect();
                    for _ in 0..50 {
                        team.for_each(n, &|i| {
                            hits[i].fetch_add(1, Ordering::Relaxed);
                        });
                    }
                    assert!(hits.iter().all(|h| h.load(Ordering::Relaxed) == 50));
                }
            });
        }
    }

    #[test]
    fn members_park_and_wake() {
        with_team(2, |team| {
            let sum = AtomicUsize::new(0);
            for round in 0..3 {
                // Longer than SPIN: the member parks between the phases.
                thread::sleep(Duration::from_millis(2));
                team.for_each(64, &|i| {
                    sum.fetch_add(i + round, Ordering::Relaxed);
                });
            }
            assert_eq!(sum.load(Ordering::Relaxed), 3 * 2016 + 64 * 3);
        });
    }

    #[test]
    fn parts_are_disjoint_mutable_pieces() {
        let mut v = vec![0usize; 1000];
        with_team(2, |team| {
            let parts = Parts::new(v.chunks_mut(64));
            team.for_each(parts.len(), &|i| {
                for (k, x) in parts.take(i).iter_mut().enumerate() {
                    *x = 64 * i + k;
                }
            });
        });
        assert!(v.iter().enumerate().all(|(k, &x)| k == x));
    }
}
