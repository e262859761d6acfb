//! Field paths for errors in JSON text the package wrote itself: a dict (a scene, a
//! study) reaches the library as JSON text, so serde's errors place themselves at "line 1
//! column 116" of a text the caller never saw. [`locate`] turns that position back into
//! the field path the command line's checks name (`dissipators[0].floor`).

use pyo3::prelude::*;

/// One open container while scanning: an object (the key being read, whether its `:` has
/// been seen) or an array (the index of the element being read).
enum Frame {
    Object { key: Option<String>, value: bool },
    Array { index: usize },
}

/// The field path at byte `offset` of the JSON `text`: the keys and indices of the
/// containers open there (`dissipators[0].floor`); empty at the top level.
pub fn path_at(text: &str, offset: usize) -> String {
    let bytes = text.as_bytes();
    let end = offset.min(bytes.len());
    let mut stack: Vec<Frame> = Vec::new();
    let mut i = 0;
    while i < end {
        match bytes[i] {
            b'{' => stack.push(Frame::Object {
                key: None,
                value: false,
            }),
            b'[' => stack.push(Frame::Array { index: 0 }),
            b'}' | b']' => {
                stack.pop();
            }
            b':' => {
                if let Some(Frame::Object { value, .. }) = stack.last_mut() {
                    *value = true;
                }
            }
            b',' => match stack.last_mut() {
                Some(Frame::Array { index }) => *index += 1,
                Some(Frame::Object { key, value }) => {
                    *key = None;
                    *value = false;
                }
                None => {}
            },
            b'"' => {
                let start = i + 1;
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' {
                    i += if bytes[i] == b'\\' { 2 } else { 1 };
                }
                if let Some(Frame::Object { key, value: false }) = stack.last_mut() {
                    let raw = &text[start..i.min(bytes.len())];
                    *key = Some(
                        serde_json::from_str(&format!("\"{raw}\""))
                            .unwrap_or_else(|_| raw.to_string()),
                    );
                }
            }
            _ => {}
        }
        i += 1;
    }
    render(stack.iter().filter_map(|f| match f {
        Frame::Object { key: Some(k), .. } => Some(Step::Key(k)),
        Frame::Object { key: None, .. } => None,
        Frame::Array { index } => Some(Step::Index(*index)),
    }))
}

/// One step of a field path: a key of an object or an index of a list.
pub enum Step<'a> {
    /// A key (`slip_load`).
    Key(&'a str),
    /// An index (`[0]`).
    Index(usize),
}

/// A field path as the loaders name it (`dissipators[0].slip_load`).
pub fn render<'a>(steps: impl IntoIterator<Item = Step<'a>>) -> String {
    let mut path = String::new();
    for step in steps {
        match step {
            Step::Key(k) => {
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(k);
            }
            Step::Index(i) => path.push_str(&format!("[{i}]")),
        }
    }
    path
}

/// `message` with serde's " at line L column C" (its last) read against `text`: for a
/// dict (`from_dict`, a text the package wrote) the position is replaced by the field
/// path, after the input's name (`scene (a dict): field `dissipators[0].floor`: …`);
/// for a text of the caller's, the path is added beside the position. None when the
/// message holds no position.
pub fn locate(message: &str, text: &str, name: &str, from_dict: bool) -> Option<String> {
    let at = message.rfind(" at line ")?;
    let rest = &message[at + " at line ".len()..];
    let (line, rest) = rest.split_once(" column ")?;
    let digits = rest.chars().take_while(char::is_ascii_digit).count();
    let (column, tail) = rest.split_at(digits);
    let (line, column): (usize, usize) = (line.parse().ok()?, column.parse().ok()?);
    let line_start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    let path = path_at(text, line_start + column);
    let field = if path.is_empty() {
        "the top level".to_string()
    } else {
        format!("field `{path}`")
    };
    if !from_dict {
        return Some(format!("{message} ({field})"));
    }
    let body = format!("{}{tail}", &message[..at]);
    let prefix = format!("{name}: ");
    Some(match body.strip_prefix(&prefix) {
        Some(b) => format!("{prefix}{field}: {b}"),
        None => format!("{field}: {body}"),
    })
}

/// `err` raised again, of the same class, its message [`locate`]d against `text` (as it
/// is when it holds no position).
pub fn located(err: PyErr, text: &str, name: &str) -> PyErr {
    Python::attach(|py| {
        let message = err.value(py).to_string();
        let from_dict = name.ends_with("(a dict)");
        match locate(&message, text, name, from_dict) {
            Some(m) => match err.get_type(py).call1((m,)) {
                Ok(v) => PyErr::from_value(v),
                Err(_) => err,
            },
            None => err,
        }
    })
}
