//! Writing files safely: the one place where this crate (and the
//! `immerse` tool) creates, replaces or removes files.
//!
//! - Nothing is overwritten silently: [`check_output_dir`] refuses a
//!   non-empty folder and [`OutputFile`] an existing file unless `force` is
//!   set; both checks can run before any work.
//! - Nothing is half-written: a file is written to a temporary file in the
//!   same folder and renamed into place ([`OutputFile`], [`write_atomic`]),
//!   and a frame sequence is written to a temporary folder beside its
//!   folder and moved in when complete (`Staging`). The temporary names
//!   (`.immerse-*.tmp`) and the folders made by [`NewOutputDir`] are
//!   registered while they exist, so an interrupt handler can remove them
//!   with [`remove_partial_outputs`].
//! - `-` and `/dev/stdout` are standard output; special files (devices,
//!   FIFOs) are written through, never renamed over; symbolic links are
//!   followed ([`resolve_output`]).
//!
//! What is written (PNG sequences, GIFs, contact sheets, SVG, Lottie) is
//! the business of the other modules; they write through this one.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use crate::RenderError;

/// Paths that mean the process's standard output: `-` and `/dev/stdout`
/// (also `/dev/fd/1` and `/proc/self/fd/1`).
pub fn is_stdout(path: &Path) -> bool {
    let s = path.as_os_str();
    s == "-" || s == "/dev/stdout" || s == "/dev/fd/1" || s == "/proc/self/fd/1"
}

/// Where the bytes for one output path go, decided by [`resolve_output`].
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Destination {
    /// The process's standard output (`-`, `/dev/stdout`).
    Stdout,
    /// A special file (a device such as `/dev/null`, a FIFO, a socket, or a
    /// descriptor path such as `/dev/stderr`): written through, never
    /// renamed over, and never refused.
    Special(PathBuf),
    /// A regular file, new or existing, at this path with every symbolic
    /// link followed: written to a temporary file beside it and renamed
    /// into place, so the link (if any) stays a link.
    File(PathBuf),
}

/// Decides where the bytes for `path` go (see [`Destination`]); symbolic
/// links are followed, also when they dangle (the file is then created
/// where the link points).
///
/// # Errors
///
/// [`RenderError::Io`] for a link loop (more than 40 links) or an
/// unreadable link.
pub fn resolve_output(path: &Path) -> Result<Destination, RenderError> {
    if is_stdout(path) {
        return Ok(Destination::Stdout);
    }
    let s = path.to_string_lossy();
    if s == "/dev/stderr" || s.starts_with("/dev/fd/") || s.starts_with("/proc/self/fd/") {
        // Descriptor paths name whatever the descriptor is open on; never
        // rename over that.
        return Ok(Destination::Special(path.into()));
    }
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let target = std::fs::read_link(&p).map_err(|e| RenderError::io(path, e))?;
                p = match p.parent() {
                    Some(dir) if target.is_relative() => dir.join(target),
                    _ => target,
                };
            }
            Ok(meta) if meta.is_file() || meta.is_dir() => return Ok(Destination::File(p)),
            Ok(_) => return Ok(Destination::Special(p)),
            Err(_) => return Ok(Destination::File(p)),
        }
    }
    Err(RenderError::io(
        path,
        std::io::Error::other("too many levels of symbolic links"),
    ))
}

/// The folder a file at `path` is created in (`.` for a bare name).
fn parent_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// An OS error without the path tempfile attaches to it, so that messages
/// never show temporary names.
pub(crate) fn os_error(e: std::io::Error) -> std::io::Error {
    if let Some(code) = e.raw_os_error() {
        return std::io::Error::from_raw_os_error(code);
    }
    // tempfile wraps the OS error (with the path) as a custom error.
    let inner = e
        .get_ref()
        .and_then(|r| r.source())
        .and_then(|s| s.downcast_ref::<std::io::Error>())
        .and_then(std::io::Error::raw_os_error);
    match inner {
        Some(code) => std::io::Error::from_raw_os_error(code),
        None => std::io::Error::new(e.kind(), e.kind().to_string()),
    }
}

