//! Reading input files: the one place that opens a file brdfbake was given (a preset, a
//! texture or sidecar to read back, a MERL file, an engine's shipped table). It refuses what
//! is not a regular file before opening it — a FIFO would block the open forever, a device
//! such as /dev/zero would stream without end — and reads at most the size its format
//! allows, so no input can hang the process or exhaust its memory.

use std::io::Read;
use std::path::Path;

/// Why an input file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// Bad input: missing, not a regular file, or larger than its format allows (exit 2).
    #[error("{0}")]
    Input(String),
    /// The file exists but reading it failed (exit 1).
    #[error("{0}")]
    Io(String),
}

/// What a file type is, for messages: "a directory", "a FIFO", "a character device", ...
pub fn kind_of(t: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a directory"
    } else if t.is_symlink() {
        "a link"
    } else if t.is_file() {
        "a regular file"
    } else {
        "something other than a file"
    }
}

/// Reads the regular file `path` of at most `max_bytes`. `what` names what was expected, for
/// messages (`"a preset .json file"`).
pub fn read_regular(path: &Path, max_bytes: u64, what: &str) -> Result<Vec<u8>, InputError> {
    let p = path.display();
    // metadata does not open the file: safe on a FIFO
    let meta = std::fs::metadata(path).map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            InputError::Input(format!("{p}: no such file"))
        } else {
            InputError::Io(format!("cannot read {p}: {e}"))
        }
    })?;
    if meta.is_dir() {
        return Err(InputError::Input(format!(
            "{p}: is a directory; give {what}"
        )));
    }
    if !meta.is_file() {
        return Err(InputError::Input(format!(
            "{p}: not a regular file (a device, FIFO or socket?); give {what}"
        )));
    }
    let too_large = |len: u64| {
        InputError::Input(format!(
            "{p}: {len} bytes is larger than {what} can be (at most {max_bytes} bytes)"
        ))
    };
    if meta.len() > max_bytes {
        return Err(too_large(meta.len()));
    }
    // at most one byte past the limit: a file may grow while it is read, or (in /proc)
    // report a length of 0
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(path)
        .and_then(|f| f.take(max_bytes + 1).read_to_end(&mut bytes))
        .map_err(|e| InputError::Io(format!("cannot read {p}: {e}")))?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// The first `n` bytes (fewer if the file is shorter) of the regular file `path`, or `None`
/// when it is not a readable regular file (never opened then: safe on a FIFO).
pub fn read_head(path: &Path, n: u64) -> Option<Vec<u8>> {
    if !std::fs::metadata(path).ok()?.is_file() {
        return None;
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(n).read_to_end(&mut bytes))
        .ok()?;
    Some(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_what_is_not_a_bounded_regular_file() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("a");
        std::fs::write(&f, b"12345").unwrap();
        assert_eq!(read_regular(&f, 5, "x").unwrap(), b"12345");
        let e = read_regular(&f, 4, "a thing").unwrap_err().to_string();
        assert!(e.contains("larger than a thing can be"), "{e}");
        let e = read_regular(dir.path(), 10, "a thing")
            .unwrap_err()
            .to_string();
        assert!(e.contains("is a directory"), "{e}");
        let e = read_regular(&dir.path().join("b"), 10, "x").unwrap_err();
        assert!(matches!(e, InputError::Input(_)) && e.to_string().contains("no such file"));
        #[cfg(unix)]
        {
            let e = read_regular(Path::new("/dev/zero"), 10, "x")
                .unwrap_err()
                .to_string();
            assert!(e.contains("not a regular file"), "{e}");
            let fifo = dir.path().join("fifo");
            let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
            // SAFETY: a valid NUL-terminated path.
            assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
            let e = read_regular(&fifo, 10, "x").unwrap_err().to_string();
            assert!(e.contains("not a regular file"), "{e}");
        }
    }
}
