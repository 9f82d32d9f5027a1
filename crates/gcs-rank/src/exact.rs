//! The certified exact path: elimination modulo primes, lifted to ℚ and checked exactly.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::Field;
use crate::Rat;
use crate::echelon::{EchelonOptions, Insertion, RowAnalysis, analyse_rows};
use crate::error::RankError;
use crate::modp::{ModP, ModQ, bigint_mod, inv_mod, nth_lifting_prime, with_modulus};
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
        /// The primes whose product was used (the most any one dependency needed), the
        /// elimination prime first.
        primes: Vec<u64>,
    },
    /// Elimination modulo `prime`, whose pivots prove the lower bound; some dependencies were
    /// proven by exact kernel vectors ([`KernelHint`]: the circuit leaves no motion the
    /// dependent row can see), the others lifted to ℚ and checked as above.
    KernelCertified {
        /// The prime, [`ModP::PRIME`].
        prime: u64,
        /// How many dependencies the kernel vectors proved.
        kernel: usize,
        /// The primes used to lift the others (the elimination prime first).
        primes: Vec<u64>,
    },
    /// No arithmetic: the generic rank of a 2D bar framework by the (2,3) pebble game, which
    /// Laman's theorem proves equal to it (`gcs_rigidity::pebble_game`).
    PebbleGame,
}

impl Proof {
    /// A short name for reports: `"rational"`, `"modular"` or `"multimodular"`.
    pub fn name(&self) -> &'static str {
        match self {
            Proof::Rational => "rational",
            Proof::ModularCertified { .. } => "modular",
            Proof::MultiModularCertified { .. } => "multimodular",
            Proof::KernelCertified { .. } => "kernel",
            Proof::PebbleGame => "pebble game",
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
                write!(f, "elimination modulo {}, certified over Q", product(primes))
            }
            Proof::KernelCertified { prime, kernel, primes } => {
                write!(
                    f,
                    "elimination modulo {prime}, certified over Q: {kernel} {} proven by exact \
                     kernel vectors",
                    if *kernel == 1 { "dependency" } else { "dependencies" }
                )?;
                if primes.len() > 1 {
                    write!(f, ", others lifted modulo {}", product(primes))?;
                }
                Ok(())
            }
            Proof::PebbleGame => {
                write!(f, "the (2,3) pebble game of the bar framework (Laman's theorem)")
            }
        }
    }
}

