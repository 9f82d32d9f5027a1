//! Pins of the papers: what the witness paper (Michelucci et al., SPM 2010; `data/paper/`)
//! and the flow paper (Jermann et al., IJCAI 2003) say of their examples, and every claim that
//! the header comments of the models in `data/` make about what the analysis computes (rank,
//! DOF, trivial motions, redundant constraints and their spanning groups, clusters, and the
//! W-decompositions where a header states one).
//!
//! The headers count in degrees of freedom: a homogeneous line or plane is charged its DOF,
//! not its coordinates, and its normalisation row is not an equation. The report counts
//! columns and rows of the Jacobian (`unknowns`, `equations`, `rank` include the
//! entity-internal rows), so the table below compares `unknowns − internal_equations`,
//! `equations − internal_equations` and `rank − internal_equations` with the headers.

use std::collections::BTreeSet;
use std::path::Path;

use gcs_analysis::{Analysis, AnalysisOptions, DecompositionNode, analyze};
use gcs_jacobian::{Layout, RowOwner, WitnessOptions, WitnessSource, find_witness};
use gcs_model::System;
use gcs_rank::{BigRational, Echelon, EchelonOptions, Insertion, SparseRow};
use gcs_suite::load;

fn read(file: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(file);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn analysis(system: &System, decompose: bool) -> Analysis {
    let options = AnalysisOptions { decompose, ..AnalysisOptions::default() };
    analyze(system, &options).unwrap_or_else(|e| panic!("{}: {e}", system.name()))
}

fn cid(system: &System, c: gcs_model::ConstraintIdx) -> String {
    system.constraint(c).id.clone()
}

/// `(constraint, rows, doc, spanning group)` with ids.
fn redundant(system: &System, a: &Analysis) -> Vec<(String, usize, usize, Vec<String>)> {
    a.redundant
        .iter()
        .map(|r| {
            let group = r.spanning_group.iter().map(|c| cid(system, *c)).collect();
            (cid(system, r.constraint), r.rows, r.doc, group)
        })
        .collect()
}

fn strings(ids: &[&str]) -> Vec<String> {
    ids.iter().map(|s| (*s).to_owned()).collect()
}

fn q(num: i64, den: i64) -> BigRational {
    BigRational::new(num.into(), den.into())
}

// ---------------------------------------------------------------------------------------------
// The kite (witness paper, fig. 4, tables 1 and 2)

#[test]
fn kite_rank_redundancy_and_rigidity() {
    let s = load("data/paper/kite.ron");
    let a = analysis(&s, false);
    assert_eq!(a.witness.source, WitnessSource::Sketch, "table 1's witness is the sketch");
    assert_eq!((a.unknowns, a.equations, a.internal_equations), (8, 6, 0));
    assert_eq!(a.rank, 5);
    assert_eq!((a.dof_absolute, a.trivial_motions, a.dof), (3, 3, 0));
    assert!(a.rigid());
    assert!(!a.well_constrained());
    assert_eq!(
        redundant(&s, &a),
        vec![("c6".to_owned(), 1, 1, strings(&["c1", "c2", "c3", "c4", "c5"]))]
    );
    // The count is fooled: 8 − 6 = 2 < 3 displacements says "over-constrained by one" and
    // nothing about which constraint; the analysis says exactly c6 (or one of c1..c5).
    assert_eq!(s.naive_dof(), 2);
}

/// Table 1: the reduced row echelon form of r1..r5 at p1=(2,7), p2=(5,6), p3=(1,1),
/// p4=(6,3), and r6 = 4 (r'2 − r'1).
#[test]
fn kite_reduced_row_echelon_form_of_table_1() {
    let s = load("data/paper/kite.ron");
    let layout = Layout::new(&s);
    let witness = find_witness(&s, &layout, &WitnessOptions::default()).unwrap();
    assert_eq!(witness.source, WitnessSource::Sketch);
    let ints: Vec<BigRational> = [2, 7, 5, 6, 1, 1, 6, 3].into_iter().map(|v| q(v, 1)).collect();
    assert_eq!(witness.coords, ints, "the witness of table 1");
    // Columns x1 y1 x2 y2 x3 y3 x4 y4, in this order.
    let names = ["x1", "y1", "x2", "y2", "x3", "y3", "x4", "y4"];
    for (k, e) in s.entity_indices().enumerate() {
        assert_eq!(layout.columns(e), 2 * k..2 * k + 2, "columns of {}", s.entity(e).id);
    }

    let jacobian = witness.jacobian::<BigRational>(&s, &layout).unwrap();
    assert_eq!(jacobian.ncols, 8);
    assert_eq!(jacobian.rows.len(), 6);
    for (row, owner) in jacobian.owners.iter().enumerate() {
        assert_eq!(*owner, RowOwner::Constraint(gcs_model::ConstraintIdx(row as u32)));
    }

    let mut echelon = Echelon::new(8, EchelonOptions::default());
    for (k, row) in jacobian.rows[..5].iter().enumerate() {
        assert!(echelon.insert(row.clone()).is_independent(), "r{} is independent", k + 1);
    }
    assert_eq!(echelon.rank(), 5);
    let pivots: Vec<&str> = echelon.pivot_columns().iter().map(|&c| names[c]).collect();
    let free: Vec<&str> = echelon.free_columns().iter().map(|&c| names[c]).collect();
    assert_eq!(pivots, ["x1", "y1", "x2", "y2", "x3"]);
    assert_eq!(free, ["y3", "x4", "y4"]);

    // x1 − 4/5 y3 − x4 + 4/5 y4,  y1 − 4/5 y3 − 1/5 y4,  x2 − 3/5 y3 − x4 + 3/5 y4,
    // y2 − 1/5 y3 − 4/5 y4,  x3 + 2/5 y3 − x4 − 2/5 y4  (columns y3 = 5, x4 = 6, y4 = 7).
    let expected: [(usize, [(i64, i64); 3]); 5] = [
        (0, [(-4, 5), (-1, 1), (4, 5)]),
        (1, [(-4, 5), (0, 1), (-1, 5)]),
        (2, [(-3, 5), (-1, 1), (3, 5)]),
        (3, [(-1, 5), (0, 1), (-4, 5)]),
        (4, [(2, 5), (-1, 1), (-2, 5)]),
    ];
    let mut reduced = Vec::new();
    for (pivot, free_part) in expected {
        let mut entries = vec![(pivot, q(1, 1))];
        for (col, (n, d)) in [5, 6, 7].into_iter().zip(free_part) {
            if n != 0 {
                entries.push((col, q(n, d)));
            }
        }
        let want = SparseRow::from_entries(entries);
        let got = echelon.pivot_row(pivot).expect("a pivot row");
        assert_eq!(got, &want, "RREF row of pivot {}", names[pivot]);
        reduced.push(want);
    }

    // r6 = dist(p1, p4) is proportional to (−4, 4, 0, 0, 0, 0, 4, −4) = 4 (r'2 − r'1).
    let r6 = &jacobian.rows[5];
    let scale = r6.get(0).expect("an x1 entry").clone() / q(-4, 1);
    let table = SparseRow::from_entries(
        [(0, -4), (1, 4), (6, 4), (7, -4)].into_iter().map(|(c, v)| (c, q(v, 1))).collect(),
    );
    assert_eq!(r6, &table.scaled(&scale), "r6 is (−4, 4, 0, 0, 0, 0, 4, −4) up to scale");
    let four_diff = SparseRow::from_entries(
        (0..8)
            .map(|c| {
                let at = |r: &SparseRow<BigRational>| r.get(c).cloned().unwrap_or_else(|| q(0, 1));
                (c, q(4, 1) * (at(&reduced[1]) - at(&reduced[0])))
            })
            .filter(|(_, v)| *v != q(0, 1))
            .collect(),
    );
    assert_eq!(four_diff, table, "4 (r'2 − r'1) is r6 of table 1");
    assert!(echelon.reduce(r6).is_zero(), "r6 reduces to zero: c6 is redundant");
    match echelon.insert(r6.clone()) {
        Insertion::Dependent { .. } => {}
        other => panic!("r6 must be dependent, got {other:?}"),
    }
    assert_eq!(echelon.rank(), 5);
}

// ---------------------------------------------------------------------------------------------
// The double banana (witness paper, fig. 5)

#[test]
fn double_banana_fools_the_count_but_not_the_witness() {
    let s = load("data/paper/double_banana.ron");
    // Σ DOF − Σ DOC = 24 − 18 = 6 = the displacements of space: the count says rigid.
    assert_eq!((s.dof_sum(), s.doc_sum()), (24, 18));
    assert_eq!(s.naive_dof(), s.dim().displacements() as i64);
    assert_eq!(s.naive_dof(), 6);

    let a = analysis(&s, false);
    assert_eq!(a.rank, 17);
    assert_eq!((a.trivial_motions, a.dof), (6, 1), "one internal DOF: a banana turns about NS");
    assert!(!a.rigid());
    let last = s.constraints().last().unwrap();
    assert_eq!(last.id, "Sb3");
    let others: Vec<String> =
        s.constraints()[..s.constraints().len() - 1].iter().map(|c| c.id.clone()).collect();
    assert_eq!(others.len(), 17);
    assert_eq!(redundant(&s, &a), vec![("Sb3".to_owned(), 1, 1, others)]);
}

// ---------------------------------------------------------------------------------------------
// Fig. 6: the harmonic conjugate

#[test]
fn fig6_redundancy_induced_by_a_theorem() {
    let text = read("data/paper/fig6_harmonic.ron");
    let s = System::from_ron_str(&text, Some("fig6_harmonic.ron")).unwrap();
    let a = analysis(&s, false);
    assert_eq!(s.constraints().last().unwrap().id, "d_ay");
    let earlier: Vec<String> =
        s.constraints()[..12].iter().map(|c| c.id.clone()).collect::<Vec<_>>();
    assert_eq!(redundant(&s, &a), vec![("d_ay".to_owned(), 1, 1, earlier)]);
    assert_eq!(a.dof, 3, "p moves freely (2) and l turns about x (1)");
    assert_eq!(a.trivial_motions, 3);

    // What every count says: d_ay removes one more degree of freedom (DOC 1 on top of an
    // independent system). Without it the system has the same 3 internal DOF.
    let without: String =
        text.lines().filter(|l| !l.contains(r#"id: "d_ay""#)).collect::<Vec<_>>().join("\n");
    let s0 = System::from_ron_str(&without, Some("fig6_without_d_ay.ron")).unwrap();
    assert_eq!(s0.constraints().len(), 12);
    assert_eq!(s.naive_dof(), s0.naive_dof() - 1, "the count charges d_ay one DOF");
    let a0 = analysis(&s0, false);
    assert!(a0.redundant.is_empty());
    assert_eq!(a0.rank, a.rank, "d_ay adds nothing to the rank");
    assert_eq!(a0.dof, a.dof, "with or without d_ay: 3 internal DOF");
}

// ---------------------------------------------------------------------------------------------
// The flow paper's fig. 1a: three parallel lines

#[test]
fn flow_fig1a_parallel_lines_admit_two_trivial_motions() {
    let s = load("data/paper/flow_fig1a.ron");
    let a = analysis(&s, false);
    assert_eq!(a.trivial_motions, 2, "a translation along the lines moves no line");
    assert_eq!(a.dof_absolute, 2);
    assert_eq!(a.dof, 0);
    assert!(a.rigid());
    assert!(a.redundant.is_empty());
    assert!(a.well_constrained());
}

// ---------------------------------------------------------------------------------------------
// CAD rectangles

#[test]
fn rectangle_is_well_constrained_and_fixed_in_place() {
    let s = load("data/sketches/rectangle.ron");
    let a = analysis(&s, false);
    assert_eq!((a.unknowns, a.rank, a.dof_absolute), (8, 8, 0));
    assert_eq!(a.trivial_motions, 0, "Fix and Horizontal/Vertical remove every displacement");
    assert_eq!(a.dof, 0);
    assert!(a.well_constrained());
}

#[test]
fn overdimensioned_rectangle_flags_the_last_width() {
    let s = load("data/sketches/rectangle_overdimensioned.ron");
    let a = analysis(&s, false);
    assert_eq!((a.rank, a.dof_absolute, a.trivial_motions, a.dof), (8, 0, 0, 0));
    assert!(a.rigid() && !a.well_constrained());
    assert_eq!(
        redundant(&s, &a),
        vec![("width_top".to_owned(), 1, 1, strings(&["v_right", "v_left", "width"]))]
    );
}

// ---------------------------------------------------------------------------------------------
// Every header claim, table-driven

/// What a header of `data/` says the analysis must find. Counts are in DOF terms (see the
/// module documentation); `None` where the header says nothing.
struct Claim {
    file: &'static str,
    unknowns: Option<usize>,
    equations: Option<usize>,
    rank: usize,
    dof_absolute: usize,
    trivial_motions: usize,
    dof: usize,
    /// `(constraint, spanning group)`, in file order; every one is a full redundancy (rows = doc).
    redundant: &'static [(&'static str, &'static [&'static str])],
    /// Clusters stated by the header, as `(entities, constraints)`; `None` for the
    /// constraints when the header lists only the entities. `None` when the header does not
    /// list all clusters.
    clusters: Option<&'static [HeaderCluster]>,
}

