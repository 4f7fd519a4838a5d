//! Inputs and outputs: `-` for stdin/stdout, size limits, atomic writes.
//!
//! Every output file is written to a temporary file in the target's
//! directory and renamed over the target only when complete, so a failure
//! never leaves a truncated file or clobbers the previous one, and no
//! temporary file is left behind (it is deleted when dropped). A symbolic
//! link is followed and the file it names is replaced, so the link stays.
//! A new file gets the usual mode (0666 less the umask), a replaced one
//! keeps its mode.
//! A target that is neither a file nor a directory (`/dev/null`, a named
//! pipe, a terminal) is written straight into: renaming a file over it
//! would replace the device or pipe itself.

use std::fs;
use std::io::{self, BufWriter, IsTerminal, Read, Write};
use std::path::{Path, PathBuf};

use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, InputError, io_error};
use stlc::pipeline::Bound;

use super::error::FrontEndError;

/// Whether `output` names the same file as `input` (the same device and
/// inode, which covers links, different spellings of one path, and
/// standard input redirected from the output file: `- -o g.od < g.od`, or
/// `-o /dev/stdin`). An output that does not exist yet is no input, and
/// neither is standard input that is no regular file (a pipe, a terminal).
pub fn same_file(input: &Input, output: &Output) -> bool {
    let Output::Path(o) = output else {
        return false;
    };
    let input = match input {
        Input::Path(i) => fs::metadata(i),
        Input::Stdin => stdin_metadata()
            .filter(|m| m.is_file())
            .ok_or_else(|| io::Error::other("standard input is no file")),
    };
    match (input, fs::metadata(o)) {
        (Ok(a), Ok(b)) => same_inode(&a, &b),
        _ => false,
    }
}

/// What standard input is (the file it was redirected from, a pipe...),
/// if it is open.
#[cfg(unix)]
fn stdin_metadata() -> Option<fs::Metadata> {
    use std::os::fd::AsFd;
    let fd = io::stdin().as_fd().try_clone_to_owned().ok()?;
    fs::File::from(fd).metadata().ok()
}

#[cfg(not(unix))]
fn stdin_metadata() -> Option<fs::Metadata> {
    None
}

#[cfg(unix)]
fn same_inode(a: &fs::Metadata, b: &fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    a.dev() == b.dev() && a.ino() == b.ino()
}

#[cfg(not(unix))]
fn same_inode(_a: &fs::Metadata, _b: &fs::Metadata) -> bool {
    false
}

/// Where input comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Input {
    /// Standard input (`-`).
    Stdin,
    /// A file.
    Path(PathBuf),
}

impl Input {
    /// `-` is stdin, anything else a path.
    pub fn parse(s: &str) -> Input {
        if s == "-" {
            Input::Stdin
        } else {
            Input::Path(PathBuf::from(s))
        }
    }

    /// The name diagnostics show.
    pub fn display_name(&self) -> String {
        match self {
            Input::Stdin => "<stdin>".to_string(),
            Input::Path(p) => p.display().to_string(),
        }
    }

    /// Reads the whole input, refusing more than `limit` bytes without
    /// reading further.
    pub fn read(&self, limit: u64) -> Result<Vec<u8>, Diagnostics> {
        let mut buf = Vec::new();
        let res = match self {
            Input::Stdin => io::stdin().lock().take(limit + 1).read_to_end(&mut buf),
            Input::Path(p) => {
                std::fs::File::open(p).and_then(|f| f.take(limit + 1).read_to_end(&mut buf))
            }
        };
        if let Err(e) = res {
            let what = match self {
                Input::Stdin => "cannot read standard input".to_string(),
                Input::Path(p) => format!("cannot read `{}`", p.display()),
            };
            let mut d = Diagnostic::error(ErrorKind::Io {
                doing: what,
                error: e.to_string(),
            });
            if e.kind() == io::ErrorKind::NotFound {
                d = d.with_help("check the path; `-` reads standard input");
            }
            return Err(d.into());
        }
        if buf.len() as u64 > limit {
            return Err(Diagnostic::error(InputError::InputTooLarge {
                size: buf.len() as u64,
                limit,
            })
            .with_help(Bound::InputBytes.raise())
            .into());
        }
        Ok(buf)
    }
}

/// Where output goes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Output {
    /// Standard output (`-`).
    Stdout,
    /// A file, written atomically.
    Path(PathBuf),
}

impl Output {
    /// `-` is stdout, anything else a path.
    pub fn parse(s: &str) -> Output {
        if s == "-" {
            Output::Stdout
        } else {
            Output::Path(PathBuf::from(s))
        }
    }

    /// Whether this is a terminal (binary output there is refused).
    pub fn is_terminal(&self) -> bool {
        matches!(self, Output::Stdout) && io::stdout().is_terminal()
    }

    /// Runs `write` against this output. A file is written to a temporary
    /// file beside it and renamed into place only if `write` succeeds.
    pub fn write_with(
        &self,
        write: impl FnOnce(&mut dyn Write) -> Result<(), Diagnostics>,
    ) -> Result<(), Diagnostics> {
        match self {
            Output::Stdout => {
                let stdout = io::stdout();
                let mut w = BufWriter::with_capacity(STDOUT_HELD, stdout.lock());
                if let Err(e) = write(&mut w) {
                    // Dropping the writer would flush what it holds: a
                    // failure in the first STDOUT_HELD bytes writes none.
                    let _ = w.into_parts();
                    return Err(e);
                }
                w.flush()
                    .map_err(|e| io_error(&e, "cannot write to standard output"))?;
                Ok(())
            }
            Output::Path(target) => write_atomically(target, write),
        }
    }
}

