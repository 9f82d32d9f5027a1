//! Exact numbers: decimals read as the rationals they denote, rationals written back exactly.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

/// Parses a decimal numeral (`-12`, `3.1623`, `1.5e-3`, `+7`, `.5`) or a fraction (`-2/3`,
/// `1.5/7`) as the exact rational it denotes. Surrounding whitespace is allowed.
///
/// Returns `None` for anything else (including `inf` and `NaN`).
///
/// # Example
/// ```
/// use gcs_model::number::parse_exact;
/// use num_rational::BigRational;
/// assert_eq!(parse_exact("0.1"), Some(BigRational::new(1.into(), 10.into())));
/// assert_eq!(parse_exact("-2/6"), Some(BigRational::new((-1).into(), 3.into())));
/// ```
pub fn parse_exact(text: &str) -> Option<BigRational> {
    let text = text.trim();
    if let Some((num, den)) = text.split_once('/') {
        let num = parse_decimal(num.trim())?;
        let den = parse_decimal(den.trim())?;
        if den.is_zero() {
            return None;
        }
        return Some(num / den);
    }
    parse_decimal(text)
}

fn parse_decimal(text: &str) -> Option<BigRational> {
    let (negative, body) = match text.as_bytes().first()? {
        b'-' => (true, &text[1..]),
        b'+' => (false, &text[1..]),
        _ => (false, text),
    };
    let (mantissa, exponent) = match body.find(['e', 'E']) {
        Some(i) => (&body[..i], body[i + 1..].parse::<i64>().ok()?),
        None => (body, 0),
    };
    let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    if int_part.is_empty() && frac_part.is_empty() {
        return None;
    }
    let digits_ok = |s: &str| s.bytes().all(|b| b.is_ascii_digit() || b == b'_');
    if !digits_ok(int_part) || !digits_ok(frac_part) {
        return None;
    }
    let frac_len = frac_part.bytes().filter(|b| *b != b'_').count() as i64;
    let scale = exponent.checked_sub(frac_len)?;
    if let Some(value) = small_decimal(int_part, frac_part, scale) {
        return Some(if negative { -value } else { value });
    }
    let digits: String = int_part.chars().chain(frac_part.chars()).filter(|c| *c != '_').collect();
    if digits.is_empty() {
        return None;
    }
    let mantissa: BigInt = digits.parse().ok()?;
    // Refuse absurd exponents instead of allocating huge powers of ten.
    if scale.unsigned_abs() > 10_000 {
        return None;
    }
    let ten = BigInt::from(10u32);
    let power = num_traits::pow(ten, scale.unsigned_abs() as usize);
    let mut value = if scale >= 0 {
        BigRational::from_integer(mantissa * power)
    } else {
        BigRational::new(mantissa, power)
    };
    if negative {
        value = -value;
    }
    Some(value)
}

/// `digits · 10^scale` (the digits of `int_part` then `frac_part`, ASCII digits and `_`) in
/// lowest terms without big-integer arithmetic, when the digits fit in 36 decimal places and
/// `|scale| ≤ 36` (CAD coordinates: `12.3456789` is 123456789 / 10^7); `None` otherwise, and for
/// no digits at all. The denominator of a decimal is a power of ten, so the only common factors
/// are twos and fives: dividing them out leaves the fraction in lowest terms, the value
/// `BigRational::new` would give after its gcd.
fn small_decimal(int_part: &str, frac_part: &str, scale: i64) -> Option<BigRational> {
    let mut mantissa: u128 = 0;
    let mut count = 0;
    for b in int_part.bytes().chain(frac_part.bytes()).filter(|b| *b != b'_') {
        count += 1;
        if count > 36 {
            return None;
        }
        mantissa = mantissa * 10 + u128::from(b - b'0');
    }
    if count == 0 || scale.unsigned_abs() > 36 {
        return None;
    }
    let k = scale.unsigned_abs() as u32;
    if scale >= 0 {
        let value = mantissa.checked_mul(10u128.checked_pow(k)?)?;
        return Some(BigRational::from_integer(value.into()));
    }
    if mantissa == 0 {
        return Some(BigRational::from_integer(0.into()));
    }
    let twos = mantissa.trailing_zeros().min(k);
    mantissa >>= twos;
    let mut fives = 0;
    while fives < k && mantissa.is_multiple_of(5) {
        mantissa /= 5;
        fives += 1;
    }
    let denominator = (1u128 << (k - twos)) * 5u128.pow(k - fives);
    Some(BigRational::new_raw(mantissa.into(), denominator.into()))
}

