//! Points of small polynomial systems modulo a prime: the placement's last resort for a loop
//! that its one-entity-at-a-time construction cannot close (a regular hexagon by equal chords
//! on a circle, an equilateral triangle inscribed with its vertices on given lines).
//!
//! The equations of a group are the constraints' own laws evaluated on polynomials
//! ([`Poly`] is a [`Field`] whose variables are the group's coordinates: the laws never divide),
//! so there is no second copy of an equation. Their solution set is cut by random affine
//! hyperplanes until it is finite (each a random point of the solution set's top-dimensional
//! parts, as a free choice of the construction is), then solved: a Gröbner basis
//! (Buchberger, degree-reverse-lexicographic order), the eliminant of the last variable (the
//! minimal polynomial of its class in the quotient ring, from normal forms), its roots in the
//! prime field (distinct-degree then equal-degree splitting), and each root substituted in turn.
//!
//! Everything is bounded (variables, basis size, pairs, degrees): beyond the bounds the answer
//! is "not found", never a wrong point; every point returned satisfies every equation, which
//! the caller checks again with the laws in the placement's own arithmetic.

use std::cmp::Ordering;
use std::collections::BTreeMap;

use gcs_rank::{BigRational, Field, PrimeField, RankError, Rat};

/// The most variables a system may have.
pub(crate) const MAX_VARS: usize = 31;

/// The byte of a monomial that holds its total degree (after the exponents).
const DEG: usize = MAX_VARS;

/// Exponents of a monomial, then its total degree (byte [`DEG`]): 32 bytes compared as four
/// words.
type Mono = [u8; MAX_VARS + 1];

const ONE_MONO: Mono = [0; MAX_VARS + 1];

fn degree(m: &Mono) -> u32 {
    u32::from(m[DEG])
}

fn word(m: &Mono, w: usize) -> u64 {
    let mut b = [0u8; 8];
    b.copy_from_slice(&m[8 * w..8 * w + 8]);
    u64::from_le_bytes(b)
}

/// Degree reverse lexicographic order: by total degree, then the monomial with the smaller
/// exponent of the last variable where they differ is the greater.
fn grevlex(a: &Mono, b: &Mono) -> Ordering {
    a[DEG].cmp(&b[DEG]).then_with(|| {
        // The degrees being equal, the highest differing byte is an exponent's.
        for w in (0..4).rev() {
            let x = word(a, w) ^ word(b, w);
            if x != 0 {
                let byte = 8 * w + (63 - x.leading_zeros() as usize) / 8;
                return b[byte].cmp(&a[byte]);
            }
        }
        Ordering::Equal
    })
}

/// The high bit of every byte of a word.
const HIGH: u64 = 0x8080_8080_8080_8080;

/// Whether `a` divides `b`: every exponent of `a` at most `b`'s, compared eight bytes at a
/// time (the reduction asks this for every term against every divisor). Per byte, with
/// `t = (x | 0x80) − (y & 0x7f)` (no borrow leaves the byte), the high bit of `t` says whether
/// the low seven bits of `x` are at least `y`'s, and `x ≥ y` when the high bits decide it or
/// are equal and `t`'s does.
fn divides(a: &Mono, b: &Mono) -> bool {
    (0..4).all(|w| {
        let (x, y) = (word(b, w), word(a, w));
        let t = (x | HIGH) - (y & !HIGH);
        ((x & !y) | (!(x ^ y) & t)) & HIGH == HIGH
    })
}

fn lcm(a: &Mono, b: &Mono) -> Mono {
    let mut m = ONE_MONO;
    let mut d = 0u8;
    for i in 0..MAX_VARS {
        m[i] = a[i].max(b[i]);
        d = d.saturating_add(m[i]);
    }
    m[DEG] = d;
    m
}

/// `a / b` (`b` divides `a`; the degrees subtract too).
fn quotient(a: &Mono, b: &Mono) -> Mono {
    let mut m = ONE_MONO;
    for i in 0..=DEG {
        m[i] = a[i] - b[i];
    }
    m
}

/// `a · b` (the degrees add too), `None` when an exponent overflows. Eight bytes at a time:
/// the low seven bits of each byte add without a carry leaving it, the high bits by `^`, and a
/// byte overflows when the carry out of its high bit is set.
fn product(a: &Mono, b: &Mono) -> Option<Mono> {
    let mut m = ONE_MONO;
    for w in 0..4 {
        let (x, y) = (word(a, w), word(b, w));
        let sum = ((x & !HIGH) + (y & !HIGH)) ^ ((x ^ y) & HIGH);
        if ((x & y) | ((x | y) & !sum)) & HIGH != 0 {
            return None;
        }
        m[8 * w..8 * w + 8].copy_from_slice(&sum.to_le_bytes());
    }
    Some(m)
}

