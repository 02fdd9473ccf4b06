//! The machine a report was measured on, named in the report.

use std::process::Command;

/// What the report says about the machine and toolchain.
pub struct MachineInfo {
    /// CPU model name (from /proc/cpuinfo), or "unknown".
    pub cpu: String,
    /// Logical cores available to this process.
    pub cores: usize,
    /// Total memory (GiB), 0 if unknown.
    pub memory_gib: f64,
    /// `rustc -V`.
    pub rustc: String,
    /// Kernel and architecture (`uname -srm`).
    pub os: String,
}

impl MachineInfo {
    /// Reads the machine's description; fields it cannot read say "unknown".
    #[must_use]
    pub fn read() -> Self {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let cpu = cpuinfo
            .lines()
            .find_map(|l| l.strip_prefix("model name"))
            .and_then(|l| l.split(':').nth(1))
            .map_or_else(|| "unknown".to_string(), |s| s.trim().to_string());
        let meminfo = std::fs::read_to_string("/proc/meminfo").unwrap_or_default();
        let memory_gib = meminfo
            .lines()
            .find_map(|l| l.strip_prefix("MemTotal:"))
            .and_then(|l| l.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
            .map_or(0.0, |kib| kib / (1024.0 * 1024.0));
        Self {
            cpu,
            cores: std::thread::available_parallelism().map_or(1, usize::from),
            memory_gib,
            rustc: command_output("rustc", &["-V"]),
            os: command_output("uname", &["-srm"]),
        }
    }

    /// One markdown line naming the machine.
    #[must_use]
    pub fn markdown(&self) -> String {
        format!(
            "{} ({} logical cores, {:.0} GiB), {}, {}",
            self.cpu, self.cores, self.memory_gib, self.os, self.rustc
        )
    }
}

fn command_output(program: &str, args: &[&str]) -> String {
    Command::new(program)
        .args(args)
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map_or_else(|| "unknown".to_string(), |s| s.trim().to_string())
}
