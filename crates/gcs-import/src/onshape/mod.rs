//! Reader: not yet written.

use crate::{ImportError, ir};

/// Reads every sketch of the file.
///
/// # Errors
/// See [`crate::read`].
pub fn read(file: &str, _bytes: &[u8]) -> Result<Vec<ir::Sketch>, ImportError> {
    Err(ImportError::new(file, "this format's reader is not written yet"))
}
