//! Target `script`: a viewer script loaded as `sweepffd view --script` loads it (from a file in
//! a temporary folder: the parser reads a path), then played for up to 1,000 frames of 1/60 s.

use std::time::{Duration, Instant};

use sweepffd_cli::view::script::{Player, load};

use super::{Outcome, without_dir};

/// The most frames played.
const FRAMES: u32 = 1000;

/// Loads and plays the script `data`.
pub fn script(data: &[u8]) -> Outcome {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("script.json");
    std::fs::write(&path, data).expect("the script is written");
    let steps = load(&path).map_err(|e| without_dir(&e, dir.path()))?;
    let mut player = Player::new(steps, dir.path().to_path_buf());
    let start = Instant::now();
    for frame in 0..FRAMES {
        if player.finished() {
            break;
        }
        let _actions = player.frame(start + Duration::from_secs(1) * frame / 60);
    }
    Ok(())
}
