//! The one atomic file writer (issue 35, item 3): a file is written under a temporary name
//! beside it (`.NAME.part`) and renamed over its name when complete, so a reader never sees
//! half a file and a killed writer leaves the old file or none. Used by fe-model's writers and
//! the apps' output folder.

use std::io::Write;
use std::path::{Path, PathBuf};

/// The temporary name of `path` while it is written: `.NAME.part` beside it.
pub fn part_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.part"))
}

/// Write `bytes` to `path` through [`part_path`], flushed to disk and renamed over `path`
/// (atomic on one file system); the temporary file is removed when anything fails.
///
/// # Errors
/// The operating system's error of creating, writing, flushing or renaming the file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = part_path(path);
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A second write replaces the first and leaves no temporary file; a write into a missing
    /// folder fails and leaves nothing (reference: the folder's listing).
    #[test]
    fn replaces_whole_files_and_leaves_no_part() {
        let dir = std::env::temp_dir().join(format!("mbd-core-output-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("a.txt");
        assert_eq!(part_path(&f), dir.join(".a.txt.part"));
        write_atomic(&f, b"first").unwrap();
        write_atomic(&f, b"second").unwrap();
        assert_eq!(std::fs::read(&f).unwrap(), b"second");
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(names.len(), 1, "{names:?}");
        assert!(write_atomic(&dir.join("none/b.txt"), b"x").is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
