//! The certified exact path: elimination modulo primes, lifted to ℚ and checked exactly.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::Field;
use crate::echelon::{EchelonOptions, Insertion, RowAnalysis, analyse_rows};
use crate::error::RankError;
use crate::modp::{ModP, ModPrime, bigint_mod, inv_mod};
use crate::sparse::{SparseRow, linear_combination};

/// The second prime of multi-modular lifting, `2^64 − 59`.
pub const SECOND_PRIME: u64 = 18_446_744_073_709_551_557;
/// The third prime of multi-modular lifting, `2^63 − 25`.
pub const THIRD_PRIME: u64 = 9_223_372_036_854_775_783;

/// How an exact rank (and the outcome of every row) was proven.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Proof {
    /// Exact rational Gauss-Jordan elimination (`rug::Rational` with the `rug` feature,
    /// `num` [`BigRational`] otherwise).
    Rational,
    /// Elimination modulo `prime`: its pivots prove the lower bound, and every dependency it
    /// found, lifted to ℚ by rational reconstruction modulo `prime`, was checked exactly.
    ModularCertified {
        /// The prime, [`ModP::PRIME`].
        prime: u64,
    },
    /// As `ModularCertified` with the first prime, but some dependencies needed their
    /// coefficients lifted from the product of several primes (Chinese remaindering) before
    /// they passed the exact check.
    MultiModularCertified {
        /// The primes whose product was used, the elimination prime first.
        primes: Vec<u64>,
    },
}

impl Proof {
    /// A short name for reports: `"rational"`, `"modular"` or `"multimodular"`.
    pub fn name(&self) -> &'static str {
        match self {
            Proof::Rational => "rational",
            Proof::ModularCertified { .. } => "modular",
            Proof::MultiModularCertified { .. } => "multimodular",
        }
    }
}

impl std::fmt::Display for Proof {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Proof::Rational => write!(f, "exact rational elimination"),
            Proof::ModularCertified { prime } => {
                write!(f, "elimination modulo {prime}, certified over Q")
            }
            Proof::MultiModularCertified { primes } => {
                let primes: Vec<String> = primes.iter().map(u64::to_string).collect();
                write!(f, "elimination modulo {}, certified over Q", primes.join(" · "))
            }
        }
    }
}

/// Rational reconstruction: the fraction `n/d` with `|n|, d <= sqrt(m/2)` and
/// `n ≡ a·d (mod m)`, if there is one (it is then unique), by the extended Euclidean algorithm
/// stopped at the first remainder below the bound (Wang's method).
///
/// `m` must be positive and odd (a prime or a product of odd primes); `a` is reduced first.
/// Returns `None` when no such fraction exists, which is how a coefficient too large for the
/// modulus shows up.
pub fn rational_reconstruction(a: &BigInt, m: &BigInt) -> Option<BigRational> {
    if !m.is_positive() {
        return None;
    }
    let bound = (m / 2u32).sqrt();
    let (mut r0, mut r1) = (m.clone(), a.mod_floor(m));
    let (mut t0, mut t1) = (BigInt::zero(), BigInt::one());
    while r1 > bound {
        let (q, r) = r0.div_rem(&r1);
        (r0, r1) = (r1, r);
        let t = &t0 - &q * &t1;
        (t0, t1) = (t1, t);
    }
    if t1.is_zero() || t1.abs() > bound || !r1.gcd(&t1).is_one() {
        return None;
    }
    let (n, d) = if t1.is_negative() { (-r1, -t1) } else { (r1, t1) };
    Some(BigRational::new_raw(n, d))
}

/// [`rational_reconstruction`] for a modulus below 2^64, in machine integers.
fn reconstruct_u64(a: u64, m: u64) -> Option<BigRational> {
    let bound = (m / 2).isqrt() as i128;
    let (mut r0, mut r1) = (m as i128, (a % m) as i128);
    let (mut t0, mut t1) = (0i128, 1i128);
    while r1 > bound {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (t0, t1) = (t1, t0 - q * t1);
    }
    if t1 == 0 || t1.abs() > bound || r1.gcd(&t1.abs()) != 1 {
        return None;
    }
    let (n, d) = if t1 < 0 { (-r1, -t1) } else { (r1, t1) };
    Some(BigRational::new_raw(BigInt::from(n), BigInt::from(d)))
}

