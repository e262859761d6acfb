//! Contract (issue 37): the modules of each crate form no import cycle, and no Rust file
//! of a crate is over 1,000 lines.
//!
//! For every crate under `crates/*/src` the test builds the module graph and fails naming
//! each cycle: the files around it and the paths that tie them. Modules are files
//! (`x.rs` and `x/mod.rs` are module `x`, `lib.rs` or `main.rs` the root); an inline
//! `mod x { … }` belongs to its file. An edge goes from a file to the module a path of
//! its code names: `use crate::…`, `use super::…`, `use self::…` (grouped trees too), a
//! `pub use`, a path in code (`crate::a::b::f(…)`, `super::x::Y`), and a path that starts
//! at a child module or at a module imported by `use` (`child::f`). A path resolves to
//! the deepest module file along it; when that module only imports the name the path
//! ends in (`pub use child::Name`, or a private `use` its children can see), the
//! import is followed to the module that defines it, so a facade `mod.rs` does not make
//! false cycles (glob imports are not followed). Comments, doc comments, string and
//! character literals, and every `#[cfg(test)]` item (the `mod tests` blocks) are left
//! out. A cycle is a strongly connected set of files: every edge inside it is listed.
//!
//! The same test fails on any `.rs` file under `crates/*/{src,tests,benches}` over
//! 1,000 lines, naming it. Nothing here depends on more than the standard library.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Most lines of one Rust file.
const MAX_LINES: usize = 1000;

// ---------------------------------------------------------------------------------------
// Tokens
// ---------------------------------------------------------------------------------------

