//! Axis references in a front-end's config: an axis by its index in the machine or by its
//! `name` (`axes = [0, "x"]`, `axis = "e10"`), resolved against the machine's axes once, here,
//! for every front-end.
//!
//! Input: the references as the config gives them, and the machine's axis names in index order
//! (`[[axes]] name`, `None` for an unnamed axis). Output: axis indices, or an [`AxisRefError`]
//! whose text is the `reason` of the config error (the caller adds `file: key:`).

use serde::{Deserialize, Serialize};

/// An axis by its index in the machine or its `name`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(untagged)]
pub enum AxisRef {
    Index(usize),
    Name(String),
}

/// Why a reference names no axis of the machine.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum AxisRefError {
    #[error("axis {index} does not exist (the machine has {count})")]
    NoSuchIndex { index: usize, count: usize },
    #[error("no axis is named `{0}`")]
    NoSuchName(String),
}

impl AxisRef {
    /// The index of the axis this names; `names` are the machine's axes' names in index order.
    pub fn resolve<S: AsRef<str>>(&self, names: &[Option<S>]) -> Result<usize, AxisRefError> {
        match self {
            AxisRef::Index(index) if *index < names.len() => Ok(*index),
            AxisRef::Index(index) => Err(AxisRefError::NoSuchIndex {
                index: *index,
                count: names.len(),
            }),
            AxisRef::Name(name) => names
                .iter()
                .position(|n| n.as_ref().is_some_and(|n| n.as_ref() == name))
                .ok_or_else(|| AxisRefError::NoSuchName(name.clone())),
        }
    }
}

/// The indices of `refs`, in their order (an axis named twice is there twice: a map's blocks may
/// repeat an axis); every axis of the machine, in index order, when `refs` is empty. The first
/// reference that names no axis is the error.
pub fn resolve_all<S: AsRef<str>>(
    refs: &[AxisRef],
    names: &[Option<S>],
) -> Result<Vec<usize>, AxisRefError> {
    if refs.is_empty() {
        return Ok((0..names.len()).collect());
    }
    refs.iter().map(|r| r.resolve(names)).collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// Three axes: `x`, unnamed, `z`.
    fn names() -> Vec<Option<String>> {
        vec![Some("x".into()), None, Some("z".into())]
    }

    #[test]
    fn an_index_in_range_and_a_name_resolve() {
        let names = names();
        assert_eq!(AxisRef::Index(1).resolve(&names), Ok(1));
        assert_eq!(AxisRef::Name("z".into()).resolve(&names), Ok(2));
        // Names and indices mix, in the config's order.
        let refs = [AxisRef::Name("z".into()), AxisRef::Index(0)];
        assert_eq!(resolve_all(&refs, &names), Ok(vec![2, 0]));
    }

    #[test]
    fn an_index_out_of_range_says_how_many_axes_there_are() {
        let e = AxisRef::Index(3).resolve(&names()).unwrap_err();
        assert_eq!(e, AxisRefError::NoSuchIndex { index: 3, count: 3 });
        assert_eq!(e.to_string(), "axis 3 does not exist (the machine has 3)");
    }

    #[test]
    fn an_unknown_name_is_named() {
        let e = AxisRef::Name("y".into()).resolve(&names()).unwrap_err();
        assert_eq!(e.to_string(), "no axis is named `y`");
        // An unnamed axis is not reached by an empty name.
        let e = AxisRef::Name(String::new()).resolve(&names()).unwrap_err();
        assert_eq!(e, AxisRefError::NoSuchName(String::new()));
    }

    #[test]
    fn an_empty_list_is_every_axis() {
        assert_eq!(resolve_all(&[], &names()), Ok(vec![0, 1, 2]));
        assert_eq!(resolve_all::<&str>(&[], &[]), Ok(vec![]));
    }

    #[test]
    fn an_axis_named_twice_is_kept_twice_and_the_first_bad_reference_is_the_error() {
        let refs = [AxisRef::Index(0), AxisRef::Name("x".into())];
        assert_eq!(resolve_all(&refs, &names()), Ok(vec![0, 0]));
        let refs = [
            AxisRef::Index(0),
            AxisRef::Name("nope".into()),
            AxisRef::Index(9),
        ];
        assert_eq!(
            resolve_all(&refs, &names()),
            Err(AxisRefError::NoSuchName("nope".into()))
        );
    }

    #[test]
    fn references_parse_from_numbers_and_strings() {
        let refs: Vec<AxisRef> = serde_json::from_str(r#"[2, "x"]"#).unwrap();
        assert_eq!(refs, [AxisRef::Index(2), AxisRef::Name("x".into())]);
    }
}