/// Whether `rows[i] == Σ coef · rows[id]` exactly, with every id below `i`.
fn check_combination(
    rows: &[SparseRow<BigRational>],
    i: usize,
    combination: &[(usize, BigRational)],
) -> bool {
    combination.iter().all(|(id, _)| *id < i) && reproduces(&rows[i], rows, combination)
}

/// Whether `row == Σ coef · rows[id]` exactly (an id without a row fails).
fn reproduces(
    row: &SparseRow<BigRational>,
    rows: &[SparseRow<BigRational>],
    combination: &[(usize, BigRational)],
) -> bool {
    let mut terms: Vec<(&BigRational, &[(usize, BigRational)])> = Vec::new();
    for (id, coef) in combination {
        match rows.get(*id) {
            Some(r) => terms.push((coef, r.entries())),
            None => return false,
        }
    }
    linear_combination(row.entries().to_vec(), &terms, |_| false, |_| false).is_empty()
}

/// Lifts a dependency found modulo [`ModP::PRIME`] to ℚ and proves it: rational reconstruction
/// of every coefficient, then the exact check `row == Σ coef · rows[id]`.
///
/// For incremental use of an [`Echelon`](crate::Echelon) over [`ModP`] (with combinations
/// tracked) on rows known exactly: `rows` are the inserted rows over ℚ (by insertion id), `row`
/// the dependent one and `combination` what [`Insertion::Dependent`] reported. `Some` is a
/// proof that `row` is in the span of the rows it names, with the exact coefficients; `None`
/// means the coefficients are too large for one prime (or the dependency does not hold over ℚ,
/// which mod-p elimination cannot produce for rows whose images were inserted): fall back to
/// [`analyse_rows_exact`] or to an exact backend.
pub fn lift_dependency(
    rows: &[SparseRow<BigRational>],
    row: &SparseRow<BigRational>,
    combination: &[(usize, ModP)],
) -> Option<Vec<(usize, BigRational)>> {
    let lifted: Vec<(usize, BigRational)> = combination
        .iter()
        .map(|(id, c)| reconstruct_u64(c.value(), ModP::PRIME).map(|q| (*id, q)))
        .collect::<Option<_>>()?;
    reproduces(row, rows, &lifted).then_some(lifted)
}

/// One elimination modulo a prime, with combinations, or `None` when the prime divides a
/// denominator.
fn modular_pass<F: Field>(ncols: usize, rows: &[SparseRow<BigRational>]) -> Option<RowAnalysis<F>> {
    let mut images = Vec::with_capacity(rows.len());
    for row in rows {
        images.push(row.map(F::from_rational).ok()?);
    }
    Some(analyse_rows(ncols, images, EchelonOptions::tracked()))
}

/// Residues of the combination of a dependent outcome, as `(id, residue)`.
fn residues<F: Field>(outcome: &Insertion<F>, value: impl Fn(&F) -> u64) -> Residues {
    outcome.combination().unwrap_or(&[]).iter().map(|(id, c)| (*id, value(c))).collect()
}

/// `(insertion id, residue)` pairs of one combination, sorted by id.
type Residues = Vec<(usize, u64)>;

/// A dependency whose coefficients are being lifted by Chinese remaindering.
struct Lift {
    row: usize,
    /// `(id, residue modulo the current modulus)`, sorted by id.
    residues: Vec<(usize, BigInt)>,
}

impl Lift {
    /// Combines with the residues modulo the next prime `p` (sorted by id); `modulus` is the
    /// product so far. An id missing on one side has residue zero there.
    fn absorb(&mut self, modulus: &BigInt, p: u64, next: &[(usize, u64)]) {
        let m_inv = inv_mod(bigint_mod(modulus, p), p);
        // x = r + M · ((s − r) · M⁻¹ mod p)
        let combine = |r: BigInt, s: u64| {
            let r_mod_p = bigint_mod(&r, p);
            let diff = if s >= r_mod_p { s - r_mod_p } else { p - (r_mod_p - s) };
            let k = ((diff as u128 * m_inv as u128) % p as u128) as u64;
            r + modulus * BigInt::from(k)
        };
        let old = std::mem::take(&mut self.residues);
        let mut merged = Vec::with_capacity(old.len().max(next.len()));
        let mut old = old.into_iter().peekable();
        let mut next = next.iter().peekable();
        loop {
            let (id, r, s) = match (old.peek(), next.peek()) {
                (None, None) => break,
                (Some((i, _)), Some((j, _))) if i == j => {
                    let (id, r) = old.next().unwrap_or_default();
                    let s = next.next().map_or(0, |(_, s)| *s);
                    (id, r, s)
                }
                (Some((i, _)), Some((j, _))) if j < i => {
                    let (id, s) = next.next().copied().unwrap_or_default();
                    (id, BigInt::zero(), s)
                }
                (None, Some(_)) => {
                    let (id, s) = next.next().copied().unwrap_or_default();
                    (id, BigInt::zero(), s)
                }
                _ => {
                    let (id, r) = old.next().unwrap_or_default();
                    (id, r, 0)
                }
            };
            merged.push((id, combine(r, s)));
        }
        self.residues = merged;
    }