/// Checks that the folder of a new file at `path` exists and can be
/// written in, by creating and removing a temporary file there.
fn check_folder_writable(path: &Path, shown: &Path) -> Result<(), RenderError> {
    let folder = parent_of(path);
    match std::fs::metadata(folder) {
        Ok(meta) if meta.is_dir() => {}
        Ok(_) => {
            return Err(RenderError::NoFolder {
                path: shown.into(),
                folder: folder.into(),
            });
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(RenderError::NoFolder {
                path: shown.into(),
                folder: folder.into(),
            });
        }
        Err(e) => return Err(RenderError::io(shown, e)),
    }
    // Created and removed while the registry of partial outputs is held,
    // so an interrupt handler never exits between the two and leaves it.
    let pending = pending();
    pending
        .refuse_if_interrupted()
        .and_then(|()| temp_builder().tempfile_in(folder))
        .map(drop)
        .map_err(|e| RenderError::io(shown, os_error(e)))
}

/// Checks, before any work, that a file can be written at `path`: standard
/// output and special files always can; a regular file needs its folder to
/// exist and be writable, and an existing file needs `force`.
///
/// # Errors
///
/// [`RenderError::FileExists`], [`RenderError::IsADir`],
/// [`RenderError::NoFolder`], or [`RenderError::Io`] when the folder is not
/// writable.
pub fn check_output_file(path: &Path, force: bool) -> Result<(), RenderError> {
    match resolve_output(path)? {
        Destination::Stdout | Destination::Special(_) => Ok(()),
        Destination::File(real) => {
            match std::fs::metadata(&real) {
                Ok(meta) if meta.is_dir() => {
                    return Err(RenderError::IsADir { path: path.into() });
                }
                Ok(_) if !force => return Err(RenderError::FileExists { path: path.into() }),
                _ => {}
            }
            check_folder_writable(&real, path)
        }
    }
}

/// Checks, before any work, that a folder of frames can be written at
/// `dir`: a missing folder needs its parent to exist and be writable; an
/// existing one must be a folder, writable, and empty unless `force`.
///
/// # Errors
///
/// [`RenderError::DirNotEmpty`], [`RenderError::NotADir`],
/// [`RenderError::NoFolder`], or [`RenderError::Io`].
pub fn check_output_dir(dir: &Path, force: bool) -> Result<(), RenderError> {
    match std::fs::metadata(dir) {
        Ok(meta) if !meta.is_dir() => Err(RenderError::NotADir { path: dir.into() }),
        Ok(_) => {
            let mut entries = std::fs::read_dir(dir).map_err(|e| RenderError::io(dir, e))?;
            if !force && entries.next().is_some() {
                return Err(RenderError::DirNotEmpty { path: dir.into() });
            }
            // Frames are staged in a temporary folder inside it, then
            // moved into place.
            check_folder_writable(&dir.join("frame"), dir)
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => check_folder_writable(dir, dir),
        Err(e) => Err(RenderError::io(dir, e)),
    }
}

/// Temporary files and folders being written, removed by
/// [`remove_partial_outputs`] when the process is interrupted.
struct Pending {
    /// Set once [`remove_partial_outputs`] ran: no new temporary output may
    /// start.
    interrupted: bool,
    paths: Vec<PathBuf>,
}

static PENDING: Mutex<Pending> = Mutex::new(Pending {
    interrupted: false,
    paths: Vec::new(),
});

fn pending() -> MutexGuard<'static, Pending> {
    PENDING.lock().unwrap_or_else(PoisonError::into_inner)
}

impl Pending {
    fn forget(&mut self, path: &Path) {
        self.paths.retain(|p| p != path);
    }

    fn refuse_if_interrupted(&self) -> std::io::Result<()> {
        if self.interrupted {
            Err(std::io::Error::new(
                std::io::ErrorKind::Interrupted,
                "interrupted",
            ))
        } else {
            Ok(())
        }
    }
}

/// Removes every temporary file and folder an unfinished writer of this
/// crate holds (`.immerse-*.tmp`), and makes later writers fail; returns
/// how many were removed. Call it from a Ctrl-C or termination handler just
/// before the process exits, so that an interrupted run leaves nothing
/// half-written behind. Finished outputs are not touched.
pub fn remove_partial_outputs() -> usize {
    let mut pending = pending();
    pending.interrupted = true;
    let mut removed = 0;
    for p in std::mem::take(&mut pending.paths) {
        let gone = if p.is_dir() {
            std::fs::remove_dir_all(&p)
        } else {
            std::fs::remove_file(&p)
        };
        removed += usize::from(gone.is_ok());
    }
    // The guard is dropped here; a writer that starts later sees
    // `interrupted` and fails before creating anything.
    removed
}

