//! The `sweepffd` command line: bind, deform, volume and demo (see the README).

mod cli;

fn main() -> std::process::ExitCode {
    cli::run()
}