/// A cluster as a header states it: its entities, and its constraints when listed.
type HeaderCluster = (&'static [&'static str], Option<&'static [&'static str]>);

const K4_R: &[&str] = &["r1r2", "r1r3", "r1r4", "r2r3", "r2r4"];
const K4_S: &[&str] = &["s1s2", "s1s3", "s1s4", "s2s3", "s2s4"];
const K4_T: &[&str] = &["t1t2", "t1t3", "t1t4", "t2t3", "t2t4"];

const CLAIMS: &[Claim] = &[
    Claim {
        file: "data/paper/butterfly.ron",
        unknowns: Some(10),
        equations: Some(6),
        rank: 6,
        dof_absolute: 4,
        trivial_motions: 3,
        dof: 1,
        redundant: &[],
        clusters: Some(&[
            (&["p0", "p1", "p2"], Some(&["d01", "d12", "d20"])),
            (&["p0", "p3", "p4"], Some(&["d03", "d34", "d40"])),
        ]),
    },
    Claim {
        file: "data/paper/chain.ron",
        unknowns: Some(14),
        equations: Some(9),
        rank: 9,
        dof_absolute: 5,
        trivial_motions: 3,
        dof: 2,
        redundant: &[],
        clusters: Some(&[
            (&["p1", "p2", "p3"], Some(&["d12", "d13", "d23"])),
            (&["p3", "p4", "p5"], Some(&["d34", "d35", "d45"])),
            (&["p5", "p6", "p7"], Some(&["d56", "d57", "d67"])),
        ]),
    },
    Claim {
        file: "data/paper/double_banana.ron",
        unknowns: Some(24),
        equations: Some(18),
        rank: 17,
        dof_absolute: 7,
        trivial_motions: 6,
        dof: 1,
        redundant: &[(
            "Sb3",
            &[
                "a1a2", "a2a3", "a3a1", "Na1", "Na2", "Na3", "Sa1", "Sa2", "Sa3", "b1b2", "b2b3",
                "b3b1", "Nb1", "Nb2", "Nb3", "Sb1", "Sb2",
            ],
        )],
        clusters: Some(&[
            (
                &["N", "S", "a1", "a2", "a3"],
                Some(&["a1a2", "a2a3", "a3a1", "Na1", "Na2", "Na3", "Sa1", "Sa2", "Sa3"]),
            ),
            (
                &["N", "S", "b1", "b2", "b3"],
                Some(&["b1b2", "b2b3", "b3b1", "Nb1", "Nb2", "Nb3", "Sb1", "Sb2", "Sb3"]),
            ),
        ]),
    },
    Claim {
        file: "data/paper/fig6_harmonic.ron",
        unknowns: Some(18),
        equations: Some(13),
        rank: 12,
        dof_absolute: 6,
        trivial_motions: 3,
        dof: 3,
        redundant: &[(
            "d_ay",
            &[
                "x_on_ab",
                "d_ab",
                "d_bx",
                "x_on_l",
                "p1_on_ap",
                "p1_on_l",
                "p2_on_bp",
                "p2_on_l",
                "pp_on_ap2",
                "pp_on_bp1",
                "y_on_ab",
                "y_on_ppp",
            ],
        )],
        // Checked separately (fig6_clusters): the header leaves the listing of segments open.
        clusters: None,
    },
    Claim {
        file: "data/paper/fig9a_w_decomposable.ron",
        unknowns: Some(40),
        equations: Some(40),
        rank: 37,
        dof_absolute: 3,
        trivial_motions: 3,
        dof: 0,
        redundant: &[("r3r4", K4_R), ("s3s4", K4_S), ("t3t4", K4_T)],
        // One cluster with everything: checked by `whole`.
        clusters: None,
    },
    Claim {
        file: "data/paper/fig9b_w_indecomposable.ron",
        unknowns: Some(16),
        equations: Some(13),
        rank: 13,
        dof_absolute: 3,
        trivial_motions: 3,
        dof: 0,
        redundant: &[],
        clusters: None,
    },
    Claim {
        file: "data/paper/fig9c_w_indecomposable_member.ron",
        unknowns: Some(20),
        equations: Some(17),
        rank: 17,
        dof_absolute: 3,
        trivial_motions: 3,
        dof: 0,
        redundant: &[],
        clusters: None,
    },
    Claim {
        file: "data/paper/flow_fig1a.ron",
        unknowns: Some(6),
        equations: Some(4),
        rank: 4,
        dof_absolute: 2,
        trivial_motions: 2,
        dof: 0,
        redundant: &[],
        clusters: Some(&[(&["A", "B", "C"], Some(&["par_AB", "par_BC", "d_AB", "d_BC"]))]),
    },
    Claim {
        file: "data/paper/flow_fig1b.ron",
        unknowns: Some(19),
        equations: Some(13),
        rank: 12,
        dof_absolute: 7,
        trivial_motions: 6,
        dof: 1,
        redundant: &[("d_EF", &["C_on_A", "D_on_A", "E_on_A", "d_CD", "d_DE", "d_CF", "d_DF"])],
        clusters: Some(&[
            (
                &["A", "C", "D", "E", "F"],
                Some(&["C_on_A", "D_on_A", "E_on_A", "d_CD", "d_DE", "d_CF", "d_DF", "d_EF"]),
            ),
            (&["A", "B"], Some(&["B_on_A"])),
        ]),
    },
    Claim {
        file: "data/paper/kite.ron",
        unknowns: Some(8),
        equations: Some(6),
        rank: 5,
        dof_absolute: 3,
        trivial_motions: 3,
        dof: 0,
        redundant: &[("c6", &["c1", "c2", "c3", "c4", "c5"])],
        clusters: Some(&[(&["p1", "p2", "p3", "p4"], Some(&["c1", "c2", "c3", "c4", "c5", "c6"]))]),
    },
    Claim {
        file: "data/paper/prism.ron",
        unknowns: Some(12),
        equations: Some(9),
        rank: 9,
        dof_absolute: 3,
        trivial_motions: 3,
        dof: 0,
        redundant: &[],
        clusters: None,
    },
    Claim {
        file: "data/paper/two_k33.ron",
        unknowns: Some(24),
        equations: Some(21),
        rank: 21,
        dof_absolute: 3,
        trivial_motions: 3,
        dof: 0,
        redundant: &[],
        clusters: None,
    },
    Claim {
        file: "data/sketches/block_3d.ron",
        unknowns: Some(21),
        equations: Some(16),
        rank: 15,
        dof_absolute: 6,
        trivial_motions: 6,
        dof: 0,
        redundant: &[(
            "diag_ab",
            &["perp_XZ", "O_on_X", "O_on_Z", "a_on_X", "b_on_Z", "len_a", "len_b"],
        )],
        clusters: None,
    },
    Claim {
        file: "data/sketches/fillet.ron",
        unknowns: Some(17),
        equations: Some(17),
        rank: 17,
        dof_absolute: 0,
        trivial_motions: 0,
        dof: 0,
        redundant: &[],
        clusters: None,
    },
    Claim {
        file: "data/sketches/flange.ron",
        unknowns: Some(11),
        equations: Some(10),
        rank: 8,
        dof_absolute: 3,
        trivial_motions: 3,
        dof: 0,
        redundant: &[("c_hub_rim", &["c_bore_hub", "c_bore_rim"])],
        clusters: None,
    },
    Claim {
        file: "data/sketches/four_bar.ron",
        unknowns: Some(8),
        equations: Some(7),
        rank: 7,
        dof_absolute: 1,
        trivial_motions: 0,
        dof: 1,
        redundant: &[],
        clusters: Some(&[
            (&["A", "D", "ground"], None),
            (&["A", "B", "crank"], None),
            (&["B", "C", "coupler"], None),
            (&["C", "D", "rocker"], None),
        ]),
    },
    Claim {
        file: "data/sketches/ratios.ron",
        unknowns: Some(8),
        equations: Some(8),
        rank: 8,
        dof_absolute: 0,
        trivial_motions: 0,
        dof: 0,
        redundant: &[],
        clusters: None,
    },
    Claim {
        file: "data/sketches/rectangle.ron",
        unknowns: Some(8),
        equations: Some(8),
        rank: 8,
        dof_absolute: 0,
        trivial_motions: 0,
        dof: 0,
        redundant: &[],
        clusters: None,
    },
    Claim {
        file: "data/sketches/rectangle_overdimensioned.ron",
        unknowns: Some(8),
        equations: None,
        rank: 8,
        dof_absolute: 0,
        trivial_motions: 0,
        dof: 0,
        redundant: &[("width_top", &["v_right", "v_left", "width"])],
        clusters: None,
    },
    Claim {
        file: "data/sketches/slot.ron",
        unknowns: Some(16),
        equations: Some(16),
        rank: 16,
        dof_absolute: 0,
        trivial_motions: 0,
        dof: 0,
        redundant: &[],
        clusters: None,
    },
    Claim {
        file: "data/sketches/spline.ron",
        unknowns: Some(14),
        equations: Some(14),
        rank: 14,
        dof_absolute: 0,
        trivial_motions: 0,
        dof: 0,
        redundant: &[],
        clusters: None,
    },
];

