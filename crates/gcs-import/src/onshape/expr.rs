//! Onshape's quantity expressions (`15 mm`, `(0.5/2)*inch`, `45.0 deg`, `(71.374+30) mm`),
//! evaluated exactly.
//!
//! SketchGraphs' files keep a dimension only as the expression the user typed: the numeric
//! `value` field of every quantity is 0. The expression is a small arithmetic language over
//! decimals and units; this module evaluates it over the rationals, carrying the physical
//! dimension (length, angle) so that `2*(0.5*inch)` is a length and `45 deg` an angle. Lengths
//! come out in millimetres (an inch is exactly 25.4 mm), angles in degrees; a radian is
//! 180/π degrees, which is irrational: it is taken as the shortest decimal of the double
//! nearest it, the only inexact step. Variables (`#width`), functions and anything else give
//! `None` with a reason.

use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::ir::Number;

/// What a dimension measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Measure {
    /// A length, in millimetres.
    Length,
    /// An angle, in degrees.
    Angle,
}

/// Evaluates `text` as a quantity of kind `measure`: `Ok(value in mm or degrees)`, or `Err`
/// with why it cannot be read.
pub(super) fn evaluate(text: &str, measure: Measure) -> Result<Number, String> {
    let tokens = tokenize(text)?;
    let mut parser = Parser { tokens: &tokens, pos: 0, depth: 0 };
    let q = parser.expr()?;
    if parser.pos != tokens.len() {
        return Err(format!("unexpected text in the expression `{text}`"));
    }
    let want = match measure {
        Measure::Length => (1, 0),
        Measure::Angle => (0, 1),
    };
    if (q.length, q.angle) == (0, 0) {
        return Err(format!(
            "the expression `{text}` has no unit (the document's default unit is not in the file)"
        ));
    }
    if (q.length, q.angle) != want {
        let what = match measure {
            Measure::Length => "a length",
            Measure::Angle => "an angle",
        };
        return Err(format!("the expression `{text}` is not {what}"));
    }
    Ok(Number(q.value))
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Num(BigRational),
    Ident(String),
    Op(char),
}

fn tokenize(text: &str) -> Result<Vec<Token>, String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            // An exponent only when digits follow (`2e3`), so that `2em` is not misread.
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    while j < chars.len() && chars[j].is_ascii_digit() {
                        j += 1;
                    }
                    i = j;
                }
            }
            let literal: String = chars[start..i].iter().collect();
            let value = Number::parse(&literal)
                .ok_or_else(|| format!("bad number `{literal}` in the expression"))?;
            out.push(Token::Num(value.0));
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push(Token::Ident(chars[start..i].iter().collect()));
        } else if "+-*/()".contains(c) {
            out.push(Token::Op(c));
            i += 1;
        } else if c == '#' {
            let start = i;
            i += 1;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            let name: String = chars[start..i].iter().collect();
            return Err(format!(
                "the expression uses the variable `{name}`, whose value is not in the file"
            ));
        } else {
            return Err(format!("unsupported character `{c}` in the expression"));
        }
    }
    Ok(out)
}

/// A value with its physical dimension: length^`length` · angle^`angle`.
#[derive(Clone, Debug)]
struct Quantity {
    value: BigRational,
    length: i32,
    angle: i32,
}

impl Quantity {
    fn scalar(value: BigRational) -> Quantity {
        Quantity { value, length: 0, angle: 0 }
    }
}

/// Nesting limit: the parser recurses on parentheses and unary signs.
const MAX_DEPTH: usize = 64;

struct Parser<'t> {
    tokens: &'t [Token],
    pos: usize,
    depth: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.pos)
    }

    fn expr(&mut self) -> Result<Quantity, String> {
        let mut acc = self.term()?;
        while let Some(Token::Op(op @ ('+' | '-'))) = self.peek() {
            let op = *op;
            self.pos += 1;
            let rhs = self.term()?;
            if (acc.length, acc.angle) != (rhs.length, rhs.angle) {
                return Err("the expression adds quantities of different units".into());
            }
            acc.value = if op == '+' { acc.value + rhs.value } else { acc.value - rhs.value };
        }
        Ok(acc)
    }

    fn term(&mut self) -> Result<Quantity, String> {
        let mut acc = self.factor()?;
        loop {
            let divide = match self.peek() {
                Some(Token::Op('*')) => {
                    self.pos += 1;
                    false
                }
                Some(Token::Op('/')) => {
                    self.pos += 1;
                    true
                }
                // Juxtaposition multiplies: `15 mm`, `(1/2) in`.
                Some(Token::Ident(_) | Token::Op('(')) => false,
                _ => return Ok(acc),
            };
            let rhs = self.factor()?;
            if divide {
                if rhs.value.is_zero() {
                    return Err("division by zero in the expression".into());
                }
                acc.value /= rhs.value;
                acc.length -= rhs.length;
                acc.angle -= rhs.angle;
            } else {
                acc.value *= rhs.value;
                acc.length += rhs.length;
                acc.angle += rhs.angle;
            }
            if acc.length.abs() > 8 || acc.angle.abs() > 8 {
                return Err("the expression's units are out of range".into());
            }
        }
    }

    fn factor(&mut self) -> Result<Quantity, String> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err("the expression is nested too deeply".into());
        }
        let result = self.factor_inner();
        self.depth -= 1;
        result
    }

    fn factor_inner(&mut self) -> Result<Quantity, String> {
        let token = self.peek().cloned().ok_or("the expression ends too early")?;
        self.pos += 1;
        match token {
            Token::Op('-') => {
                let mut q = self.factor()?;
                q.value = -q.value;
                Ok(q)
            }
            Token::Op('+') => self.factor(),
            Token::Op('(') => {
                let q = self.expr()?;
                match self.peek() {
                    Some(Token::Op(')')) => {
                        self.pos += 1;
                        Ok(q)
                    }
                    _ => Err("unbalanced parentheses in the expression".into()),
                }
            }
            Token::Num(value) => Ok(Quantity::scalar(value)),
            Token::Ident(name) => unit(&name),
            Token::Op(c) => Err(format!("unexpected `{c}` in the expression")),
        }
    }
}

