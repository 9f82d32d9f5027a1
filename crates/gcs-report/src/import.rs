//! The import section of a report (format §4, "Importing CAD files"): for a model read from a
//! CAD file, whether everything in the sketch was expressed, and what was not.

use gcs_import::Lowered;
use serde::{Deserialize, Serialize};

/// An item of a CAD file that was not imported, and why.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SkippedReport {
    /// The source's id of the item (`Constraint7`, `c.00000003`, an Onshape id).
    pub item: String,
    /// Why.
    pub reason: String,
}

/// The import fields of a model read from a CAD file. In the JSON line they sit beside the
/// analysis fields (flattened); a model read from RON has none of them.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ImportReport {
    /// The sketch's human label in the CAD program, when it has one beside its name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// Every entity and driving constraint of the sketch is in the model (normative).
    pub complete_import: bool,
    /// What could not be expressed, in order, each with its reason (normative; empty when
    /// the import is complete).
    pub skipped: Vec<SkippedReport>,
    /// Items not imported although nothing is lost: said by another item, or not geometry.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<SkippedReport>,
    /// Reference (driven, non-driving) dimensions: measured, not imposed.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reference: Vec<String>,
    /// What the CAD program recorded about its own solution (FreeCAD's `FullyConstrained`),
    /// verbatim, as `[name, value]` pairs.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub source_verdict: Vec<(String, String)>,
}

impl ImportReport {
    /// The import section of a lowered sketch.
    pub fn new(lowered: &Lowered) -> ImportReport {
        let items = |v: &[gcs_import::ir::Skipped]| {
            v.iter()
                .map(|s| SkippedReport { item: s.item.clone(), reason: s.reason.clone() })
                .collect()
        };
        ImportReport {
            label: lowered.label.clone(),
            complete_import: lowered.complete(),
            skipped: items(&lowered.skipped),
            notes: items(&lowered.notes),
            reference: lowered.reference.clone(),
            source_verdict: lowered.source_verdict.clone(),
        }
    }

    /// The section as text lines (each ending in a newline), for the text reports.
    pub fn text(&self) -> String {
        let mut out = String::new();
        if let Some(label) = &self.label {
            out.push_str(&format!("  label: {label}\n"));
        }
        if self.complete_import {
            out.push_str("  import: complete\n");
        } else {
            let n = self.skipped.len();
            out.push_str(&format!(
                "  import: INCOMPLETE, {n} item{} not expressed (the analysis is of the rest):\n",
                if n == 1 { "" } else { "s" }
            ));
            for s in &self.skipped {
                out.push_str(&format!("    {}: {}\n", s.item, s.reason));
            }
        }
        if !self.reference.is_empty() {
            out.push_str(&format!(
                "  reference dimensions (measured, not imposed): {}\n",
                self.reference.join(", ")
            ));
        }
        for (name, value) in &self.source_verdict {
            out.push_str(&format!("  the CAD program recorded: {name} = {value}\n"));
        }
        out
    }
}
