//! The whitespace-separated words of a legacy ASCII VTK file after its three header lines, each with its line number.

/// One word of the file and the line it stands on (1-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Token<'a> {
    /// The word.
    pub text: &'a str,
    /// Its line, counted from 1 at the top of the file.
    pub line: usize,
}

/// The words of a text, read one at a time; cloning it is a cheap look-ahead.
#[derive(Debug, Clone)]
pub(crate) struct Tokens<'a> {
    rest: &'a str,
    line: usize,
}

impl<'a> Tokens<'a> {
    /// The words of `text`, whose first line is line `first_line` of the file.
    pub fn new(text: &'a str, first_line: usize) -> Self {
        Tokens { rest: text, line: first_line }
    }

    /// The line the reader stands on: that of the last word read, or later where only blank lines followed it.
    pub fn line(&self) -> usize {
        self.line
    }

    /// Bytes not read yet (a bound on how many words can still come).
    pub fn remaining_len(&self) -> usize {
        self.rest.len()
    }

    /// The next word without reading it.
    pub fn peek(&self) -> Option<Token<'a>> {
        self.clone().next()
    }
}

impl<'a> Iterator for Tokens<'a> {
    type Item = Token<'a>;

    fn next(&mut self) -> Option<Token<'a>> {
        let bytes = self.rest.as_bytes();
        let mut start = 0;
        while start < bytes.len() && bytes[start].is_ascii_whitespace() {
            if bytes[start] == b'\n' {
                self.line += 1;
            }
            start += 1;
        }
        if start == bytes.len() {
            self.rest = "";
            return None;
        }
        let mut end = start;
        while end < bytes.len() && !bytes[end].is_ascii_whitespace() {
            end += 1;
        }
        // Both ends sit on ASCII bytes (or the text's ends), so they are character boundaries.
        let text = &self.rest[start..end];
        self.rest = &self.rest[end..];
        Some(Token { text, line: self.line })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_carry_their_lines() {
        let words: Vec<_> = Tokens::new("POINTS 2 float\r\n\n 0 1\t2\n", 5).map(|t| (t.text, t.line)).collect();
        assert_eq!(words, vec![("POINTS", 5), ("2", 5), ("float", 5), ("0", 7), ("1", 7), ("2", 7)]);
    }
}
