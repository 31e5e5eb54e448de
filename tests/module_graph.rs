//! The library's module graph, read from the source: no import loops between files, and
//! the GPU-free layers never reach into wgpu, the renderer or the UI (docs/architecture.md,
//! "Dependency direction"). Imports are read as text: `crate::…`, `super::…` and
//! `self::…` paths, `use` groups expanded, each resolved to the file that defines the
//! name (through a parent's `pub use` re-exports). Test modules inside a file
//! (`#[cfg(test)] mod …`) are left out: their `super` is the file itself.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Top-level modules that must not touch the GPU layer (`render`), the editor (`ui`), or
/// wgpu, egui and eframe themselves.
const GPU_FREE: &[&str] = &[
    "sh",
    "terrain",
    "scene",
    "blockers",
    "bake",
    "paint",
    "penumbra",
    "shading",
    "project",
    "reference",
    "random",
    "panic_guard",
    "session",
];

/// Longest a hand-written source file may grow (generated tables are exempt).
const MAX_LINES: usize = 600;
const GENERATED: &[&str] = &["src/sh/ol_tables.rs"];
/// Files still over [`MAX_LINES`], each to be split (issue: one renderer, clear rooms).
/// The list may only shrink: a file on it that fits fails the test, so it is removed.
const AWAITING_SPLIT: &[&str] = &[];

struct Crate {
    root: PathBuf,
    /// Module path (segments below the crate root) → its file.
    files: BTreeMap<Vec<String>, PathBuf>,
}

impl Crate {
    fn read(root: &Path) -> Crate {
        let mut files = BTreeMap::new();
        collect(root, &root.join("src"), &mut files);
        Crate {
            root: root.to_path_buf(),
            files,
        }
    }

    fn source(&self, module: &[String]) -> String {
        let text = std::fs::read_to_string(&self.files[module]).expect("readable source");
        without_test_modules(&without_comments(&text))
    }

    fn name(&self, module: &[String]) -> String {
        self.files[module]
            .strip_prefix(&self.root)
            .unwrap_or(&self.files[module])
            .display()
            .to_string()
    }

    /// The file a path (absolute segments from the crate root) names: the deepest module
    /// it walks through, then, if the next segment is an item a module re-exports from
    /// a child, that child (recursively).
    fn resolve(&self, path: &[String]) -> Vec<String> {
        let mut module: Vec<String> = Vec::new();
        let mut rest = path;
        while let Some((first, tail)) = rest.split_first() {
            let mut next = module.clone();
            next.push(first.clone());
            if !self.files.contains_key(&next) {
                break;
            }
            module = next;
            rest = tail;
        }
        if let Some(item) = rest.first()
            && let Some(target) = self.reexport_source(&module, item)
        {
            return self.resolve(&target);
        }
        module
    }

    /// Where `module` takes the item `name` it re-exports with `pub use`, as an absolute
    /// path to resolve further.
    fn reexport_source(&self, module: &[String], name: &str) -> Option<Vec<String>> {
        let source = self.source(module);
        for statement in use_statements(&source).into_iter().filter(|s| s.public) {
            for path in statement.paths {
                if path.last().map(String::as_str) == Some(name) {
                    let Some(absolute) = absolute(&self.files, module, &path) else {
                        continue;
                    };
                    if absolute.starts_with(module) && absolute.len() > module.len() {
                        return Some(absolute);
                    }
                }
            }
        }
        None
    }

    /// Whether `module`'s file is `mod.rs` or `lib.rs` (its `super` is its parent's
    /// parent) rather than `name.rs`.
    fn is_directory_module(&self, module: &[String]) -> bool {
        let file = &self.files[module];
        matches!(
            file.file_name().and_then(|n| n.to_str()),
            Some("mod.rs") | Some("lib.rs")
        )
    }

    /// Edges file → file of every reference outside the file's own re-exports.
    fn edges(&self) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
        let mut edges: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
        for module in self.files.keys() {
            let source = self.source(module);
            let directory = self.is_directory_module(module);
            let mut paths: Vec<Vec<String>> = Vec::new();
            for statement in use_statements(&source) {
                // A parent re-exporting its children is not a dependency of its code.
                if statement.public && directory {
                    continue;
                }
                paths.extend(statement.paths);
            }
            paths.extend(inline_paths(&source));
            let targets = edges.entry(module.clone()).or_default();
            for path in paths {
                let Some(absolute) = absolute(&self.files, module, &path) else {
                    continue;
                };
                let target = self.resolve(&absolute);
                if &target != module && !target.is_empty() {
                    targets.insert(target);
                }
            }
        }
        edges
    }
}

