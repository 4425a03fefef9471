//! `sweepffd view`: the interactive viewer ([`sweepffd::view`]); with `--script`, a replayed
//! session whose report (frame times, screenshots) is printed as JSON.

use std::io::Write;
use std::path::PathBuf;

use super::CliResult;
use sweepffd::mesh::write_atomically;
use sweepffd::view::{ViewOptions, run};

pub struct Args {
    pub options: ViewOptions,
    pub report: Option<PathBuf>,
}

pub fn run_view(args: Args) -> CliResult {
    let Some(report) = run(args.options)? else { return Ok(()) };
    let json = serde_json::to_string_pretty(&report)?;
    println!("{json}");
    if let Some(path) = &args.report {
        write_atomically(path, |out| writeln!(out, "{json}"))
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    if !report.errors.is_empty() {
        return Err(format!("the script met {} errors: {}", report.errors.len(), report.errors.join("; ")).into());
    }
    Ok(())
}