    fn reconstruct(&self, modulus: &BigInt) -> Option<Vec<(usize, BigRational)>> {
        let mut out = Vec::with_capacity(self.residues.len());
        for (id, r) in &self.residues {
            let q = rational_reconstruction(r, modulus)?;
            if !Field::is_zero(&q) {
                out.push((*id, q));
            }
        }
        Some(out)
    }
}

/// A field whose elements are residues modulo a prime below 2^64.
trait Residue: Field {
    fn residue(&self) -> u64;
}

impl Residue for ModP {
    fn residue(&self) -> u64 {
        self.value()
    }
}

impl<const P: u64> Residue for ModPrime<P> {
    fn residue(&self) -> u64 {
        self.value()
    }
}

/// The independent/dependent pattern and the residues of every combination.
type ResiduePass = fn(usize, &[SparseRow<BigRational>]) -> Option<(Vec<bool>, Vec<Residues>)>;

/// One elimination modulo the prime of `F`, reduced to its pattern and residues.
fn residue_pass<F: Residue>(
    ncols: usize,
    rows: &[SparseRow<BigRational>],
) -> Option<(Vec<bool>, Vec<Residues>)> {
    let analysis: RowAnalysis<F> = modular_pass(ncols, rows)?;
    let pattern = analysis.outcomes.iter().map(Insertion::is_independent).collect();
    let by_row = analysis.outcomes.iter().map(|o| residues(o, F::residue)).collect();
    Some((pattern, by_row))
}

/// The exact path: the rank over ℚ and the outcome of every row, proven, at modular speed.
///
/// Eliminates modulo `p = 2^61 − 1` ([`ModP`]) with combinations tracked. Pivots found mod `p`
/// prove the lower bound (a minor nonzero mod `p` is nonzero over ℚ), and each dependency found
/// mod `p` is lifted to ℚ by [`rational_reconstruction`] of its coefficients and checked
/// exactly against the rational rows, which proves the upper bound; together they prove that
/// every row has the same outcome over ℚ as mod `p`. Dependencies whose coefficients are too
/// large for one prime (numerators and denominators above about 2^30) are lifted again modulo
/// `p·p₂` and then `p·p₂·p₃` ([`SECOND_PRIME`], [`THIRD_PRIME`], bounds about 2^61 and 2^93)
/// by Chinese remaindering. If a lift or check still fails, the primes disagree on which rows
/// are dependent, or a prime divides a denominator, the function falls back to exact rational
/// elimination and reports [`Proof::Rational`].
///
/// The returned combinations (when `track_combinations`) are over ℚ, exact, and equal to those
/// of [`analyse_rows`] over [`BigRational`]. The pivot columns are those found mod `p`: they
/// always form a valid (nonsingular) pivot set over ℚ, and equal the rational elimination's
/// choice unless `p` divides one of the reduced entries.
///
/// Rows with entries at or beyond `ncols` extend the matrix, as in
/// [`Echelon::insert`](crate::Echelon::insert).
///
/// # Errors
/// None at present (every input has a rational answer); the `Result` leaves room for limits.
pub fn analyse_rows_exact(
    ncols: usize,
    rows: &[SparseRow<BigRational>],
    track_combinations: bool,
) -> Result<(RowAnalysis<BigRational>, Proof), RankError> {
    if let Some(result) = certified(ncols, rows, track_combinations) {
        return Ok(result);
    }
    Ok((rational_analysis(ncols, rows, track_combinations), Proof::Rational))
}