fn collect(root: &Path, dir: &Path, files: &mut BTreeMap<Vec<String>, PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("readable source folder")
        .map(|e| e.expect("folder entry").path())
        .collect();
    entries.sort();
    for path in entries {
        let relative = path.strip_prefix(root.join("src")).expect("under src").to_path_buf();
        // The binaries (main.rs with its cli/, and bin/) are crates of their own over the
        // library.
        if relative == Path::new("main.rs") || relative.starts_with("bin") || relative.starts_with("cli") {
            continue;
        }
        if path.is_dir() {
            collect(root, &path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let mut segments: Vec<String> = relative
                .with_extension("")
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if matches!(segments.last().map(String::as_str), Some("mod") | Some("lib")) {
                segments.pop();
            }
            files.insert(segments, path);
        }
    }
}

/// `path` (as written: from crate, super or self, or from a child module of `module`)
/// made absolute from `module` (a `mod.rs` is the folder's module, so its `super` is the
/// folder's parent, as a `name.rs`'s `super` is its folder); None for other crates.
fn absolute(files: &BTreeMap<Vec<String>, PathBuf>, module: &[String], path: &[String]) -> Option<Vec<String>> {
    let (first, rest) = path.split_first()?;
    let mut base: Vec<String> = match first.as_str() {
        "crate" => Vec::new(),
        "self" => module.to_vec(),
        "super" => {
            let mut base = module.to_vec();
            base.pop()?;
            base
        }
        child => {
            let mut base = module.to_vec();
            base.push(child.to_string());
            if !files.contains_key(&base) {
                return None;
            }
            base
        }
    };
    let mut rest = rest;
    while rest.first().map(String::as_str) == Some("super") {
        base.pop()?;
        rest = &rest[1..];
    }
    base.extend(rest.iter().filter(|s| s.as_str() != "self").cloned());
    Some(base)
}

struct UseStatement {
    public: bool,
    paths: Vec<Vec<String>>,
}

/// Every `use …;` of `source`, its groups expanded into paths (a trailing `*` or `self`
/// dropped, so the path names the module).
fn use_statements(source: &str) -> Vec<UseStatement> {
    let mut statements = Vec::new();
    let mut rest = source;
    while let Some(at) = find_keyword(rest, "use ") {
        let before = rest[..at].trim_end();
        let public = before.ends_with("pub") || before.ends_with(')') && before.contains("pub(");
        let Some(end) = rest[at..].find(';') else { break };
        let body = &rest[at + 4..at + end];
        let mut paths = Vec::new();
        expand(
            &body.split_whitespace().collect::<Vec<_>>().join(" "),
            &mut Vec::new(),
            &mut paths,
        );
        statements.push(UseStatement { public, paths });
        rest = &rest[at + end + 1..];
    }
    statements
}

/// The position of `keyword` at the start of a statement (after a newline, `{`, `;`, or
/// `pub`/`pub(crate)`).
fn find_keyword(source: &str, keyword: &str) -> Option<usize> {
    let mut from = 0;
    while let Some(offset) = source[from..].find(keyword) {
        let at = from + offset;
        let before = source[..at].trim_end();
        let starts = before.is_empty()
            || before.ends_with(['\n', '{', ';', '}'])
            || before.ends_with("pub")
            || before.ends_with(')')
            || source[..at].ends_with('\n')
            || source[..at].ends_with("    ");
        if starts && (at == 0 || !source.as_bytes()[at - 1].is_ascii_alphanumeric()) {
            return Some(at);
        }
        from = at + keyword.len();
    }
    None
}

fn expand(tree: &str, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    let tree = tree.trim();
    if let Some(open) = tree.find('{') {
        let head: Vec<String> = segments(tree[..open].trim_end_matches("::"));
        let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
        let depth = prefix.len();
        prefix.extend(head);
        for part in split_top_level(inner) {
            expand(part, prefix, out);
        }
        prefix.truncate(depth);
    } else {
        let name = tree.split(" as ").next().unwrap_or(tree);
        let mut path = prefix.clone();
        path.extend(segments(name));
        while matches!(path.last().map(String::as_str), Some("*") | Some("self")) {
            path.pop();
        }
        if !path.is_empty() {
            out.push(path);
        }
    }
}

fn split_top_level(inner: &str) -> Vec<&str> {
    let (mut parts, mut depth, mut start) = (Vec::new(), 0, 0);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts.into_iter().filter(|p| !p.trim().is_empty()).collect()
}

fn segments(path: &str) -> Vec<String> {
    path.split("::")
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(str::to_string)
        .collect()
}

/// `crate::a::b`, `super::a` and `self::a` paths written in code outside `use`.
fn inline_paths(source: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let bytes = source.as_bytes();
    for start in ["crate::", "super::", "self::"] {
        let mut from = 0;
        while let Some(offset) = source[from..].find(start) {
            let at = from + offset;
            from = at + start.len();
            if at > 0 && (bytes[at - 1].is_ascii_alphanumeric() || bytes[at - 1] == b'_' || bytes[at - 1] == b':') {
                continue;
            }
            let end = source[at..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == ':'))
                .map_or(source.len(), |e| at + e);
            let path = segments(source[at..end].trim_end_matches(':'));
            if path.len() > 1 {
                paths.push(path);
            }
        }
    }
    paths
}