/// A monomial ordered by [`grevlex`], as a map key.
#[derive(Clone, Copy, PartialEq, Eq)]
struct Key(Mono);

impl Ord for Key {
    fn cmp(&self, other: &Key) -> Ordering {
        grevlex(&self.0, &other.0)
    }
}

impl PartialOrd for Key {
    fn partial_cmp(&self, other: &Key) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A polynomial in at most [`MAX_VARS`] variables: its nonzero terms, greatest monomial first.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Poly<F> {
    terms: Vec<(Mono, F)>,
}

impl<F: Field> Poly<F> {
    pub(crate) fn constant(c: F) -> Poly<F> {
        if c.is_zero() { Poly { terms: Vec::new() } } else { Poly { terms: vec![(ONE_MONO, c)] } }
    }

    /// Variable `i` (`i < MAX_VARS`).
    pub(crate) fn var(i: usize) -> Poly<F> {
        let mut m = ONE_MONO;
        m[i] = 1;
        m[DEG] = 1;
        Poly { terms: vec![(m, F::one())] }
    }

    fn from_map(map: BTreeMap<Key, F>) -> Poly<F> {
        Poly {
            terms: map
                .into_iter()
                .rev()
                .filter(|(_, c)| !c.is_zero())
                .map(|(k, c)| (k.0, c))
                .collect(),
        }
    }

    fn to_map(&self) -> BTreeMap<Key, F> {
        self.terms.iter().map(|(m, c)| (Key(*m), c.clone())).collect()
    }

    fn lead(&self) -> Option<&Mono> {
        self.terms.first().map(|(m, _)| m)
    }

    /// Whether this is a nonzero constant.
    fn is_unit(&self) -> bool {
        matches!(&self.terms[..], [(m, _)] if *m == ONE_MONO)
    }

    /// Divided by its leading coefficient.
    fn monic(mut self) -> Poly<F> {
        if let Some(inv) = self.terms.first().and_then(|(_, c)| c.inv()) {
            for (_, c) in &mut self.terms {
                *c = c.mul(&inv);
            }
        }
        self
    }

    pub(crate) fn max_degree(&self) -> u32 {
        self.terms.iter().map(|(m, _)| degree(m)).max().unwrap_or(0)
    }

    fn combine(&self, other: &Poly<F>, sign: bool) -> Poly<F> {
        let mut map = self.to_map();
        for (m, c) in &other.terms {
            let e = map.entry(Key(*m)).or_insert_with(F::zero);
            *e = if sign { e.add(c) } else { e.sub(c) };
        }
        Poly::from_map(map)
    }

    fn times(&self, other: &Poly<F>) -> Poly<F> {
        let mut map: BTreeMap<Key, F> = BTreeMap::new();
        for (a, x) in &self.terms {
            for (b, y) in &other.terms {
                // (Exponents past 255 cannot arise within the bounds the solver keeps.)
                let m = product(a, b).unwrap_or(*a);
                let e = map.entry(Key(m)).or_insert_with(F::zero);
                e.sub_mul_assign(&x.neg(), y);
            }
        }
        Poly::from_map(map)
    }

    /// The value with variable `v` replaced by `a` (its exponent dropped).
    fn substitute(&self, v: usize, a: &F) -> Poly<F> {
        let mut map: BTreeMap<Key, F> = BTreeMap::new();
        for (m, c) in &self.terms {
            let mut k = *m;
            let mut c = c.clone();
            for _ in 0..m[v] {
                c = c.mul(a);
            }
            k[DEG] -= k[v];
            k[v] = 0;
            let e = map.entry(Key(k)).or_insert_with(F::zero);
            *e = e.add(&c);
        }
        Poly::from_map(map)
    }

    /// The polynomial with variable `v` replaced by the polynomial `e`, its term operations
    /// added to `work`; `None` once that passes [`MAX_WORK`] (a substitution can expand a
    /// polynomial of high degree beyond any use).
    fn compose(&self, v: usize, e: &Poly<F>, work: &mut u64) -> Option<Poly<F>> {
        if self.terms.iter().all(|(m, _)| m[v] == 0) {
            return Some(self.clone());
        }
        let mut powers = vec![Poly::one()];
        let mut sum: BTreeMap<Key, F> = BTreeMap::new();
        for (m, c) in &self.terms {
            let k = usize::from(m[v]);
            while powers.len() <= k {
                let last = &powers[powers.len() - 1];
                *work += (last.terms.len() * e.terms.len()) as u64;
                if *work > MAX_WORK {
                    return None;
                }
                let next = last.times(e);
                powers.push(next);
            }
            let mut rest = *m;
            rest[DEG] -= rest[v];
            rest[v] = 0;
            *work += powers[k].terms.len() as u64;
            if *work > MAX_WORK {
                return None;
            }
            for (pm, pc) in &powers[k].terms {
                let key = product(&rest, pm).unwrap_or(rest);
                let entry = sum.entry(Key(key)).or_insert_with(F::zero);
                *entry = entry.add(&c.mul(pc));
            }
        }
        Some(Poly::from_map(sum))
    }

