//! Reading the RON model format (`docs/format.md` §1) into a validated [`System`].

use num_rational::BigRational;
use serde::Deserialize;

use crate::entity::RawEntity;
use crate::error::{ModelError, ModelErrorKind, Position};
use crate::kinds::{ConstraintKind, Dim};
use crate::locate::{ItemLoc, locate};
use crate::number::Num;
use crate::system::{Coords, System, SystemBuilder};

#[derive(Deserialize)]
#[serde(rename = "System", deny_unknown_fields)]
struct RawSystem {
    #[serde(default)]
    name: Option<String>,
    dim: u64,
    #[serde(default)]
    entities: Vec<RawEntity>,
    #[serde(default)]
    constraints: Vec<RawConstraint>,
}

#[derive(Deserialize)]
#[serde(rename = "Constraint", deny_unknown_fields)]
enum RawConstraint {
    Coincident {
        id: String,
        a: String,
        b: String,
    },
    Distance {
        id: String,
        a: String,
        b: String,
        #[serde(default)]
        value: Option<Num>,
    },
    Angle {
        id: String,
        a: String,
        b: String,
        #[serde(default)]
        value: Option<Num>,
    },
    Parallel {
        id: String,
        a: String,
        b: String,
    },
    Perpendicular {
        id: String,
        a: String,
        b: String,
    },
    Incident {
        id: String,
        a: String,
        b: String,
    },
    Tangent {
        id: String,
        a: String,
        b: String,
    },
    Radius {
        id: String,
        a: String,
        #[serde(default)]
        value: Option<Num>,
    },
    EqualLength {
        id: String,
        a: String,
        b: String,
    },
    Midpoint {
        id: String,
        point: String,
        segment: String,
    },
    Symmetric {
        id: String,
        a: String,
        b: String,
        axis: String,
    },
    Horizontal {
        id: String,
        a: String,
    },
    Vertical {
        id: String,
        a: String,
    },
    Fix {
        id: String,
        a: String,
    },
}

impl RawConstraint {
    fn parts(&self) -> (ConstraintKind, &str, Vec<&str>, Option<&Num>) {
        use ConstraintKind as K;
        use RawConstraint as R;
        match self {
            R::Coincident { id, a, b } => (K::Coincident, id, vec![a, b], None),
            R::Distance { id, a, b, value } => (K::Distance, id, vec![a, b], value.as_ref()),
            R::Angle { id, a, b, value } => (K::Angle, id, vec![a, b], value.as_ref()),
            R::Parallel { id, a, b } => (K::Parallel, id, vec![a, b], None),
            R::Perpendicular { id, a, b } => (K::Perpendicular, id, vec![a, b], None),
            R::Incident { id, a, b } => (K::Incident, id, vec![a, b], None),
            R::Tangent { id, a, b } => (K::Tangent, id, vec![a, b], None),
            R::Radius { id, a, value } => (K::Radius, id, vec![a], value.as_ref()),
            R::EqualLength { id, a, b } => (K::EqualLength, id, vec![a, b], None),
            R::Midpoint { id, point, segment } => (K::Midpoint, id, vec![point, segment], None),
            R::Symmetric { id, a, b, axis } => (K::Symmetric, id, vec![a, b, axis], None),
            R::Horizontal { id, a } => (K::Horizontal, id, vec![a], None),
            R::Vertical { id, a } => (K::Vertical, id, vec![a], None),
            R::Fix { id, a } => (K::Fix, id, vec![a], None),
        }
    }
}

pub(crate) fn number(
    item: &'static str,
    owner: &str,
    field: &'static str,
    n: &Num,
) -> Result<BigRational, ModelError> {
    match n {
        Num::Exact(q) => Ok(q.clone()),
        Num::NonFinite => {
            Err(ModelError::new(ModelErrorKind::NonFinite { item, owner: owner.to_owned(), field }))
        }
        Num::Invalid(text) => Err(ModelError::new(ModelErrorKind::NotANumber {
            item,
            owner: owner.to_owned(),
            field,
            text: text.clone(),
        })),
    }
}

pub(crate) fn read_coords(
    owner: &str,
    field: &'static str,
    v: &[Num],
) -> Result<Coords, ModelError> {
    v.iter().map(|n| number("entity", owner, field, n)).collect()
}

pub(crate) fn two_coords(
    owner: &str,
    field: &'static str,
    v: &[Vec<Num>],
) -> Result<[Coords; 2], ModelError> {
    if v.len() != 2 {
        return Err(ModelError::new(ModelErrorKind::WrongPositionCount {
            id: owner.to_owned(),
            field,
            expected: 2,
            found: v.len(),
        }));
    }
    Ok([read_coords(owner, field, &v[0])?, read_coords(owner, field, &v[1])?])
}