/// The models whose header says: one cluster, every entity and every constraint.
const WHOLE: &[&str] = &[
    "data/sketches/fillet.ron",
    "data/sketches/flange.ron",
    "data/paper/fig9a_w_decomposable.ron",
    "data/paper/fig9b_w_indecomposable.ron",
    "data/paper/fig9c_w_indecomposable_member.ron",
    "data/paper/kite.ron",
    "data/paper/prism.ron",
    "data/paper/two_k33.ron",
    "data/sketches/block_3d.ron",
    "data/sketches/rectangle.ron",
    "data/sketches/rectangle_overdimensioned.ron",
    "data/sketches/ratios.ron",
    "data/sketches/slot.ron",
    "data/sketches/spline.ron",
];

type ClusterSet = BTreeSet<(Vec<String>, Option<Vec<String>>)>;

fn cluster_set(s: &System, a: &Analysis, with_constraints: &[bool]) -> ClusterSet {
    a.clusters
        .iter()
        .zip(with_constraints)
        .map(|(c, &with)| {
            let mut e: Vec<String> = c.entities.iter().map(|e| s.entity(*e).id.clone()).collect();
            e.sort();
            let k = with.then(|| {
                let mut k: Vec<String> = c.constraints.iter().map(|c| cid(s, *c)).collect();
                k.sort();
                k
            });
            (e, k)
        })
        .collect()
}

