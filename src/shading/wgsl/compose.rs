//! WGSL has no `#include`; this is ours. A module says what it uses in comment lines
//!
//! ```text
//! // #import common scene
//! ```
//!
//! (one or more names per line, anywhere in the file; a plain comment to WGSL, so every
//! file stays valid WGSL on its own). [`compose`] writes the modules a shader needs once
//! each, every module after the ones it imports (a depth-first walk in import order), and
//! refuses an unknown name or a circle of imports, naming them. Module-scope WGSL may use
//! a declaration before it appears, so the order only keeps the output readable; the
//! imports say which code depends on which, and `tests/wgsl_validate.rs` checks that every
//! module composes and validates.

use std::collections::HashMap;
use std::fmt;

/// What marks an import line.
const IMPORT_MARK: &str = "// #import ";

/// A named WGSL source: a file under `shaders/` or code generated for a frame's settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WgslModule<'a> {
    pub name: &'a str,
    pub source: &'a str,
}

/// Why a shader could not be composed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ComposeError {
    /// `module` imports `name`, which no module is called.
    Unknown { name: String, module: String },
    /// The modules import each other in a circle (first and last the same).
    Circle(Vec<String>),
}

impl fmt::Display for ComposeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ComposeError::Unknown { name, module } => {
                write!(f, "WGSL module `{module}` imports `{name}`, which does not exist")
            }
            ComposeError::Circle(chain) => {
                write!(f, "WGSL modules import each other in a circle: {}", chain.join(" → "))
            }
        }
    }
}

impl std::error::Error for ComposeError {}

/// The names a source imports, in the order written.
pub fn imports_of(source: &str) -> Vec<&str> {
    source
        .lines()
        .filter_map(|line| line.trim_start().strip_prefix(IMPORT_MARK))
        .flat_map(str::split_whitespace)
        .collect()
}

/// The sources of `roots` and of everything they import, each once, each after its
/// imports, as one WGSL source. `modules` are the modules there are to import.
pub fn compose(roots: &[&str], modules: &[WgslModule<'_>]) -> Result<String, ComposeError> {
    let by_name: HashMap<&str, &str> = modules.iter().map(|m| (m.name, m.source)).collect();
    let mut walk = Walk {
        by_name,
        state: HashMap::new(),
        path: Vec::new(),
        out: String::new(),
    };
    for root in roots {
        walk.visit(root, "(the shader)")?;
    }
    Ok(walk.out)
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Visit {
    /// On the current path of imports.
    Open,
    /// Written out.
    Done,
}

struct Walk<'a> {
    by_name: HashMap<&'a str, &'a str>,
    state: HashMap<&'a str, Visit>,
    path: Vec<&'a str>,
    out: String,
}

impl<'a> Walk<'a> {
    fn visit(&mut self, name: &str, importer: &str) -> Result<(), ComposeError> {
        let Some((&name, &source)) = self.by_name.get_key_value(name) else {
            return Err(ComposeError::Unknown {
                name: name.to_string(),
                module: importer.to_string(),
            });
        };
        match self.state.get(name) {
            Some(Visit::Done) => return Ok(()),
            Some(Visit::Open) => {
                let from = self.path.iter().position(|m| *m == name).unwrap_or(0);
                let mut chain: Vec<String> = self.path[from..].iter().map(|m| m.to_string()).collect();
                chain.push(name.to_string());
                return Err(ComposeError::Circle(chain));
            }
            None => {}
        }
        self.state.insert(name, Visit::Open);
        self.path.push(name);
        for import in imports_of(source) {
            self.visit(import, name)?;
        }
        self.path.pop();
        self.state.insert(name, Visit::Done);
        self.out.push_str(&format!("// ---- module {name} ----\n"));
        self.out.push_str(source);
        if !source.ends_with('\n') {
            self.out.push('\n');
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn module<'a>(name: &'a str, source: &'a str) -> WgslModule<'a> {
        WgslModule { name, source }
    }

    fn order_of(out: &str) -> Vec<&str> {
        out.lines()
            .filter_map(|l| l.strip_prefix("// ---- module "))
            .map(|l| l.trim_end_matches(" ----"))
            .collect()
    }

    #[test]
    fn import_lines_are_read_anywhere_with_several_names_each() {
        let source = "// #import a b\nfn f() {}\n  // #import c\n// import d\n";
        assert_eq!(imports_of(source), vec!["a", "b", "c"]);
    }

    #[test]
    fn each_module_comes_once_and_after_its_imports() {
        // A diamond: top imports left and right, both import base.
        let modules = [
            module("base", "const B = 1;\n"),
            module("left", "// #import base\nconst L = B;\n"),
            module("right", "// #import base\nconst R = B;\n"),
            module("top", "// #import left right\nconst T = L + R;\n"),
        ];
        let out = compose(&["top"], &modules).unwrap();
        assert_eq!(order_of(&out), vec!["base", "left", "right", "top"]);
        assert_eq!(out.matches("const B = 1;").count(), 1);
        // A second root already written adds nothing.
        let twice = compose(&["top", "left"], &modules).unwrap();
        assert_eq!(twice, out);
    }

    #[test]
    fn an_unknown_import_names_the_module_and_the_name() {
        let modules = [module("a", "// #import missing\n")];
        let err = compose(&["a"], &modules).unwrap_err();
        assert_eq!(
            err,
            ComposeError::Unknown {
                name: "missing".into(),
                module: "a".into()
            }
        );
        assert!(err.to_string().contains("`a` imports `missing`"));
        assert!(matches!(
            compose(&["nothing"], &modules),
            Err(ComposeError::Unknown { .. })
        ));
    }

    #[test]
    fn a_circle_of_imports_is_refused_with_its_chain() {
        let modules = [
            module("a", "// #import b\n"),
            module("b", "// #import c\n"),
            module("c", "// #import b\n"),
        ];
        let err = compose(&["a"], &modules).unwrap_err();
        assert_eq!(err, ComposeError::Circle(vec!["b".into(), "c".into(), "b".into()]));
        let itself = [module("s", "// #import s\n")];
        assert_eq!(
            compose(&["s"], &itself).unwrap_err(),
            ComposeError::Circle(vec!["s".into(), "s".into()])
        );
    }
}