/// A product of primes for messages: every factor up to three, else the first and a count.
fn product(primes: &[u64]) -> String {
    if primes.len() <= 3 {
        primes.iter().map(u64::to_string).collect::<Vec<_>>().join(" · ")
    } else {
        format!("{} · … ({} primes)", primes[0], primes.len())
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
    let reduced = a.mod_floor(m);
    // (Lehmer's batches far from the bound, Euclid's steps near it: the same stopping step.)
    let (_, r1, _, t1) =
        crate::gcd::euclid_to_bound(m.magnitude(), reduced.magnitude(), bound.magnitude());
    let r1 = BigInt::from(r1);
    if t1.is_zero() || t1.abs() > bound || !crate::gcd::gcd_int(&r1, &t1).is_one() {
        return None;
    }
    let (n, d) = if t1.is_negative() { (-r1, -t1) } else { (r1, t1) };
    Some(BigRational::new_raw(n, d))
}

/// [`rational_reconstruction`] step by step with num-bigint's division (the reference the
/// tests hold the batched one to).
#[cfg(test)]
fn rational_reconstruction_plain(a: &BigInt, m: &BigInt) -> Option<BigRational> {
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

/// `(insertion id, residue)` pairs of one combination, sorted by id.
type Residues = Vec<(usize, u64)>;

/// A dependency whose coefficients are being lifted by Chinese remaindering.
struct Lift {
    /// `(id, residue modulo the current modulus)`, sorted by id.
    residues: Vec<(usize, BigInt)>,
    /// The id whose reconstruction failed last ([`Lift::reconstruct`]).
    failed: Option<usize>,
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

    /// Every coefficient reconstructed from its residue, `None` when one does not reconstruct.
    /// The one that failed last is tried first: the largest coefficient needs the most primes,
    /// so it usually fails again, and one failure decides (the answer is the same in any
    /// order).
    fn reconstruct(&mut self, modulus: &BigInt) -> Option<Vec<(usize, BigRational)>> {
        if let Some(id) = self.failed
            && let Some((_, r)) = self.residues.iter().find(|(x, _)| *x == id)
            && rational_reconstruction(r, modulus).is_none()
        {
            return None;
        }
        let mut out = Vec::with_capacity(self.residues.len());
        for (id, r) in &self.residues {
            let Some(q) = rational_reconstruction(r, modulus) else {
                self.failed = Some(*id);
                return None;
            };
            if !Field::is_zero(&q) {
                out.push((*id, q));
            }
        }
        Some(out)
    }
}

/// The exact path: the rank over ℚ and the outcome of every row, proven, at modular speed.
///
/// Eliminates modulo `p = 2^61 − 1` ([`ModP`]) with combinations tracked. Pivots found mod `p`
/// prove the lower bound (a minor nonzero mod `p` is nonzero over ℚ), and each dependency found
/// mod `p` is lifted to ℚ by [`rational_reconstruction`] of its coefficients and checked
/// exactly against the rational rows, which proves the upper bound; together they prove that
/// every row has the same outcome over ℚ as mod `p`. Dependencies whose coefficients are too
/// large for one prime (numerators and denominators above about 2^30) are lifted again through
/// as many further primes as they need ([`SECOND_PRIME`], [`THIRD_PRIME`], then primes below
/// 2^62), eliminating only the rows of their circuit modulo each, by Chinese remaindering with
/// early termination: the first reconstruction that passes the exact check ends it, and
/// Hadamard's bound on the coefficients caps the number of primes. Only if the primes
/// disagree on which rows are dependent (a prime divides a minor), or a prime divides a
/// denominator, does the function fall back to exact rational elimination and report
/// [`Proof::Rational`].
///
/// The returned combinations (when `track_combinations`) are over ℚ, exact, and equal to those
/// of [`analyse_rows`] over [`BigRational`]. The pivot columns are those found mod `p` in plain
/// row echelon form ([`analyse_rows_plain`](crate::analyse_rows_plain): leading columns): they
/// always form a valid (nonsingular) pivot set over ℚ, and equal a plain rational elimination's
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
    if let Some(core) = certify(ncols, rows, None) {
        let outcomes = core
            .outcomes
            .into_iter()
            .map(|o| match o {
                Outcome::Independent { pivot } => Insertion::Independent { pivot },
                Outcome::Dependent { coefficients, .. } => Insertion::Dependent {
                    combination: if track_combinations { coefficients } else { None },
                },
            })
            .collect();
        return Ok((RowAnalysis { rank: core.rank, outcomes }, core.proof));
    }
    Ok((rational_analysis(ncols, rows, track_combinations), Proof::Rational))
}

/// Exact vectors that may prove dependencies without their coefficients: in the witness
/// method, the infinitesimal displacements, which every row of a displacement-invariant
/// constraint annihilates.
///
/// A dependency found modulo the prime, `row_i = Σ_{j ∈ C} λ_j row_j` over its circuit `C`, is
/// proven by them when the rows of `C` (with the free rows of the columns they touch) leave no
/// other kernel: let `X` be the columns of every group `C ∪ {i}` touches and `S` those rows; the
/// combinations `W` of the vectors that `S` annihilates (computed exactly) lie in the kernel of
/// `S` on `X`, whose dimension is at most `|X| − rank_p(S)`. When `rank_p(W) ≥ |X| − rank_p(S)`
/// the kernel is exactly `span(W)`, and `row_i · W = 0` (checked exactly) puts `row_i` in the
/// row space of `S` over ℚ. Both ranks are lower bounds computed modulo the prime, so the
/// argument is a proof. In rigidity terms: the circuit minus the row is rigid, so the row,
/// invariant under displacements, is implied. It costs one modular rank of the circuit, where
/// lifting the coefficients would need as many primes as they have digits (thousands of bits
/// for a large circuit at a sketch with decimal coordinates).
#[derive(Clone, Debug, PartialEq)]
pub struct KernelHint {
    /// Dense vectors over the columns (length at least the number of columns).
    pub vectors: Vec<Vec<BigRational>>,
    /// The group of each column (the entity that owns it); a certificate takes whole groups.
    pub groups: Vec<usize>,
    /// Rows `0..free_rows` may join any certificate whose groups contain their columns
    /// (entity-internal rows: normalisations); they may then be missing from the circuits
    /// reported, which only ever list rows of the combination found modulo the prime.
    pub free_rows: usize,
}

/// The outcome of [`certify_rows`].
#[derive(Clone, Debug, PartialEq)]
pub struct CertifiedRows {
    /// The rank over ℚ.
    pub rank: usize,
    /// Per row, in order: `None` when independent of the rows before it, else the ids of the
    /// earlier rows in its fundamental circuit (sorted; see [`KernelHint::free_rows`]).
    pub circuits: Vec<Option<Vec<usize>>>,
    /// How it was proven.
    pub proof: Proof,
}

/// The rank over ℚ, the outcome of every row and the support of every dependency (its
/// fundamental circuit), proven, without the coefficients of the dependencies: as
/// [`analyse_rows_exact`], but a dependency whose coefficients a prime cannot reconstruct is
/// first tried against the kernel vectors of `hint` ([`KernelHint`]), and only then lifted
/// through further primes.
///
/// The circuit of a dependency is the support of its combination modulo the prime; it is the
/// support over ℚ because the combination over ℚ reduces to it (its denominators divide a
/// minor of the circuit that the prime does not divide), and a coefficient cannot vanish over
/// ℚ and not modulo the prime; the converse (a coefficient over ℚ divisible by the prime) is
/// excluded by the exact check of lifted coefficients, and for kernel certificates by the
/// certificate's rows being the circuit itself (with free rows only).
///
/// # Errors
/// None at present (every input has a rational answer); the `Result` leaves room for limits.
pub fn certify_rows(
    ncols: usize,
    rows: &[SparseRow<BigRational>],
    hint: Option<&KernelHint>,
) -> Result<CertifiedRows, RankError> {
    if let Some(core) = certify(ncols, rows, hint) {
        let circuits = core
            .outcomes
            .into_iter()
            .map(|o| match o {
                Outcome::Independent { .. } => None,
                Outcome::Dependent { circuit, .. } => Some(circuit),
            })
            .collect();
        return Ok(CertifiedRows { rank: core.rank, circuits, proof: core.proof });
    }
    let analysis = rational_analysis(ncols, rows, true);
    let circuits = analysis
        .outcomes
        .iter()
        .map(|o| o.combination().map(|c| c.iter().map(|(id, _)| *id).collect()))
        .collect();
    Ok(CertifiedRows { rank: analysis.rank, circuits, proof: Proof::Rational })
}

/// One row's certified outcome.
enum Outcome {
    Independent {
        pivot: usize,
    },
    Dependent {
        /// The ids of the combination found modulo the prime.
        circuit: Vec<usize>,
        /// The coefficients over ℚ, when they were lifted (not for kernel certificates).
        coefficients: Option<Vec<(usize, BigRational)>>,
    },
}

struct Core {
    rank: usize,
    outcomes: Vec<Outcome>,
    proof: Proof,
}

fn certify(
    ncols: usize,
    rows: &[SparseRow<BigRational>],
    hint: Option<&KernelHint>,
) -> Option<Core> {
    let mut images = Vec::with_capacity(rows.len());
    for row in rows {
        images.push(row.map(ModP::from_rational).ok()?);
    }
    // The elimination modulo p, in plain row echelon form: its pivots prove the lower bound,
    // and without dependencies there is nothing to lift. (The reduced form with tracked
    // combinations would fill in to the dense inverse of the basis.)
    let first: RowAnalysis<ModP> = crate::analyse_rows_plain(ncols, images.iter().cloned());
    if first.rank == rows.len() {
        let outcomes = first
            .outcomes
            .iter()
            .map(|o| Outcome::Independent { pivot: o.pivot().unwrap_or(0) })
            .collect();
        return Some(Core {
            rank: first.rank,
            outcomes,
            proof: Proof::ModularCertified { prime: ModP::PRIME },
        });
    }
    let mut kernel = KernelCertifier::new(hint, &first, rows);
    let mut primes_used = 1;
    let mut by_kernel = 0;
    let mut outcomes = Vec::with_capacity(rows.len());
    for (i, outcome) in first.outcomes.iter().enumerate() {
        let combination = match outcome {
            Insertion::Independent { pivot } => {
                outcomes.push(Outcome::Independent { pivot: *pivot });
                continue;
            }
            Insertion::Dependent { combination } => combination.as_deref().unwrap_or(&[]),
        };
        let circuit: Vec<usize> = combination.iter().map(|(id, _)| *id).collect();
        // One prime: small coefficients.
        let one: Option<Vec<(usize, BigRational)>> = combination
            .iter()
            .map(|(id, c)| reconstruct_u64(c.value(), ModP::PRIME).map(|q| (*id, q)))
            .collect();
        if let Some(q) = one.filter(|q| check_combination(rows, i, q)) {
            outcomes.push(Outcome::Dependent { circuit, coefficients: Some(q) });
            continue;
        }
        // Exact kernel vectors: no coefficients needed.
        if let Some(k) = kernel.as_mut()
            && k.certifies(rows, &images, i, &circuit)
        {
            by_kernel += 1;
            outcomes.push(Outcome::Dependent { circuit, coefficients: None });
            continue;
        }
        // As many primes as the coefficients need, on the circuit alone.
        let (q, used) = lift_circuit(ncols, rows, i, combination)?;
        primes_used = primes_used.max(used);
        outcomes.push(Outcome::Dependent { circuit, coefficients: Some(q) });
    }
    let mut primes = vec![ModP::PRIME];
    primes.extend((0..primes_used - 1).map(nth_lifting_prime));
    let proof = if by_kernel > 0 {
        Proof::KernelCertified { prime: ModP::PRIME, kernel: by_kernel, primes }
    } else if primes.len() == 1 {
        Proof::ModularCertified { prime: ModP::PRIME }
    } else {
        Proof::MultiModularCertified { primes }
    };
    Some(Core { rank: first.rank, outcomes, proof })
}

/// Lifts the dependency of row `i` found modulo [`ModP::PRIME`] (`first`: its combination)
/// through further primes, eliminating only the rows of its circuit modulo each, until a
/// rational reconstruction passes the exact check; gives up past Hadamard's bound on the
/// coefficients. Returns the coefficients and the number of primes used (the first included).
fn lift_circuit(
    ncols: usize,
    rows: &[SparseRow<BigRational>],
    i: usize,
    first: &[(usize, ModP)],
) -> Option<(Vec<(usize, BigRational)>, usize)> {
    let circuit: Vec<usize> = first.iter().map(|(id, _)| *id).collect();
    let mut lift = Lift {
        residues: first.iter().map(|(id, c)| (*id, BigInt::from(c.value()))).collect(),
        failed: None,
    };
    let mut modulus = BigInt::from(ModP::PRIME);
    let needed = 2 * coefficient_bound_bits(rows, &circuit, i) + 2;
    let mut used = 1;
    let mut k = 0;
    while modulus.bits() <= needed + 64 {
        let q = nth_lifting_prime(k);
        k += 1;
        // A prime that divides a denominator or a minor of the circuit cannot help: skip it.
        let Some(residues) = with_modulus(q, || circuit_residues(ncols, rows, &circuit, i)) else {
            continue;
        };
        lift.absorb(&modulus, q, &residues);
        modulus *= BigInt::from(q);
        used += 1;
        if let Some(q) = lift.reconstruct(&modulus)
            && check_combination(rows, i, &q)
        {
            return Some((q, used));
        }
    }
    None
}

/// The combination of row `i` over the rows `circuit` modulo the current [`ModQ`] prime, as
/// `(id, residue)` sorted by id; `None` when the circuit's rows are dependent there or row `i`
/// is not in their span (the prime divides a minor or a denominator).
fn circuit_residues(
    ncols: usize,
    rows: &[SparseRow<BigRational>],
    circuit: &[usize],
    i: usize,
) -> Option<Residues> {
    let mut echelon = crate::Echelon::<ModQ>::new(ncols, EchelonOptions::tracked());
    for &j in circuit {
        let image = rows[j].map(ModQ::from_rational).ok()?;
        if !echelon.insert(image).is_independent() {
            return None;
        }
    }
    let image = rows[i].map(ModQ::from_rational).ok()?;
    match echelon.insert(image) {
        Insertion::Dependent { combination: Some(c) } => {
            Some(c.iter().map(|(local, v)| (circuit[*local], v.value())).collect())
        }
        _ => None,
    }
}

/// Bits of Hadamard's bound on the numerators and denominators of the coefficients of row `i`
/// over its circuit: with each row scaled to integers by the lcm `d_r` of its denominators,
/// Cramer's rule makes every coefficient a ratio of minors times `d_j / d_i`, and a minor is at
/// most the product of the rows' Euclidean norms.
fn coefficient_bound_bits(rows: &[SparseRow<BigRational>], circuit: &[usize], i: usize) -> u64 {
    let mut total = 0;
    let mut largest_denominator = 0;
    for &r in circuit.iter().chain(std::iter::once(&i)) {
        let entries = rows[r].entries();
        let mut lcm = BigInt::one();
        for (_, v) in entries {
            lcm = lcm.lcm(v.denom());
        }
        let biggest =
            entries.iter().map(|(_, v)| (v.numer() * (&lcm / v.denom())).bits()).max().unwrap_or(0);
        // ‖R‖₂ ≤ √nnz · max |entry|
        total += biggest + (entries.len().max(1) as u64).ilog2() as u64 / 2 + 1;
        largest_denominator = largest_denominator.max(lcm.bits());
    }
    total + largest_denominator
}

/// The kernel-vector certificates of [`KernelHint`], with their working data.
struct KernelCertifier<'h> {
    hint: &'h KernelHint,
    /// Group → its columns.
    columns: Vec<Vec<usize>>,
    /// Group → the free rows (independent modulo the prime) within it.
    free: Vec<Vec<usize>>,
    /// Row → its products with the hint's vectors, exact (computed on demand, in [`Rat`]:
    /// machine words while the numbers are small).
    products: Vec<Option<Vec<Rat>>>,
    /// The hint's vectors in [`Rat`].
    vectors: Vec<Vec<Rat>>,
    /// The hint's vectors modulo the prime.
    vectors_p: Vec<Vec<ModP>>,
}

