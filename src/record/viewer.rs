//! The viewer set-up that travels with a run: written beside every recording, so that a user
//! who has only the `wbv` binary can open the run as plots.
//!
//! - [`LAYOUT_FILE`]: the Foxglove / Lichtblick layout (`tools/viewer/wbv-layout.json`): 3-D scene,
//!   base, seat and head acceleration and the seat force. Both viewers import a layout from a JSON
//!   file (*Layout* → *Import from file…*); no documented way to take one from an MCAP attachment
//!   was found, so it is a file.
//! - [`BLUEPRINT_FILE`]: the Rerun blueprint (`tools/viewer/wbv.rbl`, written by
//!   `tools/viewer/rerun_blueprint.py` with rerun-sdk, the only writer of Rerun's format) with the
//!   same four signals as time series, for recordings of application id [`RERUN_APPLICATION_ID`].
//!
//! The bytes are the committed files', so they are the same for every run.

use crate::error::Result;
use crate::io::atomic::{Overwrite, write_atomic};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The Foxglove / Lichtblick layout written beside a run.
pub const LAYOUT_FILE: &str = "wbv-layout.json";
/// The Rerun blueprint written beside a run.
pub const BLUEPRINT_FILE: &str = "wbv.rbl";
/// The application id of [`BLUEPRINT_FILE`]: Rerun applies a blueprint to recordings of its id.
pub const RERUN_APPLICATION_ID: &str = "wbv";

const FILES: [(&str, &[u8]); 2] = [
    (
        LAYOUT_FILE,
        include_bytes!("../../tools/viewer/wbv-layout.json"),
    ),
    (BLUEPRINT_FILE, include_bytes!("../../tools/viewer/wbv.rbl")),
];

/// The viewer files beside the recording `run`.
pub fn paths(run: &Path) -> Vec<PathBuf> {
    let dir = run.parent().unwrap_or(Path::new(""));
    FILES.iter().map(|(name, _)| dir.join(name)).collect()
}

/// Writes the viewer files beside the recording `run` (atomically). A file that already holds
/// the same bytes is left as it is; one with other content (a layout the user edited) is kept
/// unless `overwrite` allows replacing it. Returns the files that are now the shipped ones.
pub fn write_beside(run: &Path, overwrite: Overwrite) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for (path, (_, bytes)) in paths(run).into_iter().zip(FILES) {
        match std::fs::read(&path) {
            Ok(old) if old == bytes => {}
            Ok(_) if overwrite == Overwrite::Refuse => continue,
            _ => write_atomic(&path, Overwrite::Allow, |w| {
                w.write_all(bytes).map_err(|e| crate::Error::io(&path, e))
            })?,
        }
        written.push(path);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_are_written_once_and_an_edited_layout_is_kept() {
        let dir = tempfile::tempdir().unwrap();
        let run = dir.path().join("run.mcap");
        assert_eq!(write_beside(&run, Overwrite::Refuse).unwrap(), paths(&run));
        let layout = dir.path().join(LAYOUT_FILE);
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&layout).unwrap()).unwrap();
        assert!(json["configById"]["Plot!accel"].is_object());
        std::fs::write(&layout, "{}").unwrap();
        let kept = write_beside(&run, Overwrite::Refuse).unwrap();
        assert_eq!(kept, [dir.path().join(BLUEPRINT_FILE)]);
        assert_eq!(std::fs::read_to_string(&layout).unwrap(), "{}");
        write_beside(&run, Overwrite::Allow).unwrap();
        assert_eq!(std::fs::read(&layout).unwrap(), FILES[0].1);
    }
}
