//! The file being edited: read as it is now (never from memory), named by
//! a version (a hash of its bytes), and written only over the version an
//! edit is based on. Another tab's Save, or another program's write, is
//! never overwritten in silence: the write is refused and the page offers
//! theirs, mine, or both side by side.
//!
//! The file is read with bounds ([`read_served`]), whatever another
//! program put in its place: a regular file only (a named pipe, a device
//! such as `/dev/zero`, a directory are refused), opened without blocking
//! (opening a named pipe waits for a writer otherwise), at most
//! `--max-input` bytes (its size is known before reading), counted against
//! the memory budget, and within [`READ_TIME`].

use std::hash::{DefaultHasher, Hasher};
use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant, SystemTime};

use super::memory::{self, Memory};
use crate::frontend::io::Output;
use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use stlc::pipeline::{Bound, InputKind};

/// How long reading the served file may take (a file on a stalled network
/// or FUSE file system): past it the read stops with an error.
pub const READ_TIME: Duration = Duration::from_secs(10);

/// How recent a change may be for the metadata not to tell it: a write
/// within one tick of the file system's clock (a jiffy for most; a second
/// or two on some) after the last read may leave every time stamp as it
/// was, so a file changed that recently is read again, not trusted
/// ("racy" in git's words).
const RACY: Duration = Duration::from_secs(2);

/// Who a file is and when it last changed, as `fstat` tells: its device
/// and inode (another file renamed into place is another inode), size,
/// modification time, and change time (which no program can set back:
/// setting the modification time sets it to now).
#[derive(Debug, Clone, PartialEq, Eq)]
struct Stamp {
    id: [i64; 6],
    len: u64,
    modified: Option<SystemTime>,
}

impl Stamp {
    fn of(m: &std::fs::Metadata) -> Self {
        #[cfg(unix)]
        let id = {
            use std::os::unix::fs::MetadataExt;
            [
                m.dev() as i64,
                m.ino() as i64,
                m.ctime(),
                m.ctime_nsec(),
                m.mtime(),
                m.mtime_nsec(),
            ]
        };
        #[cfg(not(unix))]
        let id = [0; 6];
        Stamp {
            id,
            len: m.len(),
            modified: m.modified().ok(),
        }
    }

    /// When the file last changed (its change time, where there is one).
    fn changed(&self) -> Option<SystemTime> {
        #[cfg(unix)]
        {
            let (s, ns) = (self.id[2], self.id[3]);
            let since = Duration::new(s.unsigned_abs(), ns.clamp(0, 999_999_999) as u32);
            if s >= 0 {
                SystemTime::UNIX_EPOCH.checked_add(since)
            } else {
                SystemTime::UNIX_EPOCH.checked_sub(since)
            }
        }
        #[cfg(not(unix))]
        self.modified
    }
}

/// The served file read with bounds: `None` if it does not exist.
pub struct Served {
    /// Its bytes.
    pub bytes: Vec<u8>,
    /// Who it was while read; `None` if it changed during the read.
    stamp: Option<Stamp>,
}

/// Reads the served file at `path` with the bounds above: a regular file
/// only, opened without blocking, at most `max_bytes` bytes (larger is
/// refused before reading), with a reservation of its size from `memory`
/// (if given) held while reading, within [`READ_TIME`]. `Ok(None)`: the
/// file does not exist.
pub fn read_served(
    path: &Path,
    max_bytes: u64,
    memory: Option<&Arc<Memory>>,
) -> Result<Option<Served>, Diagnostics> {
    let shown = path.display();
    let cannot = |error: String, help: &str| -> Diagnostics {
        Diagnostic::error(ErrorKind::Io {
            doing: format!("cannot open `{shown}` in the editor"),
            error,
        })
        .with_help(help)
        .into()
    };
    let mut file = match open_without_blocking(path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(io_error(&e, &format!("cannot read `{shown}`")).into()),
    };
    let meta = file
        .metadata()
        .map_err(|e| io_error(&e, &format!("cannot read `{shown}`")))?;
    if !meta.is_file() {
        return Err(cannot(
            format!("it is {}, not a regular file", what_it_is(&meta)),
            "put the file back (a regular file), or start stlc serve with another file",
        ));
    }
    if meta.len() > max_bytes {
        return Err(cannot(
            format!(
                "it has {} bytes, more than --max-input {max_bytes}",
                meta.len()
            ),
            &Bound::InputBytes.raise().spell(&stlc::api::Page::Served),
        ));
    }
    // The bytes read, the text made of them and the answer that carries it.
    let _reserved = match memory {
        Some(m) => Some(m.reserve_now(memory::file_need(meta.len())).map_err(|r| {
            cannot(
                memory::refusal(r),
                "try again in a moment, or start stlc serve with a larger --memory-budget",
            )
        })?),
        None => None,
    };
    let before = Stamp::of(&meta);
    let started = Instant::now();
    let mut bytes = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0));
    let mut chunk = vec![0u8; 1 << 16];
    loop {
        if started.elapsed() > READ_TIME {
            return Err(cannot(
                format!("reading it took more than {} s", READ_TIME.as_secs()),
                "check the disk or network the file is on",
            ));
        }
        let n = match file.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(io_error(&e, &format!("cannot read `{shown}`")).into()),
        };
        // It grew while read (another program writes it): at most one
        // chunk past the limit is ever held.
        if (bytes.len() + n) as u64 > max_bytes {
            return Err(cannot(
                format!("it grew past --max-input {max_bytes} bytes while read"),
                &Bound::InputBytes.raise().spell(&stlc::api::Page::Served),
            ));
        }
        bytes.extend_from_slice(&chunk[..n]);
    }
    let after = file.metadata().ok().map(|m| Stamp::of(&m));
    let stamp =
        (after.as_ref() == Some(&before) && before.len == bytes.len() as u64).then_some(before);
    Ok(Some(Served { bytes, stamp }))
}