/// The tokens of Rust source that paths are made of: identifiers (keywords among them,
/// raw identifiers without their `r#`), `::`, and every other punctuation character on
/// its own. Comments, literals and lifetimes are dropped (a literal leaves `"` behind, so
/// tokens on either side of it never join into a path).
fn tokens(src: &str) -> Vec<String> {
    let c: Vec<char> = src.chars().collect();
    let n = c.len();
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let is_start = |ch: char| ch == '_' || ch.is_alphabetic();
    let is_cont = |ch: char| ch == '_' || ch.is_alphanumeric();
    let mut out = Vec::new();
    let mut i = 0;
    while i < n {
        let ch = c[i];
        if ch.is_whitespace() {
            i += 1;
        } else if ch == '/' && at(i + 1) == '/' {
            while i < n && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < n {
                if c[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if ch == '"' {
            i = skip_string(&c, i + 1);
            out.push("\"".into());
        } else if let Some(end) = raw_or_byte_literal(&c, i) {
            i = end;
            out.push("\"".into());
        } else if ch == '\'' {
            if at(i + 1) == '\\' {
                // an escaped character literal: up to its closing quote
                i += 2;
                while i < n && c[i] != '\'' {
                    i += 1;
                }
                i += 1;
                out.push("\"".into());
            } else if at(i + 2) == '\'' {
                i += 3; // 'x'
                out.push("\"".into());
            } else {
                // a lifetime or a label
                i += 1;
                while i < n && is_cont(c[i]) {
                    i += 1;
                }
            }
        } else if is_start(ch) {
            let start = if ch == 'r' && at(i + 1) == '#' && is_start(at(i + 2)) {
                i + 2
            } else {
                i
            };
            i = start;
            while i < n && is_cont(c[i]) {
                i += 1;
            }
            out.push(c[start..i].iter().collect());
        } else if ch.is_ascii_digit() {
            while i < n && (is_cont(c[i]) || (c[i] == '.' && at(i + 1).is_ascii_digit())) {
                i += 1;
            }
            out.push("0".into());
        } else if ch == ':' && at(i + 1) == ':' {
            out.push("::".into());
            i += 2;
        } else {
            out.push(ch.to_string());
            i += 1;
        }
    }
    out
}

/// The index after a `"…"` string whose body starts at `i` (escapes skipped).
fn skip_string(c: &[char], mut i: usize) -> usize {
    while i < c.len() {
        match c[i] {
            '\\' => i += 2,
            '"' => return i + 1,
            _ => i += 1,
        }
    }
    i
}

/// The index after a literal with a prefix at `i`: `b"…"`, `c"…"`, `b'…'`, `r"…"`,
/// `r#"…"#`, `br#"…"#`, `cr"…"`; `None` when `i` starts no such literal.
fn raw_or_byte_literal(c: &[char], i: usize) -> Option<usize> {
    let at = |k: usize| c.get(k).copied().unwrap_or('\0');
    let mut k = i;
    if matches!(at(k), 'b' | 'c') {
        k += 1;
        if at(k) == '"' {
            return Some(skip_string(c, k + 1));
        }
        if at(i) == 'b' && at(k) == '\'' {
            let mut j = k + 1;
            while j < c.len() && c[j] != '\'' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            return Some(j + 1);
        }
    }
    if at(k) != 'r' {
        return None;
    }
    k += 1;
    let mut hashes = 0;
    while at(k) == '#' {
        hashes += 1;
        k += 1;
    }
    if at(k) != '"' {
        return None;
    }
    k += 1;
    while k < c.len() {
        if c[k] == '"' && (1..=hashes).all(|h| at(k + h) == '#') {
            return Some(k + 1 + hashes);
        }
        k += 1;
    }
    Some(k)
}

/// The index after the bracketed group that opens at `i` (`(`, `[` or `{`).
fn close(t: &[String], i: usize) -> usize {
    let mut depth = 0i32;
    let mut k = i;
    while k < t.len() {
        match t[k].as_str() {
            "(" | "[" | "{" => depth += 1,
            ")" | "]" | "}" => {
                depth -= 1;
                if depth == 0 {
                    return k + 1;
                }
            }
            _ => {}
        }
        k += 1;
    }
    k
}

/// `t` without its `#[cfg(test)]` items (the attribute, any attributes after it, and
/// the item up to its `;` or the end of its braces); nothing when the whole file is
/// `#![cfg(test)]`.
fn without_test_items(t: Vec<String>) -> Vec<String> {
    let is = |k: usize, s: &[&str]| {
        s.iter()
            .enumerate()
            .all(|(j, w)| t.get(k + j).is_some_and(|x| x == w))
    };
    if (0..t.len()).any(|k| is(k, &["#", "!", "[", "cfg", "(", "test", ")", "]"])) {
        return Vec::new();
    }
    let mut out = Vec::new();
    let mut i = 0;
    while i < t.len() {
        if !is(i, &["#", "[", "cfg", "(", "test", ")", "]"]) {
            out.push(t[i].clone());
            i += 1;
            continue;
        }
        let mut k = i + 7;
        while t.get(k).is_some_and(|x| x == "#") && t.get(k + 1).is_some_and(|x| x == "[") {
            k = close(&t, k + 1);
        }
        while k < t.len() {
            match t[k].as_str() {
                ";" => {
                    k += 1;
                    break;
                }
                "{" => {
                    k = close(&t, k);
                    break;
                }
                "(" | "[" => k = close(&t, k),
                _ => k += 1,
            }
        }
        i = k;
    }
    out
}

// ---------------------------------------------------------------------------------------
// Modules and their paths
// ---------------------------------------------------------------------------------------

/// A path of `use` or of code, as written.
#[derive(Debug, Clone)]
struct Written {
    /// The module the path is written in (the file's, plus inline `mod` blocks).
    module: Vec<String>,
    segments: Vec<String>,
}

impl Written {
    fn text(&self) -> String {
        self.segments.join("::")
    }
}

/// One `use` leaf: its path and the name it brings in (`None` for `as _` and globs).
#[derive(Debug, Clone)]
struct Import {
    path: Written,
    name: Option<String>,
    /// Written at the top of the file (not in a function or an inline module): a name
    /// other modules can reach through this one.
    top: bool,
}

/// What one file says.
#[derive(Debug, Default)]
struct Source {
    imports: Vec<Import>,
    /// Paths written in code (outside `use`).
    paths: Vec<Written>,
}

/// The `use` tree starting at `t[i]` (after `use`), each leaf with `prefix` before it;
/// returns the index after the tree.
fn use_tree(
    t: &[String],
    mut i: usize,
    mut prefix: Vec<String>,
    leaves: &mut Vec<(Vec<String>, Option<String>)>,
) -> usize {
    loop {
        let Some(tok) = t.get(i) else { return i };
        match tok.as_str() {
            "::" => i += 1,
            "{" => {
                i += 1;
                while t.get(i).is_some_and(|x| x != "}") {
                    i = use_tree(t, i, prefix.clone(), leaves);
                    if t.get(i).is_some_and(|x| x == ",") {
                        i += 1;
                    }
                }
                return i + 1;
            }
            "*" => {
                prefix.push("*".into());
                leaves.push((prefix, None));
                return i + 1;
            }
            _ => {
                prefix.push(tok.clone());
                i += 1;
                if t.get(i).is_some_and(|x| x == "::") {
                    i += 1;
                    continue;
                }
                let name = if t.get(i).is_some_and(|x| x == "as") {
                    i += 2;
                    Some(t[i - 1].clone()).filter(|a| a != "_")
                } else if tok == "self" {
                    prefix.iter().rev().nth(1).cloned()
                } else {
                    Some(tok.clone())
                };
                leaves.push((prefix, name));
                return i;
            }
        }
    }
}

fn is_ident(s: &str) -> bool {
    s.chars()
        .next()
        .is_some_and(|c| c == '_' || c.is_alphabetic())
}

/// Reads the imports and the paths of one file of module `module`.
fn read_source(src: &str, module: &[String]) -> Source {
    let t = without_test_items(tokens(src));
    let mut s = Source::default();
    // inline `mod x {` blocks open: (name, the brace depth inside them)
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0usize;
    let here = |inline: &[(String, usize)]| -> Vec<String> {
        module
            .iter()
            .cloned()
            .chain(inline.iter().map(|(m, _)| m.clone()))
            .collect()
    };
    let mut i = 0;
    while i < t.len() {
        match t[i].as_str() {
            "{" => {
                depth += 1;
                i += 1;
            }
            "}" => {
                if inline.last().is_some_and(|(_, d)| *d == depth) {
                    inline.pop();
                }
                depth = depth.saturating_sub(1);
                i += 1;
            }
            "mod" if t.get(i + 2).is_some_and(|x| x == "{") => {
                inline.push((t[i + 1].clone(), depth + 1));
                depth += 1;
                i += 3;
            }
            "use" => {
                let mut leaves = Vec::new();
                i = use_tree(&t, i + 1, Vec::new(), &mut leaves);
                let m = here(&inline);
                for (segments, name) in leaves {
                    s.imports.push(Import {
                        path: Written {
                            module: m.clone(),
                            segments,
                        },
                        name,
                        top: depth == 0,
                    });
                }
            }
            tok if is_ident(tok)
                && t.get(i + 1).is_some_and(|x| x == "::")
                && t.get(i + 2).is_some_and(|x| is_ident(x))
                && !(i > 0 && (t[i - 1] == "::" || t[i - 1] == ".")) =>
            {
                let mut segments = vec![tok.to_string()];
                let mut k = i + 1;
                while t.get(k).is_some_and(|x| x == "::")
                    && t.get(k + 1).is_some_and(|x| is_ident(x))
                {
                    segments.push(t[k + 1].clone());
                    k += 2;
                }
                s.paths.push(Written {
                    module: here(&inline),
                    segments,
                });
                i = k;
            }
            _ => i += 1,
        }
    }
    s
}

/// One crate: its module files and what each says.
struct Crate {
    name: String,
    /// Module path → file (relative to `src/`).
    files: BTreeMap<Vec<String>, String>,
    sources: BTreeMap<Vec<String>, Source>,
}

/// The `.rs` files under `dir`, recursively, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return out;
    };
    for e in entries {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(rust_files(&p));
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
    out.sort();
    out
}

impl Crate {
    fn read(dir: &Path) -> Option<Crate> {
        let src = dir.join("src");
        if !src.is_dir() {
            return None;
        }
        let root = if src.join("lib.rs").is_file() {
            "lib"
        } else {
            "main"
        };
        let mut files = BTreeMap::new();
        let mut sources = BTreeMap::new();
        for f in rust_files(&src) {
            let rel = f.strip_prefix(&src).unwrap();
            let mut module: Vec<String> = rel
                .with_extension("")
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if module.first().is_some_and(|m| m == "bin") {
                continue; // a crate of its own
            }
            if module.last().is_some_and(|m| m == "mod") {
                module.pop();
            }
            if module.len() == 1 && (module[0] == "lib" || module[0] == "main") {
                if module[0] != root {
                    continue; // a binary beside the library: a crate of its own
                }
                module.clear();
            }
            let text = std::fs::read_to_string(&f).unwrap();
            sources.insert(module.clone(), read_source(&text, &module));
            files.insert(module, rel.to_string_lossy().replace('\\', "/"));
        }
        Some(Crate {
            name: dir.file_name().unwrap().to_string_lossy().into_owned(),
            files,
            sources,
        })
    }

    /// The absolute module path of `w` (crate root = empty), or `None` for a path that
    /// leaves the crate (another crate, the standard library, a local name).
    fn absolute(&self, w: &Written) -> Option<Vec<String>> {
        self.resolve(w, true)
    }

    /// [`Crate::absolute`]; `aliases`: whether a path may start at a module imported by
    /// `use` (not when resolving such an import itself).
    fn resolve(&self, w: &Written, aliases: bool) -> Option<Vec<String>> {
        let seg = &w.segments;
        let mut out: Vec<String>;
        let mut rest = &seg[..];
        match seg.first()?.as_str() {
            "crate" => {
                out = Vec::new();
                rest = &seg[1..];
            }
            "self" => {
                out = w.module.clone();
                rest = &seg[1..];
            }
            "super" => {
                out = w.module.clone();
                while rest.first().is_some_and(|s| s == "super") {
                    out.pop()?;
                    rest = &rest[1..];
                }
            }
            first => {
                let mut child = w.module.clone();
                child.push(first.to_string());
                if self.files.contains_key(&child) {
                    out = w.module.clone();
                } else if let Some(target) = aliases.then(|| self.module_import(w, first)).flatten()
                {
                    out = target;
                    rest = &seg[1..];
                } else {
                    return None;
                }
            }
        }
        out.extend(rest.iter().filter(|s| *s != "self").cloned());
        Some(out)
    }

    /// The module a `use` of the file of `w` brings in under `name`, when it is one.
    fn module_import(&self, w: &Written, name: &str) -> Option<Vec<String>> {
        let file = self.file_of(&w.module);
        self.sources[&file]
            .imports
            .iter()
            .filter(|im| im.name.as_deref() == Some(name))
            .find_map(|im| {
                let abs = self.resolve(&im.path, false)?;
                self.files.contains_key(&abs).then_some(abs)
            })
    }

    /// The module file holding module path `m`: its deepest prefix that is a file.
    fn file_of(&self, m: &[String]) -> Vec<String> {
        (0..=m.len())
            .rev()
            .map(|k| m[..k].to_vec())
            .find(|p| self.files.contains_key(p))
            .unwrap_or_default()
    }

    /// The file that defines what `w` names: the deepest module file along the path,
    /// then through the imports that only pass its next name on. `None` when the path
    /// leaves the crate, or ends at a name a module imports from another crate.
    fn target(&self, w: &Written) -> Option<Vec<String>> {
        let mut abs = self.absolute(w)?;
        for _ in 0..16 {
            let file = self.file_of(&abs);
            let Some(name) = abs.get(file.len()) else {
                return Some(file);
            };
            let Some(import) = self.sources[&file]
                .imports
                .iter()
                .find(|im| im.top && im.name.as_deref() == Some(name.as_str()))
            else {
                return Some(file); // defined there
            };
            let mut next = self.absolute(&import.path)?;
            next.extend(abs[file.len() + 1..].iter().cloned());
            abs = next;
        }
        Some(self.file_of(&abs))
    }

    /// Edges between files (file → file → the paths written), self-edges left out.
    fn edges(&self) -> BTreeMap<Vec<String>, BTreeMap<Vec<String>, BTreeSet<String>>> {
        let mut out: BTreeMap<_, BTreeMap<_, BTreeSet<String>>> = BTreeMap::new();
        for (m, s) in &self.sources {
            let written = s.imports.iter().map(|im| &im.path).chain(&s.paths);
            for w in written {
                if w.segments.last().is_some_and(|x| x == "*") && w.segments.len() == 1 {
                    continue;
                }
                let mut w = w.clone();
                if w.segments.last().is_some_and(|x| x == "*") {
                    w.segments.pop(); // a glob: the module it opens
                }
                if let Some(to) = self.target(&w)
                    && to != *m
                {
                    out.entry(m.clone())
                        .or_default()
                        .entry(to)
                        .or_default()
                        .insert(w.text());
                }
            }
        }
        out
    }

    /// Every cycle: each strongly connected set of two or more files, with its edges.
    fn cycles(&self) -> Vec<String> {
        let edges = self.edges();
        let nodes: Vec<&Vec<String>> = self.files.keys().collect();
        let index: BTreeMap<&Vec<String>, usize> =
            nodes.iter().enumerate().map(|(i, n)| (*n, i)).collect();
        let adj: Vec<Vec<usize>> = nodes
            .iter()
            .map(|n| {
                edges
                    .get(*n)
                    .map(|e| e.keys().filter_map(|t| index.get(t).copied()).collect())
                    .unwrap_or_default()
            })
            .collect();
        let file = |m: &Vec<String>| self.files[m].clone();
        let mut out = Vec::new();
        for scc in strongly_connected(&adj) {
            if scc.len() < 2 {
                continue;
            }
            let members: BTreeSet<usize> = scc.iter().copied().collect();
            let names: Vec<String> = members.iter().map(|&i| file(nodes[i])).collect();
            let mut text = format!("crate `{}`: {}", self.name, names.join(", "));
            for cycle in shortest_cycles(&adj, &members) {
                let round: Vec<String> = cycle
                    .iter()
                    .chain(cycle.first())
                    .map(|&i| file(nodes[i]))
                    .collect();
                text.push_str(&format!("\n    cycle: {}", round.join(" -> ")));
            }
            for &i in &members {
                for (to, paths) in &edges[nodes[i]] {
                    if index.get(to).is_some_and(|j| members.contains(j)) {
                        let paths: Vec<&str> = paths.iter().map(String::as_str).collect();
                        text.push_str(&format!(
                            "\n    {} -> {}: {}",
                            file(nodes[i]),
                            file(to),
                            paths.join(", ")
                        ));
                    }
                }
            }
            out.push(text);
        }
        out.sort();
        out
    }
}

/// The shortest cycle through each edge inside `members` (a strongly connected set),
/// each once, starting at its smallest node; shortest first.
fn shortest_cycles(adj: &[Vec<usize>], members: &BTreeSet<usize>) -> Vec<Vec<usize>> {
    let mut found = BTreeSet::new();
    for &u in members {
        for &v in adj[u].iter().filter(|v| members.contains(v)) {
            // breadth first from v back to u, inside the set
            let mut before: BTreeMap<usize, usize> = BTreeMap::new();
            let mut queue = std::collections::VecDeque::from([v]);
            let mut seen = BTreeSet::from([v]);
            while let Some(x) = queue.pop_front() {
                if x == u {
                    break;
                }
                for &y in adj[x].iter().filter(|y| members.contains(y)) {
                    if seen.insert(y) {
                        before.insert(y, x);
                        queue.push_back(y);
                    }
                }
            }
            let mut path = vec![u];
            let mut x = u;
            while x != v {
                x = before[&x];
                path.push(x);
            }
            // path runs u, …, v backwards: the cycle is u -> v -> … -> u
            path.reverse();
            path.rotate_right(1);
            let start = (0..path.len()).min_by_key(|&k| path[k]).unwrap_or(0);
            path.rotate_left(start);
            found.insert((path.len(), path));
        }
    }
    found.into_iter().map(|(_, c)| c).collect()
}

/// Tarjan's strongly connected components of a graph given by its adjacency lists.
fn strongly_connected(adj: &[Vec<usize>]) -> Vec<Vec<usize>> {
    struct State<'a> {
        adj: &'a [Vec<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(s: &mut State, v: usize) {
        s.index[v] = Some(s.next);
        s.low[v] = s.next;
        s.next += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        for k in 0..s.adj[v].len() {
            let w = s.adj[v][k];
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(iw) if s.on_stack[w] => s.low[v] = s.low[v].min(iw),
                Some(_) => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut scc = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack[w] = false;
                scc.push(w);
                if w == v {
                    break;
                }
            }
            s.out.push(scc);
        }
    }
    let n = adj.len();
    let mut s = State {
        adj,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if s.index[v].is_none() {
            visit(&mut s, v);
        }
    }
    s.out
}