#[test]
fn every_header_claim_holds() {
    let mut failures = Vec::new();
    let mut seen = BTreeSet::new();
    for claim in CLAIMS {
        seen.insert(claim.file);
        let s = load(claim.file);
        let a = analysis(&s, false);
        let internal = a.internal_equations;
        let mut check = |what: &str, got: String, want: String| {
            if got != want {
                failures.push(format!("{}: {what}: got {got}, header says {want}", claim.file));
            }
        };
        if let Some(u) = claim.unknowns {
            check("unknowns", (a.unknowns - internal).to_string(), u.to_string());
        }
        if let Some(e) = claim.equations {
            check("equations", (a.equations - internal).to_string(), e.to_string());
        }
        check("rank", (a.rank - internal).to_string(), claim.rank.to_string());
        check("dof_absolute", a.dof_absolute.to_string(), claim.dof_absolute.to_string());
        check("trivial motions", a.trivial_motions.to_string(), claim.trivial_motions.to_string());
        check("dof", a.dof.to_string(), claim.dof.to_string());
        check(
            "rigid / well-constrained",
            format!("{} / {}", a.rigid(), a.well_constrained()),
            format!("{} / {}", claim.dof == 0, claim.dof == 0 && claim.redundant.is_empty()),
        );
        let want: Vec<(String, usize, usize, Vec<String>)> = claim
            .redundant
            .iter()
            .map(|(c, group)| {
                let doc = s.constraint(s.constraint_by_id(c).expect("a constraint id")).doc;
                ((*c).to_owned(), doc, doc, strings(group))
            })
            .collect();
        check("redundant", format!("{:?}", redundant(&s, &a)), format!("{want:?}"));
        if let Some(clusters) = claim.clusters {
            let want: ClusterSet = clusters
                .iter()
                .map(|(e, k)| {
                    let mut e = strings(e);
                    e.sort();
                    let k = k.map(|k| {
                        let mut k = strings(k);
                        k.sort();
                        k
                    });
                    (e, k)
                })
                .collect();
            // Compare with constraints only where the header lists them: match each
            // computed cluster to the header's cluster with the same entities.
            let with: Vec<bool> = a
                .clusters
                .iter()
                .map(|c| {
                    let mut e: Vec<String> =
                        c.entities.iter().map(|e| s.entity(*e).id.clone()).collect();
                    e.sort();
                    clusters.iter().any(|(he, hk)| {
                        let mut he = strings(he);
                        he.sort();
                        he == e && hk.is_some()
                    })
                })
                .collect();
            check("clusters", format!("{:?}", cluster_set(&s, &a, &with)), format!("{want:?}"));
        }
        if WHOLE.contains(&claim.file) {
            let all_e: Vec<_> = s.entity_indices().collect();
            let all_c: Vec<_> = s.constraint_indices().collect();
            let whole = a.clusters.len() == 1
                && a.clusters[0].entities == all_e
                && a.clusters[0].constraints == all_c;
            check("one cluster with everything", whole.to_string(), "true".to_owned());
        }
    }
    for file in WHOLE {
        assert!(seen.contains(file), "{file} has no claim row");
    }
    assert!(failures.is_empty(), "header claims that do not hold:\n{}", failures.join("\n"));
}

