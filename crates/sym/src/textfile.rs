//! Reading a text input file: the one reader of every file a command takes
//! as input (derivations, notes manifests, scenes, CSV clouds).
//!
//! - The bytes are decoded as UTF-8 (a leading byte-order mark is dropped);
//!   a file that is not is an error at the line and column of its first
//!   bad byte, and a UTF-16 file is named as such ("save it as UTF-8").
//! - Every file read is recorded as an input of this process
//!   ([`inputs`]): `hdot_num::fsio` refuses to write over any of them, so
//!   no command can destroy a file it reads.
//!
//! This crate holds it (and not `hdot-num`) because it is the lowest crate
//! that reads files: the derivation loader reads through it too.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The files this process has read through [`read`] (absolute paths).
static INPUTS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// A file that could not be read or decoded.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReadError {
    /// The file, as given.
    pub path: PathBuf,
    /// Where in the file: the byte offset of the first byte that is not
    /// UTF-8, and the file decoded with that byte (and any later bad one)
    /// replaced by U+FFFD, for a snippet. `None` when the file as a whole
    /// is at fault (it cannot be read, or it is UTF-16).
    pub at: Option<(usize, String)>,
    /// What is wrong.
    pub message: String,
    /// The kind of I/O error when the file could not be read at all.
    pub io: Option<std::io::ErrorKind>,
}

impl ReadError {
    /// The 1-based line and column (in characters) of [`ReadError::at`].
    pub fn line_column(&self) -> Option<(usize, usize)> {
        let (offset, text) = self.at.as_ref()?;
        let before = &text[..*offset];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Some((
            before.matches('\n').count() + 1,
            before[line_start..].chars().count() + 1,
        ))
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line_column() {
            Some((l, c)) => write!(f, "{}:{l}:{c}: {}", self.path.display(), self.message),
            None => write!(f, "{}: {}", self.path.display(), self.message),
        }
    }
}

impl std::error::Error for ReadError {}

/// Reads the text file at `path` (see the module documentation) and
/// records it as an input of this process.
pub fn read(path: &Path) -> Result<String, ReadError> {
    let bytes = std::fs::read(path).map_err(|e| ReadError {
        path: path.to_path_buf(),
        at: None,
        message: format!("cannot read the file: {e}"),
        io: Some(e.kind()),
    })?;
    record_input(path);
    decode(path, bytes)
}

/// Decodes the bytes of a text file; `path` names it in errors.
///
/// # Example
/// ```
/// use hdot_sym::textfile::decode;
/// let e = decode("a.toml".as_ref(), b"x = 1\ny = \"\xff\"\n".to_vec()).unwrap_err();
/// assert_eq!(e.to_string(), "a.toml:2:6: the file is not UTF-8 text: byte 0xFF (byte 12 of the file) is not part of a UTF-8 character; save the file as UTF-8");
/// let e = decode("a.toml".as_ref(), b"\xff\xfex\x00".to_vec()).unwrap_err();
/// assert!(e.to_string().contains("the file is UTF-16"));
/// assert_eq!(decode("a.toml".as_ref(), b"\xef\xbb\xbfx = 1".to_vec()).unwrap(), "x = 1");
/// ```
pub fn decode(path: &Path, mut bytes: Vec<u8>) -> Result<String, ReadError> {
    if bytes.starts_with(b"\xef\xbb\xbf") {
        bytes.drain(..3);
    }
    if let Some(order) = utf16(&bytes) {
        return Err(ReadError {
            path: path.to_path_buf(),
            at: None,
            message: format!("the file is UTF-16 ({order}), not UTF-8 text; save it as UTF-8"),
            io: None,
        });
    }
    String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let bytes = e.into_bytes();
        ReadError {
            path: path.to_path_buf(),
            message: format!(
                "the file is not UTF-8 text: byte 0x{:02X} (byte {} of the file) is not part of a UTF-8 character; save the file as UTF-8",
                bytes[offset],
                offset + 1
            ),
            at: Some((offset, String::from_utf8_lossy(&bytes).into_owned())),
            io: None,
        }
    })
}

/// Whether `bytes` look like UTF-16: a byte-order mark, or a zero byte in
/// every other place of the first characters (ASCII text saved as UTF-16
/// without a mark). Returns the byte order.
fn utf16(bytes: &[u8]) -> Option<&'static str> {
    if bytes.starts_with(b"\xff\xfe") {
        return Some("little-endian");
    }
    if bytes.starts_with(b"\xfe\xff") {
        return Some("big-endian");
    }
    let head = &bytes[..bytes.len().min(64) & !1];
    if head.len() < 4 {
        return None;
    }
    let zero_at = |parity: usize| head.iter().skip(parity).step_by(2).all(|&b| b == 0);
    let text_at = |parity: usize| head.iter().skip(parity).step_by(2).all(|&b| b != 0);
    if zero_at(1) && text_at(0) {
        Some("little-endian")
    } else if zero_at(0) && text_at(1) {
        Some("big-endian")
    } else {
        None
    }
}

/// Records `path` as an input of this process (done by [`read`]; for a
/// reader that cannot read through it).
pub fn record_input(path: &Path) {
    let p = std::fs::canonicalize(path)
        .or_else(|_| std::path::absolute(path))
        .unwrap_or_else(|_| path.to_path_buf());
    let mut inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
    if !inputs.contains(&p) {
        inputs.push(p);
    }
}

/// The files this process has read as inputs (absolute paths), in the
/// order first read.
pub fn inputs() -> Vec<PathBuf> {
    INPUTS.lock().unwrap_or_else(|e| e.into_inner()).clone()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bad_byte_is_located_and_utf16_is_named() {
        let p = Path::new("f.toml");
        let e = decode(
            p,
            "α = 1\n\tβ\u{e9}\x01".bytes().chain([0xC3, b'x']).collect(),
        )
        .unwrap_err();
        assert_eq!(e.line_column(), Some((2, 5)));
        for text in ["title = \"x\"\n", "a"] {
            let le: Vec<u8> = text.encode_utf16().flat_map(u16::to_le_bytes).collect();
            let be: Vec<u8> = text.encode_utf16().flat_map(u16::to_be_bytes).collect();
            let with_mark = [vec![0xFF, 0xFE], le.clone()].concat();
            assert!(decode(p, with_mark).unwrap_err().message.contains("UTF-16"));
            if text.len() > 2 {
                assert!(decode(p, le).unwrap_err().message.contains("little-endian"));
                assert!(decode(p, be).unwrap_err().message.contains("big-endian"));
            }
        }
        assert_eq!(decode(p, b"ok\n".to_vec()).unwrap(), "ok\n");
    }

    #[test]
    fn a_file_read_is_recorded_as_an_input() {
        let dir = std::env::temp_dir().join(format!("hdot-textfile-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("in.txt");
        std::fs::write(&f, "x").unwrap();
        assert_eq!(read(&f).unwrap(), "x");
        let canonical = std::fs::canonicalize(&f).unwrap();
        assert!(inputs().contains(&canonical));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