// ---------------------------------------------------------------------------------------
// The checks
// ---------------------------------------------------------------------------------------

/// The cycles of every crate under `crates` (a `crates/` folder).
fn cycles_under(crates: &Path) -> Vec<String> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(crates)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    dirs.iter()
        .filter_map(|d| Crate::read(d))
        .flat_map(|c| c.cycles())
        .collect()
}

/// The Rust files under `crates/*/{src,tests,benches}` over [`MAX_LINES`] lines.
fn long_files_under(crates: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(crates)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    for d in dirs {
        for part in ["src", "tests", "benches"] {
            for f in rust_files(&d.join(part)) {
                let lines = std::fs::read_to_string(&f).unwrap().lines().count();
                if lines > MAX_LINES {
                    let rel = f.strip_prefix(crates).unwrap_or(&f);
                    out.push(format!("crates/{}: {lines} lines", rel.display()));
                }
            }
        }
    }
    out
}

#[test]
fn no_import_cycle_between_modules_and_no_file_over_1000_lines() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let cycles = cycles_under(&crates);
    let long = long_files_under(&crates);
    let mut report = String::new();
    if !cycles.is_empty() {
        report.push_str(&format!(
            "{} import cycle(s) between the modules of one crate (each file of a cycle \
             reaches every other; the paths that tie them):\n  {}\n",
            cycles.len(),
            cycles.join("\n  ")
        ));
    }
    if !long.is_empty() {
        report.push_str(&format!(
            "{} Rust file(s) over {MAX_LINES} lines (split them by role):\n  {}\n",
            long.len(),
            long.join("\n  ")
        ));
    }
    assert!(report.is_empty(), "{report}");
}

