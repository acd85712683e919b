//! The INI layer of CiA 306 files: `[section]` headers, `key=value` lines and `;` comments
//! (whole lines, or after whitespace at the end of a line).
//! Section names and keys are case-insensitive; CRLF and a UTF-8 byte-order mark are accepted.
//! A key given twice, or a section defined twice, is an error: which one a tool would use is
//! not defined, and silently taking one hides a broken file.

use std::collections::HashMap;

use super::error::{EdsError, Place, Reason};

/// One `key=value` line.
#[derive(Clone, Debug)]
pub(crate) struct Item<'a> {
    pub key: &'a str,
    pub value: &'a str,
    pub line: usize,
}

/// One section with its items, in file order.
#[derive(Clone, Debug)]
pub(crate) struct Section<'a> {
    pub name: &'a str,
    pub line: usize,
    pub items: Vec<Item<'a>>,
    /// Lower-case key → position in `items`, once a section has more keys than a scan is
    /// cheap for (object sections have about eight; a hostile file may have millions).
    by_key: Option<HashMap<String, usize>>,
}

/// Up to this many keys a section is searched by scanning.
const SCANNED_KEYS: usize = 16;

impl<'a> Section<'a> {
    /// The item with `key`, in any case.
    pub fn get(&self, key: &str) -> Option<&Item<'a>> {
        match &self.by_key {
            None => self.items.iter().find(|i| i.key.eq_ignore_ascii_case(key)),
            Some(map) => map
                .get(&key.to_ascii_lowercase())
                .and_then(|&i| self.items.get(i)),
        }
    }

    fn push(&mut self, item: Item<'a>) {
        if let Some(map) = &mut self.by_key {
            map.insert(item.key.to_ascii_lowercase(), self.items.len());
        }
        self.items.push(item);
        if self.by_key.is_none() && self.items.len() > SCANNED_KEYS {
            let map = self
                .items
                .iter()
                .enumerate()
                .map(|(i, item)| (item.key.to_ascii_lowercase(), i))
                .collect();
            self.by_key = Some(map);
        }
    }

    pub fn place(&self) -> Place<'a> {
        Place::section(self.name, self.line)
    }
}

impl<'a> Item<'a> {
    pub fn place(&self, section: &Section<'a>) -> Place<'a> {
        Place::key(section.name, self.key, self.line)
    }
}

/// A parsed file: sections in file order, found by case-insensitive name.
#[derive(Clone, Debug, Default)]
pub(crate) struct Document<'a> {
    pub sections: Vec<Section<'a>>,
    by_name: HashMap<String, usize>,
}

impl<'a> Document<'a> {
    /// The section called `name` (which must be lower case).
    pub fn section(&self, name: &str) -> Option<&Section<'a>> {
        debug_assert_eq!(name, name.to_ascii_lowercase());
        self.by_name.get(name).and_then(|&i| self.sections.get(i))
    }

    pub fn parse(file: &str, text: &'a str) -> Result<Document<'a>, EdsError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut doc = Document::default();
        for (n, raw) in text.split('\n').enumerate() {
            let line = n + 1;
            let trimmed = strip_inline_comment(raw).trim();
            if trimmed.is_empty() || trimmed.starts_with(';') || trimmed.starts_with('#') {
                continue;
            }
            let at = Place {
                line: Some(line),
                ..Place::default()
            };
            if let Some(rest) = trimmed.strip_prefix('[') {
                let name = rest
                    .strip_suffix(']')
                    .ok_or_else(|| at.error(file, Reason::UnclosedSection))?
                    .trim();
                if name.is_empty() {
                    return Err(at.error(file, Reason::EmptySectionName));
                }
                let lower = name.to_ascii_lowercase();
                if let Some(first) = doc.by_name.get(&lower).and_then(|&i| doc.sections.get(i)) {
                    let first_line = first.line;
                    return Err(Place::section(name, line)
                        .error(file, Reason::DuplicateSection { first_line }));
                }
                doc.by_name.insert(lower, doc.sections.len());
                doc.sections.push(Section {
                    name,
                    line,
                    items: Vec::new(),
                    by_key: None,
                });
                continue;
            }
            let Some((key, value)) = trimmed.split_once('=') else {
                let mut shown: String = trimmed.chars().take(40).collect();
                if shown.len() < trimmed.len() {
                    shown.push('…');
                }
                return Err(at.error(file, Reason::Syntax(shown)));
            };
            let (key, value) = (key.trim(), value.trim());
            let Some(section) = doc.sections.last_mut() else {
                return Err(at.error(file, Reason::KeyOutsideSection));
            };
            if key.is_empty() {
                return Err(Place::section(section.name, line).error(file, Reason::EmptyKey));
            }
            if let Some(first) = section.get(key) {
                let first_line = first.line;
                return Err(Place::key(section.name, key, line)
                    .error(file, Reason::DuplicateKey { first_line }));
            }
            section.push(Item { key, value, line });
        }
        Ok(doc)
    }
}

