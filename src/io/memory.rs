//! The process's peak resident memory, to show that a run's memory does not grow with its duration.

/// Peak resident set size of this process in bytes (`VmHWM` of `/proc/self/status`), `None` where
/// the platform does not report it.
pub fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
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
}
