//! The Dulmage–Mendelsohn decomposition of the equation–unknown bipartite graph.
//!
//! Survey §4.2.1, "D-M": the system is seen at the level of equations. Each constraint
//! contributes DOC equation nodes, each adjacent to every unknown of the entities it binds
//! (segments replaced by their points); each entity contributes DOF unknown nodes. Nothing
//! else is known about the equations: this is the structural (sparsity-pattern) view.
//!
//! A maximum matching (Hopcroft–Karp, [`hopcroft_karp`]) gives the canonical coarse
//! decomposition:
//!
//! - **over-determined** part: the equations reachable by alternating paths from unmatched
//!   equations (equation → any of its unknowns → the equation matched to it), with all their
//!   unknowns — more equations than unknowns;
//! - **under-determined** part: the unknowns reachable by alternating paths from unmatched
//!   unknowns (unknown → any of its equations → the unknown matched to it), with those
//!   equations — more unknowns than equations;
//! - **well-determined** part: the rest, perfectly matched; its **fine blocks** are the
//!   strongly connected components of the digraph "equation `e` uses the unknown matched to
//!   `e′`", listed in solving order (a block only uses unknowns of earlier blocks, of its own,
//!   or of the over-determined part).
//!
//! The decomposition does not depend on which maximum matching was found.
//!
//! **Copies do not split.** The DOC equation nodes of one constraint have identical
//! neighbourhoods, and so have the DOF unknown nodes of one entity ("identical twins"). Twins
//! always land in the same part and in the same fine block: if one is reached by an alternating
//! path, the other is reached one step later through the twin's matched partner, and in the
//! well part twins reach each other in the digraph. So each constraint and each entity belongs
//! to exactly one part (the crate's tests check this on random systems), and the report lists
//! them without splitting.
//!
//! D-M knows nothing of displacements: a free rigid 2D framework has its 3 displacement
//! DOF left as unmatched unknowns, so a well-constrained sketch without `Fix` appears as
//! under-determined, and the over-determined part only shows what the equation count alone
//! proves (a `Fix` twice, too many constraints on one entity…), not the kite's redundant bar.

use gcs_model::{ConstraintIdx, EntityIdx, System};

pub use gcs_rank::bipartite::{
    Bipartite, DmNodes, Matching, Part, dulmage_mendelsohn, hopcroft_karp,
};
/// One part of the decomposition at the level of the model.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DmPart {
    /// The constraints with an equation in the part, in file order.
    pub constraints: Vec<ConstraintIdx>,
    /// The entities with an unknown in the part, in file order (never segments: they have no
    /// unknowns).
    pub entities: Vec<EntityIdx>,
    /// Number of equation nodes in the part.
    pub equations: usize,
    /// Number of unknown nodes in the part.
    pub unknowns: usize,
}

/// The Dulmage–Mendelsohn decomposition of a system.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DmDecomposition {
    /// The over-determined part.
    pub over: DmPart,
    /// The well-determined part.
    pub well: DmPart,
    /// The under-determined part.
    pub under: DmPart,
    /// The fine blocks of the well part, in solving order.
    pub blocks: Vec<DmPart>,
    /// Equation nodes (ΣDOC).
    pub equations: usize,
    /// Unknown nodes (ΣDOF).
    pub unknowns: usize,
    /// Size of the maximum matching.
    pub matched: usize,
}

/// The equation–unknown bipartite graph of a system at the DOF level, with the constraint of
/// each row and the entity of each column.
pub fn equation_graph(system: &System) -> (Bipartite, Vec<ConstraintIdx>, Vec<EntityIdx>) {
    let mut first_col = vec![0usize; system.entities().len()];
    let mut col_entity = Vec::new();
    for e in system.entity_indices() {
        first_col[e.index()] = col_entity.len();
        for _ in 0..system.entity_dof(e) {
            col_entity.push(e);
        }
    }
    let mut row_constraint = Vec::new();
    let mut rows: Vec<Vec<usize>> = Vec::new();
    for c in system.constraint_indices() {
        let cols: Vec<usize> = system
            .constraint_base_entities(c)
            .iter()
            .flat_map(|e| first_col[e.index()]..first_col[e.index()] + system.entity_dof(*e))
            .collect();
        for _ in 0..system.constraint(c).doc {
            row_constraint.push(c);
            rows.push(cols.clone());
        }
    }
    (Bipartite::new(col_entity.len(), rows), row_constraint, col_entity)
}

fn part_of(
    rows: impl Iterator<Item = usize>,
    cols: impl Iterator<Item = usize>,
    row_constraint: &[ConstraintIdx],
    col_entity: &[EntityIdx],
) -> DmPart {
    let mut p = DmPart::default();
    for r in rows {
        p.equations += 1;
        p.constraints.push(row_constraint[r]);
    }
    for c in cols {
        p.unknowns += 1;
        p.entities.push(col_entity[c]);
    }
    p.constraints.sort_unstable();
    p.constraints.dedup();
    p.entities.sort_unstable();
    p.entities.dedup();
    p
}

/// The Dulmage–Mendelsohn decomposition of a system's equation–unknown graph, reported by
/// constraints and entities (a constraint or entity is in a part when one of its nodes is; as
/// explained in the module documentation, all its nodes then are).
///
/// # Example
/// ```
/// use gcs_model::{ConstraintKind, Dim, SystemBuilder, number::int};
/// let mut b = SystemBuilder::new("twice", Dim::Two);
/// b.point("a", Some(vec![int(0), int(0)])).unwrap();
/// b.point("b", Some(vec![int(1), int(1)])).unwrap();
/// b.constraint(ConstraintKind::Fix, "f1", &["a"], None).unwrap();
/// b.constraint(ConstraintKind::Fix, "f2", &["a"], None).unwrap();
/// let dm = gcs_rigidity::dm_decomposition(&b.build());
/// assert_eq!(dm.over.equations, 4);
/// assert_eq!(dm.over.unknowns, 2);
/// assert_eq!(dm.under.entities, vec![gcs_model::EntityIdx(1)]);
/// ```
pub fn dm_decomposition(system: &System) -> DmDecomposition {
    let (g, row_constraint, col_entity) = equation_graph(system);
    let nodes = dulmage_mendelsohn(&g);
    let part = |which: Part| {
        part_of(
            (0..g.rows()).filter(|&r| nodes.row_part[r] == which),
            (0..g.cols()).filter(|&c| nodes.col_part[c] == which),
            &row_constraint,
            &col_entity,
        )
    };
    let blocks = nodes
        .blocks
        .iter()
        .map(|(rs, cs)| {
            part_of(rs.iter().copied(), cs.iter().copied(), &row_constraint, &col_entity)
        })
        .collect();
    DmDecomposition {
        over: part(Part::Over),
        well: part(Part::Well),
        under: part(Part::Under),
        blocks,
        equations: g.rows(),
        unknowns: g.cols(),
        matched: nodes.matching.size,
    }
}
