//! Readers of CAD sketch files into gcs models.
//!
//! Three formats are read into one neutral sketch form ([`ir::Sketch`]), which
//! [`lower`] turns into [`gcs_model::System`]s:
//! - SolveSpace `.slvs` ([`slvs`]),
//! - FreeCAD `.FCStd` ([`freecad`]),
//! - Onshape sketch features as JSON, as SketchGraphs distributes them ([`onshape`]).
//!
//! A library: it never panics on input and never prints.

pub mod error;
pub mod freecad;
pub mod ir;
pub mod lower;
pub mod onshape;
pub mod slvs;

pub use error::ImportError;
pub use lower::{Lowered, lower};

/// A format this crate reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// SolveSpace `.slvs`.
    Slvs,
    /// FreeCAD `.FCStd`.
    FreeCad,
    /// Onshape sketch features as JSON.
    Onshape,
}

impl Format {
    /// The format of a file: by extension (`.slvs`, `.fcstd` in any case, `.json`), then by
    /// content (the SolveSpace header, a zip's magic number, a JSON array or object). `None`
    /// for anything else (a gcs `.ron` model among them).
    pub fn detect(path: &str, bytes: &[u8]) -> Option<Format> {
        let lower = path.to_ascii_lowercase();
        if lower.ends_with(".slvs") {
            return Some(Format::Slvs);
        }
        if lower.ends_with(".fcstd") {
            return Some(Format::FreeCad);
        }
        if lower.ends_with(".json") {
            return Some(Format::Onshape);
        }
        if lower.ends_with(".ron") {
            return None;
        }
        let head = &bytes[..bytes.len().min(64)];
        if head.windows(b"SolveSpaceREV".len()).any(|w| w == b"SolveSpaceREV") {
            return Some(Format::Slvs);
        }
        if head.starts_with(b"PK\x03\x04") {
            return Some(Format::FreeCad);
        }
        match head.iter().find(|b| !b.is_ascii_whitespace()) {
            Some(b'[' | b'{') => Some(Format::Onshape),
            _ => None,
        }
    }
}

/// Reads every sketch of a file in `format`. `file` names it in errors and gives the file stem
/// of the model names.
///
/// # Errors
/// An [`ImportError`] naming the file, the position and the element when the file cannot be
/// read at all; items that cannot be expressed are listed in each sketch's `skipped` instead.
pub fn read(format: Format, file: &str, bytes: &[u8]) -> Result<Vec<ir::Sketch>, ImportError> {
    match format {
        Format::Slvs => slvs::read(file, bytes),
        Format::FreeCad => freecad::read(file, bytes),
        Format::Onshape => onshape::read(file, bytes),
    }
}

/// The file stem of `file` (`dir/Bielle.FCStd` → `Bielle`), for model names.
pub fn file_stem(file: &str) -> String {
    std::path::Path::new(file)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| file.to_owned())
}

/// Reads every sketch of a file (format detected by [`Format::detect`]) and lowers each into a
/// gcs model.
///
/// # Errors
/// An [`ImportError`] when the format is not recognised or the file cannot be read at all.
pub fn import(file: &str, bytes: &[u8]) -> Result<Vec<Lowered>, ImportError> {
    let format = Format::detect(file, bytes).ok_or_else(|| {
        ImportError::new(
            file,
            "not a SolveSpace, FreeCAD or Onshape sketch file (by extension or content)",
        )
    })?;
    Ok(read(format, file, bytes)?.iter().map(lower).collect())
}
