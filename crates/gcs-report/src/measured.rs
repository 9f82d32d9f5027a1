//! Reference (driven) dimensions, measured: at the drawing (`gcs analyze`) and at the solution
//! (`gcs solve`). They are no equations of the system ([`gcs_model::System::references`]); what
//! a CAD program shows beside them is their measure, taken with the same measure functions as
//! the dimensions that are imposed ([`gcs_jacobian::Equations::measure`]).

use gcs_jacobian::{Equations, Layout};
use gcs_model::System;
use num_traits::ToPrimitive;
use serde::{Deserialize, Serialize};

/// One reference dimension and its measure.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeasuredReport {
    /// Its id.
    pub constraint: String,
    /// Its kind (`Distance`, `Angle`, `Radius`, …).
    pub kind: String,
    /// The measure (model units, degrees, a ratio); `null` where the configuration does not
    /// give one (an entity without a sketch position, a line of zero length).
    pub value: Option<f64>,
    /// The value written in the file, when it has one: what the CAD program showed when it
    /// saved.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub written: Option<f64>,
}

/// Every reference dimension measured at `x` (a configuration over the layout; `None`: not
/// measured).
pub fn measured(system: &System, layout: &Layout, x: Option<&[f64]>) -> Vec<MeasuredReport> {
    let equations = Equations::new(system, layout);
    system
        .references()
        .iter()
        .map(|c| MeasuredReport {
            constraint: c.id.clone(),
            kind: c.kind.name().to_owned(),
            value: x.and_then(|x| equations.measure(c, x)),
            written: c.value.as_ref().and_then(ToPrimitive::to_f64),
        })
        .collect()
}

/// Every reference dimension measured at the drawing (nothing computed without references).
pub fn at_drawing(system: &System) -> Vec<MeasuredReport> {
    if system.references().is_empty() {
        return Vec::new();
    }
    let layout = Layout::new(system);
    let x = gcs_jacobian::sketch::drawing_in::<f64>(system, &layout);
    measured(system, &layout, x.as_deref())
}

/// The text line of the measures (`None` without reference dimensions).
pub fn measured_text(measured: &[MeasuredReport], at: &str) -> Option<String> {
    if measured.is_empty() {
        return None;
    }
    let items: Vec<String> = measured
        .iter()
        .map(|m| match m.value {
            Some(v) => format!("{} = {}", m.constraint, shown(v)),
            None => format!("{} not measured", m.constraint),
        })
        .collect();
    Some(format!("  reference dimensions (measured {at}, not imposed): {}", items.join(", ")))
}

/// A measure to six decimals, trailing zeros dropped.
fn shown(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".to_owned() } else { s.to_owned() }
}
