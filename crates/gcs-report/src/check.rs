//! The report of `gcs check` (format §4): the counts of a model, before any analysis.

use gcs_model::System;
use serde::{Deserialize, Serialize};

use crate::report::SCHEMA;

/// The counts of one model: entities, constraints, Σ DOF, Σ DOC and the naive count.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CheckReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// The model's name.
    pub model: String,
    /// The file, as given.
    pub file: String,
    /// 2 or 3.
    pub dim: usize,
    /// Number of entities.
    pub entities: usize,
    /// Number of constraints.
    pub constraints: usize,
    /// Σ DOF of the entities.
    pub entity_dof: usize,
    /// Σ DOC of the constraints.
    pub constraint_doc: usize,
    /// Σ DOF − Σ DOC.
    pub naive_dof: i64,
    /// 3 or 6.
    pub displacements: usize,
    /// For a model read from a CAD file: the import section (flattened into the line).
    #[serde(default, flatten, skip_serializing_if = "Option::is_none")]
    pub import: Option<crate::ImportReport>,
}

impl CheckReport {
    /// The counts of `system`, read from `file`.
    pub fn new(system: &System, file: &str) -> CheckReport {
        CheckReport {
            schema: SCHEMA,
            model: system.name().to_owned(),
            file: file.to_owned(),
            dim: system.dim().coords(),
            entities: system.written_entities(),
            constraints: system.written_constraints(),
            entity_dof: system.dof_sum(),
            constraint_doc: system.doc_sum(),
            naive_dof: system.naive_dof(),
            displacements: system.dim().displacements(),
            import: None,
        }
    }

    /// The same counts with the import section of a model read from a CAD file.
    pub fn with_import(mut self, import: Option<crate::ImportReport>) -> CheckReport {
        self.import = import;
        self
    }

    /// One line of JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// One line of text.
    pub fn text(&self) -> String {
        let r = self;
        format!(
            "{}: {}, {}D, {} entities, {} constraints: DOF {} − DOC {} = {} (naive count; a free rigid body keeps {})",
            r.file,
            r.model,
            r.dim,
            r.entities,
            r.constraints,
            r.entity_dof,
            r.constraint_doc,
            r.naive_dof,
            r.displacements,
        )
    }
}
