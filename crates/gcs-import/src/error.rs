//! The error type of the readers.

use std::fmt;

/// Why a file could not be read. Names the file (when known), the element (a record, an XML
/// element, a JSON path, with the source's own id where it has one) and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ImportError {
    /// The file, as given to the reader (may be empty when reading bytes without a name).
    pub file: String,
    /// Where in the file: a line (1-based) when the format has lines, else `None`.
    pub line: Option<usize>,
    /// The element: `Constraint 7`, `Sketch005/Constrain[12]`, `features[3].entities[2]`, …
    pub element: Option<String>,
    /// What is wrong.
    pub message: String,
}

impl ImportError {
    /// An error about `file` with a message and no position yet.
    pub fn new(file: &str, message: impl Into<String>) -> ImportError {
        ImportError { file: file.to_owned(), line: None, element: None, message: message.into() }
    }

    /// The same error at `line`.
    pub fn at_line(mut self, line: usize) -> ImportError {
        self.line = Some(line);
        self
    }

    /// The same error in `element`.
    pub fn in_element(mut self, element: impl Into<String>) -> ImportError {
        self.element = Some(element.into());
        self
    }
}

impl fmt::Display for ImportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(if self.file.is_empty() { "<input>" } else { &self.file })?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if let Some(element) = &self.element {
            write!(f, ": {element}")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for ImportError {}