impl<'h> KernelCertifier<'h> {
    fn new(
        hint: Option<&'h KernelHint>,
        first: &RowAnalysis<ModP>,
        rows: &[SparseRow<BigRational>],
    ) -> Option<Self> {
        let hint = hint?;
        let ngroups = hint.groups.iter().max().map_or(0, |g| g + 1);
        let mut columns = vec![Vec::new(); ngroups];
        for (c, g) in hint.groups.iter().enumerate() {
            columns[*g].push(c);
        }
        let vectors_p = hint
            .vectors
            .iter()
            .map(|v| v.iter().map(ModP::from_rational).collect::<Result<Vec<_>, _>>())
            .collect::<Result<Vec<_>, _>>()
            .ok()?;
        let mut free = vec![Vec::new(); ngroups];
        for (r, outcome) in first.outcomes.iter().enumerate().take(hint.free_rows) {
            if outcome.is_independent()
                && let Some(g) = rows[r].entries().first().and_then(|(c, _)| hint.groups.get(*c))
            {
                free[*g].push(r);
            }
        }
        Some(KernelCertifier {
            hint,
            columns,
            free,
            products: vec![None; first.outcomes.len()],
            vectors: hint.vectors.iter().map(|v| v.iter().map(Rat::from).collect()).collect(),
            vectors_p,
        })
    }

