//! The machine's state directory: files that outlive a run (Modbus memory areas marked
//! `persist`; later CANopen's stored parameters). Every file is replaced atomically (write a
//! temporary file in the same directory, sync it, rename it over the old one, sync the
//! directory), so a kill at any moment leaves either the old or the new contents, never a mix.

use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use crate::config::Config;

/// Where a machine keeps its state.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StateDir {
    path: PathBuf,
}

impl StateDir {
    pub fn new(path: impl Into<PathBuf>) -> StateDir {
        StateDir { path: path.into() }
    }

    /// The directory for `config` (read from `file`): `cli` (`--state-dir`) first, then
    /// `[machine] state_dir` relative to the config file, then the user's state directory
    /// (`$XDG_STATE_HOME/mcemu/<machine>`, else `$HOME/.local/state/mcemu/<machine>`). `None`
    /// when none of them can be found (no home directory): state then lives for the run only.
    pub fn resolve(config: &Config, file: &str, cli: Option<&Path>) -> Option<StateDir> {
        if let Some(path) = cli {
            return Some(StateDir::new(path));
        }
        if let Some(dir) = &config.machine.state_dir {
            let base = Path::new(file).parent().unwrap_or(Path::new(""));
            return Some(StateDir::new(base.join(dir)));
        }
        let machine = file_name(&config.machine.name);
        let home_state = || {
            std::env::var_os("HOME")
                .filter(|h| !h.is_empty())
                .map(|h| PathBuf::from(h).join(".local/state"))
        };
        std::env::var_os("XDG_STATE_HOME")
            .filter(|x| !x.is_empty())
            .map(PathBuf::from)
            .or_else(home_state)
            .map(|base| StateDir::new(base.join("mcemu").join(machine)))
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The contents of `name`, or `None` if it was never written.
    pub fn read(&self, name: &str) -> io::Result<Option<Vec<u8>>> {
        match fs::read(self.path.join(name)) {
            Ok(bytes) => Ok(Some(bytes)),
            Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(None),
            Err(e) => Err(e),
        }
    }

    /// Replace `name` with `bytes` atomically, creating the directory if needed.
    pub fn write(&self, name: &str, bytes: &[u8]) -> io::Result<()> {
        let target = self.path.join(name);
        let dir = target.parent().unwrap_or(&self.path).to_path_buf();
        fs::create_dir_all(&dir)?;
        let temp = dir.join(format!(
            ".{}.{}.tmp",
            target
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            std::process::id()
        ));
        let written = (|| {
            let mut f = File::create(&temp)?;
            f.write_all(bytes)?;
            f.sync_all()?;
            fs::rename(&temp, &target)?;
            // The rename itself is durable only once the directory is.
            File::open(&dir)?.sync_all()
        })();
        if written.is_err() {
            let _ = fs::remove_file(&temp);
        }
        written
    }

    /// A display form for messages.
    pub fn display(&self, name: &str) -> String {
        self.path.join(name).display().to_string()
    }
}

/// A machine name as one path component: separators and other awkward characters become `_`.
fn file_name(name: &str) -> String {
    let cleaned: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    match cleaned.trim_matches('.') {
        "" => "mcemu".into(),
        s => s.to_string(),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    fn temp(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("mcemu-state-dir-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn writes_replace_the_file_and_leave_no_temporaries() {
        let dir = StateDir::new(temp("replace"));
        assert_eq!(dir.read("a/b.json").unwrap(), None);
        dir.write("a/b.json", b"one").unwrap();
        dir.write("a/b.json", b"two").unwrap();
        assert_eq!(dir.read("a/b.json").unwrap().unwrap(), b"two");
        let names: Vec<_> = fs::read_dir(dir.path().join("a"))
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, ["b.json"]);
        fs::remove_dir_all(dir.path()).unwrap();
    }

    #[test]
    fn the_config_and_the_command_line_choose_the_directory() {
        let mut c = Config::default();
        c.machine.name = "my/machine".into();
        c.machine.state_dir = Some("state".into());
        assert_eq!(
            StateDir::resolve(&c, "/etc/mcemu/m.toml", None),
            Some(StateDir::new("/etc/mcemu/state"))
        );
        assert_eq!(
            StateDir::resolve(&c, "/etc/mcemu/m.toml", Some(Path::new("/tmp/s"))),
            Some(StateDir::new("/tmp/s"))
        );
        assert_eq!(file_name("my/machine"), "my_machine");
        assert_eq!(file_name(".."), "mcemu");
    }
}
