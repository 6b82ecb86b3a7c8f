//! How long a simulation ran: its wall time and the CPU time of the thread that ran it.
//! Simulator speed per core is taken over the CPU time: unlike the wall time, it does not grow
//! when other processes share the cores.

use std::time::{Duration, Instant};

/// CPU time the calling thread has run so far (`CLOCK_THREAD_CPUTIME_ID`, exact to the
/// nanosecond); `None` where it cannot be read.
#[cfg(all(target_os = "linux", target_pointer_width = "64"))]
fn thread_cpu_time() -> Option<Duration> {
    /// `struct timespec` of 64-bit Linux.
    #[repr(C)]
    struct Timespec {
        tv_sec: i64,
        tv_nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, time: *mut Timespec) -> i32;
    }
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut t = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid, writable timespec; libc (linked by std) fills it or fails.
    let ok = unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut t) } == 0;
    ok.then(|| Duration::new(t.tv_sec as u64, t.tv_nsec as u32))
}

#[cfg(not(all(target_os = "linux", target_pointer_width = "64")))]
fn thread_cpu_time() -> Option<Duration> {
    None
}

/// A stopwatch of one thread's simulation: wall and CPU time from [`SimClock::start`].
pub struct SimClock {
    wall: Instant,
    cpu: Option<Duration>,
}

impl SimClock {
    pub fn start() -> Self {
        SimClock {
            wall: Instant::now(),
            cpu: thread_cpu_time(),
        }
    }

    /// (wall, CPU) time since the start, on the thread that started it; the CPU time is zero
    /// where the OS does not say.
    pub fn elapsed(&self) -> (Duration, Duration) {
        let cpu =
            (self.cpu.zip(thread_cpu_time())).map_or(Duration::ZERO, |(a, b)| b.saturating_sub(a));
        (self.wall.elapsed(), cpu)
    }
}

/// Seconds one core spent simulating: the CPU time, or the wall time where it is unknown.
pub fn core_seconds(wall: Duration, cpu: Duration) -> f64 {
    let t = if cpu.is_zero() { wall } else { cpu };
    t.as_secs_f64().max(1e-9)
}
