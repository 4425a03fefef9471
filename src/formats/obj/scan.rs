//! The OBJ line scanner shared by the reader and the faithful writer, so that both always agree
//! on which bytes form which statement and which `v` statement is which vertex.
//!
//! A *logical line* is one or more physical lines joined by `\` line continuations. Physical
//! lines end in LF or CRLF; the final line may have no ending. The statement is the text
//! before the first `#` (a comment), split on ASCII whitespace; its first word is the keyword.

use std::borrow::Cow;
use std::ops::Range;

/// One logical line of an OBJ file.
#[derive(Debug)]
pub(crate) struct LogicalLine<'a> {
    /// 1-based number of its first physical line.
    pub number: usize,
    /// Byte offset of its first byte in the file.
    pub start: usize,
    /// All its bytes in the file, continuations and the final line ending included.
    pub raw: &'a [u8],
    /// Its text without the final line ending; each `\` + line ending of a continuation is
    /// replaced by one space.
    pub body: Cow<'a, [u8]>,
    /// The final line ending: `b"\n"`, `b"\r\n"` or empty at the end of the file.
    pub ending: &'a [u8],
}

/// Iterator over the logical lines of an OBJ file's bytes.
#[derive(Debug)]
pub(crate) struct Scanner<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Scanner<'a> {
    /// Scans `bytes` from the start.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes, pos: 0, line: 1 }
    }

    /// Scans `bytes` from the byte `pos`, the start of its physical line `line` (1-based).
    pub fn resume(bytes: &'a [u8], pos: usize, line: usize) -> Self {
        Self { bytes, pos, line }
    }

    /// Where the next logical line starts: its byte offset and its line number.
    pub fn position(&self) -> (usize, usize) {
        (self.pos, self.line)
    }

    /// The next physical line from `pos`: (content range, ending range).
    fn physical(&self, pos: usize) -> (Range<usize>, Range<usize>) {
        match memchr::memchr(b'\n', &self.bytes[pos..]) {
            Some(i) => {
                let lf = pos + i;
                let content_end = if lf > pos && self.bytes[lf - 1] == b'\r' { lf - 1 } else { lf };
                (pos..content_end, content_end..lf + 1)
            }
            None => (pos..self.bytes.len(), self.bytes.len()..self.bytes.len()),
        }
    }
}

impl<'a> Iterator for Scanner<'a> {
    type Item = LogicalLine<'a>;

    fn next(&mut self) -> Option<LogicalLine<'a>> {
        if self.pos >= self.bytes.len() {
            return None;
        }
        let start = self.pos;
        let number = self.line;
        let mut body: Cow<'a, [u8]> = Cow::Borrowed(&[]);
        let mut first = true;
        loop {
            let (content, ending) = self.physical(self.pos);
            self.pos = ending.end;
            self.line += 1;
            let text = &self.bytes[content];
            let continued = text.last() == Some(&b'\\');
            let text = if continued { &text[..text.len() - 1] } else { text };
            if first {
                body = Cow::Borrowed(text);
                first = false;
            } else {
                body.to_mut().extend_from_slice(text);
            }
            if !continued || ending.is_empty() {
                return Some(LogicalLine {
                    number,
                    start,
                    raw: &self.bytes[start..self.pos],
                    body,
                    ending: &self.bytes[ending],
                });
            }
            body.to_mut().push(b' ');
        }
    }
}

/// The statement part of a line body: everything before the first `#`.
pub(crate) fn code(body: &[u8]) -> &[u8] {
    let end = memchr::memchr(b'#', body).unwrap_or(body.len());
    &body[..end]
}

/// The byte ranges of the whitespace-separated words of `code`.
pub(crate) fn words(code: &[u8]) -> impl Iterator<Item = Range<usize>> + '_ {
    let mut pos = 0;
    std::iter::from_fn(move || {
        let start = pos + code[pos..].iter().position(|b| !b.is_ascii_whitespace())?;
        let len = code[start..].iter().position(|b| b.is_ascii_whitespace()).unwrap_or(code.len() - start);
        pos = start + len;
        Some(start..pos)
    })
}