/// The builder of temporary files (`folder` false) and folders: named
/// `.immerse-*.tmp`, with ordinary permissions (0666 or 0777 less the
/// umask), not the private 0600 or 0700 of temporary files, since they are
/// renamed into place.
fn temp_builder_for(folder: bool) -> tempfile::Builder<'static, 'static> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".immerse-").suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = if folder { 0o777 } else { 0o666 };
        builder.permissions(std::fs::Permissions::from_mode(mode));
    }
    #[cfg(not(unix))]
    let _ = folder;
    builder
}

fn temp_builder() -> tempfile::Builder<'static, 'static> {
    temp_builder_for(false)
}

enum Sink {
    Stdout(std::io::Stdout),
    Special(std::io::BufWriter<std::fs::File>),
    Temp {
        file: Option<std::io::BufWriter<tempfile::NamedTempFile>>,
        dest: PathBuf,
        force: bool,
    },
}

/// One output file being written: standard output, a special file written
/// through, or a temporary file renamed into place by
/// [`finish`](OutputFile::finish) (see [`Destination`]). Dropped without
/// `finish`, the temporary file is removed; so is it, by
/// [`remove_partial_outputs`], when the process is interrupted.
///
/// Write errors never name the temporary file.
///
/// # Examples
///
/// ```
/// use std::io::Write;
/// use immerse_render::OutputFile;
///
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("hello.txt");
/// let mut out = OutputFile::create(&path, false)?;
/// out.write_all(b"hello")?;
/// out.finish()?;
/// assert_eq!(std::fs::read(&path)?, b"hello");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct OutputFile {
    shown: PathBuf,
    sink: Sink,
}

impl std::fmt::Debug for OutputFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OutputFile")
            .field("path", &self.shown)
            .finish_non_exhaustive()
    }
}

impl OutputFile {
    /// Starts writing `path` (see [`Destination`]). Without `force` an
    /// existing regular file is refused, now and again when the file is put
    /// in place.
    ///
    /// # Errors
    ///
    /// As [`check_output_file`], or [`RenderError::Io`] when a special file
    /// cannot be opened.
    pub fn create(path: &Path, force: bool) -> Result<OutputFile, RenderError> {
        let sink = match resolve_output(path)? {
            Destination::Stdout => Sink::Stdout(std::io::stdout()),
            Destination::Special(p) => {
                let file = std::fs::OpenOptions::new()
                    .append(true)
                    .open(&p)
                    .map_err(|e| RenderError::io(path, e))?;
                Sink::Special(std::io::BufWriter::new(file))
            }
            Destination::File(dest) => {
                match std::fs::metadata(&dest) {
                    Ok(meta) if meta.is_dir() => {
                        return Err(RenderError::IsADir { path: path.into() });
                    }
                    Ok(_) if !force => return Err(RenderError::FileExists { path: path.into() }),
                    _ => {}
                }
                let folder = parent_of(&dest);
                if !folder.is_dir() {
                    return Err(RenderError::NoFolder {
                        path: path.into(),
                        folder: folder.into(),
                    });
                }
                let file = {
                    let mut pending = pending();
                    pending
                        .refuse_if_interrupted()
                        .and_then(|()| temp_builder().tempfile_in(folder))
                        .inspect(|file| pending.paths.push(file.path().into()))
                        .map_err(|e| RenderError::io(path, os_error(e)))?
                };
                Sink::Temp {
                    file: Some(std::io::BufWriter::with_capacity(1 << 16, file)),
                    dest,
                    force,
                }
            }
        };
        Ok(OutputFile {
            shown: path.into(),
            sink,
        })
    }

