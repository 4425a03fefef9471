//! `sweepffd batch`: the deform jobs of a manifest, one shard of them, as a scheduler runs them
//! (a Slurm job array, a Kubernetes Indexed Job): each job is `deform` of one mesh by one pose
//! of its rig, the jobs of one (mesh, rig) pair share one binding, a job whose output exists
//! is done already (outputs are written atomically, so one that exists is whole), and every
//! job runs whatever the others do; the shard's report says what became of each.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::CliResult;
use super::backend::{Backend, resolve};
use super::bind::{Inputs, is_empty_rig, load_inputs};
use super::deform::{BoundMesh, non_finite, warn_of_folds};
use sweepffd::atomic_file::write_atomically;
use sweepffd::formats::{Format, LoadedMesh};

/// The arguments of `sweepffd batch`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The jobs, one JSON object a line: {"mesh": M, "rig": R, "pose": P, "out": OUT}, paths
    /// relative to the manifest's folder. Jobs are numbered by line from 0; blank lines hold
    /// none.
    #[arg(long)]
    pub manifest: PathBuf,
    /// The shard K/N to run (K from 0): the jobs whose number is K modulo N. Default: from
    /// SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT (less SLURM_ARRAY_TASK_MIN), or from
    /// JOB_COMPLETION_INDEX with --shards; without either, every job.
    #[arg(long)]
    pub shard: Option<Shard>,
    /// The number of shards N where the scheduler gives only the index (a Kubernetes Indexed
    /// Job's JOB_COMPLETION_INDEX).
    #[arg(long)]
    pub shards: Option<usize>,
    /// Where to write the shard's report: one JSON line per job of the shard (its number,
    /// files, status done, skipped or failed, the error, the seconds it took).
    #[arg(long)]
    pub report: PathBuf,
    /// Where to bind and deform, as for `deform`.
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    pub backend: Backend,
}

/// One shard of N: the jobs whose number is `index` modulo `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;

    fn from_str(text: &str) -> Result<Shard, String> {
        let invalid = || format!("expected K/N with 0 <= K < N, such as 0/4, not {text:?}");
        let (k, n) = text.split_once('/').ok_or_else(invalid)?;
        let (index, count): (usize, usize) =
            (k.trim().parse().map_err(|_| invalid())?, n.trim().parse().map_err(|_| invalid())?);
        if index >= count {
            return Err(invalid());
        }
        Ok(Shard { index, count })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The shard to run: `--shard`, else the scheduler's variables (`env` reads one), else every
/// job. A Slurm array's task ids run from SLURM_ARRAY_TASK_MIN (often 1); its shard is the id
/// less that. `JOB_COMPLETION_INDEX` needs the count from `--shards`.
pub fn shard_to_run(
    shard: Option<Shard>,
    shards: Option<usize>,
    env: impl Fn(&str) -> Option<String>,
) -> Result<Shard, String> {
    if let Some(shard) = shard {
        return Ok(shard);
    }
    let number = |name: &str| -> Result<Option<usize>, String> {
        env(name)
            .map(|value| value.trim().parse::<usize>().map_err(|_| format!("{name}={value:?} is not a whole number")))
            .transpose()
    };
    let checked = |index: usize, count: usize, from: &str| {
        if index < count { Ok(Shard { index, count }) } else { Err(format!("{from}: shard {index} of {count}")) }
    };
    if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
        let count = number("SLURM_ARRAY_TASK_COUNT")?
            .ok_or("SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not; give --shard K/N")?;
        let min = number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
        let index =
            id.checked_sub(min).ok_or(format!("SLURM_ARRAY_TASK_ID {id} is below SLURM_ARRAY_TASK_MIN {min}"))?;
        return checked(index, count, "the Slurm array");
    }
    if let Some(index) = number("JOB_COMPLETION_INDEX")? {
        let count = shards.ok_or("JOB_COMPLETION_INDEX is set: give the number of shards with --shards N")?;
        return checked(index, count, "JOB_COMPLETION_INDEX");
    }
    Ok(Shard { index: 0, count: 1 })
}

