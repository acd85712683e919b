//! Artefacts a front-end's config names: register maps, EDS files … either shipped (embedded in
//! the binary, named by a bare name: `map = "himc"`) or a file, named by a path relative to the
//! config file's directory (`map = "maps/press.toml"`).
//!
//! A front-end declares its kind of artefact once, as an [`Artefacts`] (what it is called, the
//! file endings that make a name a path, the shipped ones). Input: the name the config gives and
//! the config file's path. Output: [`Artefacts::locate`] says which shipped artefact or which
//! file is meant; [`Artefacts::load`] also reads the file. Errors name what was asked, the
//! shipped candidates and the path tried.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

/// One kind of artefact a front-end uses, and the ones it ships.
#[derive(Clone, Copy, Debug)]
pub struct Artefacts {
    /// What one is called in messages: `map`, `EDS`.
    pub kind: &'static str,
    /// How messages call a file of this kind: `a map file`, `a file`.
    pub file_noun: &'static str,
    /// A name ending in one of these is a path (`.toml`; `.eds`, `.dcf`); any other is a shipped
    /// artefact's name.
    pub file_endings: &'static [&'static str],
    /// The shipped artefacts: (name, text).
    pub shipped: &'static [(&'static str, &'static str)],
}

/// Which artefact a name means.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Located {
    /// A shipped one: its name and embedded text.
    Shipped {
        name: &'static str,
        text: &'static str,
    },
    /// A file: the config file's directory joined with the name (an absolute name stays as it is).
    File(PathBuf),
}

/// An artefact's text and where it came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Artefact {
    pub text: Cow<'static, str>,
    pub from: Located,
}

/// Why a named artefact cannot be had.
#[derive(Debug, thiserror::Error)]
pub enum ArtefactError {
    #[error(
        "`{asked}` is not a shipped {kind} ({}); {file_noun}'s path ends in {}",
        shipped.join(", "),
        file_endings.join(" or ")
    )]
    NotShipped {
        kind: &'static str,
        file_noun: &'static str,
        /// The name the config gave.
        asked: String,
        /// The names that are shipped.
        shipped: Vec<&'static str>,
        file_endings: &'static [&'static str],
    },
    #[error("cannot read {kind} `{}`: {source}", path.display())]
    Read {
        kind: &'static str,
        /// The name the config gave.
        asked: String,
        /// The path tried.
        path: PathBuf,
        source: std::io::Error,
    },
}

impl Artefacts {
    /// The shipped artefact `name` is, or the file it names relative to `config_file`'s
    /// directory; a name is a path when it ends in one of [`Artefacts::file_endings`].
    pub fn locate(&self, name: &str, config_file: &str) -> Result<Located, ArtefactError> {
        if self.file_endings.iter().any(|e| name.ends_with(e)) {
            return Ok(Located::File(config_dir(config_file).join(name)));
        }
        self.shipped
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(name, text)| Located::Shipped { name, text })
            .ok_or_else(|| ArtefactError::NotShipped {
                kind: self.kind,
                file_noun: self.file_noun,
                asked: name.to_string(),
                shipped: self.shipped.iter().map(|(n, _)| *n).collect(),
                file_endings: self.file_endings,
            })
    }

    /// [`Artefacts::locate`], and a file's text read (UTF-8).
    pub fn load(&self, name: &str, config_file: &str) -> Result<Artefact, ArtefactError> {
        let from = self.locate(name, config_file)?;
        let text = match &from {
            Located::Shipped { text, .. } => Cow::Borrowed(*text),
            Located::File(path) => {
                Cow::Owned(
                    std::fs::read_to_string(path).map_err(|source| ArtefactError::Read {
                        kind: self.kind,
                        asked: name.to_string(),
                        path: path.clone(),
                        source,
                    })?,
                )
            }
        };
        Ok(Artefact { text, from })
    }
}

/// The directory relative paths in `config_file` start from: its parent (empty: the working
/// directory).
pub fn config_dir(config_file: &str) -> PathBuf {
    Path::new(config_file)
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    const MAPS: Artefacts = Artefacts {
        kind: "map",
        file_noun: "a map file",
        file_endings: &[".toml"],
        shipped: &[("generic", "[generic]"), ("himc", "[himc]")],
    };

    const EDS: Artefacts = Artefacts {
        kind: "EDS",
        file_noun: "a file",
        file_endings: &[".eds", ".dcf"],
        shipped: &[("ct-e10", "[ct-e10]")],
    };

    /// A fresh directory with `file` holding `text`.
    fn dir_with(test: &str, file: &str, text: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("mcemu-artefact-{}-{test}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join(file), text).unwrap();
        dir
    }

    #[test]
    fn a_shipped_name_is_the_embedded_text() {
        let a = MAPS.load("himc", "/anywhere/m.toml").unwrap();
        assert_eq!(a.text, "[himc]");
        assert_eq!(
            a.from,
            Located::Shipped {
                name: "himc",
                text: "[himc]"
            }
        );
    }

    #[test]
    fn a_relative_path_starts_from_the_config_files_directory() {
        let dir = dir_with("relative", "press.toml", "[press]");
        let config = dir.join("m.toml");
        let a = MAPS.load("press.toml", config.to_str().unwrap()).unwrap();
        assert_eq!(a.text, "[press]");
        assert_eq!(a.from, Located::File(dir.join("press.toml")));
        // A config file named without a directory: the working directory.
        assert_eq!(
            EDS.locate("drive.dcf", "m.toml").unwrap(),
            Located::File(PathBuf::from("drive.dcf"))
        );
    }

    #[test]
    fn an_absolute_path_is_taken_as_it_is() {
        let dir = dir_with("absolute", "drive.eds", "[drive]");
        let path = dir.join("drive.eds");
        let a = EDS
            .load(path.to_str().unwrap(), "/elsewhere/m.toml")
            .unwrap();
        assert_eq!(a.text, "[drive]");
        assert_eq!(a.from, Located::File(path));
    }

    #[test]
    fn a_missing_file_names_the_path_tried_and_keeps_the_io_error() {
        let e = MAPS.load("missing.toml", "/tmp/m.toml").unwrap_err();
        let ArtefactError::Read {
            asked,
            path,
            source,
            ..
        } = &e
        else {
            panic!("{e:?}");
        };
        assert_eq!(asked, "missing.toml");
        assert_eq!(path, &PathBuf::from("/tmp/missing.toml"));
        assert_eq!(source.kind(), std::io::ErrorKind::NotFound);
        assert!(
            e.to_string()
                .starts_with("cannot read map `/tmp/missing.toml`: "),
            "{e}"
        );
        let cause = std::error::Error::source(&e).unwrap();
        assert!(cause.downcast_ref::<std::io::Error>().is_some());
    }

    #[test]
    fn an_unknown_name_lists_the_shipped_ones() {
        let e = MAPS.load("nope", "m.toml").unwrap_err();
        assert_eq!(
            e.to_string(),
            "`nope` is not a shipped map (generic, himc); a map file's path ends in .toml"
        );
        let ArtefactError::NotShipped { shipped, .. } = &e else {
            panic!("{e:?}");
        };
        assert_eq!(shipped, &["generic", "himc"]);
        // A file ending of another kind is a name for this one.
        let e = EDS.locate("ct-e10.toml", "m.toml").unwrap_err();
        assert_eq!(
            e.to_string(),
            "`ct-e10.toml` is not a shipped EDS (ct-e10); a file's path ends in .eds or .dcf"
        );
    }
}