    /// Flushes the data and puts the file in place.
    ///
    /// # Errors
    ///
    /// [`RenderError::FileExists`] when, without `force`, a file appeared
    /// at the path meanwhile, or [`RenderError::Io`]. Nothing is left
    /// behind on error.
    pub fn finish(mut self) -> Result<(), RenderError> {
        let io = |e: std::io::Error| RenderError::io(&self.shown, os_error(e));
        match &mut self.sink {
            Sink::Stdout(out) => out.flush().map_err(io),
            Sink::Special(out) => out.flush().map_err(io),
            Sink::Temp { file, dest, force } => {
                let Some(buffered) = file.take() else {
                    return Ok(());
                };
                let tmp = buffered.into_inner().map_err(|e| io(e.into_error()))?;
                let mut pending = pending();
                let tmp_path = tmp.path().to_path_buf();
                let persisted = if *force {
                    tmp.persist(&*dest)
                } else {
                    tmp.persist_noclobber(&*dest)
                };
                // On failure the returned temporary file is dropped, which
                // deletes it, before the registry forgets it.
                let result = persisted.map(drop).map_err(|e| {
                    if e.error.kind() == std::io::ErrorKind::AlreadyExists {
                        RenderError::FileExists {
                            path: self.shown.clone(),
                        }
                    } else {
                        RenderError::io(&self.shown, os_error(e.error))
                    }
                });
                pending.forget(&tmp_path);
                result
            }
        }
    }
}

impl Write for OutputFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match &mut self.sink {
            Sink::Stdout(out) => out.write(buf),
            Sink::Special(out) => out.write(buf),
            Sink::Temp { file, .. } => match file {
                Some(f) => f.write(buf).map_err(os_error),
                None => Ok(0),
            },
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match &mut self.sink {
            Sink::Stdout(out) => out.flush(),
            Sink::Special(out) => out.flush(),
            Sink::Temp { file, .. } => match file {
                Some(f) => f.flush().map_err(os_error),
                None => Ok(()),
            },
        }
    }
}

impl Drop for OutputFile {
    fn drop(&mut self) {
        if let Sink::Temp { file, .. } = &mut self.sink
            && let Some(buffered) = file.take()
        {
            let mut pending = pending();
            let tmp_path = buffered.get_ref().path().to_path_buf();
            // Dropping the temporary file deletes it.
            drop(buffered.into_parts().0);
            pending.forget(&tmp_path);
        }
    }
}

/// Writes `bytes` to `path` with an [`OutputFile`]: a regular file is
/// written to a temporary file in its folder and renamed into place
/// (symbolic links are followed); `-` and `/dev/stdout` are standard
/// output; special files are written through. Without `force` an existing
/// regular file is refused (and left untouched, even if it appears
/// meanwhile).
///
/// # Errors
///
/// As [`OutputFile::create`] and [`OutputFile::finish`]. On error no
/// temporary file is left behind.
pub fn write_atomic(path: &Path, bytes: &[u8], force: bool) -> Result<(), RenderError> {
    let mut out = OutputFile::create(path, force)?;
    out.write_all(bytes)
        .map_err(|e| RenderError::io(path, os_error(e)))?;
    out.finish()
}

/// A folder created for this run's output, removed again unless
/// [`keep`](NewOutputDir::keep) is called (also when the process is
/// interrupted, by [`remove_partial_outputs`]).
#[derive(Debug)]
pub struct NewOutputDir {
    path: Option<PathBuf>,
}

impl NewOutputDir {
    /// Creates the folder `dir`, whose parent must exist.
    ///
    /// # Errors
    ///
    /// [`RenderError::NoFolder`] or [`RenderError::Io`] (also when `dir`
    /// exists).
    pub fn create(dir: &Path) -> Result<NewOutputDir, RenderError> {
        let parent = parent_of(dir);
        if !parent.is_dir() {
            return Err(RenderError::NoFolder {
                path: dir.into(),
                folder: parent.into(),
            });
        }
        let mut pending = pending();
        pending
            .refuse_if_interrupted()
            .and_then(|()| std::fs::create_dir(dir))
            .map_err(|e| RenderError::io(dir, e))?;
        pending.paths.push(dir.into());
        Ok(NewOutputDir {
            path: Some(dir.into()),
        })
    }

    /// Keeps the folder and everything in it.
    pub fn keep(mut self) {
        if let Some(p) = self.path.take() {
            pending().forget(&p);
        }
    }
}

