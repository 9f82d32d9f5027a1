//! Dulmage–Mendelsohn on small CAD-like systems checked by hand.

use gcs_model::number::int;
use gcs_model::{ConstraintKind as K, Dim, System, SystemBuilder};
use gcs_rigidity::{DmPart, dm_decomposition};

fn build(with_ab: bool) -> System {
    let mut b = SystemBuilder::new("dm", Dim::Two);
    for (id, x, y) in [("a", 0, 0), ("b", 5, 1), ("c", 9, 1), ("d", 12, 5), ("e", 14, 9)] {
        b.point(id, Some(vec![int(x), int(y)])).unwrap();
    }
    b.segment("bc", "b", "c").unwrap();
    let mut k = |kind, id: &str, args: &[&str]| {
        let value = (kind == K::Distance).then(|| int(3));
        b.constraint(kind, id, args, value).unwrap();
    };
    // a is fixed twice: 4 equations on its 2 unknowns.
    k(K::Fix, "fix_a1", &["a"]);
    k(K::Fix, "fix_a2", &["a"]);
    // b fixed, bc horizontal, |bc| given: c is determined once b is.
    k(K::Fix, "fix_b", &["b"]);
    k(K::Horizontal, "h_bc", &["bc"]);
    k(K::Distance, "d_bc", &["b", "c"]);
    // d and e hang on c by two bars: 2 equations for 4 unknowns.
    k(K::Distance, "d_cd", &["c", "d"]);
    k(K::Distance, "d_de", &["d", "e"]);
    if with_ab {
        k(K::Distance, "d_ab", &["a", "b"]);
    }
    b.build()
}

fn names(system: &System, part: &DmPart) -> (Vec<String>, Vec<String>) {
    (
        part.constraints.iter().map(|c| system.constraint(*c).id.clone()).collect(),
        part.entities.iter().map(|e| system.entity(*e).id.clone()).collect(),
    )
}

fn strs(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

#[test]
fn over_well_under_and_blocks() {
    let s = build(false);
    let dm = dm_decomposition(&s);
    // 2+2+2+1+1+1+1 = 10 equations, 5 points · 2 = 10 unknowns; matching 8.
    assert_eq!((dm.equations, dm.unknowns, dm.matched), (10, 10, 8));
    assert_eq!(names(&s, &dm.over), (strs(&["fix_a1", "fix_a2"]), strs(&["a"])));
    assert_eq!((dm.over.equations, dm.over.unknowns), (4, 2));
    assert_eq!(names(&s, &dm.well), (strs(&["fix_b", "h_bc", "d_bc"]), strs(&["b", "c"])));
    assert_eq!((dm.well.equations, dm.well.unknowns), (4, 4));
    assert_eq!(names(&s, &dm.under), (strs(&["d_cd", "d_de"]), strs(&["d", "e"])));
    assert_eq!((dm.under.equations, dm.under.unknowns), (2, 4));
    // Solving order: b first (fix_b), then c from h_bc and d_bc together.
    let blocks: Vec<_> = dm.blocks.iter().map(|b| names(&s, b)).collect();
    assert_eq!(
        blocks,
        vec![(strs(&["fix_b"]), strs(&["b"])), (strs(&["h_bc", "d_bc"]), strs(&["c"]))]
    );
}

#[test]
fn a_bar_to_an_over_determined_point_drags_its_partner_in() {
    // |ab| ties b to the over-determined a: the over part grows to {a, b} with 7 equations on 4
    // unknowns (b is fixed, so the bar adds one equation too many), and c stays well-determined
    // on its own.
    let s = build(true);
    let dm = dm_decomposition(&s);
    assert_eq!(dm.matched, 8);
    assert_eq!(
        names(&s, &dm.over),
        (strs(&["fix_a1", "fix_a2", "fix_b", "d_ab"]), strs(&["a", "b"]))
    );
    assert_eq!((dm.over.equations, dm.over.unknowns), (7, 4));
    assert_eq!(names(&s, &dm.well), (strs(&["h_bc", "d_bc"]), strs(&["c"])));
    assert_eq!(dm.blocks.len(), 1);
    assert_eq!(names(&s, &dm.under), (strs(&["d_cd", "d_de"]), strs(&["d", "e"])));
}

#[test]
fn rectangles_are_perfectly_matched() {
    let s = gcs_model::generate::rectangles(5);
    let dm = dm_decomposition(&s);
    assert_eq!(dm.matched, dm.equations);
    assert_eq!(dm.matched, dm.unknowns);
    assert_eq!(dm.well.constraints.len(), s.constraints().len());
    // Per rectangle: the fixed corner, then the corners it determines.
    assert!(dm.blocks.len() >= 5 * 2);
    let first = &dm.blocks[0];
    assert_eq!(s.constraint(first.constraints[0]).id, "r0_fix");
}
