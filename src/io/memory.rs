//! The process's peak resident memory, to show that a run's memory does not grow with its duration,
//! and its CPU time, to state what a step costs on a loaded machine (`wbv analyze --timing`).

/// Peak resident set size of this process in bytes (`VmHWM` of `/proc/self/status`), `None` where
/// the platform does not report it.
pub fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// CPU time this process has used so far, user + system, in s (`getrusage(RUSAGE_SELF)`, every
/// thread); `None` where the platform does not report it.
pub fn cpu_seconds() -> Option<f64> {
    #[cfg(unix)]
    {
        // SAFETY: getrusage writes one `rusage` into the zeroed struct it is given.
        let mut u: libc::rusage = unsafe { std::mem::zeroed() };
        if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) } != 0 {
            return None;
        }
        let s = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
        Some(s(u.ru_utime) + s(u.ru_stime))
    }
    #[cfg(not(unix))]
    {
        None
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn peak_memory_is_plausible_on_linux() {
        if cfg!(target_os = "linux") {
            let b = super::peak_resident_bytes().expect("VmHWM on Linux");
            assert!(b > 100_000 && b < 1 << 40, "{b}");
        }
    }

    #[test]
    fn cpu_time_grows_with_work() {
        if cfg!(unix) {
            let before = super::cpu_seconds().expect("getrusage on unix");
            let mut x = 0u64;
            let start = std::time::Instant::now();
            while start.elapsed().as_secs_f64() < 0.05 {
                x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
            }
            let after = super::cpu_seconds().unwrap();
            assert!(
                after > before && after - before < 10.0,
                "{before} → {after}"
            );
        }
    }
}