impl Drop for NewOutputDir {
    fn drop(&mut self) {
        if let Some(p) = self.path.take() {
            let mut pending = pending();
            let _ = std::fs::remove_dir_all(&p);
            pending.forget(&p);
        }
    }
}

/// A temporary folder in which a sequence is written, then moved into
/// place by [`Staging::commit`]: beside a new output folder (which it then
/// becomes), or inside an existing one (so that moving the files never
/// crosses file systems, even through a symbolic link).
pub(crate) struct Staging {
    dir: Option<tempfile::TempDir>,
}

impl Staging {
    pub(crate) fn create(dest: &Path) -> Result<Staging, RenderError> {
        let parent = if dest.is_dir() { dest } else { parent_of(dest) };
        let mut pending = pending();
        let dir = pending
            .refuse_if_interrupted()
            .and_then(|()| temp_builder_for(true).tempdir_in(parent))
            .map_err(|e| RenderError::io(dest, os_error(e)))?;
        pending.paths.push(dir.path().into());
        Ok(Staging { dir: Some(dir) })
    }

    pub(crate) fn path(&self) -> &Path {
        self.dir.as_ref().map_or(Path::new("."), |d| d.path())
    }

    /// Puts the staged files `names` into `dest`: a missing folder is the
    /// staging folder renamed; into an existing one each file is moved,
    /// replacing its namesake, and then every older `frame_N.ext` of
    /// this tool's naming that is not one of `names` is removed, so that no
    /// stale frame of an earlier, longer run is left.
    pub(crate) fn commit(
        mut self,
        dest: &Path,
        names: &[String],
        ext: &str,
    ) -> Result<(), RenderError> {
        let Some(dir) = self.dir.take() else {
            return Ok(());
        };
        let mut pending = pending();
        let staged = dir.path().to_path_buf();
        let io = |e: std::io::Error| RenderError::io(dest, os_error(e));
        let result = if std::fs::symlink_metadata(dest).is_err() {
            std::fs::rename(&staged, dest).map_err(io).map(|()| {
                // Renamed: nothing is left to clean up.
                let _ = dir.keep();
            })
        } else {
            let moved = names.iter().try_for_each(|name| {
                std::fs::rename(staged.join(name), dest.join(name)).map_err(io)
            });
            drop(dir);
            moved.and_then(|()| remove_stale_frames(dest, names, ext))
        };
        pending.forget(&staged);
        result
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if let Some(dir) = self.dir.take() {
            let mut pending = pending();
            let staged = dir.path().to_path_buf();
            drop(dir);
            pending.forget(&staged);
        }
    }
}

/// True for `frame_` + digits + `.ext`: the names [`frame_file_name`]
/// gives.
fn is_frame_name(name: &str, ext: &str) -> bool {
    name.strip_prefix("frame_")
        .and_then(|rest| rest.strip_suffix(ext))
        .and_then(|rest| rest.strip_suffix('.'))
        .is_some_and(|digits| !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
}

/// Removes the `frame_N.ext` files in `dir` that are not in `keep`.
fn remove_stale_frames(dir: &Path, keep: &[String], ext: &str) -> Result<(), RenderError> {
    let keep: std::collections::HashSet<&str> = keep.iter().map(String::as_str).collect();
    let entries = std::fs::read_dir(dir).map_err(|e| RenderError::io(dir, e))?;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if is_frame_name(name, ext)
            && !keep.contains(name)
            && entry.file_type().is_ok_and(|t| t.is_file())
        {
            std::fs::remove_file(entry.path()).map_err(|e| RenderError::io(entry.path(), e))?;
        }
    }
    Ok(())
}

/// The file name of frame `i` of `n`: `frame_0000.ext`, zero-padded to at
/// least four digits (more when `n` needs them).
pub fn frame_file_name(i: usize, n: usize, ext: &str) -> String {
    let digits = n.saturating_sub(1).to_string().len().max(4);
    format!("frame_{i:0digits$}.{ext}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_padded() {
        assert_eq!(frame_file_name(7, 120, "png"), "frame_0007.png");
        assert_eq!(frame_file_name(7, 10_001, "svg"), "frame_00007.svg");
        assert_eq!(frame_file_name(0, 0, "png"), "frame_0000.png");
    }
}