/// Bytes held back from standard output before the first write: a
/// command that fails before it has made this much (a limit met midway
/// through an SVG) writes nothing there, as a file output is never
/// created. Past it, output streams, and the exit status tells a failure.
const STDOUT_HELD: usize = 1 << 20;

/// Symbolic links followed before writing, at most (as many as Linux follows).
const MAX_SYMLINK_HOPS: usize = 40;

/// The path a write to `target` lands on: `target` with every symbolic link
/// followed, even a dangling one (writing creates the file it names).
fn resolve_links(target: &Path) -> Result<PathBuf, Diagnostics> {
    let mut path = target.to_path_buf();
    for _ in 0..MAX_SYMLINK_HOPS {
        match fs::symlink_metadata(&path) {
            Ok(m) if m.file_type().is_symlink() => {
                let link = fs::read_link(&path)
                    .map_err(|e| io_error(&e, &format!("cannot read link `{}`", path.display())))?;
                path = match path.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(path),
        }
    }
    Err(Diagnostic::error(FrontEndError::TooManyLinks {
        path: target.display().to_string(),
        hops: MAX_SYMLINK_HOPS,
    })
    .with_help("point -o at the file itself")
    .into())
}

/// How a temporary file of process `pid` begins (`.stlc-PID-`): a process
/// killed (SIGKILL, a power cut) while writing leaves it behind, and
/// [`sweep_stale_temps`] knows it by the process that is gone.
fn temp_prefix(pid: u32) -> String {
    format!(".stlc-{pid}-")
}

const TEMP_SUFFIX: &str = ".tmp";

/// Removes from `dir` the temporary files of stlc processes that no longer
/// run (where `/proc` tells which run; elsewhere nothing is removed).
/// Returns how many were removed. `stlc serve FILE` calls it on FILE's
/// folder when it starts: a save killed midway leaves nothing for long.
pub fn sweep_stale_temps(dir: &Path) -> usize {
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return 0;
    }
    let Ok(entries) = fs::read_dir(dir) else {
        return 0;
    };
    let mut removed = 0;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name
            .to_str()
            .and_then(|n| n.strip_prefix(".stlc-"))
            .filter(|n| n.ends_with(TEMP_SUFFIX))
            .and_then(|n| n.split_once('-'))
            .and_then(|(pid, _)| pid.parse::<u32>().ok())
        else {
            continue;
        };
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && !proc.join(pid.to_string()).exists() && fs::remove_file(entry.path()).is_ok()
        {
            removed += 1;
        }
    }
    removed
}

fn write_atomically(
    target: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    let target = &resolve_links(target)?;
    // What is there now: nothing, a file to replace, or something else.
    let existing = fs::metadata(target).ok();
    match &existing {
        Some(m) if m.is_dir() => {
            return Err(Diagnostic::error(FrontEndError::IsADirectory {
                path: target.display().to_string(),
            })
            .with_help("give a file name with -o, e.g. -o tree.png")
            .into());
        }
        Some(m) if !m.is_file() => return write_in_place(target, write),
        _ => {}
    }
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let mut builder = tempfile::Builder::new();
    let prefix = temp_prefix(std::process::id());
    builder.prefix(&prefix).suffix(TEMP_SUFFIX);
    // A new file gets the usual mode (0666 less the umask), not the 0600 of
    // a temporary file; a replaced file keeps its own mode below.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let tmp = builder.tempfile_in(&dir).map_err(|e| {
        // tempfile's message names the temporary file; the user named the
        // target, so say what the system said about the directory.
        let error = match fs::metadata(&dir) {
            Err(missing) => missing.to_string(),
            Ok(m) if !m.is_dir() => "not a directory".to_string(),
            Ok(_) => io::Error::from(e.kind()).to_string(),
        };
        Diagnostic::error(FrontEndError::CannotCreate {
            path: target.display().to_string(),
            dir: dir.display().to_string(),
            error,
        })
        .with_help("check that the directory exists and is writable")
    })?;
    let _pending = super::interrupt::Pending::new(tmp.path().to_path_buf());
    write_temp(tmp, existing, target, write)
}

/// Fills the temporary file and renames it over `target`.
fn write_temp(
    tmp: tempfile::NamedTempFile,
    existing: Option<fs::Metadata>,
    target: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    if let Some(meta) = existing {
        tmp.as_file()
            .set_permissions(meta.permissions())
            .map_err(|e| io_error(&e, &format!("cannot write `{}`", target.display())))?;
    }
    let mut w = BufWriter::with_capacity(1 << 16, tmp);
    write(&mut w)?;
    let tmp = w
        .into_inner()
        .map_err(|e| io_error(e.error(), &format!("cannot write `{}`", target.display())))?;
    tmp.as_file()
        .sync_all()
        .map_err(|e| io_error(&e, &format!("cannot write `{}`", target.display())))?;
    tmp.persist(target).map_err(|e| {
        Diagnostic::error(FrontEndError::CannotReplace {
            path: target.display().to_string(),
            error: e.error.to_string(),
        })
    })?;
    Ok(())
}

/// Writes into a device or named pipe as it is: there is no file to replace.
fn write_in_place(
    target: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    let cannot = |e: &io::Error| io_error(e, &format!("cannot write `{}`", target.display()));
    let file = fs::OpenOptions::new()
        .write(true)
        .open(target)
        .map_err(|e| cannot(&e))?;
    let mut w = BufWriter::with_capacity(1 << 16, file);
    write(&mut w)?;
    w.flush().map_err(|e| cannot(&e))?;
    Ok(())
}

/// `tree.od` with a new extension: the default output beside the input.
pub fn sibling(input: &Input, extension: &str) -> Option<Output> {
    match input {
        Input::Stdin => None,
        Input::Path(p) => Some(Output::Path(p.with_extension(extension))),
    }
}
