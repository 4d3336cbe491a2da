//! Reading a scene's input files (the scene and its point lists) with a cap
//! on their size, so that an endless file (`/dev/zero`, a pipe that keeps
//! writing) is refused instead of filling the memory.

use std::io::Read;
use std::path::Path;

/// The environment variable that sets the cap, in bytes.
pub const MAX_INPUT_BYTES_VARIABLE: &str = "MPDEM_MAX_INPUT_BYTES";

/// The default cap on an input file's size: 1 GiB, room for a point list
/// of the largest scene (2·10⁷ points at about 40 bytes a line).
pub const DEFAULT_MAX_INPUT_BYTES: u64 = 1 << 30;

/// The cap on an input file's size: [`MAX_INPUT_BYTES_VARIABLE`] if set,
/// else [`DEFAULT_MAX_INPUT_BYTES`]; the variable set to anything but a
/// number of bytes is an error, not a silent default.
pub fn max_input_bytes() -> std::io::Result<u64> {
    match std::env::var(MAX_INPUT_BYTES_VARIABLE) {
        Err(std::env::VarError::NotPresent) => Ok(DEFAULT_MAX_INPUT_BYTES),
        Ok(value) => value.trim().parse().map_err(|_| {
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!("{MAX_INPUT_BYTES_VARIABLE} is '{value}', not a number of bytes"),
            )
        }),
        Err(std::env::VarError::NotUnicode(_)) => Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("{MAX_INPUT_BYTES_VARIABLE} is not text, not a number of bytes"),
        )),
    }
}

/// The text of the file at `path`, read up to the cap; a larger file, or
/// one that is not UTF-8, is an error that says so.
pub fn read_input(path: &Path) -> std::io::Result<String> {
    let cap = max_input_bytes()?;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(cap.saturating_add(1))
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "larger than the {cap} bytes an input file may have ({MAX_INPUT_BYTES_VARIABLE} sets the cap)"
            ),
        ));
    }
    String::from_utf8(bytes).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()),
        )
    })
}
