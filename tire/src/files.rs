//! The tire's file handling: regular files of bounded size read whole, SHA-256 digests of
//! contents, and files written to a temporary file renamed onto the target when complete (a
//! reader never sees a half-written file, and a run killed while writing leaves the old file or
//! none). Errors are the reason only; callers name the field or file.

use sha2::{Digest, Sha256};
use std::io::{Read, Write};
use std::path::Path;

/// Lower-case hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    hex(&Sha256::digest(bytes))
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Lower-case hex SHA-256 of the content of the regular file `path`, read in blocks
/// (directories, devices, pipes and sockets are refused: a device such as `/dev/zero` would be
/// read without end; [`mbd_core::input::open`] without a ceiling).
pub fn file_sha256(path: &Path) -> Result<String, String> {
    let mut file = mbd_core::input::open(path, u64::MAX)
        .map_err(|e| e.reason())?
        .into_file();
    let mut hash = Sha256::new();
    let mut buf = vec![0u8; 1 << 16];
    loop {
        let n = file.read(&mut buf).map_err(|e| e.to_string())?;
        if n == 0 {
            break;
        }
        hash.update(&buf[..n]);
    }
    Ok(hex(&hash.finalize()))
}

/// The UTF-8 text of the regular file `path` if it holds at most `max_bytes` bytes, checked
/// before reading (the file's size) and while reading (a file that grows meanwhile):
/// [`mbd_core::input::read_text`], its reason without the path (callers name the file).
pub fn read_text_bounded(path: &Path, max_bytes: u64) -> Result<String, String> {
    mbd_core::input::read_text(path, max_bytes).map_err(|e| e.reason())
}

/// Write `bytes` to `path`: into a temporary file in the same folder (created if missing),
/// flushed to disk, then renamed onto `path`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create its folder: {e}"))?;
    let mut tmp = tempfile::Builder::new()
        .prefix(".flowmbd-")
        .suffix(".partial")
        .tempfile_in(dir)
        .map_err(|e| format!("cannot create a temporary file in its folder: {e}"))?;
    tmp.write_all(bytes)
        .and_then(|()| tmp.as_file().sync_all())
        .map_err(|e| e.to_string())?;
    tmp.persist(path).map_err(|e| e.error.to_string())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// FIPS 180-2 test vector: SHA-256("abc") (independent reference).
    #[test]
    fn sha256_of_abc() {
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }

    /// A device and a directory are refused before reading; a file over the ceiling is refused
    /// by its size; the atomic write replaces the file and leaves no temporary file behind.
    #[test]
    fn bounded_reads_and_atomic_writes() {
        #[cfg(unix)]
        assert!(
            read_text_bounded(Path::new("/dev/zero"), 1 << 20)
                .unwrap_err()
                .contains("not a regular file")
        );
        let dir = std::env::temp_dir().join(format!("flowmbd-tire-files-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        assert!(
            read_text_bounded(&dir, 10)
                .unwrap_err()
                .contains("directory")
        );
        let f = dir.join("sub/a.txt");
        write_atomic(&f, b"first").unwrap();
        write_atomic(&f, b"second text").unwrap();
        assert_eq!(read_text_bounded(&f, 11).unwrap(), "second text");
        assert!(
            read_text_bounded(&f, 10)
                .unwrap_err()
                .contains("ceiling of 10 bytes")
        );
        assert_eq!(file_sha256(&f).unwrap(), sha256_hex(b"second text"));
        let names: Vec<_> = std::fs::read_dir(dir.join("sub")).unwrap().collect();
        assert_eq!(names.len(), 1, "no temporary file left: {names:?}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
