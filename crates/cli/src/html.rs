//! HTML fragments for `slipload report`: escaping, the Markdown subset slipload writes
//! (headings, paragraphs, pipe tables, lists, `code`, **bold**), CSV and JSON as tables.
//! Every piece of text from a file goes through [`escape`]; nothing is passed through raw.

use std::fmt::Write as _;

/// Escapes `&`, `<`, `>`, `"` and `'` for HTML text and attribute values.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// `v` with `digits` significant digits, in plain notation, trailing zeros dropped
/// (`sig(1999.9999999999925, 6)` = "2000", `sig(0.0054799035, 4)` = "0.005480" → "0.00548").
pub fn sig(v: f64, digits: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v == 0.0 {
            "0".to_string()
        } else {
            v.to_string()
        };
    }
    let magnitude = v.abs().log10().floor() as i32;
    let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
    trim_zeros(&format!("{v:.decimals$}"))
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') && !s.contains(['e', 'E']) {
        let t = s.trim_end_matches('0').trim_end_matches('.');
        if t == "-0" {
            "0".to_string()
        } else {
            t.to_string()
        }
    } else {
        s.to_string()
    }
}

/// A number as a table shows it: slip loads (a name with a `kN` part: `slip_load_kN_1`,
/// `slip_loads_kn`) with one decimal as
/// the design tables give them; integers as integers; other values with 6 significant
/// digits, in scientific notation when very small or very large. The files keep every
/// digit; this is only what the page prints (the full value is the cell's tooltip).
pub fn display_number(name: &str, v: f64) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    if name.split('_').any(|part| part.eq_ignore_ascii_case("kn")) {
        let s = format!("{v:.1}");
        return if s == "-0.0" { "0.0".to_string() } else { s };
    }
    if v.fract() == 0.0 && v.abs() < 1e15 {
        return format!("{v:.0}");
    }
    let a = v.abs();
    if (1e-4..1e7).contains(&a) {
        sig(v, 6)
    } else {
        let s = format!("{v:.5e}");
        match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim_zeros(m)),
            None => s,
        }
    }
}

/// Inline Markdown: escapes the text, then turns `code` and **bold** spans into tags.
/// Unpaired markers stay as they are.
pub fn inline(s: &str) -> String {
    let mut out = String::new();
    let mut rest = s;
    while let Some(i) = rest.find('`') {
        let (before, after) = rest.split_at(i);
        match after[1..].find('`') {
            Some(j) => {
                out.push_str(&bold(&escape(before)));
                let _ = write!(out, "<code>{}</code>", escape(&after[1..1 + j]));
                rest = &after[j + 2..];
            }
            None => break,
        }
    }
    out.push_str(&bold(&escape(rest)));
    out
}

/// `**x**` → `<strong>x</strong>` in already escaped text.
fn bold(escaped: &str) -> String {
    let parts: Vec<&str> = escaped.split("**").collect();
    if parts.len() < 3 {
        return escaped.to_string();
    }
    let mut out = String::new();
    let pairs = (parts.len() - 1) / 2;
    for (k, p) in parts.iter().enumerate() {
        if k > 0 {
            // markers 1..=2*pairs pair up; an odd last one stays literal
            if k <= 2 * pairs {
                out.push_str(if k % 2 == 1 { "<strong>" } else { "</strong>" });
            } else {
                out.push_str("**");
            }
        }
        out.push_str(p);
    }
    out
}

/// Text alignment of a table column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Align {
    Left,
    Right,
    Center,
}

fn split_row(line: &str) -> Vec<String> {
    let t = line.trim();
    let t = t.strip_prefix('|').unwrap_or(t);
    let t = t.strip_suffix('|').unwrap_or(t);
    t.split('|').map(|c| c.trim().to_string()).collect()
}

fn is_separator(line: &str) -> bool {
    let cells = split_row(line);
    !cells.is_empty()
        && cells.iter().all(|c| {
            let c = c.trim();
            !c.is_empty() && c.chars().all(|ch| ch == '-' || ch == ':') && c.contains('-')
        })
}

fn align_of(cell: &str) -> Align {
    match (cell.starts_with(':'), cell.ends_with(':')) {
        (true, true) => Align::Center,
        (false, true) => Align::Right,
        _ => Align::Left,
    }
}

