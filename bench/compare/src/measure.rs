//! Measuring: the thread CPU clock, peak memory, medians, the alternating run order and the
//! formatting of milliseconds.

/// CPU time consumed by the calling thread, milliseconds (`CLOCK_THREAD_CPUTIME_ID`). Unlike the
/// wall clock it does not count the time the thread waits for a core, which on a shared, loaded
/// machine is most of the noise.
pub fn thread_cpu_ms() -> f64 {
    #[repr(C)]
    struct Timespec {
        tv_sec: i64,
        tv_nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, time: *mut Timespec) -> i32;
    }
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut time = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `time` is a valid, writable timespec (64-bit Linux layout).
    let status = unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut time) };
    assert_eq!(status, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID) failed");
    time.tv_sec as f64 * 1e3 + time.tv_nsec as f64 * 1e-6
}

/// Peak resident memory of this process, MiB (`VmHWM` of `/proc/self/status`; NaN if unreadable).
pub fn peak_memory_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|line| line.strip_prefix("VmHWM:"))
        .and_then(|rest| {
            rest.trim()
                .trim_end_matches("kB")
                .trim()
                .parse::<f64>()
                .ok()
        })
        .map_or(f64::NAN, |kib| kib / 1024.0)
}

/// Median of `values`, sorting them in place; NaN when empty.
pub fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// Milliseconds with about three significant digits.
pub fn ms(value: f64) -> String {
    if value < 1.0 {
        format!("{value:.3}")
    } else if value < 10.0 {
        format!("{value:.2}")
    } else {
        format!("{value:.1}")
    }
}

/// Calls `run(round, engine)` for each of `rounds` rounds and both engines (0 rebond, 1 rapier),
/// alternating which engine goes first from one round to the next.
pub fn alternate(rounds: usize, mut run: impl FnMut(usize, usize)) {
    for round in 0..rounds {
        for slot in 0..2 {
            run(round, (slot + round) % 2);
        }
    }
}