/// The exact rational a finite `f64` read from a model file stands for: the shortest decimal
/// that round-trips to it (so `3.1623` read as a double gives exactly 31623/10000). Decimals
/// written with at most 15 significant digits are therefore recovered exactly.
///
/// Returns `None` for infinities and NaN.
pub fn rational_from_f64_decimal(x: f64) -> Option<BigRational> {
    if !x.is_finite() {
        return None;
    }
    // `Display` for f64 prints the shortest representation that round-trips, never in
    // exponent notation.
    parse_decimal(&format!("{x}"))
}

/// The square root of a non-negative rational: exact when it is rational (a quotient of perfect
/// squares), else the shortest decimal of the double nearest it. `None` for a negative number.
///
/// # Example
/// ```
/// use gcs_model::number::{parse_exact, sqrt_rational};
/// assert_eq!(sqrt_rational(&parse_exact("6.25").unwrap()), parse_exact("2.5"));
/// assert_eq!(sqrt_rational(&parse_exact("2").unwrap()), parse_exact("1.4142135623730951"));
/// ```
pub fn sqrt_rational(q: &BigRational) -> Option<BigRational> {
    if q.is_negative() {
        return None;
    }
    let (n, d) = (q.numer().sqrt(), q.denom().sqrt());
    if &(&n * &n) == q.numer() && &(&d * &d) == q.denom() {
        return Some(BigRational::new(n, d));
    }
    use num_traits::ToPrimitive;
    rational_from_f64_decimal(q.to_f64()?.sqrt())
}

/// Writes a rational the way a model file holds it: an integer, a terminating decimal, or (when
/// the decimal expansion does not terminate) a quoted fraction `"p/q"`, which the reader
/// accepts too. A decimal with more significant digits than a double holds (such as
/// `85.351177000000007`) is quoted as well: bare numbers are read through a double.
///
/// # Example
/// ```
/// use gcs_model::number::{format_exact, parse_exact};
/// for s in ["7", "-0.125", "\"1/3\"", "\"85.351177000000007\""] {
///     let q = parse_exact(s.trim_matches('"')).unwrap();
///     assert_eq!(format_exact(&q), s);
/// }
/// ```
pub fn format_exact(q: &BigRational) -> String {
    if q.is_integer() {
        return q.numer().to_string();
    }
    let den = q.denom().clone();
    let (mut twos, mut fives) = (0u32, 0u32);
    let mut rest = den.clone();
    let two = BigInt::from(2u32);
    let five = BigInt::from(5u32);
    while rest.is_even() {
        rest /= &two;
        twos += 1;
    }
    while (&rest % &five).is_zero() {
        rest /= &five;
        fives += 1;
    }
    if !rest.is_one() {
        return format!("\"{}/{}\"", q.numer(), q.denom());
    }
    let places = twos.max(fives);
    let scale = num_traits::pow(BigInt::from(10u32), places as usize);
    let scaled = (q.numer() * &scale) / q.denom();
    let negative = scaled.is_negative();
    let digits = scaled.abs().to_string();
    let places = places as usize;
    let padded = if digits.len() <= places {
        format!("{}{}", "0".repeat(places + 1 - digits.len()), digits)
    } else {
        digits
    };
    let (int, frac) = padded.split_at(padded.len() - places);
    let decimal = format!("{}{}.{}", if negative { "-" } else { "" }, int, frac);
    // A bare number in RON is read through a double: a decimal with more digits than a double
    // keeps (FreeCAD writes 17) is quoted, so that it reads back exactly.
    match decimal.parse::<f64>().ok().and_then(rational_from_f64_decimal) {
        Some(back) if &back == q => decimal,
        _ => format!("\"{decimal}\""),
    }
}

