//! Reading numbers as Fortran programs write them.
//!
//! Contract: [`parse_number`] accepts what Rust's `f64::from_str` accepts (so `.5`, `-.64E-02`,
//! `5.`, `+1e3`) plus a Fortran `D` exponent (`1.0D-03`); it returns `None` for anything
//! else. Non-finite results (`NaN`, `inf`, `1e400`) are returned as such: the callers turn
//! them into [`crate::MotionError::NonFinite`] with the line they came from.

/// Parses one numeric token (surrounding blanks ignored).
pub(crate) fn parse_number(token: &str) -> Option<f64> {
    let t = token.trim();
    if t.is_empty() {
        return None;
    }
    if let Ok(v) = t.parse::<f64>() {
        return Some(v);
    }
    if t.contains(['D', 'd']) {
        let e: String = t
            .chars()
            .map(|c| if c == 'D' || c == 'd' { 'E' } else { c })
            .collect();
        return e.parse::<f64>().ok();
    }
    None
}

/// Splits a token where one number runs into the next without a blank, as fixed-column
/// Fortran output does when a value fills its field (`-0.00123-0.00456`): a new number
/// starts at a `+` or `-` that follows a digit or a decimal point (so exponent signs, which
/// follow `E`/`D`, are kept).
pub(crate) fn split_touching(token: &str) -> Vec<&str> {
    let mut pieces = Vec::new();
    let mut start = 0;
    let mut prev: Option<char> = None;
    for (i, c) in token.char_indices() {
        if (c == '-' || c == '+') && matches!(prev, Some(p) if p.is_ascii_digit() || p == '.') {
            pieces.push(&token[start..i]);
            start = i;
        }
        prev = Some(c);
    }
    pieces.push(&token[start..]);
    pieces
}

/// `true` when `value` is within `rel` × |reference| of `reference`; `false` if either is NaN.
pub(crate) fn within(value: f64, reference: f64, rel: f64) -> bool {
    (value - reference).abs() <= rel * reference.abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fortran_forms() {
        assert_eq!(parse_number("-.6403182E-02"), Some(-0.006403182));
        assert_eq!(parse_number("  .8992569E-03 "), Some(0.0008992569));
        assert_eq!(parse_number("1.0D-03"), Some(0.001));
        assert_eq!(parse_number("0.00630"), Some(0.0063));
        assert_eq!(parse_number("abc"), None);
        assert_eq!(parse_number(""), None);
        assert_eq!(parse_number("1.2.3"), None);
        assert!(parse_number("NaN").is_some_and(f64::is_nan));
    }

    #[test]
    fn splits_touching_values_but_not_exponents() {
        assert_eq!(
            split_touching("-0.00123-0.00456"),
            vec!["-0.00123", "-0.00456"]
        );
        assert_eq!(split_touching("0.5+0.25"), vec!["0.5", "+0.25"]);
        assert_eq!(
            split_touching("-.64E-02-.12E+01"),
            vec!["-.64E-02", "-.12E+01"]
        );
        assert_eq!(split_touching("1.0"), vec!["1.0"]);
    }
}