    /// The value at `x` (one value per variable, missing ones zero).
    pub(crate) fn eval(&self, x: &[F]) -> F {
        let mut sum = F::zero();
        for (m, c) in &self.terms {
            let mut t = c.clone();
            for (i, &e) in m[..DEG].iter().enumerate() {
                for _ in 0..e {
                    t = t.mul(x.get(i).unwrap_or(&F::zero()));
                }
            }
            sum = sum.add(&t);
        }
        sum
    }
}

impl<F: Field> Field for Poly<F> {
    const NAME: &'static str = "polynomial";
    const EXACT: bool = true;

    fn zero() -> Self {
        Poly { terms: Vec::new() }
    }

    fn one() -> Self {
        Poly::constant(F::one())
    }

    fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    fn from_i64(v: i64) -> Self {
        Poly::constant(F::from_i64(v))
    }

    fn from_rational(q: &BigRational) -> Result<Self, RankError> {
        F::from_rational(q).map(Poly::constant)
    }

    fn from_rat(q: &Rat) -> Result<Self, RankError> {
        F::from_rat(q).map(Poly::constant)
    }

    fn add(&self, rhs: &Self) -> Self {
        self.combine(rhs, true)
    }

    fn sub(&self, rhs: &Self) -> Self {
        self.combine(rhs, false)
    }

    fn mul(&self, rhs: &Self) -> Self {
        self.times(rhs)
    }

    fn neg(&self) -> Self {
        Poly { terms: self.terms.iter().map(|(m, c)| (*m, c.neg())).collect() }
    }

    /// Only a nonzero constant has an inverse among polynomials.
    fn inv(&self) -> Option<Self> {
        match &self.terms[..] {
            [(m, c)] if *m == ONE_MONO => c.inv().map(Poly::constant),
            _ => None,
        }
    }

    fn sub_mul_assign(&mut self, a: &Self, b: &Self) {
        *self = self.sub(&a.times(b));
    }

    fn magnitude(&self) -> f64 {
        if self.is_zero() { 0.0 } else { 1.0 }
    }
}

/// Bounds on the work of one solve.
const MAX_BASIS: usize = 400;
const MAX_PAIRS: usize = 20_000;
const MAX_DEGREE: u32 = 24;
const MAX_ELIMINANT: usize = 256;
/// Term operations of one solve (about a second).
pub(crate) const MAX_WORK: u64 = 2_000_000;

/// Why a system has no point here.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum NoPoint {
    /// Its equations contradict each other (over the algebraic closure).
    Inconsistent,
    /// It has points over the algebraic closure, none in the prime field (another prime, or
    /// other random choices, may have some).
    NoRoot,
    /// Beyond the solver's bounds.
    TooLarge,
}

/// `f` reduced completely by the monic basis `g`.
fn reduce<F: Field>(f: &Poly<F>, g: &[Poly<F>], work: &mut u64) -> Poly<F> {
    *work += f.terms.len() as u64;
    let mut map = f.to_map();
    let mut rest: Vec<(Mono, F)> = Vec::new();
    while let Some((k, c)) = map.pop_last() {
        if *work > MAX_WORK {
            // (Unfinished: every caller checks the work and gives up.)
            break;
        }
        if c.is_zero() {
            continue;
        }
        match g.iter().find(|h| h.lead().is_some_and(|l| divides(l, &k.0))) {
            Some(h) => {
                let shift = quotient(&k.0, &h.terms[0].0);
                *work += h.terms.len() as u64;
                for (m, d) in &h.terms[1..] {
                    let m = product(m, &shift).unwrap_or(*m);
                    let e = map.entry(Key(m)).or_insert_with(F::zero);
                    e.sub_mul_assign(&c, d);
                }
            }
            None => rest.push((k.0, c)),
        }
    }
    Poly { terms: rest }
}

