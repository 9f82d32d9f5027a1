//! The crate's single error type.

/// Everything that can go wrong in `gcs-rank`.
///
/// Mathematical outcomes (rank deficiency, dependent rows) are results, never errors: an error
/// means an input could not be represented or an argument was out of range.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum RankError {
    /// A rational number has no image in a prime field because the prime divides its
    /// denominator.
    #[error("the prime {prime} divides the denominator of {value}: it has no image modulo {prime}")]
    DenominatorDivisibleByPrime {
        /// The modulus of the prime field.
        prime: u64,
        /// The rational number, written as `n/d` (shortened when very long).
        value: String,
    },
    /// A rational number cannot be represented in the target field (for `f64`: it overflows to
    /// an infinity).
    #[error("{value} cannot be represented in the {field} field")]
    NotRepresentable {
        /// [`Field::NAME`](crate::Field::NAME) of the target field.
        field: &'static str,
        /// The rational number, written as `n/d` (shortened when very long).
        value: String,
    },
    /// A column index is not below the number of columns.
    #[error("column {col} is out of range: the matrix has {ncols} columns")]
    ColumnOutOfRange {
        /// The offending column index.
        col: usize,
        /// The number of columns of the matrix.
        ncols: usize,
    },
}

/// Writes a rational for an error message, shortened to at most about 80 characters.
pub(crate) fn describe(value: &impl std::fmt::Display) -> String {
    let text = value.to_string();
    if text.len() <= 80 {
        text
    } else {
        let head: String = text.chars().take(38).collect();
        let tail: String = {
            let rev: Vec<char> = text.chars().rev().take(38).collect();
            rev.into_iter().rev().collect()
        };
        format!("{head}…{tail} ({} characters)", text.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_values_are_shortened_in_messages() {
        assert_eq!(describe(&"-3/4"), "-3/4");
        let long = "7".repeat(500);
        let short = describe(&long);
        assert!(short.len() < 120, "{short}");
        assert!(short.ends_with("(500 characters)"));
        let error = RankError::DenominatorDivisibleByPrime { prime: 5, value: "1/5".into() };
        assert_eq!(
            error.to_string(),
            "the prime 5 divides the denominator of 1/5: it has no image modulo 5"
        );
    }
}
