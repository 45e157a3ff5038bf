//! The reduced-tire file of a [`TireSource`] (its `reduced_file`): reused when it holds the
//! tire the source describes, otherwise made by reducing the tire and saved.
//!
//! The default, [`CACHE`], keeps one file per tire, reduction and code version in the OS cache
//! folder, shared by every checkout and release: its name carries the SHA-256 of the source's
//! [`TireSource::fingerprint`] (generator configuration or the imported files' contents, and the
//! reduction settings) and of [`crate::CODE_VERSION`], and the file itself records both and a
//! checksum of its body (module `reduced::file`). A cached file that fails to load (damaged,
//! truncated, edited, an older format) or records another tire or code is replaced by a fresh
//! reduction, never a dead end; files are written to a temporary file renamed on completion,
//! so a run killed while saving leaves no partial file. A file named by the user is never
//! replaced: one that fails to load or holds another tire is refused
//! ([`TireError::File`], bad input).

use crate::error::TireError;
use crate::files::sha256_hex;
use crate::reduced::ReducedTire;
use crate::source::{CACHE, TireSource};
use std::path::{Path, PathBuf};

/// How [`TireSource::reduced_tire`] got its tire.
#[derive(Debug, Clone, PartialEq)]
pub enum CacheUse {
    /// Loaded from the file.
    Loaded,
    /// Reduced (no file yet, or none wanted) and saved when there is a file.
    Reduced,
    /// Reduced because the cached file could not be used (the reason), and the file replaced.
    Replaced(String),
    /// Reduced, but the cache file could not be written (the reason): the run goes on without.
    NotSaved(String),
}

/// What [`TireSource::reduced_tire`] is about to do before a reduction (for a progress line).
#[derive(Debug, Clone, Copy)]
pub struct Reducing<'a> {
    /// The tire is imported (else generated).
    pub imported: bool,
    /// The file the reduced tire will be saved to (none: `reduced_file` is empty).
    pub file: Option<&'a Path>,
    /// Why an existing cache file is not used, when it is replaced.
    pub replacing: Option<&'a str>,
}

/// A reduced tire and where it came from.
#[derive(Debug, Clone)]
pub struct SourcedTire {
    /// The reduced tire.
    pub tire: ReducedTire,
    /// The reduced-tire file (none: `reduced_file` is empty).
    pub file: Option<PathBuf>,
    /// Loaded, reduced or replaced.
    pub cache: CacheUse,
}

/// The folder of the reduced-tire cache: `flowmbd/tire` in the OS cache folder
/// (`$XDG_CACHE_HOME`, `~/.cache` on Linux), or in the system's temporary folder without one.
pub fn cache_dir() -> PathBuf {
    dirs::cache_dir()
        .unwrap_or_else(std::env::temp_dir)
        .join("flowmbd")
        .join("tire")
}

impl TireSource {
    /// The reduced-tire file used: for [`CACHE`], the file of this tire, reduction and code
    /// version in [`cache_dir`], `reduced-<truck|imported>-<n_c>c-<n_f>m-<key>.json` with
    /// `key` the first 16 hex digits of the SHA-256 of the [`TireSource::fingerprint`] and
    /// [`crate::CODE_VERSION`]; otherwise `reduced_file` itself; `None` when it is empty.
    /// Errors: an import file that cannot be read (the fingerprint hashes it).
    pub fn reduced_path(&self) -> Result<Option<PathBuf>, TireError> {
        if self.reduced_file == CACHE {
            return Ok(Some(self.cache_path(&self.fingerprint()?)));
        }
        Ok(self.named_path())
    }

    /// `reduced_file` as a path (`None` when empty or [`CACHE`]).
    fn named_path(&self) -> Option<PathBuf> {
        (!self.reduced_file.is_empty() && self.reduced_file != CACHE)
            .then(|| PathBuf::from(&self.reduced_file))
    }