/// The reduced Gröbner basis of the ideal of `input` (monic, sorted by leading monomial),
/// `[1]` when it is the whole ring.
pub(crate) fn groebner<F: Field>(
    input: &[Poly<F>],
    work: &mut u64,
) -> Result<Vec<Poly<F>>, NoPoint> {
    let mut g: Vec<Poly<F>> = Vec::new();
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    let mut pending: Vec<Poly<F>> = input.to_vec();
    let mut done = 0usize;
    loop {
        let next = if let Some(f) = pending.pop() {
            f
        } else {
            // The pair of least lcm degree.
            let Some(best) = (0..pairs.len()).min_by_key(|&k| {
                let (i, j) = pairs[k];
                degree(&lcm(&g[i].terms[0].0, &g[j].terms[0].0))
            }) else {
                break;
            };
            let (i, j) = pairs.swap_remove(best);
            done += 1;
            if done > MAX_PAIRS {
                return Err(NoPoint::TooLarge);
            }
            let (li, lj) = (g[i].terms[0].0, g[j].terms[0].0);
            let l = lcm(&li, &lj);
            if product(&li, &lj) == Some(l) {
                continue;
            }
            let shift = |p: &Poly<F>, s: Mono| Poly {
                terms: p
                    .terms
                    .iter()
                    .map(|(m, c)| (product(m, &s).unwrap_or(*m), c.clone()))
                    .collect(),
            };
            shift(&g[i], quotient(&l, &li)).sub(&shift(&g[j], quotient(&l, &lj)))
        };
        let r = reduce(&next, &g, work);
        if *work > MAX_WORK {
            return Err(NoPoint::TooLarge);
        }
        if r.is_zero() {
            continue;
        }
        let r = r.monic();
        if r.is_unit() {
            return Ok(vec![Poly::one()]);
        }
        if r.max_degree() > MAX_DEGREE || g.len() >= MAX_BASIS {
            return Err(NoPoint::TooLarge);
        }
        let t = g.len();
        let lt = r.terms[0].0;
        // Gebauer–Möller: a pair whose lcm the new leading monomial divides, strictly on both
        // sides, is decided by the two pairs through the new element.
        pairs.retain(|&(i, j)| {
            let l = lcm(&g[i].terms[0].0, &g[j].terms[0].0);
            !(divides(&lt, &l)
                && lcm(&g[i].terms[0].0, &lt) != l
                && lcm(&g[j].terms[0].0, &lt) != l)
        });
        for i in 0..t {
            pairs.push((i, t));
        }
        g.push(r);
    }
    // Minimal, then reduced.
    let leads: Vec<Mono> = g.iter().map(|p| p.terms[0].0).collect();
    let mut keep: Vec<Poly<F>> = Vec::new();
    for (i, p) in g.iter().enumerate() {
        let redundant = leads
            .iter()
            .enumerate()
            .any(|(j, l)| j != i && divides(l, &leads[i]) && (*l != leads[i] || j < i));
        if !redundant {
            keep.push(p.clone());
        }
    }
    let mut out: Vec<Poly<F>> = Vec::with_capacity(keep.len());
    for i in 0..keep.len() {
        let others: Vec<Poly<F>> =
            keep.iter().enumerate().filter(|(j, _)| *j != i).map(|(_, p)| p.clone()).collect();
        let head = Poly { terms: keep[i].terms[..1].to_vec() };
        let tail = Poly { terms: keep[i].terms[1..].to_vec() };
        out.push(head.add(&reduce(&tail, &others, work)));
    }
    if *work > MAX_WORK {
        return Err(NoPoint::TooLarge);
    }
    out.sort_by(|a, b| grevlex(&a.terms[0].0, &b.terms[0].0));
    Ok(out)
}

/// Whether the ideal of the basis `g` of a system in the variables `vars` has finitely many points:
/// a power of every variable leads an element.
fn zero_dimensional<F: Field>(g: &[Poly<F>], vars: &[usize]) -> bool {
    vars.iter().all(|&v| {
        g.iter().any(|p| {
            let m = &p.terms[0].0;
            m[v] > 0 && m[..DEG].iter().enumerate().all(|(i, &e)| i == v || e == 0)
        })
    })
}