/// `source` without `//` comments (doc comments included) and string literals' contents.
fn without_comments(source: &str) -> String {
    let mut out = String::with_capacity(source.len());
    for line in source.lines() {
        let mut in_string = false;
        let mut kept = String::new();
        let mut chars = line.chars().peekable();
        while let Some(c) = chars.next() {
            if c == '"' {
                in_string = !in_string;
                kept.push(c);
                continue;
            }
            if in_string {
                if c == '\\' {
                    chars.next();
                }
                continue;
            }
            if c == '/' && chars.peek() == Some(&'/') {
                break;
            }
            kept.push(c);
        }
        out.push_str(&kept);
        out.push('\n');
    }
    out
}

/// `source` up to its first `#[cfg(test)]` module (unit tests sit at the end of a file).
fn without_test_modules(source: &str) -> String {
    let mut from = 0;
    while let Some(offset) = source[from..].find("#[cfg(test)]") {
        let at = from + offset;
        let after = source[at + "#[cfg(test)]".len()..].trim_start();
        if after.starts_with("mod ") || after.starts_with("pub mod ") || after.starts_with("pub(crate) mod ") {
            // `mod tests;` in its own file is a module like any other; an inline one ends
            // the file's code.
            let declaration_end = after.find(['{', ';']).unwrap_or(after.len());
            if after[declaration_end..].starts_with('{') {
                return source[..at].to_string();
            }
        }
        from = at + 1;
    }
    source.to_string()
}

/// Strongly connected components with more than one file (Tarjan).
fn cycles(edges: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<Vec<Vec<String>>> {
    struct State<'a> {
        edges: &'a BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        index: BTreeMap<&'a Vec<String>, usize>,
        low: BTreeMap<&'a Vec<String>, usize>,
        stack: Vec<&'a Vec<String>>,
        on_stack: BTreeSet<&'a Vec<String>>,
        found: Vec<Vec<Vec<String>>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a Vec<String>) {
        let i = s.index.len();
        s.index.insert(v, i);
        s.low.insert(v, i);
        s.stack.push(v);
        s.on_stack.insert(v);
        if let Some(targets) = s.edges.get(v) {
            for w in targets {
                let Some((w, _)) = s.edges.get_key_value(w) else {
                    continue;
                };
                if !s.index.contains_key(w) {
                    visit(s, w);
                    let low = s.low[v].min(s.low[w]);
                    s.low.insert(v, low);
                } else if s.on_stack.contains(w) {
                    let low = s.low[v].min(s.index[w]);
                    s.low.insert(v, low);
                }
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(w);
                component.push(w.clone());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                s.found.push(component);
            }
        }
    }
    let mut state = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !state.index.contains_key(v) {
            visit(&mut state, v);
        }
    }
    state.found
}

fn repository() -> Crate {
    Crate::read(Path::new(env!("CARGO_MANIFEST_DIR")))
}

