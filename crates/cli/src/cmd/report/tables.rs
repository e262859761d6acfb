//! The HTML tables of a report page (key/value tables and grids with numbers
//! right-aligned) and the numbers they read from JSON outputs.

use crate::html::escape;
use std::fmt::Write as _;

/// A key/value table.
pub(super) fn kv_table(rows: &[(String, String)]) -> String {
    let mut out = String::from("<div class=\"scroll\"><table class=\"kv\"><tbody>\n");
    for (k, v) in rows {
        let _ = writeln!(out, "<tr><th>{}</th><td>{}</td></tr>", escape(k), escape(v));
    }
    out.push_str("</tbody></table></div>\n");
    out
}

/// An HTML table: a header row, then rows; cells are text (escaped here), numbers (cells
/// that parse as one, or "—") right-aligned.
pub(super) fn grid(head: &[String], rows: &[Vec<String>]) -> String {
    let num = |c: &str| c == "—" || c.parse::<f64>().is_ok();
    let mut out = String::from("<div class=\"scroll\"><table>\n<thead><tr>");
    for (k, h) in head.iter().enumerate() {
        let class = if k > 0 { " class=\"num\"" } else { "" };
        let _ = write!(out, "<th{class}>{}</th>", escape(h));
    }
    out.push_str("</tr></thead>\n<tbody>\n");
    for r in rows {
        out.push_str("<tr>");
        for (k, c) in r.iter().enumerate() {
            let class = if k > 0 && num(c) {
                " class=\"num\""
            } else {
                ""
            };
            let _ = write!(out, "<td{class}>{}</td>", escape(c));
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody></table></div>\n");
    out
}

/// The number at `key` of an object.
pub(super) fn f64_at(v: &serde_json::Value, key: &str) -> Option<f64> {
    v.get(key).and_then(serde_json::Value::as_f64)
}

/// The list of numbers at `key` of an object (`None` when any is not a number).
pub(super) fn f64s_at(v: &serde_json::Value, key: &str) -> Option<Vec<f64>> {
    v.get(key)?
        .as_array()?
        .iter()
        .map(serde_json::Value::as_f64)
        .collect()
}