/// Opens `path` for reading without waiting: a named pipe with no writer
/// would otherwise hold the thread until one comes.
fn open_without_blocking(path: &Path) -> std::io::Result<std::fs::File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY);
    }
    options.open(path)
}

/// What a file that is not a regular file is, in words.
fn what_it_is(m: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = m.file_type();
        if t.is_fifo() {
            return "a named pipe";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if m.is_dir() {
        "a folder"
    } else {
        "something else"
    }
}

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
    /// The memory budget reads reserve from.
    memory: Option<Arc<Memory>>,
    /// Saves one at a time, so the version check and the write are one step.
    saving: Mutex<()>,
    /// Who the file was when its version was last worked out, and that
    /// version: a watching page asks every second or so, and an unchanged
    /// file is then answered from its metadata, not read and hashed again.
    stamp: Mutex<Option<(Stamp, String)>>,
    /// How recent a change is not trusted to show in the metadata
    /// ([`RACY`]).
    racy: Duration,
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
            memory: None,
            saving: Mutex::new(()),
            stamp: Mutex::new(None),
            racy: RACY,
        }
    }

    /// The file at `path`, named `name`: read now to check that it can be
    /// edited (UTF-8 text of a known kind), or, if it does not exist yet,
    /// to be created from `template` on the first Save. Its reads reserve
    /// their memory from `memory`.
    pub fn file(
        path: PathBuf,
        name: &str,
        kind: InputKind,
        template: &'static str,
        max_bytes: u64,
        memory: Option<Arc<Memory>>,
    ) -> Result<Self, Diagnostics> {
        let doc = Document {
            path: Some(path),
            example: String::new(),
            name: name.to_string(),
            kind,
            template,
            max_bytes,
            memory,
            saving: Mutex::new(()),
            stamp: Mutex::new(None),
            racy: RACY,
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
        let Some(served) = read_served(path, self.max_bytes, self.memory.as_ref())? else {
            return Ok(Current {
                text: self.template.to_string(),
                version: None,
            });
        };
        let bytes = served.bytes;
        let v = version(&bytes);
        *self.stamp.lock().unwrap_or_else(|p| p.into_inner()) = served
            .stamp
            .filter(|s| self.settled(s, SystemTime::now()))
            .map(|s| (s, v.clone()));
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

    /// Whether a file last changed at `stamp`'s change time is told apart
    /// from any later change by its metadata, as seen at `now`: its change
    /// is older than [`RACY`] (a later write gets a later change time).
    fn settled(&self, stamp: &Stamp, now: SystemTime) -> bool {
        stamp
            .changed()
            .and_then(|c| now.duration_since(c).ok())
            .is_some_and(|age| age >= self.racy)
    }

    /// Whether the file is still at `known`, told from its metadata alone
    /// (device, inode, size, modification and change times) when they are
    /// those of the last read (a page watching the file asks every second
    /// or so). A changed modification time, or one set back, changes the
    /// change time; another file renamed into place is another inode.
    /// `false` means "read it": changed, or not known to be unchanged.
    pub fn unchanged_since(&self, known: &str) -> bool {
        let Some(path) = &self.path else {
            return version(self.example.as_bytes()) == known;
        };
        let stamp = self.stamp.lock().unwrap_or_else(|p| p.into_inner());
        match (std::fs::metadata(path), stamp.as_ref()) {
            (Ok(m), Some((s, v))) => Stamp::of(&m) == *s && v == known,
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
        // What is there must be a file to replace (or nothing): a named
        // pipe or device put in its place is refused, not written into.
        if let Ok(m) = std::fs::metadata(path)
            && !m.is_file()
        {
            return Err(Refused::Failed(
                Diagnostic::error(ErrorKind::Io {
                    doing: format!("cannot save `{}`", path.display()),
                    error: format!("it is {} now, not a regular file", what_it_is(&m)),
                })
                .with_help("put the file back (a regular file), then save again")
                .into(),
            ));
        }
        if let Some(base) = base {
            let now = read_served(path, self.max_bytes, self.memory.as_ref())
                .map_err(Refused::Failed)?
                .map(|s| version(&s.bytes));
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
        let d = Document::file(
            path.clone(),
            "t.od",
            InputKind::Od,
            "TEMPLATE\n",
            1 << 20,
            None,
        )
        .unwrap();
        (d, path)
    }

    fn message(d: &Diagnostics) -> String {
        d.iter()
            .map(|d| format!("{} ({})", d.kind, d.help_text().unwrap_or_default()))
            .collect()
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
        let (mut d, path) = doc(&dir);
        // Every change here is within the clock's tick of the last: trust
        // the metadata anyway (the next test shows why it is not).
        d.racy = Duration::ZERO;
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

    /// An edit of the same size whose modification time was set back
    /// (issue 36, problem 9) is noticed: at once, by the change time no
    /// program sets back (a change within the clock's tick of the read is
    /// read again), and by the inode when another file is renamed into
    /// place.
    #[test]
    fn a_same_size_edit_with_its_modification_time_set_back_is_noticed() {
        let dir = tempfile::tempdir().unwrap();
        let (mut d, path) = doc(&dir);
        std::fs::write(&path, "one\n").unwrap();
        let t = std::fs::metadata(&path).unwrap().modified().unwrap();
        let v = d.current().unwrap().version.unwrap();
        std::fs::write(&path, "two\n").unwrap();
        std::fs::File::options()
            .write(true)
            .open(&path)
            .unwrap()
            .set_modified(t)
            .unwrap();
        let m = std::fs::metadata(&path).unwrap();
        assert_eq!(
            (m.len(), m.modified().unwrap()),
            (4, t),
            "size and time as before"
        );
        assert!(!d.unchanged_since(&v), "the edit went unnoticed");
        assert_eq!(d.current().unwrap().version.unwrap(), version(b"two\n"));
        // Metadata trusted at once: another file renamed into place, of the
        // same size and time, is another inode.
        d.racy = Duration::ZERO;
        let w = d.current().unwrap().version.unwrap();
        assert!(d.unchanged_since(&w));
        let other = dir.path().join("other");
        std::fs::write(&other, "six\n").unwrap();
        std::fs::File::options()
            .write(true)
            .open(&other)
            .unwrap()
            .set_modified(t)
            .unwrap();
        std::fs::rename(&other, &path).unwrap();
        assert!(!d.unchanged_since(&w), "the renamed file went unnoticed");
    }

    /// The served file is read with bounds (issue 36, problems 2 and 3): a
    /// named pipe is refused at once (not waited on), a link to
    /// `/dev/zero` is refused as a device, a 10 GB sparse file by its size
    /// before a byte is read, and Save writes into none of them.
    #[test]
    fn only_a_regular_file_within_the_limit_is_read() {
        let dir = tempfile::tempdir().unwrap();
        let (d, path) = doc(&dir);
        let fifo = std::process::Command::new("mkfifo")
            .arg(&path)
            .status()
            .unwrap();
        assert!(fifo.success());
        let e = message(&d.current().err().unwrap());
        assert!(e.contains("it is a named pipe, not a regular file"), "{e}");
        let Err(Refused::Failed(e)) = d.save("x\n", None) else {
            panic!("saved into a named pipe");
        };
        assert!(message(&e).contains("a named pipe now"), "{}", message(&e));
        std::fs::remove_file(&path).unwrap();

        std::os::unix::fs::symlink("/dev/zero", &path).unwrap();
        let e = message(&d.current().err().unwrap());
        assert!(e.contains("it is a device, not a regular file"), "{e}");
        std::fs::remove_file(&path).unwrap();

        let sparse = std::fs::File::create(&path).unwrap();
        sparse.set_len(10 << 30).unwrap();
        let e = message(&d.current().err().unwrap());
        assert!(
            e.contains("it has 10737418240 bytes, more than --max-input 1048576")
                && e.contains("--max-input"),
            "{e}"
        );
        let Err(Refused::Failed(e)) = d.save("x\n", Some(Some("v"))) else {
            panic!("a save read the sparse file");
        };
        assert!(message(&e).contains("more than --max-input"));
        // Within the limit: read.
        sparse.set_len(1 << 20).unwrap();
        assert_eq!(d.current().unwrap().text.len(), 1 << 20);
    }

    /// Reading reserves the file's size from the memory budget: a file
    /// larger than one request may have is refused with the budget's
    /// words.
    #[test]
    fn reading_counts_against_the_memory_budget() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.od");
        std::fs::write(&path, vec![b'#'; 600]).unwrap();
        let memory = Arc::new(Memory::new(1000, None));
        let e = read_served(&path, 1 << 20, Some(&memory)).err().unwrap();
        assert!(
            message(&e).contains("more than one request may have"),
            "{}",
            message(&e)
        );
        std::fs::write(&path, vec![b'#'; 200]).unwrap();
        let read = read_served(&path, 1 << 20, Some(&memory)).unwrap().unwrap();
        assert_eq!(read.bytes.len(), 200);
    }

    #[test]
    fn versions_tell_texts_apart() {
        assert_eq!(version(b"abc"), version(b"abc"));
        assert_ne!(version(b"abc"), version(b"abd"));
        assert_ne!(version(b""), version(b"\n"));
    }
}