/// A number as written in a model file, before validation: exact when it could be read
/// exactly, or the non-finite double the parser produced.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Num {
    Exact(BigRational),
    NonFinite,
    /// A string that is not a number.
    Invalid(String),
}

impl<'de> serde::Deserialize<'de> for Num {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = Num;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a number (integer, decimal, or a string \"p/q\")")
            }
            fn visit_i64<E>(self, v: i64) -> Result<Num, E> {
                Ok(Num::Exact(BigRational::from_integer(v.into())))
            }
            fn visit_u64<E>(self, v: u64) -> Result<Num, E> {
                Ok(Num::Exact(BigRational::from_integer(v.into())))
            }
            fn visit_i128<E>(self, v: i128) -> Result<Num, E> {
                Ok(Num::Exact(BigRational::from_integer(v.into())))
            }
            fn visit_u128<E>(self, v: u128) -> Result<Num, E> {
                Ok(Num::Exact(BigRational::from_integer(v.into())))
            }
            fn visit_f64<E>(self, v: f64) -> Result<Num, E> {
                Ok(rational_from_f64_decimal(v).map_or(Num::NonFinite, Num::Exact))
            }
            fn visit_str<E>(self, v: &str) -> Result<Num, E> {
                Ok(parse_exact(v).map_or_else(|| Num::Invalid(v.to_owned()), Num::Exact))
            }
        }
        d.deserialize_any(V)
    }
}

/// `BigRational` from a small integer ratio; a convenience for tests and generators.
///
/// # Panics
/// Panics when `den` is zero (a programming error, never user input).
pub fn ratio(num: i64, den: i64) -> BigRational {
    BigRational::new(num.into(), den.into())
}

/// `BigRational` from an integer.
pub fn int(v: i64) -> BigRational {
    BigRational::from_integer(v.into())
}

/// Whether a rational is zero, a helper for callers that do not import `num_traits`.
pub fn is_zero(q: &BigRational) -> bool {
    q.is_zero()
}

/// One, as a rational.
pub fn one() -> BigRational {
    BigRational::one()
}

