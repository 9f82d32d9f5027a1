//! Where the count is exact, the structural methods and the witness analysis agree: on random
//! 2D bar frameworks (Laman's theorem: generic rigidity of bar frameworks is the count), the
//! structural verdict equals the witness verdict, and the over-dense subsystem Dense finds
//! contains a constraint the witness analysis finds redundant.

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_rigidity::{RuleDor, Verdict, dense_analysis, over_rigid_analysis};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn count_and_witness_agree_on_bar_frameworks(
        seed in 0u64..100_000,
        n in 3usize..=12,
        removed in 0usize..3,
        added in 0usize..3,
    ) {
        let (s, _) = gcs_suite::random_bar_framework(seed, n, removed, added);
        let w = analyze(&s, &AnalysisOptions::default()).unwrap();
        let witness_verdict = if !w.redundant.is_empty() {
            Verdict::OverRigid
        } else if w.dof == 0 {
            Verdict::WellRigid
        } else {
            Verdict::UnderRigid
        };
        let dense = dense_analysis(&s);
        let over = over_rigid_analysis(&s, &RuleDor::for_system(&s));
        prop_assert_eq!(dense.verdict, witness_verdict);
        prop_assert_eq!(over.verdict, witness_verdict);
        if let Some(sub) = &dense.subsystem {
            let redundant: Vec<_> = w.redundant.iter().map(|r| r.constraint).collect();
            // The over-dense subsystem holds a dependency, whose last constraint in file order
            // is redundant in the witness analysis.
            prop_assert!(
                sub.constraints.iter().any(|c| redundant.contains(c)),
                "Dense's subsystem {:?} holds no redundant constraint", sub.constraints
            );
        }
    }
}