    fn group_of(&self, col: usize) -> Option<usize> {
        self.hint.groups.get(col).copied()
    }

    /// `row · v` for every hint vector, exactly.
    fn products(&mut self, rows: &[SparseRow<BigRational>], r: usize) -> Option<&[Rat]> {
        if self.products[r].is_none() {
            let row: Vec<(usize, Rat)> =
                rows[r].entries().iter().map(|(c, a)| (*c, Rat::from(a))).collect();
            let mut out = Vec::with_capacity(self.vectors.len());
            for v in &self.vectors {
                let mut sum = Rat::ZERO;
                for (c, a) in &row {
                    let x = v.get(*c)?;
                    if !x.is_zero() {
                        sum += a * x;
                    }
                }
                out.push(sum);
            }
            self.products[r] = Some(out);
        }
        self.products[r].as_deref()
    }

    /// Whether the kernel vectors prove that row `i` is in the span of the rows `circuit`
    /// (see [`KernelHint`]).
    fn certifies(
        &mut self,
        rows: &[SparseRow<BigRational>],
        images: &[SparseRow<ModP>],
        i: usize,
        circuit: &[usize],
    ) -> bool {
        self.try_certify(rows, images, i, circuit).unwrap_or(false)
    }

    fn try_certify(
        &mut self,
        rows: &[SparseRow<BigRational>],
        images: &[SparseRow<ModP>],
        i: usize,
        circuit: &[usize],
    ) -> Option<bool> {
        let k = self.hint.vectors.len();
        // The groups the circuit and the row touch, and their columns.
        let mut groups = Vec::new();
        for &r in circuit.iter().chain(std::iter::once(&i)) {
            for (c, _) in rows[r].entries() {
                groups.push(self.group_of(*c)?);
            }
        }
        groups.sort_unstable();
        groups.dedup();
        let cols: Vec<usize> =
            groups.iter().flat_map(|g| self.columns[*g].iter().copied()).collect();
        // The certificate's rows: the circuit, and the free rows of those groups.
        let mut set: Vec<usize> = circuit.to_vec();
        for g in &groups {
            for &r in &self.free[*g] {
                if r < i
                    && circuit.binary_search(&r).is_err()
                    && rows[r].entries().iter().all(|(c, _)| {
                        self.group_of(*c).is_some_and(|g| groups.binary_search(&g).is_ok())
                    })
                {
                    set.push(r);
                }
            }
        }
        let width = cols.len();
        let rank_s =
            crate::echelon_rank(self.hint.groups.len(), set.iter().map(|&r| images[r].clone())).0;
        if rank_s + k < width {
            return Some(false);
        }
        // The combinations of the vectors that the certificate's rows annihilate, exactly.
        let mut products = crate::Echelon::<Rat>::new(k, EchelonOptions::default());
        for &r in &set {
            if products.rank() == k {
                break;
            }
            let p = self.products(rows, r)?.to_vec();
            let row = SparseRow::from_entries(p.into_iter().enumerate().collect());
            if !row.is_zero() {
                products.insert(row);
            }
        }
        let lambdas = products.kernel_basis();
        // Their rank on the certificate's columns, modulo the prime (a lower bound).
        let local: std::collections::HashMap<usize, usize> =
            cols.iter().enumerate().map(|(l, c)| (*c, l)).collect();
        let mut w_rows = Vec::with_capacity(lambdas.len());
        for lambda in &lambdas {
            let lp: Vec<(usize, ModP)> = lambda
                .entries()
                .iter()
                .map(|(g, x)| ModP::from_rat(x).map(|v| (*g, v)))
                .collect::<Result<_, _>>()
                .ok()?;
            let mut entries = Vec::with_capacity(width);
            for &c in &cols {
                let mut sum = ModP::zero();
                for (g, x) in &lp {
                    sum = sum.add(&x.mul(self.vectors_p[*g].get(c)?));
                }
                if !sum.is_zero() {
                    entries.push((local[&c], sum));
                }
            }
            w_rows.push(SparseRow::from_entries(entries));
        }
        let rank_w = crate::echelon_rank(width, w_rows).0;
        if rank_s + rank_w < width {
            return Some(false);
        }
        // The kernel of the certificate's rows is span(W): row i must vanish on it, exactly.
        let pi = self.products(rows, i)?.to_vec();
        Some(lambdas.iter().all(|lambda| {
            let mut sum = Rat::ZERO;
            for (g, x) in lambda.entries() {
                sum += x * &pi[*g];
            }
            sum.is_zero()
        }))
    }
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
    use crate::ModPrime;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    #[test]
    fn batched_reconstruction_matches_the_step_by_step_one() {
        // Random odd moduli of 64 to 5,000 bits, against random residues (mostly no fraction)
        // and against the residues of fractions with numerator and denominator of up to half
        // the modulus' bits (found, or refused just past the bound).
        let mut state = 0x2545_F491_4F6C_DD1D_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let big = |bits: u64, next: &mut dyn FnMut() -> u64| {
            let words = bits.div_ceil(64) as usize;
            let digits: Vec<u32> = (0..2 * words).map(|_| next() as u32).collect();
            BigInt::from(num_bigint::BigUint::new(digits) >> (64 * words as u64 - bits))
        };
        let mut found = 0;
        for round in 0..600 {
            let bits = [64, 65, 127, 128, 200, 700, 1500, 5000][round % 8];
            let m = big(bits, &mut next) | BigInt::one() | (BigInt::one() << (bits - 1));
            let half = bits / 2;
            let residue = if round % 3 == 0 {
                big(bits, &mut next)
            } else {
                let n = big(1 + next() % half, &mut next);
                let d = big(1 + next() % half, &mut next) | BigInt::one();
                let Some(inv) = d.modinv(&m) else { continue };
                let n = if next() % 2 == 0 { -n } else { n };
                (n * inv).mod_floor(&m)
            };
            let batched = rational_reconstruction(&residue, &m);
            found += usize::from(batched.is_some());
            assert_eq!(batched, rational_reconstruction_plain(&residue, &m), "{residue} mod {m}");
        }
        assert!(found > 100, "only {found} fractions found: the test lost its point");
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
    fn reconstruction_tries_the_last_failure_first_with_the_same_answer() {
        // Three coefficients, the middle one too large for one prime: the lift remembers it,
        // and each answer is the one a fresh lift (no failure remembered) gives.
        let xs = [
            q(3, 7),
            BigRational::new(BigInt::from(5).pow(40u32), BigInt::from(11).pow(12u32)),
            q(-2, 9),
        ];
        let image = |p: u64| -> Vec<(usize, u64)> {
            xs.iter()
                .enumerate()
                .map(|(id, x)| (id, with_modulus(p, || ModQ::from_rational(x).unwrap().value())))
                .collect()
        };
        let first = image(ModP::PRIME);
        let mut lift = Lift {
            residues: first.iter().map(|(id, r)| (*id, BigInt::from(*r))).collect(),
            failed: None,
        };
        let mut modulus = BigInt::from(ModP::PRIME);
        let mut answers = Vec::new();
        for k in 0..4 {
            let fresh =
                Lift { residues: lift.residues.clone(), failed: None }.reconstruct(&modulus);
            let answer = lift.reconstruct(&modulus);
            assert_eq!(answer, fresh);
            if answer.is_none() {
                assert_eq!(lift.failed, Some(1));
            }
            answers.push(answer);
            let p = nth_lifting_prime(k);
            lift.absorb(&modulus, p, &image(p));
            modulus *= BigInt::from(p);
        }
        assert_eq!(answers[0], None);
        assert_eq!(answers.last().cloned().flatten(), Some(xs.into_iter().enumerate().collect()));
    }

    #[test]
    fn chinese_remaindering_lifts_large_coefficients() {
        let x = BigRational::new(BigInt::from(3).pow(30u32), BigInt::from(7).pow(15u32));
        let m1 = BigInt::from(ModP::PRIME);
        let r1 = ModP::from_rational(&x).unwrap().value();
        let r2 = ModPrime::<SECOND_PRIME>::from_rational(&x).unwrap().value();
        let mut lift = Lift { residues: vec![(0, BigInt::from(r1))], failed: None };
        assert_ne!(lift.reconstruct(&m1), Some(vec![(0, x.clone())]));
        lift.absorb(&m1, SECOND_PRIME, &[(0, r2)]);
        let m12 = &m1 * BigInt::from(SECOND_PRIME);
        assert_eq!(lift.reconstruct(&m12), Some(vec![(0, x)]));
    }
}