/// The minimal polynomial of variable `v` modulo the zero-dimensional ideal of basis `g`
/// (coefficients from the constant term up, monic): the first linear dependency among the
/// normal forms of its powers.
fn eliminant<F: Field>(g: &[Poly<F>], v: usize, work: &mut u64) -> Result<Vec<F>, NoPoint> {
    // Echelon rows: each reduced by those before it, with its pivot monomial and the
    // combination of powers it stands for.
    let mut rows: Vec<(Mono, Poly<F>, Vec<F>)> = Vec::new();
    let x = Poly::var(v);
    let mut power = reduce(&Poly::one(), g, work);
    if *work > MAX_WORK {
        return Err(NoPoint::TooLarge);
    }
    for k in 0..=MAX_ELIMINANT {
        let mut r = power.clone();
        let mut comb = vec![F::zero(); k + 1];
        comb[k] = F::one();
        for (pivot, row, rc) in &rows {
            let c = r.terms.iter().find(|(m, _)| m == pivot).map(|(_, c)| c.clone());
            if let Some(c) = c {
                r = r.sub(&row.times(&Poly::constant(c.clone())));
                for (a, b) in comb.iter_mut().zip(rc) {
                    a.sub_mul_assign(&c, b);
                }
            }
        }
        if r.is_zero() {
            return Ok(comb);
        }
        let (pivot, lc) = (r.terms[0].0, r.terms[0].1.clone());
        let inv = lc.inv().ok_or(NoPoint::TooLarge)?;
        let r = r.times(&Poly::constant(inv.clone()));
        let comb: Vec<F> = comb.iter().map(|c| c.mul(&inv)).collect();
        rows.push((pivot, r, comb));
        power = reduce(&power.times(&x), g, work);
        if *work > MAX_WORK {
            return Err(NoPoint::TooLarge);
        }
    }
    Err(NoPoint::TooLarge)
}

// Univariate polynomials over the prime field: coefficients from the constant term up, no
// trailing zeros.

fn trim<F: Field>(mut a: Vec<F>) -> Vec<F> {
    while a.last().is_some_and(Field::is_zero) {
        a.pop();
    }
    a
}

/// `(a / b, a mod b)` for `b ≠ 0`.
fn divmod<F: Field>(a: &[F], b: &[F]) -> (Vec<F>, Vec<F>) {
    let mut r = trim(a.to_vec());
    let b = trim(b.to_vec());
    let Some(inv) = b.last().and_then(Field::inv) else { return (Vec::new(), r) };
    if r.len() < b.len() {
        return (Vec::new(), r);
    }
    let mut q = vec![F::zero(); r.len() - b.len() + 1];
    while r.len() >= b.len() {
        let shift = r.len() - b.len();
        let c = r[r.len() - 1].mul(&inv);
        for (i, bi) in b.iter().enumerate() {
            r[shift + i].sub_mul_assign(&c, bi);
        }
        q[shift] = c;
        r = trim(r);
    }
    (trim(q), r)
}

fn mul_mod<F: Field>(a: &[F], b: &[F], m: &[F]) -> Vec<F> {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut p = vec![F::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            p[i + j].sub_mul_assign(&x.neg(), y);
        }
    }
    divmod(&p, m).1
}

fn gcd<F: Field>(a: &[F], b: &[F]) -> Vec<F> {
    let (mut a, mut b) = (trim(a.to_vec()), trim(b.to_vec()));
    while !b.is_empty() {
        let r = divmod(&a, &b).1;
        a = b;
        b = r;
    }
    match a.last().and_then(Field::inv) {
        Some(inv) => a.iter().map(|c| c.mul(&inv)).collect(),
        None => a,
    }
}

/// `base^e mod m`.
fn pow_mod<F: Field>(base: &[F], mut e: u64, m: &[F]) -> Vec<F> {
    let mut result = divmod(&[F::one()], m).1;
    let mut b = divmod(base, m).1;
    while e > 0 {
        if e & 1 == 1 {
            result = mul_mod(&result, &b, m);
        }
        b = mul_mod(&b, &b, m);
        e >>= 1;
    }
    result
}

/// The distinct roots of `f` in the prime field.
fn roots<F: PrimeField>(f: &[F], rng: &mut dyn FnMut() -> u64) -> Vec<F> {
    let f = trim(f.to_vec());
    if f.len() < 2 {
        return Vec::new();
    }
    let p = F::prime();
    let x = vec![F::zero(), F::one()];
    // gcd(f, x^p − x): the product of its distinct linear factors.
    let xp = pow_mod(&x, p, &f);
    let mut d = xp;
    d.resize(d.len().max(2), F::zero());
    d[1] = d[1].sub(&F::one());
    let split = gcd(&f, &trim(d));
    let mut out = Vec::new();
    let mut todo = vec![split];
    let mut tries = 0;
    while let Some(g) = todo.pop() {
        match g.len() {
            0 | 1 => {}
            2 => out.push(g[0].mul(&g[1].inv().unwrap_or_else(F::one)).neg()),
            _ => {
                // (x + a)^((p−1)/2) − 1 has half the roots other than −a: a random split.
                tries += 1;
                if tries > 64 * (f.len() + 1) {
                    break;
                }
                let a = F::residue(rng());
                let mut w = pow_mod(&[a, F::one()], (p - 1) / 2, &g);
                if w.is_empty() {
                    w.push(F::zero());
                }
                w[0] = w[0].sub(&F::one());
                let h = gcd(&g, &trim(w));
                if h.len() > 1 && h.len() < g.len() {
                    let q = divmod(&g, &h).0;
                    todo.push(h);
                    todo.push(q);
                } else {
                    todo.push(g);
                }
            }
        }
    }
    out
}