    /// The cache file of the tire with this `fingerprint` ([`TireSource::reduced_path`]).
    fn cache_path(&self, fingerprint: &str) -> PathBuf {
        let key = sha256_hex(format!("{fingerprint}\n{}", crate::CODE_VERSION).as_bytes());
        let kind = if self.import.is_some() {
            "imported"
        } else {
            "truck"
        };
        cache_dir().join(format!(
            "reduced-{kind}-{}c-{}m-{}.json",
            self.reduction.contact_nodes,
            self.reduction.free_modes,
            &key[..16]
        ))
    }

    /// The reduced tire of this source: loaded from its file ([`TireSource::reduced_path`])
    /// when that holds this tire, otherwise the FE model reduced ([`TireSource::reduce_fe`]) and
    /// saved (module documentation). `reducing` is called before a reduction (it takes about
    /// 30 s for the default tire). Errors: a user-named file that cannot be read or holds
    /// another tire or reduction ([`TireError::File`]), the FE model's and the reduction's
    /// errors, a user-named file that cannot be written.
    pub fn reduced_tire(
        &self, reducing: &mut dyn FnMut(&Reducing<'_>),
    ) -> Result<SourcedTire, TireError> {
        // (the fingerprint hashes the import files: once per call)
        let fingerprint = self.fingerprint()?;
        let cached = self.reduced_file == CACHE;
        let file = if cached {
            Some(self.cache_path(&fingerprint))
        } else {
            self.named_path()
        };
        let mut replacing = None;
        if let Some(path) = file.as_deref().filter(|p| p.exists()) {
            let found = ReducedTire::load(path)
                .and_then(|red| self.check_saved(path, red, &fingerprint, cached));
            match found {
                Ok(tire) => {
                    return Ok(SourcedTire {
                        tire,
                        file,
                        cache: CacheUse::Loaded,
                    });
                }
                Err(TireError::File { reason, .. }) if cached => replacing = Some(reason),
                Err(e) => return Err(e),
            }
        }
        reducing(&Reducing {
            imported: self.import.is_some(),
            file: file.as_deref(),
            replacing: replacing.as_deref(),
        });
        let fe = self.fe_model()?;
        let (mut tire, _) = crate::reduce::reduce(&fe, &self.reduction)?;
        tire.source = fingerprint;
        let mut cache = match replacing {
            Some(why) => CacheUse::Replaced(why),
            None => CacheUse::Reduced,
        };
        if let Some(path) = file.as_deref() {
            match tire.save(path) {
                Ok(()) => {}
                Err(TireError::File { reason, .. }) if cached => cache = CacheUse::NotSaved(reason),
                Err(e) => return Err(e),
            }
        }
        Ok(SourcedTire { tire, file, cache })
    }

    /// `red` (loaded from `path`) if it holds this source's tire: the reduction's counts, then
    /// the fingerprint, and for the cache also the code version; else the [`TireError::File`]
    /// saying what differs.
    fn check_saved(
        &self, path: &Path, red: ReducedTire, fingerprint: &str, cached: bool,
    ) -> Result<ReducedTire, TireError> {
        let refuse = |reason: String| TireError::File {
            path: path.display().to_string(),
            reason,
        };
        // a file made with another reduction would silently answer a different question: the
        // specific diagnosis first (counts), then any other difference (fingerprint)
        let (nc, nf) = (red.n_contact(), red.n_free_modes);
        let want = &self.reduction;
        if nc != want.contact_nodes || nf != want.free_modes {
            return Err(refuse(format!(
                "holds {nc} contact nodes and {nf} free-node modes but tire.reduction asks for \
                 {} and {} (delete the file or name another)",
                want.contact_nodes, want.free_modes
            )));
        }
        if red.source != fingerprint {
            let why = if red.source.is_empty() {
                "does not record the tire it was made from (an older flowmbd wrote it)"
            } else {
                "was made from another tire model or reduction than tire.generator / \
                 tire.import and tire.reduction describe"
            };
            return Err(refuse(format!("{why} (delete the file or name another)")));
        }
        if cached && red.code_version != crate::CODE_VERSION {
            return Err(refuse(format!(
                "was reduced by `{}`, not by this build (`{}`)",
                red.code_version,
                crate::CODE_VERSION
            )));
        }
        Ok(red)
    }
}
