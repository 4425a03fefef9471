//! The `sweepffd` command line (see the README and `docs/cli.md`).

fn main() -> std::process::ExitCode {
    sweepffd_cli::run()
}