/// Points of the system `equations` in `n` variables (`n ≤ MAX_VARS`) over the prime field,
/// at most `cap` of them: the solution set cut by random hyperplanes until finite (their
/// number is returned beside the points: the dimension of the solutions the points were
/// chosen from), each point a random one of its part. A point of a part of lower dimension
/// than the largest is not found. `budget` is the work left to the caller (term operations):
/// what the solve used is taken off it, and at most [`MAX_WORK`] is used.
pub(crate) fn points<F: PrimeField>(
    equations: &[Poly<F>],
    n: usize,
    cap: usize,
    rng: &mut dyn FnMut() -> u64,
    budget: &mut u64,
) -> Result<(Vec<Vec<F>>, usize), NoPoint> {
    if n > MAX_VARS {
        return Err(NoPoint::TooLarge);
    }
    // The work counts up to MAX_WORK from where the budget leaves it.
    let start = MAX_WORK - (*budget).min(MAX_WORK);
    let mut work = start;
    let result = points_within(equations, n, cap, rng, &mut work);
    *budget = budget.saturating_sub(work - start);
    result
}

fn points_within<F: PrimeField>(
    equations: &[Poly<F>],
    n: usize,
    cap: usize,
    rng: &mut dyn FnMut() -> u64,
    work: &mut u64,
) -> Result<(Vec<Vec<F>>, usize), NoPoint> {
    let mut system: Vec<Poly<F>> = equations.iter().filter(|p| !p.is_zero()).cloned().collect();
    // Linear equations (coincidences, incidences on placed lines) are solved for a variable
    // each and substituted: the Gröbner basis sees only the variables that remain.
    let mut solved: Vec<(usize, Poly<F>)> = Vec::new();
    while let Some(k) = system.iter().position(|p| p.max_degree() == 1) {
        let p = system.swap_remove(k);
        let Some((m, c)) = p.terms.iter().find(|(m, _)| degree(m) == 1) else { continue };
        let v = m[..DEG].iter().position(|&e| e == 1).unwrap_or(0);
        let inv = c.inv().ok_or(NoPoint::TooLarge)?;
        let e = p.sub(&Poly::var(v).times(&Poly::constant(*c))).times(&Poly::constant(inv.neg()));
        eliminate(&mut system, &mut solved, v, e, work)?;
    }
    if system.iter().any(Poly::is_unit) {
        return Err(NoPoint::Inconsistent);
    }
    let live = |solved: &[(usize, Poly<F>)]| -> Vec<usize> {
        (0..n).filter(|v| solved.iter().all(|(u, _)| u != v)).collect()
    };
    let mut g = groebner(&system, work)?;
    let mut cuts = 0;
    loop {
        let vars = live(&solved);
        if g.first().is_some_and(Poly::is_unit) || zero_dimensional(&g, &vars) {
            break;
        }
        // A random hyperplane, solved for the last variable left.
        let Some((&v, rest)) = vars.split_last() else { break };
        let mut e = Poly::constant(F::residue(rng()));
        for &u in rest {
            e = e.add(&Poly::var(u).times(&Poly::constant(F::residue(rng()))));
        }
        system = g;
        eliminate(&mut system, &mut solved, v, e, work)?;
        cuts += 1;
        g = groebner(&system, work)?;
    }
    if g.first().is_some_and(Poly::is_unit) {
        return Err(if cuts == 0 { NoPoint::Inconsistent } else { NoPoint::NoRoot });
    }
    let vars = live(&solved);
    let mut found: Vec<Vec<(usize, F)>> = Vec::new();
    solve_finite(g, &vars, cap, rng, &mut found, work)?;
    if found.is_empty() {
        return Err(NoPoint::NoRoot);
    }
    let out = found
        .into_iter()
        .map(|values| {
            let mut x = vec![F::zero(); n];
            for (v, a) in values {
                x[v] = a;
            }
            for (v, e) in &solved {
                x[*v] = e.eval(&x);
            }
            x
        })
        .collect();
    Ok((out, cuts))
}

/// Substitutes `x_v = e` in `system` and in the expressions already solved, and records it.
fn eliminate<F: Field>(
    system: &mut Vec<Poly<F>>,
    solved: &mut Vec<(usize, Poly<F>)>,
    v: usize,
    e: Poly<F>,
    work: &mut u64,
) -> Result<(), NoPoint> {
    for p in system.iter_mut().chain(solved.iter_mut().map(|(_, p)| p)) {
        *work += p.terms.len() as u64;
        *p = p.compose(v, &e, work).ok_or(NoPoint::TooLarge)?;
    }
    system.retain(|p| !p.is_zero());
    solved.push((v, e));
    if *work > MAX_WORK { Err(NoPoint::TooLarge) } else { Ok(()) }
}

