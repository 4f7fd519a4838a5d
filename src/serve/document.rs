//! The file being edited: read as it is now (never from memory), named by
//! a version (a hash of its bytes), and written only over the version an
//! edit is based on. Another tab's Save, or another program's write, is
//! never overwritten in silence: the write is refused and the page offers
//! theirs, mine, or both side by side.

use std::hash::{DefaultHasher, Hasher};
use std::path::PathBuf;
use std::sync::Mutex;

use crate::frontend::io::Output;
use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use stlc::pipeline::InputKind;

/// A version of a file's contents: its length and a 64-bit hash of its
/// bytes, in hex. Equal texts have equal versions.
pub fn version(bytes: &[u8]) -> String {
    let mut h = DefaultHasher::new();
    h.write(bytes);
    format!("{:x}-{:016x}", bytes.len(), h.finish())
}

/// The text opened and where it comes from.
pub struct Document {
    /// The file Save writes; `None`: the example, and Save downloads.
    path: Option<PathBuf>,
    /// The example's text when there is no file.
    example: String,
    /// The name shown.
    pub name: String,
    /// The kind of the text.
    pub kind: InputKind,
    /// The text a file that does not exist yet starts from.
    template: &'static str,
    /// The most bytes a file may have to be read.
    max_bytes: u64,
    /// Saves one at a time, so the version check and the write are one step.
    saving: Mutex<()>,
    /// The file's size and modification time when its version was last
    /// worked out, and that version: a watching page asks every second or
    /// so, and an unchanged file is then answered from its metadata, not
    /// read and hashed again.
    stamp: Mutex<Option<(u64, std::time::SystemTime, String)>>,
}

/// The file as it is now.
pub struct Current {
    /// Its text (a template for a file that does not exist yet).
    pub text: String,
    /// Its version; `None`: the file does not exist yet (Save creates it).
    pub version: Option<String>,
}

/// Why a save did not write.
pub enum Refused {
    /// The file changed since the version the edit is based on: its
    /// version now (`None`: it was removed).
    Changed(Option<String>),
    /// There is no file to write (the example).
    NoFile,
    /// Reading or writing failed.
    Failed(Diagnostics),
}

impl Document {
    /// The example, when no file is named.
    pub fn example(text: &str, name: &str, kind: InputKind, max_bytes: u64) -> Self {
        Document {
            path: None,
            example: text.to_string(),
            name: name.to_string(),
            kind,
            template: "",
            max_bytes,
            saving: Mutex::new(()),
            stamp: Mutex::new(None),
        }
    }

    /// The file at `path`, named `name`: read now to check that it can be
    /// edited (UTF-8 text of a known kind), or, if it does not exist yet,
    /// to be created from `template` on the first Save.
    pub fn file(
        path: PathBuf,
        name: &str,
        kind: InputKind,
        template: &'static str,
        max_bytes: u64,
    ) -> Result<Self, Diagnostics> {
        let doc = Document {
            path: Some(path),
            example: String::new(),
            name: name.to_string(),
            kind,
            template,
            max_bytes,
            saving: Mutex::new(()),
            stamp: Mutex::new(None),
        };
        doc.current()?;
        Ok(doc)
    }

    /// Whether Save writes a file.
    pub fn can_save(&self) -> bool {
        self.path.is_some()
    }

    /// The file's path as the page keys its drafts by (absolute where it
    /// can be made so), or the example's name.
    pub fn key(&self) -> String {
        match &self.path {
            Some(p) => std::path::absolute(p)
                .unwrap_or_else(|_| p.clone())
                .display()
                .to_string(),
            None => format!("example:{}", self.name),
        }
    }