/// A cell; `content` is already HTML. Numbers never wrap (`1.2e-3` must not break at
/// its minus sign).
fn td(tag: &str, align: Align, content: &str, number: bool) -> String {
    let class = match (align, number) {
        (Align::Left, false) => "",
        (Align::Left, true) => " class=\"nw\"",
        (Align::Right, _) => " class=\"num\"",
        (Align::Center, false) => " class=\"mid\"",
        (Align::Center, true) => " class=\"mid nw\"",
    };
    format!("<{tag}{class}>{content}</{tag}>")
}

/// Renders the Markdown subset slipload writes. Headings are shifted so the file's
/// highest heading becomes `<h{top}>` (capped at `<h6>`), to fit under the page's
/// section heading whatever level the file starts at.
pub fn markdown(text: &str, top: usize) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let highest = lines
        .iter()
        .filter_map(|l| heading_level(l.trim()))
        .min()
        .unwrap_or(1);
    let heading_shift = top.saturating_sub(highest);
    let mut out = String::new();
    let mut para: Vec<&str> = Vec::new();
    let flush = |para: &mut Vec<&str>, out: &mut String| {
        if !para.is_empty() {
            let _ = writeln!(out, "<p>{}</p>", inline(&para.join(" ")));
            para.clear();
        }
    };
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let t = line.trim();
        if t.is_empty() {
            flush(&mut para, &mut out);
            i += 1;
        } else if let Some(level) = heading_level(t) {
            flush(&mut para, &mut out);
            let h = (level + heading_shift).min(6);
            let _ = writeln!(
                out,
                "<h{h}>{}</h{h}>",
                inline(t[level..].trim().trim_end_matches('#').trim())
            );
            i += 1;
        } else if t.starts_with('|') && i + 1 < lines.len() && is_separator(lines[i + 1]) {
            flush(&mut para, &mut out);
            let head = split_row(t);
            let aligns: Vec<Align> = split_row(lines[i + 1])
                .iter()
                .map(|c| align_of(c))
                .collect();
            let al = |k: usize| aligns.get(k).copied().unwrap_or(Align::Left);
            out.push_str("<div class=\"scroll\"><table>\n<thead><tr>");
            for (k, c) in head.iter().enumerate() {
                out.push_str(&td("th", al(k), &inline(c), false));
            }
            out.push_str("</tr></thead>\n<tbody>\n");
            i += 2;
            while i < lines.len() && lines[i].trim().starts_with('|') {
                out.push_str("<tr>");
                for (k, c) in split_row(lines[i]).iter().enumerate() {
                    out.push_str(&td("td", al(k), &inline(c), is_number(c)));
                }
                out.push_str("</tr>\n");
                i += 1;
            }
            out.push_str("</tbody></table></div>\n");
        } else if t.starts_with("- ") || t.starts_with("* ") {
            flush(&mut para, &mut out);
            out.push_str("<ul>\n");
            while i < lines.len() {
                let l = lines[i].trim();
                if let Some(item) = l.strip_prefix("- ").or_else(|| l.strip_prefix("* ")) {
                    let _ = writeln!(out, "<li>{}</li>", inline(item));
                    i += 1;
                } else {
                    break;
                }
            }
            out.push_str("</ul>\n");
        } else if t.starts_with("```") {
            flush(&mut para, &mut out);
            i += 1;
            let mut code = String::new();
            while i < lines.len() && !lines[i].trim().starts_with("```") {
                code.push_str(lines[i]);
                code.push('\n');
                i += 1;
            }
            i += 1; // the closing fence (or the end)
            let _ = writeln!(out, "<pre>{}</pre>", escape(&code));
        } else {
            para.push(t);
            i += 1;
        }
    }
    flush(&mut para, &mut out);
    out
}

fn heading_level(t: &str) -> Option<usize> {
    let n = t.chars().take_while(|&c| c == '#').count();
    (1..=6)
        .contains(&n)
        .then_some(n)
        .filter(|&n| t[n..].starts_with(' '))
}

/// Parses CSV (RFC 4180: quoted fields may hold commas, doubled quotes and newlines).
pub fn parse_csv(text: &str) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    let mut row = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if quoted {
            match c {
                '"' if chars.peek() == Some(&'"') => {
                    field.push('"');
                    chars.next();
                }
                '"' => quoted = false,
                c => field.push(c),
            }
        } else {
            match c {
                '"' => quoted = true,
                ',' => row.push(std::mem::take(&mut field)),
                '\r' => {}
                '\n' => {
                    row.push(std::mem::take(&mut field));
                    rows.push(std::mem::take(&mut row));
                }
                c => field.push(c),
            }
        }
    }
    if !field.is_empty() || !row.is_empty() {
        row.push(field);
        rows.push(row);
    }
    rows
}