/// The points of the zero-dimensional ideal of basis `g` in the variables `vars` (up to
/// `cap`, as values of those variables), by the roots of the last variable's eliminant, each
/// substituted in turn.
fn solve_finite<F: PrimeField>(
    g: Vec<Poly<F>>,
    vars: &[usize],
    cap: usize,
    rng: &mut dyn FnMut() -> u64,
    out: &mut Vec<Vec<(usize, F)>>,
    work: &mut u64,
) -> Result<(), NoPoint> {
    if g.first().is_some_and(Poly::is_unit) {
        return Ok(());
    }
    let Some((&v, rest)) = vars.split_last() else {
        out.push(Vec::new());
        return Ok(());
    };
    let e = eliminant(&g, v, work)?;
    let mut rs = roots(&e, rng);
    // A random order: the point kept is a random one.
    for i in (1..rs.len()).rev() {
        let j = (rng() % (i as u64 + 1)) as usize;
        rs.swap(i, j);
    }
    for a in rs {
        if out.len() >= cap {
            break;
        }
        let sub: Vec<Poly<F>> = g.iter().map(|p| p.substitute(v, &a)).collect();
        let gs = groebner(&sub, work)?;
        let start = out.len();
        solve_finite(gs, rest, cap, rng, out, work)?;
        for point in &mut out[start..] {
            point.push((v, a));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcs_rank::ModP;

    type P = Poly<ModP>;

    fn c(v: i64) -> P {
        Poly::constant(ModP::from_i64(v))
    }

    fn x(i: usize) -> P {
        Poly::var(i)
    }

    /// The word-at-a-time [`divides`] and [`product`] against byte loops, on exponents at the
    /// byte boundaries (0, 1, 127, 128, 254, 255) and random ones.
    #[test]
    fn monomial_words_match_bytes() {
        let mut next = rng();
        let edge = [0u8, 1, 2, 126, 127, 128, 129, 254, 255];
        let mono = |next: &mut dyn FnMut() -> u64| {
            let mut m = ONE_MONO;
            for e in &mut m {
                let r = next();
                *e = if r.is_multiple_of(3) {
                    edge[(r >> 8) as usize % edge.len()]
                } else {
                    (r >> 16) as u8 % 8
                };
            }
            m
        };
        for _ in 0..20_000 {
            let (a, b) = (mono(&mut next), mono(&mut next));
            // Nearby pairs too, so that `divides` is often true.
            let mut c = a;
            c[(next() % 32) as usize] = c[(next() % 32) as usize].saturating_add(1);
            for (x, y) in [(a, b), (a, c), (c, a), (a, a)] {
                assert_eq!(divides(&x, &y), x.iter().zip(&y).all(|(p, q)| p <= q), "{x:?} {y:?}");
                let bytes: Option<Vec<u8>> =
                    x.iter().zip(&y).map(|(p, q)| p.checked_add(*q)).collect();
                assert_eq!(product(&x, &y).map(|m| m.to_vec()), bytes, "{x:?} {y:?}");
            }
        }
    }

    fn rng() -> impl FnMut() -> u64 {
        let mut s = gcs_model::rng::SplitMix64::new(7);
        move || s.next_u64()
    }

    fn points_t(
        eqs: &[P],
        n: usize,
        cap: usize,
        rng: &mut dyn FnMut() -> u64,
    ) -> Result<(Vec<Vec<ModP>>, usize), NoPoint> {
        points(eqs, n, cap, rng, &mut MAX_WORK.clone())
    }

    fn check(eqs: &[P], pts: &[Vec<ModP>]) {
        assert!(!pts.is_empty());
        for p in pts {
            for e in eqs {
                assert!(e.eval(p).is_zero(), "{e:?} at {p:?}");
            }
        }
    }

    #[test]
    fn two_circles_meet_in_their_two_points() {
        // x² + y² = 25, (x − 6)² + y² = 25: x = 3, y = ±4.
        let eqs = vec![
            x(0).mul(&x(0)).add(&x(1).mul(&x(1))).sub(&c(25)),
            x(0).sub(&c(6)).mul(&x(0).sub(&c(6))).add(&x(1).mul(&x(1))).sub(&c(25)),
        ];
        let (pts, cuts) = points_t(&eqs, 2, 8, &mut rng()).unwrap();
        assert_eq!(cuts, 0);
        assert_eq!(pts.len(), 2);
        check(&eqs, &pts);
        assert!(pts.iter().all(|p| p[0] == ModP::from_i64(3)));
    }

    #[test]
    fn contradictions_and_missing_roots_are_told_apart() {
        let eqs = vec![x(0).sub(&c(1)), x(0).sub(&c(2))];
        assert_eq!(points_t(&eqs, 1, 8, &mut rng()), Err(NoPoint::Inconsistent));
        // x² = 3 has no root modulo 2^61 − 1 (3 is not a square there).
        let eqs = vec![x(0).mul(&x(0)).sub(&c(3))];
        assert_eq!(points_t(&eqs, 1, 8, &mut rng()), Err(NoPoint::NoRoot));
        // x² = 2 has two.
        let eqs = vec![x(0).mul(&x(0)).sub(&c(2))];
        let (pts, _) = points_t(&eqs, 1, 8, &mut rng()).unwrap();
        assert_eq!(pts.len(), 2);
        check(&eqs, &pts);
    }

    #[test]
    fn a_curve_is_cut_to_a_random_point_of_it() {
        // The unit circle: one hyperplane.
        let eqs = vec![x(0).mul(&x(0)).add(&x(1).mul(&x(1))).sub(&c(1))];
        let mut r = rng();
        let found = (0..8).find_map(|_| points_t(&eqs, 2, 8, &mut r).ok());
        let (pts, cuts) = found.expect("a line meets the circle in rational points half the time");
        assert_eq!(cuts, 1);
        check(&eqs, &pts);
    }

    #[test]
    fn a_square_with_equal_sides_on_a_circle_closes() {
        // Four points on the unit circle with p0 = (1, 0), equal consecutive chords and the
        // loop closed: the regular square (and folded ones), with coordinates 0 and ±1.
        let (px, py) = (|i: usize| x(2 * i), |i: usize| x(2 * i + 1));
        let pt =
            |i: usize| -> (P, P) { if i == 0 { (c(1), c(0)) } else { (px(i - 1), py(i - 1)) } };
        let d2 = |a: usize, b: usize| {
            let ((ax, ay), (bx, by)) = (pt(a), pt(b));
            let (dx, dy) = (ax.sub(&bx), ay.sub(&by));
            dx.mul(&dx).add(&dy.mul(&dy))
        };
        let mut eqs = Vec::new();
        for i in 1..4 {
            let (a, b) = pt(i);
            eqs.push(a.mul(&a).add(&b.mul(&b)).sub(&c(1)));
        }
        for i in 1..4 {
            eqs.push(d2(i, (i + 1) % 4).sub(&d2(0, 1)));
        }
        // Not a diagonal: p2 = −p0 forces the square.
        eqs.push(px(1).add(&c(1)));
        let (pts, _) = points_t(&eqs, 6, 16, &mut rng()).unwrap();
        check(&eqs, &pts);
        let one = ModP::from_i64(1);
        assert!(pts.iter().any(|p| p[1] == one || p[1] == one.neg()));
    }

    #[test]
    fn a_substitution_that_would_explode_stops_at_the_work_bound() {
        // x0^20 with x0 = 1 + x1 + … + x20 has C(40, 20) ≈ 1.4e11 terms: refused at the sixth
        // power's product (about half a second).
        let mut e = c(1);
        for i in 1..=20 {
            e = e.add(&x(i));
        }
        let mut f = c(1);
        for _ in 0..20 {
            f = f.mul(&x(0));
        }
        let mut work = 0;
        assert_eq!(f.compose(0, &e, &mut work), None);
        assert!(work > MAX_WORK);
        // A small one is the expansion: (x1 + 2)² − x1² − 4·x1 = 4.
        let sq = x(0).mul(&x(0)).sub(&x(1).mul(&x(1))).sub(&x(1).times(&c(4)));
        let mut work = 0;
        assert_eq!(sq.compose(0, &x(1).add(&c(2)), &mut work), Some(c(4)));
    }

    #[test]
    fn eliminants_and_roots() {
        // (x − 1)(x − 2)(x − 5) and a factor with no root.
        let f: Vec<ModP> = [-10i64, 17, -8, 1].iter().map(|&v| ModP::from_i64(v)).collect();
        let g: Vec<ModP> = [-3i64, 0, 1].iter().map(|&v| ModP::from_i64(v)).collect();
        let prod = {
            let mut p = vec![ModP::from_i64(0); f.len() + g.len() - 1];
            for (i, a) in f.iter().enumerate() {
                for (j, b) in g.iter().enumerate() {
                    p[i + j] = p[i + j].add(&a.mul(b));
                }
            }
            p
        };
        let mut r: Vec<u64> = roots(&prod, &mut rng()).iter().map(|v| v.value()).collect();
        r.sort_unstable();
        assert_eq!(r, vec![1, 2, 5]);
    }
}