/// Every model in `data/` has a row in the table (a new model must come with its claims).
#[test]
fn the_table_covers_every_model() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = Vec::new();
    for dir in ["data/paper", "data/sketches"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let name = entry.unwrap().file_name().to_string_lossy().into_owned();
            if name.ends_with(".ron") {
                files.push(format!("{dir}/{name}"));
            }
        }
    }
    files.sort();
    let table: Vec<&str> = CLAIMS.iter().map(|c| c.file).collect();
    assert_eq!(files, table, "CLAIMS must list every model of data/, sorted");
}

/// Clusters are sorted by their first entity in file order (format §2).
#[test]
fn clusters_are_sorted_by_first_entity() {
    for claim in CLAIMS {
        let s = load(claim.file);
        let a = analysis(&s, false);
        let firsts: Vec<_> = a.clusters.iter().map(|c| c.entities[0]).collect();
        assert!(firsts.windows(2).all(|w| w[0] <= w[1]), "{}: {firsts:?}", claim.file);
        let mut covered = vec![false; s.entities().len()];
        for c in &a.clusters {
            assert!(c.entities.windows(2).all(|w| w[0] < w[1]), "{}: file order", claim.file);
            for e in &c.entities {
                covered[e.index()] = true;
            }
        }
        assert!(covered.iter().all(|c| *c), "{}: every entity is in a cluster", claim.file);
    }
}