    /// The text as it is now, and its version.
    pub fn current(&self) -> Result<Current, Diagnostics> {
        let Some(path) = &self.path else {
            return Ok(Current {
                text: self.example.clone(),
                version: Some(version(self.example.as_bytes())),
            });
        };
        let bytes = match std::fs::read(path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Ok(Current {
                    text: self.template.to_string(),
                    version: None,
                });
            }
            Err(e) => {
                return Err(io_error(&e, &format!("cannot read `{}`", path.display())).into());
            }
        };
        if bytes.len() as u64 > self.max_bytes {
            return Err(Diagnostic::error(ErrorKind::Io {
                doing: format!("cannot open `{}` in the editor", path.display()),
                error: format!(
                    "it has {} bytes, more than --max-input {}",
                    bytes.len(),
                    self.max_bytes
                ),
            })
            .into());
        }
        let v = version(&bytes);
        if let Ok(m) = std::fs::metadata(path)
            && let Ok(t) = m.modified()
            && m.len() == bytes.len() as u64
        {
            *self.stamp.lock().unwrap_or_else(|p| p.into_inner()) = Some((m.len(), t, v.clone()));
        }
        let text = String::from_utf8(bytes).map_err(|_| {
            Diagnostics::from(Diagnostic::error(ErrorKind::Io {
                doing: format!("cannot open `{}` in the editor", path.display()),
                error: "it is not UTF-8 text".into(),
            }))
        })?;
        Ok(Current {
            text,
            version: Some(v),
        })
    }

    /// Whether the file is still at `known`, told from its size and
    /// modification time alone when they are those of the last read (a
    /// page watching the file asks every second or so). `false` means
    /// "read it": changed, or not known to be unchanged.
    pub fn unchanged_since(&self, known: &str) -> bool {
        let Some(path) = &self.path else {
            return version(self.example.as_bytes()) == known;
        };
        let stamp = self.stamp.lock().unwrap_or_else(|p| p.into_inner());
        match (std::fs::metadata(path), stamp.as_ref()) {
            (Ok(m), Some((len, time, v))) => {
                m.len() == *len && m.modified().ok() == Some(*time) && v == known
            }
            _ => false,
        }
    }

    /// Writes `text` (atomically) if the file is still at `base`, the
    /// version the edit started from (`Some(None)`: the file did not exist;
    /// `None`: no check, as a script's save); returns the new version.
    pub fn save(&self, text: &str, base: Option<Option<&str>>) -> Result<String, Refused> {
        let Some(path) = &self.path else {
            return Err(Refused::NoFile);
        };
        let _one_at_a_time = self.saving.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(base) = base {
            let now = match std::fs::read(path) {
                Ok(b) => Some(version(&b)),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
                Err(e) => {
                    return Err(Refused::Failed(
                        io_error(&e, &format!("cannot read `{}`", path.display())).into(),
                    ));
                }
            };
            if now.as_deref() != base {
                return Err(Refused::Changed(now));
            }
        }
        Output::Path(path.clone())
            .write_with(|w| {
                w.write_all(text.as_bytes())
                    .map_err(|e| io_error(&e, "cannot write the file").into())
            })
            .map_err(Refused::Failed)?;
        // The next read works the version out again from the file.
        *self.stamp.lock().unwrap_or_else(|p| p.into_inner()) = None;
        Ok(version(text.as_bytes()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(dir: &tempfile::TempDir) -> (Document, PathBuf) {
        let path = dir.path().join("t.od");
        let d = Document::file(path.clone(), "t.od", InputKind::Od, "TEMPLATE\n", 1 << 20).unwrap();
        (d, path)
    }

    #[test]
    fn a_missing_file_starts_from_the_template_and_is_created_by_the_first_save() {
        let dir = tempfile::tempdir().unwrap();
        let (d, path) = doc(&dir);
        let c = d.current().unwrap();
        assert_eq!((c.text.as_str(), c.version), ("TEMPLATE\n", None));
        // Based on "did not exist": written.
        let v = d.save("one\n", Some(None)).ok().unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "one\n");
        assert_eq!(v, version(b"one\n"));
        // A second "create" is refused: it exists now.
        assert!(
            matches!(d.save("two\n", Some(None)), Err(Refused::Changed(Some(now))) if now == v)
        );
    }

    #[test]
    fn a_save_over_another_version_is_refused_and_nothing_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let (d, path) = doc(&dir);
        std::fs::write(&path, "mine\n").unwrap();
        let base = d.current().unwrap().version.unwrap();
        // Another program writes meanwhile.
        std::fs::write(&path, "theirs\n").unwrap();
        let Err(Refused::Changed(Some(now))) = d.save("edited\n", Some(Some(&base))) else {
            panic!("the save went through");
        };
        assert_eq!(now, version(b"theirs\n"));
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "theirs\n");
        // Keep mine: saved over the version now there.
        d.save("edited\n", Some(Some(&now))).ok().unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "edited\n");
        // A script's save (no version) writes whatever is there.
        d.save("script\n", None).ok().unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "script\n");
    }

    #[test]
    fn an_unchanged_file_is_told_from_its_metadata_and_a_changed_one_is_not() {
        let dir = tempfile::tempdir().unwrap();
        let (d, path) = doc(&dir);
        std::fs::write(&path, "one\n").unwrap();
        let v = d.current().unwrap().version.unwrap();
        assert!(d.unchanged_since(&v));
        assert!(!d.unchanged_since("other"));
        // Another length: changed, whatever the clock says.
        std::fs::write(&path, "one more\n").unwrap();
        assert!(!d.unchanged_since(&v));
        let w = d.current().unwrap().version.unwrap();
        assert!(d.unchanged_since(&w));
        d.save("two\n", Some(Some(&w))).ok().unwrap();
        assert!(!d.unchanged_since(&w), "a save forgets the stamp");
    }

    #[test]
    fn versions_tell_texts_apart() {
        assert_eq!(version(b"abc"), version(b"abc"));
        assert_ne!(version(b"abc"), version(b"abd"));
        assert_ne!(version(b""), version(b"\n"));
    }
}
