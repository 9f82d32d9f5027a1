//! Reading the RON model format (`docs/format.md` §1) into a validated [`System`].

use num_rational::BigRational;
use serde::Deserialize;

use crate::entity::Geometry;
use crate::entity::RawEntity;
use crate::error::{ModelError, ModelErrorKind, Position};
use crate::kinds::{ConstraintKind, Dim};
use crate::locate::{ItemLoc, locate};
use crate::number::Num;
use crate::system::{ConstraintIdx, Coords, EntityIdx, System, SystemBuilder};

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
    #[serde(default)]
    groups: Vec<RawGroup>,
}

/// A group as written: `Group(id: "g", entities: ["a", "b"])`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
enum RawGroup {
    Group { id: String, entities: Vec<String> },
}

/// A constraint as written in a model file: its kind (the variant name), id, entity ids in the
/// order of [`ConstraintKind::fields`], and value. Read generically from the kinds' field
/// table ([`ConstraintKind::ron_fields`]), so that a new kind needs no code here. An
/// `Orientation` (kind `None`) has its points as `args` and its `sign`.
struct RawConstraint {
    kind: Option<ConstraintKind>,
    id: String,
    args: Vec<String>,
    value: Option<Num>,
    sign: Option<i64>,
    /// A reference (driven) dimension: measured, not imposed.
    reference: bool,
}

/// The variant name of an orientation condition in the `constraints` list.
const ORIENTATION: &str = "Orientation";

/// Its fields.
const ORIENTATION_FIELDS: [&str; 3] = ["id", "points", "sign"];

/// Every variant name the `constraints` list takes.
const ITEM_NAMES: [&str; ConstraintKind::ALL.len() + 1] = {
    let mut names = [ORIENTATION; ConstraintKind::ALL.len() + 1];
    let mut i = 0;
    while i < ConstraintKind::ALL.len() {
        names[i] = ConstraintKind::NAMES[i];
        i += 1;
    }
    names
};

impl<'de> Deserialize<'de> for RawConstraint {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::{self, EnumAccess, MapAccess, VariantAccess, Visitor};

        /// The variant name (`None`: an orientation).
        struct Kind(Option<ConstraintKind>);
        impl<'de> Deserialize<'de> for Kind {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct V;
                impl Visitor<'_> for V {
                    type Value = Kind;
                    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                        f.write_str("a constraint kind")
                    }
                    fn visit_str<E: de::Error>(self, v: &str) -> Result<Kind, E> {
                        if v == ORIENTATION {
                            return Ok(Kind(None));
                        }
                        ConstraintKind::ALL
                            .into_iter()
                            .find(|k| k.name() == v)
                            .map(|k| Kind(Some(k)))
                            .ok_or_else(|| E::unknown_variant(v, &ITEM_NAMES))
                    }
                }
                d.deserialize_identifier(V)
            }
        }

        /// The fields of one kind.
        struct Fields(ConstraintKind);
        impl<'de> Visitor<'de> for Fields {
            type Value = RawConstraint;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                write!(f, "the fields of {}", self.0.name())
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<RawConstraint, A::Error> {
                let kind = self.0;
                let names = kind.ron_fields();
                let entity_fields = kind.fields();
                let mut id = None;
                let mut args: Vec<Option<String>> = vec![None; entity_fields.len()];
                let mut value: Option<Option<Num>> = None;
                let mut reference = None;
                while let Some(key) = map.next_key::<String>()? {
                    if key == "reference" {
                        if reference.is_some() {
                            return Err(de::Error::duplicate_field("reference"));
                        }
                        reference = Some(map.next_value::<bool>()?);
                        continue;
                    }
                    let Some(&field) = names.iter().find(|n| **n == key) else {
                        return Err(de::Error::unknown_field(&key, names));
                    };
                    if field == "id" {
                        if id.is_some() {
                            return Err(de::Error::duplicate_field("id"));
                        }
                        id = Some(map.next_value::<String>()?);
                    } else if field == "value" {
                        if value.is_some() {
                            return Err(de::Error::duplicate_field("value"));
                        }
                        value = Some(map.next_value::<Option<Num>>()?);
                    } else if let Some(i) = entity_fields.iter().position(|f| *f == field) {
                        if args[i].is_some() {
                            return Err(de::Error::duplicate_field(field));
                        }
                        args[i] = Some(map.next_value::<String>()?);
                    }
                }
                let id = id.ok_or_else(|| de::Error::missing_field("id"))?;
                let args = args
                    .into_iter()
                    .zip(entity_fields)
                    .map(|(a, f)| a.ok_or_else(|| de::Error::missing_field(f)))
                    .collect::<Result<Vec<String>, _>>()?;
                Ok(RawConstraint {
                    kind: Some(kind),
                    id,
                    args,
                    value: value.flatten(),
                    sign: None,
                    reference: reference.unwrap_or(false),
                })
            }
        }

        /// The fields of an orientation.
        struct OrientationFields;
        impl<'de> Visitor<'de> for OrientationFields {
            type Value = RawConstraint;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("the fields of Orientation")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<RawConstraint, A::Error> {
                let (mut id, mut points, mut sign) = (None, None, None);
                while let Some(key) = map.next_key::<String>()? {
                    match key.as_str() {
                        "id" if id.is_none() => id = Some(map.next_value::<String>()?),
                        "points" if points.is_none() => {
                            points = Some(map.next_value::<Vec<String>>()?)
                        }
                        "sign" if sign.is_none() => sign = Some(map.next_value::<i64>()?),
                        "id" | "points" | "sign" => {
                            return Err(de::Error::duplicate_field(match key.as_str() {
                                "id" => "id",
                                "points" => "points",
                                _ => "sign",
                            }));
                        }
                        _ => return Err(de::Error::unknown_field(&key, &ORIENTATION_FIELDS)),
                    }
                }
                Ok(RawConstraint {
                    kind: None,
                    id: id.ok_or_else(|| de::Error::missing_field("id"))?,
                    args: points.ok_or_else(|| de::Error::missing_field("points"))?,
                    value: None,
                    sign: Some(sign.ok_or_else(|| de::Error::missing_field("sign"))?),
                    reference: false,
                })
            }
        }

        struct Variant;
        impl<'de> Visitor<'de> for Variant {
            type Value = RawConstraint;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a constraint")
            }
            fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<RawConstraint, A::Error> {
                match data.variant::<Kind>()? {
                    (Kind(Some(kind)), variant) => {
                        variant.struct_variant(kind.ron_fields(), Fields(kind))
                    }
                    (Kind(None), variant) => {
                        variant.struct_variant(&ORIENTATION_FIELDS, OrientationFields)
                    }
                }
            }
        }

        d.deserialize_enum("Constraint", &ITEM_NAMES, Variant)
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

