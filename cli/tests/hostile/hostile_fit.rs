//! A fit's cost follows its part: keys and radii beyond what the part's vertices determine are
//! refused naming the value and the most allowed, and what is allowed runs in bounded memory
//! (`fit --keys 1024` on a 48-vertex tube took 4.2 GB and 29.5 s; `--radii 4096`, 2.1 GB).

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

/// A tube of `rings` rings of `around` vertices (3 units long), all in the group `tube`, as
/// `name` in `dir`.
fn tube(dir: &Path, name: &str, rings: usize, around: usize) {
    let mut obj = String::from("g tube\n");
    for r in 0..rings {
        for a in 0..around {
            let angle = std::f64::consts::TAU * a as f64 / around as f64;
            let z = 3.0 * r as f64 / (rings - 1) as f64;
            writeln!(obj, "v {} {} {z}", 0.4 * angle.cos(), 0.4 * angle.sin()).unwrap();
        }
    }
    for r in 0..rings - 1 {
        for a in 0..around {
            let (i, j) = (r * around + a + 1, r * around + (a + 1) % around + 1);
            writeln!(obj, "f {i} {j} {} {}", j + around, i + around).unwrap();
        }
    }
    std::fs::write(dir.join(name), obj).unwrap();
}

/// `sweepffd fit` of the group `tube` of `mesh` with `args`, under an address-space limit of
/// `kilobytes`; its output and how long it took.
fn fit(dir: &Path, mesh: &str, args: &[&str], kilobytes: u64) -> (Output, Duration) {
    let start = Instant::now();
    let output = Command::new("sh")
        .arg("-c")
        .arg(format!(r#"ulimit -v {kilobytes}; exec "$0" "$@""#))
        .arg(env!("CARGO_BIN_EXE_sweepffd"))
        .args(["fit", "--mesh", mesh, "--group", "tube", "--out", "rig.json"])
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    (output, start.elapsed())
}

#[test]
fn the_most_a_small_part_allows_runs_within_a_gigabyte_and_more_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    tube(dir.path(), "tube.obj", 6, 8);
    let (output, took) = fit(dir.path(), "tube.obj", &["--keys", "48", "--max-keys", "48", "--radii", "48"], 1_000_000);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(took < Duration::from_secs(10), "{took:?}");
    for (flag, value) in [("--keys", "1024"), ("--max-keys", "49"), ("--radii", "4096")] {
        let args: Vec<&str> = if flag == "--keys" { vec![flag, value, "--max-keys", value] } else { vec![flag, value] };
        let (output, _) = fit(dir.path(), "tube.obj", &args, 1_000_000);
        assert_eq!(output.status.code(), Some(1));
        assert_eq!(
            String::from_utf8_lossy(&output.stderr),
            format!(
                "error: tube.obj: fitting sweep \"tube\": {flag} {value} is more than a part of 48 vertices determines \
                 (at most 48); nothing was written\n"
            )
        );
    }
}

/// 1,024 keys on a 1,100-vertex tube: 4.2 GB before (the key basis held every key's field at
/// every radius), 0.43 GB now.
#[test]
fn a_thousand_keys_fit_within_a_gigabyte_and_a_half() {
    let dir = tempfile::tempdir().unwrap();
    tube(dir.path(), "tube.obj", 44, 25);
    let (output, took) = fit(dir.path(), "tube.obj", &["--keys", "1024", "--max-keys", "1024"], 1_500_000);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    eprintln!("1,024 keys on 1,100 vertices: {took:?}");
}
