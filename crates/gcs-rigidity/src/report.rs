//! The `structural` section of the report (docs/format.md §3) as plain data.

use gcs_model::{EntityIdx, System};

use crate::dm::{DmDecomposition, dm_decomposition};
use crate::dor::DorOracle;
use crate::network::Network;
use crate::rigidity::{RigidityAnalysis, dense_analysis_in, over_rigid_analysis_in};

/// Everything the structural methods say about a system: docs/format.md §3's `dense`,
/// `over_rigid` (with the oracle's name in [`RigidityAnalysis::dor_source`]) and `dm`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StructuralReport {
    /// Hoffmann et al.'s Dense: s_rigidity, overload = the dimension's displacement count.
    pub dense: RigidityAnalysis,
    /// Jermann et al.'s Over-Rigid: es_rigidity, overload = the DOR of each candidate.
    pub over_rigid: RigidityAnalysis,
    /// The Dulmage–Mendelsohn decomposition of the equation–unknown graph.
    pub dm: DmDecomposition,
}

impl RigidityAnalysis {
    /// The entities of the over-rigid subsystem (objects and the segments between them, in
    /// file order), empty when none was found: docs/format.md's `subsystem` before ids are put on.
    pub fn subsystem_entities(&self) -> Vec<EntityIdx> {
        self.subsystem.as_ref().map(|s| s.entities()).unwrap_or_default()
    }
}

/// Runs Dense, Over-Rigid (with `oracle` for the DOR) and the Dulmage–Mendelsohn
/// decomposition on a system. One object–constraint network and its base flow serve both flow
/// methods.
///
/// Never fails and never panics on a valid [`System`].
///
/// # Example
/// ```
/// use gcs_rigidity::{structural_analysis, RuleDor, Verdict};
/// let s = gcs_model::generate::laman(20, 1);
/// let report = structural_analysis(&s, &RuleDor::for_system(&s));
/// assert_eq!(report.dense.verdict, Verdict::WellRigid);
/// assert_eq!(report.over_rigid.verdict, Verdict::WellRigid);
/// assert_eq!(report.over_rigid.dor_source, "rules");
/// assert!(report.dm.over.constraints.is_empty());
/// ```
pub fn structural_analysis<O: DorOracle + ?Sized>(system: &System, oracle: &O) -> StructuralReport {
    let mut network = Network::new(system);
    let dense = dense_analysis_in(&mut network);
    let over_rigid = over_rigid_analysis_in(system, &mut network, oracle);
    StructuralReport { dense, over_rigid, dm: dm_decomposition(system) }
}