fn add_entity(b: &mut SystemBuilder, raw: &RawEntity) -> Result<EntityIdx, ModelError> {
    let read = raw.read()?;
    let (id, construction) = (read.id, read.construction);
    let e = if let Geometry::Arc { center, radius, .. } = read.geometry {
        let mut owned = read.owned_points.into_iter();
        let (start, end) = (owned.next().flatten(), owned.next().flatten());
        b.arc(id, center, radius, start, end)?
    } else {
        let parts: Vec<&str> = read.refs.iter().map(|(_, id)| *id).collect();
        b.entity(id, read.geometry, &parts)?
    };
    if construction {
        b.construction(id)?;
    }
    Ok(e)
}

/// Adds a constraint (`None` for an orientation, which is no constraint of the system's).
fn add_constraint(
    b: &mut SystemBuilder,
    raw: &RawConstraint,
) -> Result<Option<ConstraintIdx>, ModelError> {
    let id = raw.id.as_str();
    let args: Vec<&str> = raw.args.iter().map(String::as_str).collect();
    let Some(kind) = raw.kind else {
        b.orientation(id, &args, raw.sign.unwrap_or(0))?;
        return Ok(None);
    };
    let value = raw.value.as_ref().map(|v| number("constraint", id, "value", v)).transpose()?;
    if raw.reference {
        b.reference(kind, id, &args, value)?;
        return Ok(None);
    }
    b.constraint(kind, id, &args, value).map(Some)
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
        let mut entity_pos = Vec::with_capacity(raw.entities.len());
        for (i, e) in raw.entities.iter().enumerate() {
            let idx = add_entity(&mut b, e)
                .map_err(|err| locate_error(err, origin, located.entities.get(i)))?;
            entity_pos.push((idx, located.entities.get(i).and_then(|l| l.start)));
        }
        let mut constraint_pos = Vec::with_capacity(raw.constraints.len());
        for (i, c) in raw.constraints.iter().enumerate() {
            let idx = add_constraint(&mut b, c)
                .map_err(|err| locate_error(err, origin, located.constraints.get(i)))?;
            if let Some(idx) = idx {
                constraint_pos.push((idx, located.constraints.get(i).and_then(|l| l.start)));
            }
        }
        for (i, RawGroup::Group { id, entities }) in raw.groups.iter().enumerate() {
            let names: Vec<&str> = entities.iter().map(String::as_str).collect();
            b.group(id, &names).map_err(|err| locate_error(err, origin, located.groups.get(i)))?;
        }
        let mut system = b.build();
        system.set_position(&entity_pos, &constraint_pos);
        Ok(system)
    }
}
