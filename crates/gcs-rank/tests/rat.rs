//! `Rat` against `BigRational` as an oracle: random sequences of operations run on both in
//! parallel must give the same values, with `Rat` in canonical form after every step.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use gcs_rank::{BigRational, Field, ModP, Rat};
use num_bigint::BigInt;
use num_traits::{Signed, ToPrimitive};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

const MIN: i64 = i64::MIN;
const MAX: i64 = i64::MAX;

fn config(cases: u32, seed: u64) -> Config {
    Config { cases, rng_seed: RngSeed::Fixed(seed), failure_persistence: None, ..Config::default() }
}

fn numerator() -> impl Strategy<Value = i64> {
    prop_oneof![
        4 => -20i64..=20,
        2 => any::<i64>(),
        2 => prop::sample::select(vec![
            MIN, MIN + 1, -(1 << 62), -(1 << 32), -1, 0, 1, 1 << 31, 1 << 32, 1 << 62, MAX - 1, MAX,
        ]),
    ]
}

fn denominator() -> impl Strategy<Value = i64> {
    prop_oneof![
        4 => 1i64..=12,
        2 => 1i64..=MAX,
        2 => prop::sample::select(vec![1, 2, 3, 1 << 31, (1 << 32) + 1, 1 << 62, MAX - 1, MAX]),
    ]
}

/// A rational of 65 to 192 bits: always stored big.
fn huge() -> impl Strategy<Value = BigRational> {
    (any::<[u64; 3]>(), 1u64.., 0u32..=2, any::<bool>()).prop_map(|(digits, den, shift, neg)| {
        let mut n = BigInt::from(digits[0] | 1 << 63);
        for d in &digits[1..] {
            n = (n << 64) + d;
        }
        let n = if neg { -n } else { n };
        BigRational::new(n, BigInt::from(den) << (64 * shift))
    })
}

/// An operand as a `BigRational`: small fractions, boundary values, any `i64` pair, huge.
fn operand() -> impl Strategy<Value = BigRational> {
    let small = (numerator(), denominator())
        .prop_map(|(n, d)| BigRational::new(BigInt::from(n), BigInt::from(d)));
    prop_oneof![5 => small, 1 => huge()]
}

#[derive(Clone, Debug)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
    AddAssign,
    SubAssign,
    MulAssign,
    DivAssign,
    Neg,
    Abs,
    Recip,
    /// `x -= a·b` ([`Field::sub_mul_assign`]) with the operand and a second one.
    SubMul(BigRational),
    /// `x = (x·a) / a`, which must come back to `x`.
    RoundTrip,
    /// `x = (x·x).sqrt_exact()`.
    Square,
    /// Replace `x` by the operand (restarts a chain that grew large).
    Set,
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        Just(Op::Add),
        Just(Op::Sub),
        Just(Op::Mul),
        Just(Op::Div),
        Just(Op::AddAssign),
        Just(Op::SubAssign),
        Just(Op::MulAssign),
        Just(Op::DivAssign),
        Just(Op::Neg),
        Just(Op::Abs),
        Just(Op::Recip),
        operand().prop_map(Op::SubMul),
        Just(Op::RoundTrip),
        Just(Op::Square),
        Just(Op::Set),
    ]
}

fn hash_of(x: &Rat) -> u64 {
    let mut h = DefaultHasher::new();
    x.hash(&mut h);
    h.finish()
}

fn fits(q: &BigRational) -> bool {
    q.numer().to_i64().is_some() && q.denom().to_i64().is_some()
}

/// Checks `x` against the oracle `y`: same value, canonical form, same text.
fn agree(x: &Rat, y: &BigRational, step: usize) -> Result<(), TestCaseError> {
    prop_assert_eq!(&x.to_big(), y, "step {}: value", step);
    prop_assert_eq!(x.is_small(), fits(y), "step {}: small iff it fits ({})", step, y);
    let rebuilt = Rat::from(y);
    prop_assert_eq!(x, &rebuilt, "step {}: structural equality", step);
    prop_assert_eq!(hash_of(x), hash_of(&rebuilt), "step {}: hash", step);
    prop_assert_eq!(x.to_string(), y.to_string(), "step {}: display", step);
    prop_assert_eq!(x.is_integer(), y.is_integer());
    prop_assert_eq!(x.is_negative(), y.is_negative());
    Ok(())
}