fn certified(
    ncols: usize,
    rows: &[SparseRow<BigRational>],
    track: bool,
) -> Option<(RowAnalysis<BigRational>, Proof)> {
    // Without dependencies there is nothing to lift: the pivots found modulo p prove that every
    // row is independent over ℚ. Tracking combinations costs much more than the elimination
    // (they fill in), so look first.
    {
        let mut images = Vec::with_capacity(rows.len());
        for row in rows {
            images.push(row.map(ModP::from_rational).ok()?);
        }
        // `echelon_rank` ignores entries at or beyond `ncols`: such rows can only lower the
        // rank found here, and then the full analysis below (which extends the matrix) runs.
        let (rank, pivots) = crate::echelon_rank(ncols, images);
        if rank == rows.len() {
            let outcomes = pivots
                .into_iter()
                .map(|p| Insertion::Independent { pivot: p.unwrap_or(0) })
                .collect();
            return Some((
                RowAnalysis { rank, outcomes },
                Proof::ModularCertified { prime: ModP::PRIME },
            ));
        }
    }
    let first: RowAnalysis<ModP> = modular_pass(ncols, rows)?;
    let mut lifted: Vec<Option<Vec<(usize, BigRational)>>> = vec![None; rows.len()];
    let mut pending: Vec<Lift> = Vec::new();
    for (i, outcome) in first.outcomes.iter().enumerate() {
        let Some(combination) = outcome.combination() else { continue };
        let lift: Option<Vec<(usize, BigRational)>> = combination
            .iter()
            .map(|(id, c)| reconstruct_u64(c.value(), ModP::PRIME).map(|q| (*id, q)))
            .collect();
        match lift {
            Some(q) if check_combination(rows, i, &q) => lifted[i] = Some(q),
            _ => pending.push(Lift {
                row: i,
                residues: residues(outcome, ModP::residue)
                    .into_iter()
                    .map(|(id, r)| (id, BigInt::from(r)))
                    .collect(),
            }),
        }
    }

    let mut primes = vec![ModP::PRIME];
    if !pending.is_empty() {
        let pattern: Vec<bool> = first.outcomes.iter().map(Insertion::is_independent).collect();
        let mut modulus = BigInt::from(ModP::PRIME);
        let passes: [(u64, ResiduePass); 2] = [
            (SECOND_PRIME, residue_pass::<ModPrime<SECOND_PRIME>>),
            (THIRD_PRIME, residue_pass::<ModPrime<THIRD_PRIME>>),
        ];
        for (p, pass) in passes {
            // A prime that divides a denominator, or finds other dependencies (it divides a
            // minor), cannot help: leave it to the rational fallback.
            let (other_pattern, by_row) = pass(ncols, rows)?;
            if other_pattern != pattern {
                return None;
            }
            for lift in &mut pending {
                lift.absorb(&modulus, p, &by_row[lift.row]);
            }
            modulus *= BigInt::from(p);
            primes.push(p);
            pending.retain(|lift| match lift.reconstruct(&modulus) {
                Some(q) if check_combination(rows, lift.row, &q) => {
                    lifted[lift.row] = Some(q);
                    false
                }
                _ => true,
            });
            if pending.is_empty() {
                break;
            }
        }
        if !pending.is_empty() {
            return None;
        }
    }

    let outcomes = first
        .outcomes
        .iter()
        .zip(lifted)
        .map(|(outcome, q)| match outcome {
            Insertion::Independent { pivot } => Insertion::Independent { pivot: *pivot },
            Insertion::Dependent { .. } => {
                Insertion::Dependent { combination: if track { q } else { None } }
            }
        })
        .collect();
    let proof = if primes.len() == 1 {
        Proof::ModularCertified { prime: ModP::PRIME }
    } else {
        Proof::MultiModularCertified { primes }
    };
    Some((RowAnalysis { rank: first.rank, outcomes }, proof))
}