#[test]
fn no_file_imports_itself_back_through_others() {
    let krate = repository();
    let edges = krate.edges();
    let loops: Vec<String> = cycles(&edges)
        .iter()
        .map(|c| c.iter().map(|m| krate.name(m)).collect::<Vec<_>>().join(" ↔ "))
        .collect();
    assert!(loops.is_empty(), "import loops:\n{}", loops.join("\n"));
}

#[test]
fn gpu_free_layers_never_reach_the_gpu_or_the_editor() {
    let krate = repository();
    let edges = krate.edges();
    let mut violations = Vec::new();
    for (module, targets) in &edges {
        if !module.first().is_some_and(|top| GPU_FREE.contains(&top.as_str())) {
            continue;
        }
        for target in targets {
            if matches!(target.first().map(String::as_str), Some("render") | Some("ui")) {
                violations.push(format!("{} imports {}", krate.name(module), krate.name(target)));
            }
        }
        let source = krate.source(module);
        for external in ["wgpu::", "egui::", "eframe::", "egui_wgpu::"] {
            if inline_mentions(&source, external) {
                violations.push(format!("{} uses {external}", krate.name(module)));
            }
        }
    }
    assert!(violations.is_empty(), "{}", violations.join("\n"));
}

fn inline_mentions(source: &str, prefix: &str) -> bool {
    source.match_indices(prefix).any(|(at, _)| {
        at == 0 || {
            let before = source.as_bytes()[at - 1];
            !(before.is_ascii_alphanumeric() || before == b'_' || before == b':')
        }
    })
}

#[test]
fn source_files_stay_small() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    every_source_file(&root.join("src"), &mut files);
    let mut over = Vec::new();
    let mut shrunk = Vec::new();
    for path in &files {
        let name = path
            .strip_prefix(root)
            .unwrap_or(path)
            .to_string_lossy()
            .replace('\\', "/");
        if GENERATED.contains(&name.as_str()) {
            continue;
        }
        let lines = std::fs::read_to_string(path).expect("readable").lines().count();
        let listed = AWAITING_SPLIT.contains(&name.as_str());
        if lines > MAX_LINES && !listed {
            over.push(format!("{name}: {lines} lines"));
        }
        if lines <= MAX_LINES && listed {
            shrunk.push(name);
        }
    }
    assert!(over.is_empty(), "files over {MAX_LINES} lines:\n{}", over.join("\n"));
    assert!(shrunk.is_empty(), "split, so take them off AWAITING_SPLIT: {shrunk:?}");
}

fn every_source_file(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable source folder") {
        let path = entry.expect("folder entry").path();
        if path.is_dir() {
            every_source_file(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The reader itself: a known loop is found, re-exports are followed, groups expand.
#[test]
fn the_reader_finds_a_planted_loop_and_follows_reexports() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let src = dir.path().join("src");
    std::fs::create_dir_all(src.join("a")).expect("folders");
    std::fs::write(src.join("lib.rs"), "pub mod a;\npub mod b;\n").expect("write");
    std::fs::write(
        src.join("a/mod.rs"),
        "mod x;\nmod y;\npub use x::Thing;\npub use y::Other;\n",
    )
    .expect("write");
    // x takes Other through a's re-export: an edge x → y, not x → a.
    std::fs::write(src.join("a/x.rs"), "use super::Other;\npub struct Thing;\n").expect("write");
    std::fs::write(
        src.join("a/y.rs"),
        "use crate::{a::Thing, b::{self, Both}};\n// crate::b::Nothing in a comment\npub struct Other;\n",
    )
    .expect("write");
    std::fs::write(
        src.join("b.rs"),
        "pub struct Both;\n#[cfg(test)]\nmod tests { use super::*; }\n",
    )
    .expect("write");
    let krate = Crate::read(dir.path());
    let edges = krate.edges();
    let x = vec!["a".to_string(), "x".to_string()];
    let y = vec!["a".to_string(), "y".to_string()];
    assert_eq!(edges[&x], BTreeSet::from([y.clone()]));
    assert_eq!(edges[&y], BTreeSet::from([x.clone(), vec!["b".to_string()]]));
    let found = cycles(&edges);
    assert_eq!(found.len(), 1, "x ↔ y");
    assert_eq!(
        found[0].iter().cloned().collect::<BTreeSet<_>>(),
        BTreeSet::from([x, y])
    );
}