/// Fig. 6: a, b, x, y (with the segment ab and d_ab, d_bx, d_ay) is the one cluster with more
/// than one point; l is rigid with one point at a time ({x, l}, {l, p1}, {l, p2}); p and p'
/// are alone.
#[test]
fn fig6_clusters() {
    let s = load("data/paper/fig6_harmonic.ron");
    let a = analysis(&s, false);
    let is_point = |e: &gcs_model::EntityIdx| s.entity(*e).kind() == gcs_model::EntityKind::Point;
    let ids = |es: &[gcs_model::EntityIdx]| -> BTreeSet<String> {
        es.iter().map(|e| s.entity(*e).id.clone()).collect()
    };
    let big: Vec<_> = a
        .clusters
        .iter()
        .filter(|c| c.entities.iter().filter(|e| is_point(e)).count() > 1)
        .collect();
    assert_eq!(big.len(), 1, "one cluster with more than one point");
    let points: Vec<_> = big[0].entities.iter().copied().filter(|e| is_point(e)).collect();
    assert_eq!(ids(&points), ["a", "b", "x", "y"].map(String::from).into());
    assert!(ids(&big[0].entities).contains("ab"));
    let k: BTreeSet<String> = big[0].constraints.iter().map(|c| cid(&s, *c)).collect();
    for c in ["d_ab", "d_bx", "d_ay"] {
        assert!(k.contains(c), "{c} in the cluster of a, b, x, y");
    }
    let sets: Vec<BTreeSet<String>> = a.clusters.iter().map(|c| ids(&c.entities)).collect();
    for pair in [["x", "l"], ["l", "p1"], ["l", "p2"]] {
        assert!(sets.contains(&pair.map(String::from).into()), "cluster {pair:?}: {sets:?}");
    }
    for alone in ["p", "pp"] {
        assert!(sets.contains(&[alone.to_owned()].into()), "{alone} alone: {sets:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// W-decompositions stated by the headers (witness paper §5, figs. 8 and 9)

fn node_ids(s: &System, n: &DecompositionNode) -> BTreeSet<String> {
    n.entities.iter().map(|e| s.entity(*e).id.clone()).collect()
}

fn decomposition(file: &str) -> (System, Vec<DecompositionNode>) {
    let s = load(file);
    let a = analysis(&s, true);
    let d = a.decomposition.expect("asked for");
    assert_eq!(d.len(), a.clusters.len(), "{file}: one tree per cluster");
    (s, d)
}

#[test]
fn w_indecomposable_systems_are_leaves() {
    for file in
        ["data/paper/fig9b_w_indecomposable.ron", "data/paper/fig9c_w_indecomposable_member.ron"]
    {
        let (s, d) = decomposition(file);
        assert_eq!(d.len(), 1, "{file}");
        assert_eq!(d[0].entities.len(), s.entities().len(), "{file}: the root is the system");
        assert!(d[0].children.is_empty(), "{file}: W-indecomposable, got {:?}", d[0].children);
    }
}

#[test]
fn two_k33_decomposes_into_the_two_k33() {
    let (s, d) = decomposition("data/paper/two_k33.ron");
    assert_eq!(d.len(), 1);
    let children: BTreeSet<BTreeSet<String>> =
        d[0].children.iter().map(|c| node_ids(&s, c)).collect();
    let left: BTreeSet<String> = ["a1", "a2", "a3", "b1", "b2", "b3"].map(String::from).into();
    let right: BTreeSet<String> = ["c1", "c2", "c3", "d1", "d2", "d3"].map(String::from).into();
    assert_eq!(children, [left, right].into());
    for c in &d[0].children {
        assert_eq!(c.constraints.len(), 9, "a K3,3 has 9 distances");
        assert!(c.children.is_empty(), "each K3,3 is W-indecomposable");
    }
}

#[test]
fn fig9a_decomposes_into_its_inner_part() {
    let (s, d) = decomposition("data/paper/fig9a_w_decomposable.ron");
    assert_eq!(d.len(), 1);
    let inner: BTreeSet<String> = (1..=8).map(|i| format!("p{i}")).collect();
    assert_eq!(d[0].children.len(), 1, "the inner part is the only non-trivial subsystem");
    let child = &d[0].children[0];
    assert_eq!(node_ids(&s, child), inner);
    assert_eq!(child.constraints.len(), 13);
    assert!(child.children.is_empty(), "the inner part (fig. 9b) is W-indecomposable");
}

// ---------------------------------------------------------------------------------------------
// Claims about the system with some items removed

/// The model without the items (entities or constraints) with these ids.
fn without(file: &str, ids: &[&str]) -> System {
    let text = read(file);
    let kept: Vec<&str> = text
        .lines()
        .filter(|l| {
            !ids.iter().any(|id| {
                l.contains(&format!("(id: \"{id}\",")) || l.contains(&format!("(id: \"{id}\")"))
            })
        })
        .collect();
    assert_eq!(text.lines().count() - kept.len(), ids.len(), "{file}: one line per removed id");
    System::from_ron_str(&kept.join("\n"), Some(file)).unwrap_or_else(|e| panic!("{e}"))
}

/// The clusters as sorted sets of entity ids.
fn cluster_ids(s: &System, a: &Analysis) -> BTreeSet<BTreeSet<String>> {
    a.clusters
        .iter()
        .map(|c| c.entities.iter().map(|e| s.entity(*e).id.clone()).collect())
        .collect()
}

fn set(ids: &[&str]) -> BTreeSet<String> {
    ids.iter().map(|s| (*s).to_owned()).collect()
}

/// The two endpoints of every distance of `s`, as clusters.
fn bars(s: &System) -> BTreeSet<BTreeSet<String>> {
    s.constraints()
        .iter()
        .map(|c| c.args.iter().map(|e| s.entity(*e).id.clone()).collect())
        .collect()
}

#[test]
fn without_the_redundant_constraint_kite_and_block_are_well_constrained() {
    for (file, id) in [("data/paper/kite.ron", "c6"), ("data/sketches/block_3d.ron", "diag_ab")] {
        let s = without(file, &[id]);
        let a = analysis(&s, false);
        assert!(a.well_constrained(), "{file} without {id}: {:?}", redundant(&s, &a));
    }
}

#[test]
fn slot_without_its_placement_is_rigid_with_three_trivial_motions() {
    let s = without("data/sketches/slot.ron", &["origin", "fix_origin", "h_low", "pos_x", "pos_y"]);
    let a = analysis(&s, false);
    assert_eq!((a.trivial_motions, a.dof), (3, 0));
    assert!(a.redundant.is_empty());
}

/// Fig. 9b and 9c: removing any distance leaves 1 internal DOF and only single bars as
/// maximal rigid subsystems.
#[test]
fn w_indecomposable_systems_minus_any_distance_leave_only_bars() {
    for file in
        ["data/paper/fig9b_w_indecomposable.ron", "data/paper/fig9c_w_indecomposable_member.ron"]
    {
        let full = load(file);
        for c in full.constraints() {
            let s = without(file, &[&c.id]);
            let a = analysis(&s, false);
            assert_eq!(a.dof, 1, "{file} without {}", c.id);
            assert!(a.redundant.is_empty(), "{file} without {}", c.id);
            assert_eq!(cluster_ids(&s, &a), bars(&s), "{file} without {}: only bars", c.id);
        }
    }
}

#[test]
fn two_k33_minus_a_middle_edge_or_a_k33_edge() {
    let file = "data/paper/two_k33.ron";
    let left = set(&["a1", "a2", "a3", "b1", "b2", "b3"]);
    let right = set(&["c1", "c2", "c3", "d1", "d2", "d3"]);
    let middle = [("e1", ["b1", "c1"]), ("m2", ["b2", "c2"]), ("m3", ["b3", "c3"])];
    for (removed, _) in middle {
        let s = without(file, &[removed]);
        let a = analysis(&s, false);
        assert_eq!(a.dof, 1, "without {removed}");
        let mut want: BTreeSet<BTreeSet<String>> = [left.clone(), right.clone()].into();
        for (other, ends) in middle {
            if other != removed {
                want.insert(set(&ends));
            }
        }
        assert_eq!(cluster_ids(&s, &a), want, "without {removed}");
    }
    // The paper's e2, an edge of the left K3,3: only the right K3,3 stays a rigid body
    // bigger than a bar.
    let s = without(file, &["a1b1"]);
    let a = analysis(&s, false);
    assert_eq!(a.dof, 1);
    let big: Vec<BTreeSet<String>> =
        cluster_ids(&s, &a).into_iter().filter(|c| c.len() > 2).collect();
    assert_eq!(big, vec![right]);
}

#[test]
fn fig9a_minus_a_linking_an_inner_or_a_k4_bar() {
    let file = "data/paper/fig9a_w_decomposable.ron";
    let full = load(file);
    let inner = set(&["p1", "p2", "p3", "p4", "p5", "p6", "p7", "p8"]);
    let k4 = |c: char| -> BTreeSet<String> { (1..=4).map(|i| format!("{c}{i}")).collect() };
    let links = ["p2r1", "p3r2", "p4s1", "p6s2", "p7t1", "p8t2", "r3s4", "s3t4", "t3r4"];
    let link_bar = |id: &str| -> BTreeSet<String> {
        let c = full.constraint(full.constraint_by_id(id).unwrap());
        c.args.iter().map(|e| full.entity(*e).id.clone()).collect()
    };

    // A linking bar: 1 DOF; the inner part, the three K4 and the other linking bars.
    for removed in links {
        let s = without(file, &[removed]);
        let a = analysis(&s, false);
        assert_eq!(a.dof, 1, "without {removed}");
        let mut want: BTreeSet<BTreeSet<String>> =
            [inner.clone(), k4('r'), k4('s'), k4('t')].into();
        want.extend(links.iter().filter(|l| **l != removed).map(|l| link_bar(l)));
        assert_eq!(cluster_ids(&s, &a), want, "without {removed}");
    }

    // An inner edge: only bars and the three K4.
    let s = without(file, &["p1p2"]);
    let a = analysis(&s, false);
    assert_eq!(a.dof, 1);
    let big: BTreeSet<BTreeSet<String>> =
        cluster_ids(&s, &a).into_iter().filter(|c| c.len() > 2).collect();
    assert_eq!(big, [k4('r'), k4('s'), k4('t')].into());

    // A K4 edge: still rigid, one cluster, no redundancy left in that K4.
    let s = without(file, &["r1r2"]);
    let a = analysis(&s, false);
    assert_eq!(a.dof, 0);
    assert_eq!(a.clusters.len(), 1);
    assert_eq!(a.clusters[0].entities.len(), 20);
    let flagged: Vec<String> = redundant(&s, &a).into_iter().map(|r| r.0).collect();
    assert_eq!(flagged, ["s3s4", "t3t4"]);
}
