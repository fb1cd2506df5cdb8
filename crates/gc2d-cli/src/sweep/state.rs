//! What a point's run directory says about it: not started, interrupted (resume it), or finished (skip it), and
//! whether it belongs to this point at all (its `scene.ron` is the point's scene).

use super::scenes::PointScene;
use crate::failure::CommandFailure;
use crate::outputs::SCENE_COPY;
use std::path::Path;

/// The state of a point's run directory.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum State {
    /// Nothing to continue from: run it from the start.
    Fresh,
    /// Started and stopped with a checkpoint: continue it with `--resume`.
    Resume,
    /// Finished; `summary.json` gives this outcome (`completed` or `failed`).
    Finished(String),
}

/// Reads the state of `point`'s run directory; a directory whose `scene.ron` is another scene is refused.
pub fn state(point: &PointScene) -> Result<State, CommandFailure> {
    let copy = point.dir.join(SCENE_COPY);
    let Ok(written) = std::fs::read_to_string(&copy) else { return Ok(State::Fresh) };
    if scene_text(&written) != point.text.trim() {
        return Err(CommandFailure::input(format!(
            "{} holds another scene than point `{}` now has (was the sweep file or the base scene changed?): move \
             the directory away, or give the sweep another output directory, before running again",
            copy.display(),
            point.name
        )));
    }
    match outcome(&point.dir) {
        Some(status) if status == "completed" || status == "failed" => Ok(State::Finished(status)),
        _ if has_checkpoint(&point.dir) => Ok(State::Resume),
        _ => Ok(State::Fresh),
    }
}

/// Writes `scene.ron` of a point about to start from the beginning.
pub fn write_scene(point: &PointScene, sweep_file: &Path) -> Result<(), CommandFailure> {
    std::fs::create_dir_all(&point.dir)
        .map_err(|e| CommandFailure::failed(format!("cannot create {}: {e}", point.dir.display())))?;
    let header = format!(
        "// Point {} of the sweep {}, as gc2d-rs {} made it from the base scene; a field left out has its default (docs/scene-format.md).\n",
        point.name,
        sweep_file.display(),
        env!("CARGO_PKG_VERSION")
    );
    let copy = point.dir.join(SCENE_COPY);
    std::fs::write(&copy, header + &point.text + "\n")
        .map_err(|e| CommandFailure::failed(format!("cannot write {}: {e}", copy.display())))
}

/// The outcome `summary.json` in `dir` gives (`completed`, `interrupted`, `failed`), if it is there and readable.
pub fn outcome(dir: &Path) -> Option<String> {
    let text = std::fs::read_to_string(dir.join("summary.json")).ok()?;
    let summary: serde_json::Value = serde_json::from_str(&text).ok()?;
    summary.get("outcome")?.get("status")?.as_str().map(str::to_owned)
}

/// The text of a scene copy without its leading comment lines.
fn scene_text(written: &str) -> &str {
    let mut rest = written;
    while rest.starts_with("//") {
        rest = rest.split_once('\n').map_or("", |(_, tail)| tail);
    }
    rest.trim()
}

/// True when `dir` holds a state to resume from (`final.ckpt` or a periodic checkpoint).
fn has_checkpoint(dir: &Path) -> bool {
    if dir.join("final.ckpt").is_file() {
        return true;
    }
    std::fs::read_dir(dir.join("checkpoints")).is_ok_and(|entries| {
        entries.flatten().any(|e| {
            let name = e.file_name();
            let name = name.to_string_lossy();
            name.starts_with("checkpoint-") && name.ends_with(".ckpt")
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leading_comments_are_not_part_of_the_scene() {
        assert_eq!(scene_text("// a\n// b\nScene(\n)\n"), "Scene(\n)");
        assert_eq!(scene_text("Scene()"), "Scene()");
    }
}
