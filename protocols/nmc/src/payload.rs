//! The payload of a request (the call's input arguments, in order) or of a successful reply
//! (its output arguments, in order), little-endian:
//!
//! | C kind | wire |
//! |---|---|
//! | `short`, `unsigned short`, `HAND`, `int`, `unsigned int`, `unsigned char` | i16, u16, u16, i32, u32, u8 |
//! | `long`, `unsigned long` | i64, u64 (the platform's `long` is 32 or 64 bits: the wire holds either) |
//! | `double`, `float` | f64 |
//! | a string (`char *`) | u16 length, then the bytes (no NUL) |
//! | an array | u16 count, then the elements |
//! | a struct | its fields in declaration order (`crate::structs`) |
//!
//! A failed reply's payload is the error's description, UTF-8 (`NMC_GetErrDesc`).

/// Builds a payload.
#[derive(Debug, Default)]
pub struct Writer {
    pub bytes: Vec<u8>,
}

impl Writer {
    pub fn new() -> Writer {
        Writer::default()
    }
    pub fn i16(&mut self, v: i16) -> &mut Self {
        self.bytes.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn u16(&mut self, v: u16) -> &mut Self {
        self.bytes.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn u8(&mut self, v: u8) -> &mut Self {
        self.bytes.push(v);
        self
    }
    pub fn i32(&mut self, v: i32) -> &mut Self {
        self.bytes.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn u32(&mut self, v: u32) -> &mut Self {
        self.bytes.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn i64(&mut self, v: i64) -> &mut Self {
        self.bytes.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn u64(&mut self, v: u64) -> &mut Self {
        self.bytes.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn f64(&mut self, v: f64) -> &mut Self {
        self.bytes.extend_from_slice(&v.to_le_bytes());
        self
    }
    /// A string, cut at 65535 bytes.
    pub fn str(&mut self, s: &[u8]) -> &mut Self {
        let s = s.get(..usize::from(u16::MAX)).unwrap_or(s);
        self.u16(u16::try_from(s.len()).unwrap_or(u16::MAX));
        self.bytes.extend_from_slice(s);
        self
    }
}

/// Why a payload does not decode.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PayloadError {
    /// It ends before argument `at` (a byte offset) is complete.
    Short { at: usize },
    /// Bytes left after the last argument.
    Trailing { extra: usize },
}

impl std::fmt::Display for PayloadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PayloadError::Short { at } => {
                write!(f, "payload ends at byte {at}, inside an argument")
            }
            PayloadError::Trailing { extra } => {
                write!(f, "{extra} bytes after the last argument")
            }
        }
    }
}

impl std::error::Error for PayloadError {}

/// Reads a payload, argument by argument; [`Reader::finish`] checks nothing is left.
#[derive(Debug)]
pub struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    pub fn new(bytes: &'a [u8]) -> Reader<'a> {
        Reader { bytes, at: 0 }
    }

    fn take<const N: usize>(&mut self) -> Result<[u8; N], PayloadError> {
        let end = self.at + N;
        let b: [u8; N] = self
            .bytes
            .get(self.at..end)
            .and_then(|s| s.try_into().ok())
            .ok_or(PayloadError::Short { at: self.at })?;
        self.at = end;
        Ok(b)
    }
    pub fn i16(&mut self) -> Result<i16, PayloadError> {
        self.take().map(i16::from_le_bytes)
    }
    pub fn u16(&mut self) -> Result<u16, PayloadError> {
        self.take().map(u16::from_le_bytes)
    }
    pub fn u8(&mut self) -> Result<u8, PayloadError> {
        self.take::<1>().map(|b| b[0])
    }
    pub fn i32(&mut self) -> Result<i32, PayloadError> {
        self.take().map(i32::from_le_bytes)
    }
    pub fn u32(&mut self) -> Result<u32, PayloadError> {
        self.take().map(u32::from_le_bytes)
    }
    pub fn i64(&mut self) -> Result<i64, PayloadError> {
        self.take().map(i64::from_le_bytes)
    }
    pub fn u64(&mut self) -> Result<u64, PayloadError> {
        self.take().map(u64::from_le_bytes)
    }
    pub fn f64(&mut self) -> Result<f64, PayloadError> {
        self.take().map(f64::from_le_bytes)
    }
    pub fn str(&mut self) -> Result<&'a [u8], PayloadError> {
        let n = usize::from(self.u16()?);
        let s = self
            .bytes
            .get(self.at..self.at + n)
            .ok_or(PayloadError::Short { at: self.at })?;
        self.at += n;
        Ok(s)
    }
    /// Bytes not yet read.
    pub fn remaining(&self) -> usize {
        self.bytes.len().saturating_sub(self.at)
    }
    /// Nothing may be left.
    pub fn finish(&self) -> Result<(), PayloadError> {
        match self.bytes.len() - self.at.min(self.bytes.len()) {
            0 => Ok(()),
            extra => Err(PayloadError::Trailing { extra }),
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_round_trips() {
        let mut w = Writer::new();
        w.i16(-3)
            .u16(65000)
            .u8(7)
            .i32(-70000)
            .u32(4_000_000_000)
            .i64(i64::MIN)
            .u64(u64::MAX)
            .f64(0.5)
            .str(b"CARD1");
        let mut r = Reader::new(&w.bytes);
        assert_eq!(r.i16().unwrap(), -3);
        assert_eq!(r.u16().unwrap(), 65000);
        assert_eq!(r.u8().unwrap(), 7);
        assert_eq!(r.i32().unwrap(), -70000);
        assert_eq!(r.u32().unwrap(), 4_000_000_000);
        assert_eq!(r.i64().unwrap(), i64::MIN);
        assert_eq!(r.u64().unwrap(), u64::MAX);
        assert_eq!(r.f64().unwrap(), 0.5);
        assert_eq!(r.str().unwrap(), b"CARD1");
        r.finish().unwrap();
    }

    #[test]
    fn short_and_trailing_payloads_are_errors() {
        let mut r = Reader::new(&[1]);
        assert_eq!(r.i16(), Err(PayloadError::Short { at: 0 }));
        let mut r = Reader::new(&[5, 0, b'a']);
        assert_eq!(r.str(), Err(PayloadError::Short { at: 2 }));
        let mut r = Reader::new(&[1, 0, 9]);
        r.i16().unwrap();
        assert_eq!(r.finish(), Err(PayloadError::Trailing { extra: 1 }));
    }
}
