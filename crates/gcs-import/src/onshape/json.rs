//! Small accessors over `serde_json::Value` whose errors say which field is wrong; the caller
//! adds the element (`features[3].entities[2] (id …)`).

use serde_json::{Map, Value};

/// A JSON object.
pub(super) type Object = Map<String, Value>;

/// The value as an object.
pub(super) fn object<'v>(value: &'v Value, what: &str) -> Result<&'v Object, String> {
    value.as_object().ok_or_else(|| format!("{what}: expected an object, found {}", kind(value)))
}

/// A required field that is an object.
pub(super) fn field_object<'v>(map: &'v Object, key: &str) -> Result<&'v Object, String> {
    match map.get(key) {
        Some(v) => object(v, key),
        None => Err(format!("missing field `{key}`")),
    }
}

/// A required number.
pub(super) fn number(map: &Object, key: &str) -> Result<f64, String> {
    match map.get(key) {
        Some(v) => {
            v.as_f64().ok_or_else(|| format!("field `{key}`: expected a number, found {}", kind(v)))
        }
        None => Err(format!("missing field `{key}`")),
    }
}

/// An optional number.
pub(super) fn opt_number(map: &Object, key: &str) -> Result<Option<f64>, String> {
    match map.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(v) => v
            .as_f64()
            .map(Some)
            .ok_or_else(|| format!("field `{key}`: expected a number, found {}", kind(v))),
    }
}

/// A required string.
pub(super) fn string<'v>(map: &'v Object, key: &str) -> Result<&'v str, String> {
    match map.get(key) {
        Some(v) => {
            v.as_str().ok_or_else(|| format!("field `{key}`: expected a string, found {}", kind(v)))
        }
        None => Err(format!("missing field `{key}`")),
    }
}

/// An optional string.
pub(super) fn opt_string<'v>(map: &'v Object, key: &str) -> Result<Option<&'v str>, String> {
    match map.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(v) => v
            .as_str()
            .map(Some)
            .ok_or_else(|| format!("field `{key}`: expected a string, found {}", kind(v))),
    }
}

/// An optional boolean, `false` when absent.
pub(super) fn flag(map: &Object, key: &str) -> Result<bool, String> {
    match map.get(key) {
        None | Some(Value::Null) => Ok(false),
        Some(v) => v
            .as_bool()
            .ok_or_else(|| format!("field `{key}`: expected true or false, found {}", kind(v))),
    }
}

/// An optional array, empty when absent.
pub(super) fn array<'v>(map: &'v Object, key: &str) -> Result<&'v [Value], String> {
    match map.get(key) {
        None | Some(Value::Null) => Ok(&[]),
        Some(v) => v
            .as_array()
            .map(Vec::as_slice)
            .ok_or_else(|| format!("field `{key}`: expected a list, found {}", kind(v))),
    }
}

/// An optional array of numbers, empty when absent.
pub(super) fn numbers(map: &Object, key: &str) -> Result<Vec<f64>, String> {
    array(map, key)?
        .iter()
        .map(|v| {
            v.as_f64().ok_or_else(|| format!("field `{key}`: expected numbers, found {}", kind(v)))
        })
        .collect()
}

/// What a value is, for messages.
pub(super) fn kind(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "a list",
        Value::Object(_) => "an object",
    }
}