/// Cut a `;` comment that follows whitespace (`DefaultValue=0x10 ; why`), as python-canopen's
/// reader does; a `;` right after other text (`a;b`) is part of the value.
fn strip_inline_comment(line: &str) -> &str {
    let bytes = line.as_bytes();
    let cut = bytes
        .windows(2)
        .position(|w| (w[0] == b' ' || w[0] == b'\t') && w[1] == b';');
    match cut {
        Some(at) => line.get(..at).unwrap_or(line),
        None => line,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    #[test]
    fn sections_keys_comments_crlf_and_bom() {
        let text = "\u{feff}; header\r\n[FileInfo]\r\nFileName = x.eds \r\n\r\n# also a comment\n[1000]\nDataType=0x0007\nDefaultValue=\n";
        let doc = Document::parse("x.eds", text).unwrap();
        assert_eq!(doc.sections.len(), 2);
        let info = doc.section("fileinfo").unwrap();
        assert_eq!(info.get("filename").unwrap().value, "x.eds");
        assert_eq!(info.line, 2);
        let obj = doc.section("1000").unwrap();
        assert_eq!(obj.get("datatype").unwrap().line, 7);
        assert_eq!(obj.get("defaultvalue").unwrap().value, "");
    }

    #[test]
    fn long_sections_find_keys_and_duplicates_too() {
        let keys: String = (0..40).map(|i| format!("Key{i}={i}\n")).collect();
        let text = format!("[a]\n{keys}");
        let doc = Document::parse("x", &text).unwrap();
        let a = doc.section("a").unwrap();
        assert_eq!(a.get("KEY3").unwrap().value, "3");
        assert_eq!(a.get("key39").unwrap().line, 41);
        let err = Document::parse("x", &format!("[a]\n{keys}KEY3=again\n")).unwrap_err();
        assert_eq!(err.reason, Reason::DuplicateKey { first_line: 5 });
        let err = Document::parse("x", &format!("[a]\n{keys}key39=again\n")).unwrap_err();
        assert_eq!(err.reason, Reason::DuplicateKey { first_line: 41 });
    }

    #[test]
    fn inline_comments_follow_whitespace() {
        let doc = Document::parse(
            "x",
            "[a] ; the a section\nk=0x10 ; why\nn=a;b\nt=x\t; tab\n",
        )
        .unwrap();
        let a = doc.section("a").unwrap();
        assert_eq!(a.get("k").unwrap().value, "0x10");
        assert_eq!(a.get("n").unwrap().value, "a;b");
        assert_eq!(a.get("t").unwrap().value, "x");
    }

    #[test]
    fn names_and_keys_are_case_insensitive() {
        let doc = Document::parse("x", "[1018SUB0]\nPARAMETERNAME=a\n").unwrap();
        let sub = doc.section("1018sub0").unwrap();
        assert_eq!(sub.name, "1018SUB0");
        assert_eq!(sub.get("parametername").unwrap().key, "PARAMETERNAME");
    }

    #[test]
    fn syntax_errors_name_the_line() {
        let cases: [(&str, Reason); 6] = [
            ("[a\n", Reason::UnclosedSection),
            ("[ ]\n", Reason::EmptySectionName),
            ("k=v\n", Reason::KeyOutsideSection),
            ("[a]\n=v\n", Reason::EmptyKey),
            ("[a]\nk=1\nK=2\n", Reason::DuplicateKey { first_line: 2 }),
            ("[a]\n[A]\n", Reason::DuplicateSection { first_line: 1 }),
        ];
        for (text, reason) in cases {
            let err = Document::parse("f.eds", text).unwrap_err();
            assert_eq!(err.reason, reason, "{text:?}");
            assert_eq!(&*err.file, "f.eds");
            assert!(err.line.is_some());
        }
        let err = Document::parse("f.eds", "[a]\njust words\n").unwrap_err();
        assert_eq!(err.reason, Reason::Syntax("just words".into()));
        assert_eq!(
            err.to_string(),
            "f.eds: expected `[section]`, `key=value` or a `;` comment, found \"just words\" (line 2)"
        );
    }
}