/// The precision a dimension is written with: half a unit of its last decimal (`3.1623`:
/// 0.00005); an integer or a fraction is meant exactly (to rounding: 1e-9 of its magnitude).
/// Shared by the drawing's check (gcs-analysis) and the solver's verdict on redundant
/// dimensions (gcs-solve).
pub fn written_precision(value: &BigRational) -> f64 {
    let magnitude = num_traits::ToPrimitive::to_f64(&value.abs()).unwrap_or(0.0);
    let rounding = 1e-9 * magnitude.max(1.0);
    let mut den = value.denom().clone();
    let mut places = 0;
    let ten = num_bigint::BigInt::from(10);
    let (two, five) = (num_bigint::BigInt::from(2), num_bigint::BigInt::from(5));
    // A terminating decimal has a denominator 2^a 5^b: it has max(a, b) places.
    let (mut a, mut b) = (0, 0);
    while (&den % &two).is_zero() {
        den /= &two;
        a += 1;
    }
    while (&den % &five).is_zero() {
        den /= &five;
        b += 1;
    }
    if den == num_bigint::BigInt::from(1) {
        places = a.max(b);
    }
    if places == 0 {
        return rounding;
    }
    let unit =
        1.0 / num_traits::ToPrimitive::to_f64(&ten.pow(places as u32)).unwrap_or(f64::INFINITY);
    (0.5 * unit).max(rounding)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_decimals_match_the_big_integer_path() {
        // The fast path against `BigRational::new` (gcd) on the cases that reduce: trailing
        // zeros, powers of two and five, negative numbers, exponents, 36 digits.
        let cases = [
            "0",
            "0.0",
            "-0.000",
            "1",
            "10",
            "12.3456789",
            "-85.945909214",
            "0.5",
            "0.25",
            "0.125",
            "0.2",
            "0.04",
            "0.008",
            "1.6",
            "7.2",
            "80.622971058",
            "1_000.000_5",
            "2.5e3",
            "2.5e-3",
            "-1.25E-1",
            "123456789012345678901234567890.123456",
            "0.000000000000000000000000000000000001",
            "3.0e36",
            "999999999999999999999999999999999999",
        ];
        for text in cases {
            let (negative, body) = match text.strip_prefix('-') {
                Some(rest) => (true, rest),
                None => (false, text),
            };
            let (mantissa, exponent) = match body.find(['e', 'E']) {
                Some(i) => (&body[..i], body[i + 1..].parse::<i64>().unwrap()),
                None => (body, 0),
            };
            let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
            let digits: String = format!("{int_part}{frac_part}").replace('_', "");
            let scale = exponent - frac_part.replace('_', "").len() as i64;
            let m: BigInt = digits.parse().unwrap();
            let p = num_traits::pow(BigInt::from(10), scale.unsigned_abs() as usize);
            let mut want =
                if scale >= 0 { BigRational::from_integer(m * p) } else { BigRational::new(m, p) };
            if negative {
                want = -want;
            }
            let got = parse_exact(text).unwrap();
            assert_eq!(got, want, "{text}");
            // Lowest terms, positive denominator: the same parts as after a gcd.
            assert_eq!((got.numer(), got.denom()), (want.numer(), want.denom()), "{text}");
        }
    }

    #[test]
    fn decimals_are_exact() {
        assert_eq!(parse_exact("3.1623"), Some(ratio(31623, 10000)));
        assert_eq!(parse_exact("-0.5"), Some(ratio(-1, 2)));
        assert_eq!(parse_exact("1e3"), Some(int(1000)));
        assert_eq!(parse_exact("1.5E-2"), Some(ratio(3, 200)));
        assert_eq!(parse_exact(".25"), Some(ratio(1, 4)));
        assert_eq!(parse_exact("7."), Some(int(7)));
        assert_eq!(parse_exact("1_000"), Some(int(1000)));
        assert_eq!(parse_exact(" 4/6 "), Some(ratio(2, 3)));
        for bad in ["", "-", ".", "e3", "1/0", "inf", "NaN", "1.2.3", "abc", "1e99999"] {
            assert_eq!(parse_exact(bad), None, "{bad}");
        }
    }

    #[test]
    fn doubles_map_back_to_their_decimal() {
        for (x, q) in [(0.1, ratio(1, 10)), (3.1623, ratio(31623, 10000)), (-2.0, int(-2))] {
            assert_eq!(rational_from_f64_decimal(x), Some(q));
        }
        assert_eq!(rational_from_f64_decimal(f64::INFINITY), None);
        assert_eq!(rational_from_f64_decimal(f64::NAN), None);
    }

    #[test]
    fn formatting_round_trips() {
        for q in [int(0), int(-3), ratio(1, 8), ratio(-7, 20), ratio(1, 3), ratio(-22, 7)] {
            let s = format_exact(&q);
            assert_eq!(parse_exact(s.trim_matches('"')), Some(q.clone()), "{s}");
        }
        assert_eq!(format_exact(&ratio(-7, 20)), "-0.35");
        assert_eq!(format_exact(&ratio(1, 3)), "\"1/3\"");
        assert_eq!(format_exact(&ratio(1, 1000)), "0.001");
    }
}