fn add_entity(b: &mut SystemBuilder, raw: &RawEntity) -> Result<(), ModelError> {
    let read = raw.read()?;
    let parts: Vec<&str> = read.refs.iter().map(|(_, id)| *id).collect();
    b.entity(read.id, read.geometry, &parts)?;
    Ok(())
}

fn add_constraint(b: &mut SystemBuilder, raw: &RawConstraint) -> Result<(), ModelError> {
    let (kind, id, args, value) = raw.parts();
    let value = value.map(|v| number("constraint", id, "value", v)).transpose()?;
    b.constraint(kind, id, &args, value)?;
    Ok(())
}

/// The model name a file gets when it does not give one: the file stem of the origin.
fn default_name(origin: Option<&str>) -> String {
    let Some(origin) = origin else { return "model".to_owned() };
    let file = origin.rsplit(['/', '\\']).next().unwrap_or(origin);
    let stem = file.strip_suffix(".ron").unwrap_or(file);
    if stem.is_empty() { "model".to_owned() } else { stem.to_owned() }
}

fn locate_error(e: ModelError, origin: Option<&str>, loc: Option<&ItemLoc>) -> ModelError {
    let field = e.kind.field();
    let position = loc.and_then(|l| l.field_or_start(field));
    e.at(origin, position)
}

impl System {
    /// Reads a model from RON text and validates it.
    ///
    /// `origin` names where the text came from (a file path); it appears in error messages and
    /// gives the model its default name (the file stem). Decimals are read as the exact
    /// rationals they denote; a quoted fraction such as `"1/3"` is accepted wherever a number
    /// is, for exact values a decimal cannot write.
    ///
    /// # Errors
    /// A [`ModelError`] naming the origin, the line and column, and the offending id or field:
    /// RON syntax, unknown or duplicate ids, a constraint applied to kinds it does not take, a
    /// sketch position of the wrong dimension, a degenerate segment, line or plane, a
    /// non-finite number, a negative distance or radius, a `Fix` without a position.
    ///
    /// # Example
    /// ```
    /// use gcs_model::System;
    /// let text = r#"System(dim: 2,
    ///     entities: [Point(id: "p", at: [0, 0]), Point(id: "q", at: [0.5, 2])],
    ///     constraints: [Distance(id: "d", a: "p", b: "q", value: 2.0616)])"#;
    /// let system = System::from_ron_str(text, Some("pq.ron")).unwrap();
    /// assert_eq!(system.name(), "pq");
    /// assert_eq!(system.naive_dof(), 3);
    ///
    /// let err = System::from_ron_str("System(dim: 2, entities: [Point(id: \"p\")],
    ///     constraints: [Fix(id: \"f\", a: \"q\")])", Some("bad.ron")).unwrap_err();
    /// assert_eq!(err.to_string(),
    ///     "bad.ron:2:35: constraint \"f\": field a: unknown entity id \"q\"");
    /// ```
    pub fn from_ron_str(text: &str, origin: Option<&str>) -> Result<System, ModelError> {
        let options = ron::Options::default()
            .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
        let raw: RawSystem = options.from_str(text).map_err(|e| {
            let position =
                Position { line: e.span.start.line.max(1), column: e.span.start.col.max(1) };
            ModelError::new(ModelErrorKind::Syntax(e.code.to_string())).at(origin, Some(position))
        })?;
        let located = locate(text);
        let dim = Dim::from_number(raw.dim).ok_or_else(|| {
            ModelError::new(ModelErrorKind::UnsupportedDim(raw.dim.to_string()))
                .at(origin, located.fields.get("dim").copied())
        })?;
        let name = raw.name.clone().unwrap_or_else(|| default_name(origin));
        let mut b = SystemBuilder::new(name, dim);
        for (i, e) in raw.entities.iter().enumerate() {
            add_entity(&mut b, e)
                .map_err(|err| locate_error(err, origin, located.entities.get(i)))?;
        }
        for (i, c) in raw.constraints.iter().enumerate() {
            add_constraint(&mut b, c)
                .map_err(|err| locate_error(err, origin, located.constraints.get(i)))?;
        }
        let mut system = b.build();
        let entity_pos: Vec<Option<Position>> = (0..raw.entities.len())
            .map(|i| located.entities.get(i).and_then(|l| l.start))
            .collect();
        let constraint_pos: Vec<Option<Position>> = (0..raw.constraints.len())
            .map(|i| located.constraints.get(i).and_then(|l| l.start))
            .collect();
        system.set_position(&entity_pos, &constraint_pos);
        Ok(system)
    }
}
