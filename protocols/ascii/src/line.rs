//! [`LineSplitter`]: bytes in, lines out. A line ends at CR, LF or CRLF (digest 004 §7.1 item 2);
//! it holds at most `max` characters (`HMPL_STR_MAX_LEN`, 512). A longer line is not kept: its
//! bytes are dropped as they come (memory stays at `max`, however long the line, even 10 MB
//! without a terminator) and it ends as one [`Line::TooLong`].

/// One line out of the splitter.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Line {
    /// A line without its terminator; bytes that are not UTF-8 are U+FFFD (the parser refuses
    /// them as a syntax error).
    Text(String),
    /// A line longer than the limit: its text is gone.
    TooLong,
}

/// Splits a byte stream into lines.
///
/// Input: [`LineSplitter::push`] with each chunk read, in order. Output: the complete lines in
/// the chunk, appended to the caller's list in order; empty lines (the LF of a CRLF split
/// across chunks included) are not lines. A partial line waits for the next chunk.
#[derive(Debug)]
pub struct LineSplitter {
    max: usize,
    buf: Vec<u8>,
    /// The current line passed `max`: drop until its end.
    overflow: bool,
    /// The last byte was a CR: an LF right after it ends nothing.
    after_cr: bool,
}

impl LineSplitter {
    pub fn new(max: usize) -> LineSplitter {
        LineSplitter {
            max,
            buf: Vec::with_capacity(max.min(1024)),
            overflow: false,
            after_cr: false,
        }
    }

    /// Bytes of an unfinished line held (at most `max`).
    pub fn pending(&self) -> usize {
        self.buf.len()
    }

    /// Whether an unfinished line has begun (a client that leaves in the middle of one).
    pub fn in_line(&self) -> bool {
        !self.buf.is_empty() || self.overflow
    }

    /// Feed `bytes`; complete lines are appended to `out`.
    pub fn push(&mut self, bytes: &[u8], out: &mut Vec<Line>) {
        for &b in bytes {
            let after_cr = std::mem::replace(&mut self.after_cr, b == b'\r');
            match b {
                b'\n' if after_cr => {}
                b'\r' | b'\n' => self.end(out),
                _ if self.overflow => {}
                _ if self.buf.len() >= self.max => {
                    self.buf.clear();
                    self.overflow = true;
                }
                _ => self.buf.push(b),
            }
        }
    }

    fn end(&mut self, out: &mut Vec<Line>) {
        if std::mem::take(&mut self.overflow) {
            out.push(Line::TooLong);
        } else if !self.buf.is_empty() {
            out.push(Line::Text(String::from_utf8_lossy(&self.buf).into_owned()));
            self.buf.clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn split(chunks: &[&[u8]], max: usize) -> Vec<Line> {
        let mut s = LineSplitter::new(max);
        let mut out = Vec::new();
        for c in chunks {
            s.push(c, &mut out);
        }
        out
    }

    fn text(s: &str) -> Line {
        Line::Text(s.into())
    }

    #[test]
    fn cr_lf_and_crlf_each_end_one_line() {
        let lines = split(&[b"a()\rb()\nc()\r\nd()"], 512);
        assert_eq!(lines, [text("a()"), text("b()"), text("c()")]);
        // A CRLF split across reads is one terminator; a blank line is no line.
        let lines = split(&[b"a()\r", b"\nb()\n\n\r\n"], 512);
        assert_eq!(lines, [text("a()"), text("b()")]);
    }

    #[test]
    fn a_line_over_the_limit_is_one_too_long_and_the_next_is_served() {
        let long = vec![b'x'; 513];
        let lines = split(&[&long, b"\nok()\n"], 512);
        assert_eq!(lines, [Line::TooLong, text("ok()")]);
        let exact = vec![b'y'; 512];
        let lines = split(&[&exact, b"\n"], 512);
        assert_eq!(lines, [Line::Text("y".repeat(512))]);
    }

    #[test]
    fn ten_megabytes_without_a_terminator_hold_no_more_than_the_limit() {
        let mut s = LineSplitter::new(512);
        let mut out = Vec::new();
        let chunk = vec![b'z'; 64 * 1024];
        for _ in 0..160 {
            s.push(&chunk, &mut out);
            assert!(s.pending() <= 512);
        }
        assert!(out.is_empty() && s.in_line());
        s.push(b"\r\n", &mut out);
        assert_eq!(out, [Line::TooLong]);
        assert!(!s.in_line());
    }

    #[test]
    fn bytes_that_are_not_utf8_become_replacement_characters() {
        let lines = split(&[b"\xff\xfe()\n"], 512);
        assert_eq!(lines, [text("\u{fffd}\u{fffd}()")]);
    }
}