/// A unit as a quantity: lengths in millimetres, angles in degrees.
fn unit(name: &str) -> Result<Quantity, String> {
    let ratio = |n: i64, d: i64| BigRational::new(n.into(), d.into());
    let length = |value: BigRational| Ok(Quantity { value, length: 1, angle: 0 });
    match name {
        "mm" | "millimeter" | "millimeters" | "millimetre" | "millimetres" => {
            length(BigRational::one())
        }
        "cm" | "centimeter" | "centimeters" | "centimetre" | "centimetres" => length(ratio(10, 1)),
        "m" | "meter" | "meters" | "metre" | "metres" => length(ratio(1000, 1)),
        "um" | "micron" | "microns" | "micrometer" | "micrometers" | "micrometre"
        | "micrometres" => length(ratio(1, 1000)),
        "in" | "inch" | "inches" => length(ratio(127, 5)),
        "ft" | "foot" | "feet" => length(ratio(1524, 5)),
        "yd" | "yard" | "yards" => length(ratio(4572, 5)),
        "deg" | "degree" | "degrees" => {
            Ok(Quantity { value: BigRational::one(), length: 0, angle: 1 })
        }
        "rad" | "radian" | "radians" => {
            let per_radian = Number::from_f64(180.0 / std::f64::consts::PI).ok_or("radian")?;
            Ok(Quantity { value: per_radian.0, length: 0, angle: 1 })
        }
        _ => Err(format!("unknown unit or function `{name}` in the expression")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mm(text: &str) -> Result<Number, String> {
        evaluate(text, Measure::Length)
    }

    #[test]
    fn lengths_are_exact_millimetres() {
        assert_eq!(mm("15 mm"), Ok(Number::parse("15").unwrap()));
        assert_eq!(mm("10.284 mm"), Ok(Number::parse("10.284").unwrap()));
        assert_eq!(mm(".5 in"), Ok(Number::parse("12.7").unwrap()));
        assert_eq!(mm("(1/8)*inch"), Ok(Number::parse("3.175").unwrap()));
        assert_eq!(mm("(71.374+30) mm"), Ok(Number::parse("101.374").unwrap()));
        assert_eq!(mm("2*(0.5*inch)"), Ok(Number::parse("25.4").unwrap()));
        assert_eq!(mm("7.2*millimeter"), Ok(Number::parse("7.2").unwrap()));
        assert_eq!(mm("1.5cm"), Ok(Number::parse("15").unwrap()));
        assert_eq!(mm("2in"), Ok(Number::parse("50.8").unwrap()));
        assert_eq!(mm("-1 mm"), Ok(Number::parse("-1").unwrap()));
        assert_eq!(mm("1e-3*m"), Ok(Number::parse("1").unwrap()));
        assert_eq!(
            mm("0.24999999999999997*in"),
            Ok(Number::parse("6.34999999999999923800").unwrap())
        );
    }

    #[test]
    fn angles_are_degrees() {
        assert_eq!(evaluate("120.0*degree", Measure::Angle), Ok(Number::parse("120").unwrap()));
        assert_eq!(evaluate("45.0 deg", Measure::Angle), Ok(Number::parse("45").unwrap()));
        let right = evaluate("1.5707963267948966*rad", Measure::Angle).unwrap().to_f64();
        assert!((right - 90.0).abs() < 1e-9);
    }

    #[test]
    fn what_cannot_be_read_says_why() {
        assert!(mm("#VentDiam").unwrap_err().contains("#VentDiam"));
        assert!(mm("(#id+9)*millimeter").unwrap_err().contains("#id"));
        assert!(mm("12").unwrap_err().contains("no unit"));
        assert!(mm("12 deg").unwrap_err().contains("not a length"));
        assert!(mm("12 mm + 1 deg").is_err());
        assert!(mm("sqrt(2) mm").is_err());
        assert!(mm("1 mm / 0").is_err());
        assert!(mm("((1 mm)").is_err());
        assert!(mm("1 mm)").is_err());
        assert!(mm("").is_err());
        assert!(mm(&"(".repeat(10_000)).is_err());
        assert!(mm(&"-".repeat(10_000)).is_err());
        assert!(mm("1e999999999 mm").is_err());
        assert!(mm("mm*mm*mm*mm*mm*mm*mm*mm*mm*mm").is_err());
    }
}