/// Why the jobs of one (mesh, rig) pair cannot share a binding.
#[derive(Clone, Debug)]
enum Shared {
    /// The rig has no sweeps: each job writes the mesh as it is, as `deform` does.
    EmptyRig(String),
    /// The mesh or rig could not be loaded or bound: each job fails with this.
    Failed(String),
}

/// A mesh and its rig: the jobs that share one binding.
type Pair = (PathBuf, PathBuf);

/// One line of the manifest.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct JobLine {
    mesh: PathBuf,
    rig: PathBuf,
    pose: PathBuf,
    out: PathBuf,
}

/// A job of the shard: its number and its line, read (paths resolved against the manifest's
/// folder) or not.
struct Job {
    number: usize,
    line: Result<JobLine, String>,
}

/// What became of one job, as the report writes it.
#[derive(Clone, Debug, Serialize)]
struct Outcome {
    job: usize,
    mesh: Option<PathBuf>,
    rig: Option<PathBuf>,
    pose: Option<PathBuf>,
    out: Option<PathBuf>,
    status: Status,
    error: Option<String>,
    seconds: f64,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
enum Status {
    /// Deformed and written.
    Done,
    /// Its output existed: done before.
    Skipped,
    /// Not written; the error says why.
    Failed,
}

pub fn run(args: &Args, quiet: bool) -> CliResult {
    let shard = shard_to_run(args.shard, args.shards, |name| std::env::var(name).ok())?;
    let text = sweepffd::limits::read_input_text(&args.manifest)
        .map_err(|e| format!("cannot read {}: {e}", args.manifest.display()))?;
    let folder = args.manifest.parent().unwrap_or(Path::new("")).to_path_buf();
    let jobs = shard_jobs(&text, shard, &folder);
    let started = Instant::now();
    let mut outcomes: Vec<Outcome> = Vec::with_capacity(jobs.len());
    // Jobs to run, grouped by (mesh, rig) in the order they first appear: one binding each.
    let mut groups: Vec<(Pair, Vec<(usize, JobLine)>)> = Vec::new();
    let mut group_of: HashMap<Pair, usize> = HashMap::new();
    for job in jobs {
        let line = match job.line {
            Ok(line) => line,
            Err(error) => {
                outcomes.push(Outcome::failed(job.number, None, error, 0.0));
                continue;
            }
        };
        if line.out.exists() {
            outcomes.push(Outcome { status: Status::Skipped, ..Outcome::of(job.number, &line) });
            continue;
        }
        let key = (line.mesh.clone(), line.rig.clone());
        let group = *group_of.entry(key.clone()).or_insert_with(|| {
            groups.push((key, Vec::new()));
            groups.len() - 1
        });
        groups[group].1.push((job.number, line));
    }
    let to_run: usize = groups.iter().map(|(_, jobs)| jobs.len()).sum();
    let device = if to_run > 0 { Some(resolve(args.backend, quiet)?) } else { None };
    let mut ran = 0;
    for ((mesh, rig), jobs) in &groups {
        let device = device.as_ref().expect("resolved when there are jobs to run");
        // What the group's jobs share: the mesh bound to its rig, or why none is.
        let loaded = load_inputs(mesh, rig).map_err(|error| {
            if is_empty_rig(&*error) { Shared::EmptyRig(error.to_string()) } else { Shared::Failed(error.to_string()) }
        });
        let mut bound = match &loaded {
            Ok(inputs) => BoundMesh::new(inputs, device, None, true).map_err(|e| Shared::Failed(e.to_string())),
            Err(why) => Err(why.clone()),
        };
        for (number, line) in jobs {
            let job_started = Instant::now();
            let result = match (&loaded, &mut bound) {
                (Ok(inputs), Ok(bound)) => deform_job(inputs, bound, line),
                (_, Err(Shared::EmptyRig(notice))) => unchanged_job(line, notice),
                (_, Err(Shared::Failed(error))) => Err(error.clone()),
                (Err(_), Ok(_)) => Err("the mesh was bound without being loaded".into()),
            };
            let seconds = job_started.elapsed().as_secs_f64();
            ran += 1;
            let outcome = match result {
                Ok(()) => Outcome { status: Status::Done, seconds, ..Outcome::of(*number, line) },
                Err(error) => Outcome::failed(*number, Some(line), error, seconds),
            };
            if !quiet {
                let what = match &outcome.error {
                    Some(error) => format!("failed: {error}"),
                    None => format!("done in {seconds:.3} s -> {}", line.out.display()),
                };
                note!("[{ran}/{to_run}] job {number}: {what}");
            }
            outcomes.push(outcome);
        }
    }
    outcomes.sort_by_key(|outcome| outcome.job);
    write_report(&args.report, &outcomes)?;
    let count = |status: Status| outcomes.iter().filter(|o| o.status == status).count();
    let (done, skipped, failed) = (count(Status::Done), count(Status::Skipped), count(Status::Failed));
    if !quiet {
        out!(
            "shard {shard}: {} jobs, {done} done, {skipped} skipped (done before), {failed} failed in {:.3} s; report -> {}",
            outcomes.len(),
            started.elapsed().as_secs_f64(),
            args.report.display()
        );
    }
    if failed > 0 {
        return Err(format!(
            "{failed} of the {} jobs of shard {shard} failed; see {}",
            outcomes.len(),
            args.report.display()
        )
        .into());
    }
    Ok(())
}

/// The jobs of `shard` in the manifest `text` (lines numbered from 0; blank lines hold none),
/// their paths resolved against `folder`.
fn shard_jobs(text: &str, shard: Shard, folder: &Path) -> Vec<Job> {
    text.lines()
        .enumerate()
        .filter(|(number, line)| number % shard.count == shard.index && !line.trim().is_empty())
        .map(|(number, line)| Job {
            number,
            line: serde_json::from_str::<JobLine>(line)
                .map(|job| JobLine {
                    mesh: folder.join(job.mesh),
                    rig: folder.join(job.rig),
                    pose: folder.join(job.pose),
                    out: folder.join(job.out),
                })
                .map_err(|e| format!("line {}: not a job: {e}", number + 1)),
        })
        .collect()
}

/// `deform` of one job on the mesh bound already: the pose loaded, deformed, written.
fn deform_job(inputs: &Inputs, bound: &mut BoundMesh, line: &JobLine) -> Result<(), String> {
    Format::of(&line.out).map_err(|e| e.to_string())?;
    let posed = inputs.rig.load_pose(&line.pose).map_err(|e| e.to_string())?;
    warn_of_folds(inputs, &posed, &line.pose);
    let (positions, owners) = bound.deform(&posed).map_err(|e| e.to_string())?;
    if let Some(error) = non_finite(inputs, &positions, &owners, &line.pose) {
        return Err(error);
    }
    inputs.file.save(&line.out, &positions).map_err(|e| e.to_string())
}

/// A job whose rig has no sweeps: the mesh written as it is, as `deform` does.
fn unchanged_job(line: &JobLine, notice: &str) -> Result<(), String> {
    Format::of(&line.out).map_err(|e| e.to_string())?;
    let file = LoadedMesh::load(&line.mesh).map_err(|e| e.to_string())?;
    file.save(&line.out, &file.mesh.positions).map_err(|e| e.to_string())?;
    note!("notice: {notice}; wrote the mesh unchanged to {}", line.out.display());
    Ok(())
}

impl Outcome {
    fn of(job: usize, line: &JobLine) -> Outcome {
        Outcome {
            job,
            mesh: Some(line.mesh.clone()),
            rig: Some(line.rig.clone()),
            pose: Some(line.pose.clone()),
            out: Some(line.out.clone()),
            status: Status::Done,
            error: None,
            seconds: 0.0,
        }
    }

