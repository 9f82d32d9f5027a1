//! Writing a [`System`] back to the RON model format, exactly (numbers that are not
//! terminating decimals are written as quoted fractions).

use std::fmt::Write;

use crate::entity::quote;
use crate::number::format_exact;
use crate::system::System;

impl System {
    /// Writes the system in the RON model format. Reading the text back with
    /// [`System::from_ron_str`] gives an equal system (positions aside).
    ///
    /// # Example
    /// ```
    /// use gcs_model::System;
    /// let text = "System(name: \"t\", dim: 2, entities: [Point(id: \"p\", at: [\"1/3\", 0.5])])";
    /// let system = System::from_ron_str(text, None).unwrap();
    /// let again = System::from_ron_str(&system.to_ron(), None).unwrap();
    /// assert_eq!(again.entities()[0].geometry, system.entities()[0].geometry);
    /// ```
    pub fn to_ron(&self) -> String {
        let mut out = String::new();
        let _ = writeln!(out, "System(");
        let _ = writeln!(out, "    name: {},", quote(self.name()));
        let _ = writeln!(out, "    dim: {},", self.dim().coords());
        let _ = writeln!(out, "    entities: [");
        // The named points of curves and the constraints holding them are the curves' own: they
        // are written by their owners' fields.
        for e in self.entities().iter().filter(|e| e.owner.is_none()) {
            let mut body = e.geometry.to_ron(&e.id, self);
            if e.construction && body.ends_with(')') {
                body.insert_str(body.len() - 1, ", construction: true");
            }
            let _ = writeln!(out, "        {body},");
        }
        let _ = writeln!(out, "    ],");
        let _ = writeln!(out, "    constraints: [");
        let written = self.constraints().iter().filter(|c| c.owner.is_none());
        for (c, reference) in
            written.map(|c| (c, false)).chain(self.references().iter().map(|c| (c, true)))
        {
            let mut s = format!("{}(id: {}", c.kind.name(), quote(&c.id));
            for (field, arg) in c.kind.fields().iter().zip(&c.args) {
                let _ = write!(s, ", {field}: {}", quote(&self.entity(*arg).id));
            }
            if let Some(v) = &c.value {
                let _ = write!(s, ", value: {}", format_exact(v));
            }
            if reference {
                s.push_str(", reference: true");
            }
            let _ = writeln!(out, "        {s}),");
        }
        for o in self.orientations() {
            let points: Vec<String> = o.points.iter().map(|p| quote(&self.entity(*p).id)).collect();
            let _ = writeln!(
                out,
                "        Orientation(id: {}, points: [{}], sign: {}),",
                quote(&o.id),
                points.join(", "),
                o.sign
            );
        }
        let _ = writeln!(out, "    ],");
        if !self.groups().is_empty() {
            let _ = writeln!(out, "    groups: [");
            for g in self.groups() {
                let entities: Vec<String> =
                    g.entities.iter().map(|e| quote(&self.entity(*e).id)).collect();
                let _ = writeln!(
                    out,
                    "        Group(id: {}, entities: [{}]),",
                    quote(&g.id),
                    entities.join(", ")
                );
            }
            let _ = writeln!(out, "    ],");
        }
        let _ = writeln!(out, ")");
        out
    }
}