/// The check itself, on a crate written to a temporary folder: a cycle of two files is
/// found (with the paths that make it), a facade that re-exports a child's name makes
/// none, and comments, strings and `#[cfg(test)]` modules add no edge.
#[test]
fn finds_a_two_file_cycle_and_not_a_facade_re_export() {
    let dir = std::env::temp_dir().join(format!("slipload-module-graph-{}", std::process::id()));
    let src = dir.join("fake/src");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(src.join("facade")).unwrap();
    let files = [
        (
            "lib.rs",
            "pub mod a;\npub mod b;\npub mod c;\npub mod facade;\n",
        ),
        // a and b: a real cycle, one side through a grouped `use`, the other in code
        ("a.rs", "use crate::{b::{Bee, other}};\npub struct Ay;\n"),
        (
            "b.rs",
            "pub struct Bee;\npub fn other() -> crate::a::Ay { crate::a::Ay }\n",
        ),
        // facade/mod.rs passes on the names of facade/deep.rs and facade/shallow.rs, and
        // deep.rs names shallow's through the facade: deep -> shallow, not a cycle
        // deep -> facade -> deep
        (
            "facade/mod.rs",
            "mod deep;\nmod shallow;\npub use self::deep::Deep;\npub use shallow::Shallow;\n",
        ),
        (
            "facade/deep.rs",
            "pub struct Deep(pub crate::facade::Shallow);\n",
        ),
        ("facade/shallow.rs", "pub struct Shallow;\n"),
        (
            "c.rs",
            concat!(
                "//! Not `crate::b::Bee` (a doc comment).\n",
                "pub struct See;\n",
                "/* crate::a::Ay */\n",
                "pub const S: &str = \"crate::a::Ay\";\n",
                "pub const R: &str = r#\"super::b::Bee\"#;\n",
                "pub fn f(_: crate::facade::Shallow) -> char { '\"' }\n",
                "#[cfg(test)]\nmod tests {\n    use crate::a::Ay;\n}\n",
            ),
        ),
    ];
    for (f, text) in files {
        std::fs::write(src.join(f), text).unwrap();
    }
    let c = Crate::read(&dir.join("fake")).unwrap();
    let edges = c.edges();
    let cycles = c.cycles();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(
        cycles,
        vec![
            "crate `fake`: a.rs, b.rs\n    cycle: a.rs -> b.rs -> a.rs\n    \
             a.rs -> b.rs: crate::b::Bee, crate::b::other\n    b.rs -> a.rs: crate::a::Ay"
                .to_string()
        ],
        "{edges:#?}"
    );
    let key = |s: &str| -> Vec<String> {
        s.split('/')
            .filter(|x| !x.is_empty())
            .map(String::from)
            .collect()
    };
    // c and deep reach the file that defines what they name through the facade; the
    // literals, comments and test module of c add nothing
    for from in ["c", "facade/deep"] {
        let to: Vec<&Vec<String>> = edges[&key(from)].keys().collect();
        assert_eq!(to, vec![&key("facade/shallow")], "{from}: {edges:#?}");
    }
    let from_facade: Vec<&Vec<String>> = edges[&key("facade")].keys().collect();
    assert_eq!(
        from_facade,
        vec![&key("facade/deep"), &key("facade/shallow")],
        "{edges:#?}"
    );
}