    fn failed(job: usize, line: Option<&JobLine>, error: String, seconds: f64) -> Outcome {
        let base = match line {
            Some(line) => Outcome::of(job, line),
            None => Outcome {
                job,
                mesh: None,
                rig: None,
                pose: None,
                out: None,
                status: Status::Failed,
                error: None,
                seconds,
            },
        };
        Outcome { status: Status::Failed, error: Some(error), seconds, ..base }
    }
}

/// Writes the report, one JSON line per outcome, atomically.
fn write_report(path: &Path, outcomes: &[Outcome]) -> CliResult {
    let mut text = String::new();
    for outcome in outcomes {
        text.push_str(&serde_json::to_string(outcome)?);
        text.push('\n');
    }
    write_atomically(path, |out| std::io::Write::write_all(out, text.as_bytes()))
        .map_err(|e| format!("cannot write {}: {e}", path.display()).into())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| pairs.iter().find(|(n, _)| *n == name).map(|(_, v)| v.to_string())
    }

    #[test]
    fn the_shard_comes_from_the_flag_then_slurm_then_kubernetes() {
        let flag = Shard { index: 1, count: 3 };
        assert_eq!(shard_to_run(Some(flag), None, env(&[("SLURM_ARRAY_TASK_ID", "0")])), Ok(flag));
        let slurm = [("SLURM_ARRAY_TASK_ID", "3"), ("SLURM_ARRAY_TASK_COUNT", "4"), ("SLURM_ARRAY_TASK_MIN", "1")];
        assert_eq!(shard_to_run(None, None, env(&slurm)), Ok(Shard { index: 2, count: 4 }));
        assert!(shard_to_run(None, None, env(&[("SLURM_ARRAY_TASK_ID", "3")])).unwrap_err().contains("COUNT"));
        let k8s = [("JOB_COMPLETION_INDEX", "5")];
        assert_eq!(shard_to_run(None, Some(8), env(&k8s)), Ok(Shard { index: 5, count: 8 }));
        assert!(shard_to_run(None, None, env(&k8s)).unwrap_err().contains("--shards"));
        assert!(shard_to_run(None, Some(4), env(&[("JOB_COMPLETION_INDEX", "4")])).is_err(), "index past the count");
        assert!(
            shard_to_run(None, Some(4), env(&[("JOB_COMPLETION_INDEX", "x")])).unwrap_err().contains("whole number")
        );
        assert_eq!(shard_to_run(None, None, env(&[])), Ok(Shard { index: 0, count: 1 }));
    }