proptest! {
    #![proptest_config(config(400, 0x05ee_d0a7))]

    #[test]
    fn operation_sequences_match_big_rational(
        start in operand(),
        steps in prop::collection::vec((op(), operand()), 1..24),
    ) {
        let mut x = Rat::from(&start);
        let mut y = start;
        agree(&x, &y, 0)?;
        for (i, (op, b)) in steps.into_iter().enumerate() {
            let a = Rat::from(&b);
            agree(&a, &b, i)?;
            prop_assert_eq!(x.cmp(&a), y.cmp(&b), "step {}: ordering", i);
            prop_assert_eq!(x == a, y == b, "step {}: equality", i);
            match op {
                Op::Add => (x, y) = (&x + &a, &y + &b),
                Op::Sub => (x, y) = (x - &a, y - &b),
                Op::Mul => (x, y) = (&x * a, &y * &b),
                Op::Div if b.is_zero() => prop_assert_eq!(x.checked_div(&a), None),
                Op::Div => (x, y) = (x / a, y / &b),
                Op::AddAssign => {
                    x += &a;
                    y += &b;
                }
                Op::SubAssign => {
                    x -= a;
                    y -= &b;
                }
                Op::MulAssign => {
                    x *= &a;
                    y *= &b;
                }
                Op::DivAssign if b.is_zero() => prop_assert_eq!(Field::inv(&a), None),
                Op::DivAssign => {
                    x /= a;
                    y /= &b;
                }
                Op::Neg => (x, y) = (-x, -y),
                Op::Abs => (x, y) = (x.abs(), y.abs()),
                Op::Recip => match x.recip() {
                    None => prop_assert!(y.is_zero()),
                    Some(r) => (x, y) = (r, y.recip()),
                },
                Op::SubMul(c) => {
                    x.sub_mul_assign(&a, &Rat::from(&c));
                    y -= &b * &c;
                }
                Op::RoundTrip if b.is_zero() => {}
                Op::RoundTrip => {
                    let back = (&x * &a) / &a;
                    prop_assert_eq!(&back, &x, "step {}: (x·a)/a", i);
                }
                Op::Square => {
                    let root = (&x * &x).sqrt_exact();
                    prop_assert_eq!(root, Some(x.abs()), "step {}: sqrt(x²)", i);
                }
                Op::Set => (x, y) = (a, b),
            }
            agree(&x, &y, i + 1)?;
            // Images in other fields agree with those of the oracle.
            prop_assert_eq!(ModP::from_rat(&x), ModP::from_rational(&y));
            prop_assert_eq!(f64::from_rat(&x), f64::from_rational(&y));
            prop_assert_eq!(x.to_f64(), y.to_f64().unwrap());
            // Keep chains from growing without bound.
            if y.numer().bits() + y.denom().bits() > 2_000 {
                (x, y) = (Rat::ONE, BigRational::from_integer(1.into()));
            }
        }
    }

    #[test]
    fn field_operations_match_big_rational(a in operand(), b in operand(), c in operand()) {
        let (x, y, z) = (Rat::from(&a), Rat::from(&b), Rat::from(&c));
        prop_assert_eq!(Field::add(&x, &y).to_big(), Field::add(&a, &b));
        prop_assert_eq!(Field::sub(&x, &y).to_big(), Field::sub(&a, &b));
        prop_assert_eq!(Field::mul(&x, &y).to_big(), Field::mul(&a, &b));
        prop_assert_eq!(Field::neg(&x).to_big(), Field::neg(&a));
        prop_assert_eq!(Field::inv(&x).map(|r| r.to_big()), Field::inv(&a));
        let mut s = z.clone();
        s.sub_mul_assign(&x, &y);
        let mut t = c.clone();
        t.sub_mul_assign(&a, &b);
        prop_assert_eq!(&s.to_big(), &t);
        prop_assert_eq!(s, Rat::from(&t));
        match x.sqrt_exact() {
            Some(r) => {
                prop_assert!(!r.is_negative());
                prop_assert_eq!(&r * &r, x.clone());
            }
            None => {
                let is_square = |n: &BigInt| n.sqrt().pow(2) == *n;
                let square = !a.is_negative() && is_square(a.numer()) && is_square(a.denom());
                prop_assert!(!square, "{} is a square", a);
            }
        }
        prop_assert_eq!(x.magnitude(), a.magnitude());
    }
}

#[test]
fn dual_number_like_dot_products_stay_small() {
    // Gradients of a distance at small rational points: every intermediate is small.
    let p: Vec<Rat> = (1..=8).map(|k| Rat::new(k * 3 - 7, 1 + k % 4).unwrap()).collect();
    let q: Vec<Rat> = (1..=8).map(|k| Rat::new(5 - k, 2 + k % 3).unwrap()).collect();
    let dot: Rat = p.iter().zip(&q).map(|(a, b)| a * b).sum();
    let expected: BigRational =
        p.iter().zip(&q).map(|(a, b)| a.to_big() * b.to_big()).sum::<BigRational>();
    assert_eq!(dot.to_big(), expected);
    assert!(dot.is_small());
    let mut acc = Rat::ZERO;
    for (a, b) in p.iter().zip(&q) {
        acc.sub_mul_assign(a, &-b);
    }
    assert_eq!(acc, dot);
}