/// The kinds of statement the mesh reader acts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Keyword {
    /// `v`: a vertex position.
    Vertex,
    /// `f` or `fo`: a polygon face.
    Face,
    /// `g`: the current group names.
    Group,
    /// `o`: the current object name.
    Object,
    /// `vt`, `vn` or `vp`: numbers kept verbatim, each checked to be finite; the name of what
    /// they are, for errors.
    Values(&'static str),
    /// Anything else, kept verbatim and otherwise ignored (`usemtl`, `s`, `l`, …).
    Other,
}

/// The keyword of a statement and the range of the text after it (in `code`).
pub(crate) fn keyword(code: &[u8]) -> (Keyword, Range<usize>) {
    let mut w = words(code);
    let Some(first) = w.next() else {
        return (Keyword::Other, code.len()..code.len());
    };
    let kind = match &code[first.clone()] {
        b"v" => Keyword::Vertex,
        b"f" | b"fo" => Keyword::Face,
        b"g" => Keyword::Group,
        b"o" => Keyword::Object,
        b"vt" => Keyword::Values("texture coordinate"),
        b"vn" => Keyword::Values("normal coordinate"),
        b"vp" => Keyword::Values("parameter-space coordinate"),
        _ => Keyword::Other,
    };
    (kind, first.end..code.len())
}

/// Why a `v` statement has no position.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum VertexIssue {
    /// A coordinate word that does not parse as a number (the word, lossily decoded).
    NotANumber(String),
    /// Fewer than three numbers.
    Missing(usize),
}

/// The position of a `v` statement whose text after the keyword is `args` (a range of
/// `code`): the first three numbers as f64 and the offset in `code` just past the third, where
/// the tail (w or a colour, and any comment if `code` is the whole body) begins.
pub(crate) fn vertex(code: &[u8], args: Range<usize>) -> Result<([f64; 3], usize), VertexIssue> {
    let mut xyz = [0.0; 3];
    let mut end = args.start;
    let mut found = 0;
    for range in words(&code[args.clone()]).take(3) {
        let word = &code[args.start + range.start..args.start + range.end];
        xyz[found] = super::float::parse(word).ok_or_else(|| VertexIssue::NotANumber(lossy(word)))?;
        end = args.start + range.end;
        found += 1;
    }
    if found < 3 {
        return Err(VertexIssue::Missing(found));
    }
    Ok((xyz, end))
}

/// Parses a word as an `i64` exactly as `str::parse::<i64>` does (an optional `+` or `-`, then
/// at least one ASCII digit, no overflow), without the UTF-8 check; `None` otherwise.
pub(crate) fn integer(word: &[u8]) -> Option<i64> {
    let (negative, digits) = match word.split_first() {
        Some((b'-', rest)) => (true, rest),
        Some((b'+', rest)) => (false, rest),
        _ => (false, word),
    };
    if digits.is_empty() {
        return None;
    }
    // Accumulated towards the sign, so that i64::MIN parses.
    let mut value: i64 = 0;
    for &b in digits {
        let d = i64::from(b.wrapping_sub(b'0'));
        if d > 9 {
            return None;
        }
        value = value.checked_mul(10)?;
        value = if negative { value.checked_sub(d)? } else { value.checked_add(d)? };
    }
    Some(value)
}