/// Exact rational elimination, with GMP when the `rug` feature is on.
#[cfg(feature = "rug")]
fn rational_analysis(
    ncols: usize,
    rows: &[SparseRow<BigRational>],
    track: bool,
) -> RowAnalysis<BigRational> {
    use crate::rug_field::{big_to_rug, rug_to_big};
    let images = rows.iter().map(|row| {
        SparseRow::from_sorted(row.entries().iter().map(|(c, v)| (*c, big_to_rug(v))).collect())
    });
    let options = EchelonOptions { track_combinations: track, tolerance: None };
    let analysis = analyse_rows::<rug::Rational>(ncols, images, options);
    let outcomes = analysis
        .outcomes
        .into_iter()
        .map(|outcome| match outcome {
            Insertion::Independent { pivot } => Insertion::Independent { pivot },
            Insertion::Dependent { combination } => Insertion::Dependent {
                combination: combination
                    .map(|c| c.iter().map(|(id, q)| (*id, rug_to_big(q))).collect()),
            },
        })
        .collect();
    RowAnalysis { rank: analysis.rank, outcomes }
}

/// Exact rational elimination, with GMP when the `rug` feature is on.
#[cfg(not(feature = "rug"))]
fn rational_analysis(
    ncols: usize,
    rows: &[SparseRow<BigRational>],
    track: bool,
) -> RowAnalysis<BigRational> {
    let options = EchelonOptions { track_combinations: track, tolerance: None };
    analyse_rows(ncols, rows.iter().cloned(), options)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    #[test]
    fn reconstruction_recovers_small_fractions() {
        let p = ModP::PRIME;
        for x in [q(0, 1), q(1, 1), q(-1, 1), q(22, 7), q(-355, 113), q(1_000_000_007, 999_999_937)]
        {
            let r = ModP::from_rational(&x).unwrap().value();
            assert_eq!(reconstruct_u64(r, p), Some(x.clone()), "u64 path, {x}");
            assert_eq!(
                rational_reconstruction(&BigInt::from(r), &BigInt::from(p)),
                Some(x.clone()),
                "BigInt path, {x}"
            );
        }
    }

    #[test]
    fn reconstruction_fails_past_the_bound() {
        // 2^40 + 1 is far beyond sqrt(p/2) ≈ 2^30: no fraction within the bounds maps to it
        // except a wrong one, which the exact check then rejects.
        let big = q((1 << 40) + 1, 1);
        let r = ModP::from_rational(&big).unwrap().value();
        assert_ne!(reconstruct_u64(r, ModP::PRIME), Some(big));
    }

    #[test]
    fn dependencies_found_mod_p_lift_to_exact_ones() {
        use crate::{Echelon, EchelonOptions};
        let q_rows: Vec<SparseRow<BigRational>> = [
            vec![(0, q(1, 2)), (1, q(3, 1))],
            vec![(1, q(2, 3)), (2, q(-1, 1))],
            vec![(0, q(1, 4)), (1, q(11, 6)), (2, q(-1, 2))],
        ]
        .into_iter()
        .map(SparseRow::from_entries)
        .collect();
        let mut echelon = Echelon::<ModP>::new(3, EchelonOptions::tracked());
        let mut outcome = None;
        for r in &q_rows {
            outcome = Some(echelon.insert(r.map(ModP::from_rational).unwrap()));
        }
        let combination = outcome.unwrap().combination().unwrap().to_vec();
        let lifted = lift_dependency(&q_rows[..2], &q_rows[2], &combination);
        assert_eq!(lifted, Some(vec![(0, q(1, 2)), (1, q(1, 2))]));
        // a wrong row, or a missing one, is not certified
        assert_eq!(lift_dependency(&q_rows[..2], &q_rows[0], &combination), None);
        assert_eq!(lift_dependency(&q_rows[..1], &q_rows[2], &combination), None);
    }

    #[test]
    fn chinese_remaindering_lifts_large_coefficients() {
        let x = BigRational::new(BigInt::from(3).pow(30u32), BigInt::from(7).pow(15u32));
        let m1 = BigInt::from(ModP::PRIME);
        let r1 = ModP::from_rational(&x).unwrap().value();
        let r2 = ModPrime::<SECOND_PRIME>::from_rational(&x).unwrap().value();
        let mut lift = Lift { row: 0, residues: vec![(0, BigInt::from(r1))] };
        assert_ne!(lift.reconstruct(&m1), Some(vec![(0, x.clone())]));
        lift.absorb(&m1, SECOND_PRIME, &[(0, r2)]);
        let m12 = &m1 * BigInt::from(SECOND_PRIME);
        assert_eq!(lift.reconstruct(&m12), Some(vec![(0, x)]));
    }
}
