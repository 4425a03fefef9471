//! The lines of an OFF file that hold data: comments (`#` to the end of the line) removed,
//! blank lines skipped, each token with its byte offset in the file.

/// A line with data: its 1-based number and its tokens.
pub(crate) struct Line<'a> {
    /// 1-based line number.
    pub number: usize,
    /// The whitespace-separated tokens before any `#`, with their byte offsets in the file.
    pub tokens: Vec<(usize, &'a [u8])>,
}

/// The data lines of a file, in order.
pub(crate) struct Lines<'a> {
    bytes: &'a [u8],
    at: usize,
    /// The number of the last line read (data or not); 0 before the first.
    pub number: usize,
}

impl<'a> Lines<'a> {
    /// The data lines of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Lines { bytes, at: 0, number: 0 }
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = Line<'a>;

    fn next(&mut self) -> Option<Line<'a>> {
        while self.at < self.bytes.len() {
            let start = self.at;
            let rest = &self.bytes[start..];
            let length = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
            self.at = start + length + 1;
            self.number += 1;
            let line = &rest[..length];
            let code = &line[..line.iter().position(|&b| b == b'#').unwrap_or(line.len())];
            let tokens = tokens(code, start);
            if !tokens.is_empty() {
                return Some(Line { number: self.number, tokens });
            }
        }
        None
    }
}

/// The whitespace-separated tokens of `code`, which starts at byte `base` of the file.
fn tokens(code: &[u8], base: usize) -> Vec<(usize, &[u8])> {
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < code.len() {
        if code[i].is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let start = i;
        while i < code.len() && !code[i].is_ascii_whitespace() {
            i += 1;
        }
        tokens.push((base + start, &code[start..i]));
    }
    tokens
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_blank_lines_are_skipped_and_offsets_kept() {
        let text = b"# c\n\nOFF # header\r\n  1 2\t3\n";
        let lines: Vec<Line> = Lines::new(text).collect();
        assert_eq!(lines.len(), 2);
        assert_eq!(lines[0].number, 3);
        assert_eq!(lines[0].tokens, vec![(5, &b"OFF"[..])]);
        assert_eq!(lines[1].number, 4);
        let offsets: Vec<usize> = lines[1].tokens.iter().map(|t| t.0).collect();
        assert_eq!(offsets, [21, 23, 25]);
    }
}
