//! Figures made safe to inline into a report page: an SVG file from its `<svg` on, with
//! a `viewBox`, refused when it could run code.

/// An SVG file ready to inline: from its `<svg` on (XML prolog and doctype dropped),
/// with a `viewBox` so it scales with the page. `Err` says why it is not inlined:
/// anything that could run code (scripts, event handlers, foreign objects) is refused,
/// since the page must be safe to open.
pub(super) fn inline_svg(text: &str) -> Result<String, &'static str> {
    let lower = text.to_ascii_lowercase();
    if lower.contains("<script")
        || lower.contains("javascript:")
        || lower.contains("<foreignobject")
        || has_event_handler(&lower)
    {
        return Err("it holds a script, an event handler or a foreign object");
    }
    let start = lower.find("<svg").ok_or("no <svg> element")?;
    let svg = &text[start..];
    let tag_end = svg.find('>').ok_or("unterminated <svg> tag")?;
    let tag = &svg[..tag_end];
    if tag.contains("viewBox") {
        return Ok(svg.to_string());
    }
    let attr = |name: &str| -> Option<f64> {
        let i = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        let rest = &tag[i..];
        let v = &rest[..rest.find('"')?];
        v.trim_end_matches("px").parse().ok()
    };
    match (attr("width"), attr("height")) {
        (Some(w), Some(h)) => Ok(format!(
            "<svg viewBox=\"0 0 {w} {h}\"{}",
            &svg["<svg".len()..]
        )),
        _ => Ok(svg.to_string()),
    }
}

/// ` onload=`, ` onclick=` … anywhere in (lower-cased) markup.
fn has_event_handler(lower: &str) -> bool {
    lower.match_indices(" on").any(|(i, _)| {
        let rest = &lower[i + 3..];
        let name_len = rest.chars().take_while(|c| c.is_ascii_alphabetic()).count();
        name_len > 0 && rest[name_len..].trim_start().starts_with('=')
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_gets_a_viewbox_and_loses_its_prolog() {
        let s = inline_svg("<?xml version=\"1.0\"?>\n<svg width=\"800\" height=\"600\" xmlns=\"http://www.w3.org/2000/svg\"><rect/></svg>").unwrap();
        assert!(
            s.starts_with("<svg viewBox=\"0 0 800 600\" width=\"800\""),
            "{s}"
        );
        let kept = inline_svg("<svg viewBox=\"0 0 1 1\"></svg>").unwrap();
        assert_eq!(kept, "<svg viewBox=\"0 0 1 1\"></svg>");
    }

    #[test]
    fn svg_with_code_is_refused() {
        for bad in [
            "<svg><script>alert(1)</script></svg>",
            "<svg onload=\"alert(1)\"></svg>",
            "<svg><a href=\"javascript:x\"/></svg>",
            "<svg><foreignObject/></svg>",
        ] {
            assert!(inline_svg(bad).is_err(), "{bad}");
        }
        // text that merely contains " on" is fine
        assert!(inline_svg("<svg><text>based on data</text></svg>").is_ok());
    }
}
