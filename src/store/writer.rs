//! Which process wrote a row, and whether that process is known to be
//! gone. A writer is named `host/boot/pid/start` (hostname, the kernel's
//! boot id, process id, and its start time in clock ticks since boot): on
//! the same host and boot a process whose id no longer runs, or now runs
//! with another start time, is gone; a writer of another host or an
//! unreadable `/proc` is never judged gone (its rows wait for the grace
//! period instead). Containers sharing a kernel have their own hostnames.

use std::sync::OnceLock;

/// Field of `/proc/<pid>/stat` holding the start time, counted after the
/// command name's closing parenthesis (field 22 of the whole line).
const START_TIME_FIELD_AFTER_COMM: usize = 19;

fn read_trimmed(path: &str) -> Option<String> {
    std::fs::read_to_string(path)
        .ok()
        .map(|s| s.trim().to_string())
}

/// Start time of process `pid`, clock ticks since boot.
fn start_time(pid: &str) -> Option<String> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let after_comm = &stat[stat.rfind(')')? + 1..];
    after_comm
        .split_whitespace()
        .nth(START_TIME_FIELD_AFTER_COMM)
        .map(str::to_string)
}

/// This host and boot: `host/boot`, when `/proc` tells them.
fn host_boot() -> Option<String> {
    let host = read_trimmed("/proc/sys/kernel/hostname")?;
    let boot = read_trimmed("/proc/sys/kernel/random/boot_id")?;
    Some(format!("{host}/{boot}"))
}

/// This process as a writer.
pub fn current() -> &'static str {
    static CURRENT: OnceLock<String> = OnceLock::new();
    CURRENT.get_or_init(|| {
        let pid = std::process::id().to_string();
        match (host_boot(), start_time("self")) {
            (Some(host_boot), Some(start)) => format!("{host_boot}/{pid}/{start}"),
            _ => format!("unknown/{pid}"),
        }
    })
}

/// Whether `writer` is a process of this host and boot that no longer
/// runs. Anything it cannot tell is "may still run".
pub fn is_gone(writer: &str) -> bool {
    let Some(here) = host_boot() else {
        return false;
    };
    let Some(rest) = writer
        .strip_prefix(here.as_str())
        .and_then(|r| r.strip_prefix('/'))
    else {
        return false;
    };
    let Some((pid, start)) = rest.split_once('/') else {
        return false;
    };
    if pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return false;
    }
    start_time(pid).as_deref() != Some(start)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn this_process_runs_and_a_finished_child_is_gone() {
        assert!(!is_gone(current()), "{}", current());
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let pid = child.id().to_string();
        let start = start_time(&pid);
        child.wait().unwrap();
        let here = host_boot().unwrap();
        if let Some(start) = start {
            assert!(is_gone(&format!("{here}/{pid}/{start}")));
        }
        // The same pid with another start time: a reused id, gone.
        let me = std::process::id();
        assert!(is_gone(&format!("{here}/{me}/1")));
        // Another host, or a malformed name: may still run.
        assert!(!is_gone("elsewhere/boot/1/1"));
        assert!(!is_gone(&format!("{here}/x/1")));
        assert!(!is_gone("unknown/1"));
    }
}