fn is_number(s: &str) -> bool {
    !s.is_empty() && s.parse::<f64>().is_ok()
}

/// A CSV file as an HTML table: the header row and at most `max_rows` data rows
/// (a note says how many were left out). Numeric cells are right-aligned.
pub fn csv_table(text: &str, max_rows: usize) -> String {
    let rows = parse_csv(text);
    let Some((head, body)) = rows.split_first() else {
        return "<p class=\"note\">(empty file)</p>\n".to_string();
    };
    let mut out = String::from("<div class=\"scroll\"><table>\n<thead><tr>");
    for c in head {
        let _ = write!(out, "<th>{}</th>", escape(c));
    }
    out.push_str("</tr></thead>\n<tbody>\n");
    for r in body.iter().take(max_rows) {
        out.push_str("<tr>");
        for (k, c) in r.iter().enumerate() {
            match c.parse::<f64>() {
                Ok(v) if !c.is_empty() => {
                    let shown = display_number(head.get(k).map_or("", String::as_str), v);
                    if shown == *c {
                        out.push_str(&td("td", Align::Right, &escape(c), true));
                    } else {
                        let _ = write!(
                            out,
                            "<td class=\"num\" title=\"{}\">{}</td>",
                            escape(c),
                            escape(&shown)
                        );
                    }
                }
                _ => out.push_str(&td("td", Align::Left, &escape(c), false)),
            }
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody></table></div>\n");
    if body.len() > max_rows {
        let _ = writeln!(
            out,
            "<p class=\"note\">First {max_rows} of {} rows shown; the file holds them all.</p>",
            body.len()
        );
    }
    out
}

/// A scalar (or an array of scalars) as text; numbers rounded for display by the name
/// of the field that holds them ([`display_number`]).
fn scalar(name: &str, v: &serde_json::Value) -> Option<String> {
    use serde_json::Value;
    match v {
        Value::Null => Some("—".to_string()),
        Value::Bool(b) => Some(b.to_string()),
        Value::Number(n) => Some(match n.as_f64() {
            Some(x) if !(n.is_i64() || n.is_u64()) => display_number(name, x),
            _ => n.to_string(),
        }),
        Value::String(s) => Some(s.clone()),
        Value::Array(a) if a.iter().all(|x| !x.is_array() && !x.is_object()) => Some(
            a.iter()
                .filter_map(|x| scalar(name, x))
                .collect::<Vec<_>>()
                .join(", "),
        ),
        _ => None,
    }
}

/// A JSON value as nested HTML tables: an object becomes a key/value table, an array of
/// objects a table with one column per key, scalars and arrays of scalars text.
/// Nesting deeper than `depth` is shown as compact JSON.
pub fn json_table(v: &serde_json::Value, depth: usize) -> String {
    json_table_named("", v, depth)
}

/// [`json_table`] of the value of field `name` (which decides how its numbers round).
fn json_table_named(name: &str, v: &serde_json::Value, depth: usize) -> String {
    use serde_json::Value;
    if let Some(s) = scalar(name, v) {
        return escape(&s);
    }
    if depth == 0 {
        return format!("<code>{}</code>", escape(&v.to_string()));
    }
    match v {
        Value::Object(map) => {
            let mut out = String::from("<table class=\"kv\"><tbody>\n");
            for (k, x) in map {
                let _ = writeln!(
                    out,
                    "<tr><th>{}</th><td>{}</td></tr>",
                    escape(k),
                    json_table_named(k, x, depth - 1)
                );
            }
            out.push_str("</tbody></table>");
            out
        }
        Value::Array(items) => {
            let mut keys: Vec<&String> = Vec::new();
            for it in items {
                if let Value::Object(m) = it {
                    for k in m.keys() {
                        if !keys.contains(&k) {
                            keys.push(k);
                        }
                    }
                }
            }
            if keys.is_empty() || items.iter().any(|it| !it.is_object()) {
                let cells: Vec<String> = items
                    .iter()
                    .map(|x| json_table_named(name, x, depth - 1))
                    .collect();
                return cells.join("<br>");
            }
            let mut out = String::from("<table><thead><tr>");
            for k in &keys {
                let _ = write!(out, "<th>{}</th>", escape(k));
            }
            out.push_str("</tr></thead><tbody>\n");
            for it in items {
                out.push_str("<tr>");
                for k in &keys {
                    let cell = it
                        .get(k.as_str())
                        .map_or(String::new(), |x| json_table_named(k, x, depth - 1));
                    let _ = write!(out, "<td>{cell}</td>");
                }
                out.push_str("</tr>\n");
            }
            out.push_str("</tbody></table>");
            out
        }
        _ => escape(&v.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_markup_in_text() {
        assert_eq!(
            escape("<b>\"a\" & 'b'</b>"),
            "&lt;b&gt;&quot;a&quot; &amp; &#39;b&#39;&lt;/b&gt;"
        );
    }

    #[test]
    fn inline_code_and_bold_are_escaped_inside() {
        assert_eq!(
            inline("run `a<b` and **c&d**"),
            "run <code>a&lt;b</code> and <strong>c&amp;d</strong>"
        );
        assert_eq!(inline("a ` b"), "a ` b");
        assert_eq!(inline("x ** y"), "x ** y");
    }

    #[test]
    fn markdown_table_keeps_alignment_and_escapes_cells() {
        let html = markdown(
            "## T\n\ntext <x>\n\n| a | b |\n|---|---:|\n| <s> | 1.5 |\n\n### U\n",
            3,
        );
        assert!(html.contains("<h3>T</h3>"), "{html}");
        assert!(html.contains("<h4>U</h4>"), "{html}");
        assert!(html.contains("<p>text &lt;x&gt;</p>"), "{html}");
        assert!(
            html.contains("<td>&lt;s&gt;</td><td class=\"num\">1.5</td>"),
            "{html}"
        );
        assert!(!html.contains("<s>"), "{html}");
    }

    #[test]
    fn csv_quotes_commas_and_truncation() {
        let rows = parse_csv("a,b\n1,\"x, \"\"y\"\"\"\n2,z\n");
        assert_eq!(rows[1], vec!["1".to_string(), "x, \"y\"".to_string()]);
        let html = csv_table("a,b\n1,2\n3,4\n5,6\n", 2);
        assert_eq!(html.matches("<tr>").count(), 3, "header + 2 rows: {html}");
        assert!(html.contains("First 2 of 3 rows"), "{html}");
    }

    #[test]
    fn numbers_are_rounded_for_people_and_kept_in_the_tooltip() {
        // slip loads to 0.1 kN as the design tables give them
        assert_eq!(
            display_number("slip_load_kN_2", 1999.9999999999925),
            "2000.0"
        );
        assert_eq!(
            display_number("slip_loads_kn", 1950.4456797051607),
            "1950.4"
        );
        // other values: 6 significant digits, integers as integers, tiny ones scientific
        assert_eq!(
            display_number("objective", 0.005479903502075623),
            "0.0054799"
        );
        assert_eq!(display_number("rank", 50.0), "50");
        assert_eq!(display_number("x", 4.656612873077393e-10), "4.65661e-10");
        assert_eq!(sig(1999.9999999999925, 6), "2000");
        assert_eq!(sig(-0.00001, 2), "-0.00001");
        let html = csv_table("slip_load_kN_1,objective\n1999.9999999999925,0.5\n", 10);
        assert!(
            html.contains("<td class=\"num\" title=\"1999.9999999999925\">2000.0</td>"),
            "{html}"
        );
        assert!(html.contains("<td class=\"num\">0.5</td>"), "{html}");
        let v: serde_json::Value =
            serde_json::from_str(r#"{"slip_loads_kN": [1999.9999999999925, 0.0]}"#).unwrap();
        assert!(json_table(&v, 2).contains("<td>2000.0, 0.0</td>"));
    }

    #[test]
    fn json_objects_and_arrays_become_tables() {
        let v: serde_json::Value =
            serde_json::from_str(r#"{"a": [1, 2], "b": [{"x": 1, "y": "<"}, {"x": 2}]}"#).unwrap();
        let html = json_table(&v, 4);
        assert!(html.contains("<th>a</th><td>1, 2</td>"), "{html}");
        assert!(html.contains("<th>x</th><th>y</th>"), "{html}");
        assert!(html.contains("<td>&lt;</td>"), "{html}");
    }
}