/// A word as text, invalid UTF-8 replaced.
pub(crate) fn lossy(word: &[u8]) -> String {
    String::from_utf8_lossy(word).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (number, raw, body, ending) of each logical line.
    type Lines = Vec<(usize, Vec<u8>, Vec<u8>, Vec<u8>)>;

    fn lines(text: &[u8]) -> Lines {
        Scanner::new(text).map(|l| (l.number, l.raw.to_vec(), l.body.into_owned(), l.ending.to_vec())).collect()
    }

    #[test]
    fn lf_crlf_and_missing_final_ending() {
        let got = lines(b"v 1 2 3\r\nf 1 2 3\n# end");
        assert_eq!(got.len(), 3);
        assert_eq!(got[0], (1, b"v 1 2 3\r\n".to_vec(), b"v 1 2 3".to_vec(), b"\r\n".to_vec()));
        assert_eq!(got[1].2, b"f 1 2 3");
        assert_eq!(got[1].3, b"\n");
        assert_eq!(got[2], (3, b"# end".to_vec(), b"# end".to_vec(), vec![]));
    }

    #[test]
    fn raw_lines_concatenate_to_the_input() {
        let text: &[u8] = b"\n\r\n  v 1 2 3 \\\r\n 4\nf 1 2 \\\n3\\\n\\";
        let joined: Vec<u8> = Scanner::new(text).flat_map(|l| l.raw.to_vec()).collect();
        assert_eq!(joined, text);
    }

    #[test]
    fn continuation_joins_lines_and_keeps_the_first_line_number() {
        let got = lines(b"# a\nf 1 2\\\n 3 \\\r\n4\nv 0 0 0\n");
        assert_eq!(got[1].0, 2);
        assert_eq!(got[1].2, b"f 1 2  3  4");
        assert_eq!(got[1].3, b"\n");
        assert_eq!(got[2].0, 5);
        assert_eq!(got[2].2, b"v 0 0 0");
    }

    #[test]
    fn backslash_at_end_of_file_is_dropped() {
        let got = lines(b"v 1 2 3\\");
        assert_eq!(got.len(), 1);
        assert_eq!(got[0].1, b"v 1 2 3\\");
        assert_eq!(got[0].2, b"v 1 2 3");
    }

    #[test]
    fn comment_is_cut_at_first_hash() {
        assert_eq!(code(b"v 1 2 3 # note"), b"v 1 2 3 ");
        assert_eq!(code(b"# whole line"), b"");
        assert_eq!(keyword(code(b"#v 1 2 3")).0, Keyword::Other);
    }

    #[test]
    fn keywords_with_leading_whitespace_and_tabs() {
        assert_eq!(keyword(b"  \tv\t1 2 3").0, Keyword::Vertex);
        assert_eq!(keyword(b"fo 1 2 3").0, Keyword::Face);
        assert_eq!(keyword(b"g").0, Keyword::Group);
        assert_eq!(keyword(b"o thing").0, Keyword::Object);
        assert_eq!(keyword(b"vt 0 0").0, Keyword::Values("texture coordinate"));
        assert_eq!(keyword(b"vn 0 0 1").0, Keyword::Values("normal coordinate"));
        assert_eq!(keyword(b"usemtl red").0, Keyword::Other);
        assert_eq!(keyword(b"").0, Keyword::Other);
        assert_eq!(keyword(b"   ").0, Keyword::Other);
    }

    #[test]
    fn vertex_reads_three_numbers_and_finds_the_tail() {
        let c = b"v  1.5 -2 3e2 0.25 0.5 0.75";
        let (_, args) = keyword(c);
        let (xyz, tail) = vertex(c, args).unwrap();
        assert_eq!(xyz, [1.5, -2.0, 300.0]);
        assert_eq!(&c[tail..], b" 0.25 0.5 0.75");
    }

    #[test]
    fn vertex_with_too_few_or_bad_numbers() {
        let c = b"v 1 2";
        assert_eq!(vertex(c, keyword(c).1), Err(VertexIssue::Missing(2)));
        let c = b"v 1 abc 3";
        assert_eq!(vertex(c, keyword(c).1), Err(VertexIssue::NotANumber("abc".into())));
        let c = b"v 1 \xff 3";
        assert_eq!(vertex(c, keyword(c).1), Err(VertexIssue::NotANumber("\u{fffd}".into())));
    }

    #[test]
    fn integer_parses_as_str_parse_does() {
        let words: [&[u8]; 22] = [
            b"0",
            b"1",
            b"-1",
            b"+7",
            b"007",
            b"-0",
            b"+",
            b"-",
            b"",
            b"1/2",
            b"12a",
            b"\xff1",
            b" 1",
            b"--1",
            b"+-1",
            b"9223372036854775807",
            b"9223372036854775808",
            b"-9223372036854775808",
            b"-9223372036854775809",
            b"99999999999999999999",
            b"\xd9\xa3",
            b"1e3",
        ];
        for word in words {
            let expected = std::str::from_utf8(word).ok().and_then(|s| s.parse::<i64>().ok());
            assert_eq!(integer(word), expected, "{:?}", lossy(word));
        }
    }

    #[test]
    fn words_split_on_any_ascii_whitespace() {
        let c = b" a\tbb \x0c c ";
        let got: Vec<&[u8]> = words(c).map(|r| &c[r]).collect();
        assert_eq!(got, vec![&b"a"[..], b"bb", b"c"]);
    }
}
