//! Writing a [`System`] back to the RON model format, exactly (numbers that are not
//! terminating decimals are written as quoted fractions).

use std::fmt::Write;

use crate::number::format_exact;
use crate::system::{Coords, Geometry, System};

fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{{{:x}}}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn coords(c: &Coords) -> String {
    let parts: Vec<String> = c.iter().map(format_exact).collect();
    format!("[{}]", parts.join(", "))
}

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
        for e in self.entities() {
            let id = quote(&e.id);
            let body = match &e.geometry {
                Geometry::Point { at } => match at {
                    Some(at) => format!("Point(id: {id}, at: {})", coords(at)),
                    None => format!("Point(id: {id})"),
                },
                Geometry::Line { at } | Geometry::Plane { at } => {
                    let name = e.kind().name();
                    match at {
                        Some([p, q]) => {
                            format!("{name}(id: {id}, at: [{}, {}])", coords(p), coords(q))
                        }
                        None => format!("{name}(id: {id})"),
                    }
                }
                Geometry::Segment { from, to } => format!(
                    "Segment(id: {id}, from: {}, to: {})",
                    quote(&self.entity(*from).id),
                    quote(&self.entity(*to).id)
                ),
                Geometry::Circle { center, radius } | Geometry::Sphere { center, radius } => {
                    let mut s = format!("{}(id: {id}", e.kind().name());
                    if let Some(c) = center {
                        let _ = write!(s, ", center: {}", coords(c));
                    }
                    if let Some(r) = radius {
                        let _ = write!(s, ", radius: {}", format_exact(r));
                    }
                    s.push(')');
                    s
                }
            };
            let _ = writeln!(out, "        {body},");
        }
        let _ = writeln!(out, "    ],");
        let _ = writeln!(out, "    constraints: [");
        for c in self.constraints() {
            let mut s = format!("{}(id: {}", c.kind.name(), quote(&c.id));
            for (field, arg) in c.kind.fields().iter().zip(&c.args) {
                let _ = write!(s, ", {field}: {}", quote(&self.entity(*arg).id));
            }
            if let Some(v) = &c.value {
                let _ = write!(s, ", value: {}", format_exact(v));
            }
            let _ = writeln!(out, "        {s}),");
        }
        let _ = writeln!(out, "    ],");
        let _ = writeln!(out, ")");
        out
    }
}