    #[test]
    fn shards_parse_as_k_of_n() {
        assert_eq!("2/4".parse::<Shard>(), Ok(Shard { index: 2, count: 4 }));
        for bad in ["4/4", "1", "a/b", "1/0", "-1/3"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }

    #[test]
    fn jobs_are_numbered_by_line_and_dealt_round_robin() {
        let line = r#"{"mesh": "m.obj", "rig": "r.json", "pose": "p.json", "out": "o.obj"}"#;
        let text = format!("{line}\n\n{line}\nnot json\n{line}\n");
        let numbers = |k| -> Vec<usize> {
            shard_jobs(&text, Shard { index: k, count: 2 }, Path::new("dir")).iter().map(|j| j.number).collect()
        };
        assert_eq!(numbers(0), vec![0, 2, 4]);
        assert_eq!(numbers(1), vec![3], "line 1 is blank: no job");
        let jobs = shard_jobs(&text, Shard { index: 1, count: 2 }, Path::new("dir"));
        assert!(jobs[0].line.as_ref().unwrap_err().starts_with("line 4: not a job"));
        let first = shard_jobs(&text, Shard { index: 0, count: 1 }, Path::new("dir"));
        assert_eq!(first[0].line.as_ref().unwrap().out, Path::new("dir").join("o.obj"));
    }
}
