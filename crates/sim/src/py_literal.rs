//! User text (scene, building and record names, AT2 title lines) written into a Python
//! program ([`crate::opensees`]) as data that Python can never read as code: printable
//! ASCII alone, so no name can change how Python decodes the file (PEP 263 encoding
//! declarations) or end a literal or a comment line.

use std::fmt::Write as _;

/// `text` fit for a `#` comment line: the body of [`py_str`]'s literal, so the comment is
/// ASCII, one line, and shows every character of the name (a newline as `\n`, a
/// non-ASCII letter as `\xe9` or `\u5730`).
pub(crate) fn comment(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    escape_into(&mut out, text);
    out
}

/// A Python string literal of `text`, written in printable ASCII alone: quotes and
/// backslashes escaped, control characters as `\n`, `\r`, `\t` or `\xNN`, every other
/// character past ASCII as `\xNN` (to U+00FF), `\uXXXX` or `\UXXXXXXXX`. Whatever a user
/// wrote, it reads back as the same text and can never end the literal, start a line of
/// code or, being ASCII, change how Python decodes the file.
pub(crate) fn py_str(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    escape_into(&mut out, text);
    out.push('"');
    out
}

/// Appends `text` escaped as the inside of a double-quoted Python literal, ASCII only.
fn escape_into(out: &mut String, text: &str) {
    for c in text.chars() {
        let code = u32::from(c);
        match c {
            '\\' => out.push_str("\\\\"),
            '"' => out.push_str("\\\""),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            ' '..='~' => out.push(c),
            _ if code < 0x100 => {
                let _ = write!(out, "\\x{code:02x}");
            }
            _ if code < 0x10000 => {
                let _ = write!(out, "\\u{code:04x}");
            }
            _ => {
                let _ = write!(out, "\\U{code:08x}");
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every hostile character becomes an escape Python reads back as that character, and
    /// the literal is printable ASCII with no line break.
    #[test]
    fn literals_are_ascii_and_escape_every_hostile_character() {
        let text = "a\"b\\c\nd\re\tf\0g\u{7f}\u{85}\u{2028}é😀'";
        let lit = py_str(text);
        assert!(lit.bytes().all(|b| (b' '..=b'~').contains(&b)), "{lit}");
        assert_eq!(
            lit,
            r#""a\"b\\c\nd\re\tf\x00g\x7f\x85\u2028\xe9\U0001f600'""#
        );
        assert_eq!(comment(text), lit[1..lit.len() - 1]);
    }
}
