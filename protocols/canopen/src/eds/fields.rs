//! Typed reads of one section's keys, with errors that name file, section and key.

use super::error::{EdsError, Reason};
use super::ini::{Item, Section};
use super::value::parse_integer;

/// One section of one file, read key by key. Keys are given in their CiA 306 spelling
/// (`ParameterName`): that is what an error shows when the key is missing.
#[derive(Clone, Copy)]
pub(crate) struct Fields<'d, 'a> {
    pub file: &'d str,
    pub section: &'d Section<'a>,
}

impl<'d, 'a> Fields<'d, 'a> {
    pub fn new(file: &'d str, section: &'d Section<'a>) -> Fields<'d, 'a> {
        Fields { file, section }
    }

    pub fn item(&self, key: &str) -> Option<&'d Item<'a>> {
        self.section.get(key)
    }

    pub fn text(&self, key: &str) -> Option<&'a str> {
        self.item(key).map(|item| item.value)
    }

    pub fn required(&self, key: &str) -> Result<&'d Item<'a>, EdsError> {
        self.item(key).ok_or_else(|| self.missing(key))
    }

    pub fn missing(&self, key: &str) -> EdsError {
        let mut place = self.section.place();
        place.key = Some(key);
        place.error(self.file, Reason::Missing)
    }

    /// An error about `item` of this section.
    pub fn error(&self, item: &Item<'a>, reason: Reason) -> EdsError {
        item.place(self.section).error(self.file, reason)
    }

    /// An error about the section as a whole.
    pub fn section_error(&self, reason: Reason) -> EdsError {
        self.section.place().error(self.file, reason)
    }

    /// An unsigned integer key in `T`'s range (`range` names it in the error).
    pub fn unsigned<T: TryFrom<i128>>(
        &self,
        key: &str,
        range: &'static str,
    ) -> Result<Option<T>, EdsError> {
        let Some(item) = self.item(key) else {
            return Ok(None);
        };
        self.parse_unsigned(item, range).map(Some)
    }

    pub fn parse_unsigned<T: TryFrom<i128>>(
        &self,
        item: &Item<'a>,
        range: &'static str,
    ) -> Result<T, EdsError> {
        let literal = parse_integer(item.value).map_err(|why| {
            self.error(
                item,
                Reason::NotANumber {
                    text: item.value.to_string(),
                    why,
                },
            )
        })?;
        T::try_from(literal.value).map_err(|_| {
            self.error(
                item,
                Reason::OutOfRangeFor {
                    text: item.value.to_string(),
                    range,
                },
            )
        })
    }

    /// A 0/1 key.
    pub fn flag(&self, key: &str) -> Result<Option<bool>, EdsError> {
        let Some(item) = self.item(key) else {
            return Ok(None);
        };
        self.parse_flag(item).map(Some)
    }

    pub fn parse_flag(&self, item: &Item<'a>) -> Result<bool, EdsError> {
        match parse_integer(item.value).map(|l| l.value) {
            Ok(0) => Ok(false),
            Ok(1) => Ok(true),
            _ => Err(self.error(
                item,
                Reason::NotABool {
                    text: item.value.to_string(),
                },
            )),
        }
    }
}
