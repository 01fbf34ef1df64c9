//! The dependency graph of `src/` is one-way: no import cycle between modules at any depth, and no
//! top-level import that points up the layer table of `docs/architecture.md`.
//!
//! Edges come from the `crate::…` and `super::…` paths of each file and a module file's paths into
//! its own child modules (outside its `#[cfg(test)]` part and comments). An edge between two
//! modules is lifted to the children of their lowest common ancestor
//! (`analysis::report → analysis::stream` is an edge between siblings). A module file is itself a
//! sibling of its children, [`OWN`]: a child using an item *defined* in its parent's file (or all
//! of it, `super::*`) depends on that file, and the file using the child depends on the child, so
//! an orchestrator and a stage that call each other are a cycle. An item the parent only
//! re-exports (`pub use outcome::Ranked`) is followed to the module that defines it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

type Module = Vec<String>;

fn modules() -> BTreeMap<Module, String> {
    fn walk(dir: &Path, out: &mut BTreeMap<Module, String>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "rs") {
                let rel = p.strip_prefix("src").unwrap().with_extension("");
                let mut parts: Module = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                if parts.last().is_some_and(|l| l == "mod") {
                    parts.pop();
                }
                // A `tests.rs` file is a `#[cfg(test)] mod tests;` split out of its parent: test
                // code, like the `#[cfg(test)]` part of a file.
                if parts == ["lib"]
                    || parts == ["main"]
                    || parts.last().is_some_and(|l| l == "tests")
                {
                    continue;
                }
                out.insert(parts, std::fs::read_to_string(&p).unwrap());
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(Path::new("src"), &mut out);
    out
}

/// The code of a file without its test module and comments.
fn code(text: &str) -> String {
    let body = text.split("#[cfg(test)]").next().unwrap_or("");
    body.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// `crate::a::b::c` or `super::x::y` paths in `code`, as (root, segments).
fn paths(code: &str) -> Vec<(String, Vec<String>)> {
    let mut out = Vec::new();
    for root in ["crate", "super"] {
        let mut rest = code;
        while let Some(i) = rest.find(root) {
            let before = rest[..i].chars().last();
            rest = &rest[i + root.len()..];
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                continue;
            }
            let mut segs = Vec::new();
            let mut tail = rest;
            while let Some(t) = tail.strip_prefix("::") {
                let name: String = t
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if name.is_empty() {
                    break;
                }
                tail = &t[name.len()..];
                segs.push(name);
            }
            // A group `…::{a::b, c}`: one path per item.
            if let Some(group) = tail.strip_prefix("::{") {
                let mut depth = 1;
                let end = group
                    .char_indices()
                    .find(|&(_, c)| {
                        depth += match c {
                            '{' => 1,
                            '}' => -1,
                            _ => 0,
                        };
                        depth == 0
                    })
                    .map_or(group.len(), |(i, _)| i);
                for item in group[..end].split([',', '{', '}']) {
                    let item: Vec<String> = item
                        .trim()
                        .split("::")
                        .map(|s| s.trim().to_string())
                        .filter(|s| {
                            !s.is_empty() && s.chars().all(|c| c.is_alphanumeric() || c == '_')
                        })
                        .collect();
                    if !item.is_empty() {
                        out.push((root.to_string(), segs.iter().cloned().chain(item).collect()));
                    }
                }
            } else if !segs.is_empty() {
                out.push((root.to_string(), segs));
            } else if root == "super" && tail.starts_with("::*") {
                out.push((root.to_string(), vec!["*".to_string()]));
            }
        }
    }
    out
}

/// The name of a module file's own node among its children's.
const OWN: &str = "(mod)";

/// Modules whose own file is an orchestrator of its child files (stages called in order): there
/// the file counts as a sibling of its children, so a child calling back into it is a cycle.
/// Elsewhere a parent file defining the types its children implement is containment.
const ORCHESTRATORS: [&[&str]; 1] = [&["diagnosis"]];

fn orchestrator(m: &[String]) -> bool {
    ORCHESTRATORS
        .iter()
        .any(|o| o.len() == m.len() && o.iter().zip(m).all(|(a, b)| a == b))
}

/// The child modules a module file declares (`mod x;`, `pub mod x;`).
fn children(code: &str) -> Vec<String> {
    code.split(';')
        .filter_map(|stmt| {
            let words: Vec<&str> = stmt.split_whitespace().collect();
            let i = words.iter().position(|w| *w == "mod")?;
            (i + 2 == words.len()).then(|| words[i + 1].to_string())
        })
        .collect()
}

/// Paths from a module file into its own children (`measure::Path`), relative to the module;
/// re-exports (`pub use child::Item;`) only name the child's items and are left out.
fn child_paths(code: &str) -> Vec<Vec<String>> {
    let code: String = code
        .split(';')
        .filter(|stmt| {
            let Some(i) = stmt.find("use ") else {
                return true;
            };
            let before = stmt[..i].split_whitespace().last().unwrap_or("");
            !(before == "pub" || before.starts_with("pub("))
        })
        .collect::<Vec<_>>()
        .join(";");
    let code = code.as_str();
    let mut out = Vec::new();
    for child in children(code) {
        let pat = format!("{child}::");
        let mut rest = code;
        while let Some(i) = rest.find(&pat) {
            let before = rest[..i].chars().last();
            rest = &rest[i + pat.len()..];
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let item: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            out.push(vec![child.clone(), item]);
        }
    }
    out
}

/// The items a module file re-exports (`pub use a::b::{C, D as E};`): name → full path.
fn reexports(m: &Module, code: &str) -> BTreeMap<String, Vec<String>> {
    let mut out = BTreeMap::new();
    for stmt in code.split(';') {
        let Some(i) = stmt.find("use ") else { continue };
        let before = stmt[..i].split_whitespace().last().unwrap_or("");
        if !(before == "pub" || before.starts_with("pub(")) {
            continue;
        }
        let body: String = stmt[i + 4..]
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        let (prefix, items) = match body.split_once("::{") {
            Some((p, g)) => (p.to_string(), g.trim_end_matches('}').to_string()),
            None => match body.rsplit_once("::") {
                Some((p, it)) => (p.to_string(), it.to_string()),
                None => continue,
            },
        };
        let mut base: Vec<String> = prefix.split("::").map(str::to_string).collect();
        match base[0].as_str() {
            "crate" => {
                base.remove(0);
            }
            "super" => {
                base.remove(0);
                base.splice(0..0, m[..m.len() - 1].iter().cloned());
            }
            _ => base.splice(0..0, m.iter().cloned()).for_each(drop),
        }
        for item in items.split(',') {
            let words: Vec<&str> = item.split_whitespace().collect();
            let Some(first) = words.first() else { continue };
            let path: Vec<String> = first.split("::").map(str::to_string).collect();
            let name = if words.len() == 3 {
                words[2]
            } else {
                path.last().unwrap()
            };
            out.insert(name.to_string(), base.iter().cloned().chain(path).collect());
        }
    }
    out
}

fn edges(mods: &BTreeMap<Module, String>) -> BTreeSet<(Module, Module)> {
    let resolve = |parts: &[String]| -> Option<Module> {
        (1..=parts.len())
            .rev()
            .map(|k| parts[..k].to_vec())
            .find(|m| mods.contains_key(m))
    };
    let codes: BTreeMap<&Module, String> = mods.iter().map(|(m, t)| (m, code(t))).collect();
    let own = |m: &[String]| -> Module { m.iter().cloned().chain([OWN.to_string()]).collect() };
    let mut out = BTreeSet::new();
    for (m, code) in &codes {
        let m: &Module = m;
        let mut found: Vec<Vec<String>> = paths(code)
            .into_iter()
            .map(|(root, segs)| {
                if root == "crate" {
                    segs
                } else {
                    m[..m.len() - 1].iter().cloned().chain(segs).collect()
                }
            })
            .collect();
        found.extend(
            child_paths(code)
                .into_iter()
                .map(|p| m.iter().cloned().chain(p).collect()),
        );
        for mut full in found {
            let Some(mut t) = resolve(&full) else {
                continue;
            };
            // An item a parent re-exports: the module that defines it.
            if m.starts_with(&t)
                && let Some(src) = full
                    .get(t.len())
                    .and_then(|name| reexports(&t, &codes[&t]).get(name).cloned())
                && let Some(s) = resolve(&src)
            {
                full = src;
                t = s;
            }
            let common = m.iter().zip(&t).take_while(|(a, b)| a == b).count();
            if common == m.len() && common == t.len() {
                continue;
            }
            let (from, to) = if common == t.len() {
                // A child uses an item of its ancestor `t`'s own file.
                if full.len() == t.len() || !orchestrator(&t) {
                    continue;
                }
                (m[..=common].to_vec(), own(&t))
            } else if common == m.len() {
                // A module file uses its descendant.
                if !orchestrator(m) {
                    continue;
                }
                (own(m), t[..=common].to_vec())
            } else {
                (m[..=common].to_vec(), t[..=common].to_vec())
            };
            out.insert((from, to));
        }
    }
    out
}

/// Strongly connected components with more than one module (Tarjan).
fn cycles(edges: &BTreeSet<(Module, Module)>) -> Vec<Vec<Module>> {
    let nodes: BTreeSet<&Module> = edges.iter().flat_map(|(a, b)| [a, b]).collect();
    let nodes: Vec<&Module> = nodes.into_iter().collect();
    let id = |m: &Module| nodes.iter().position(|n| *n == m).unwrap();
    let mut adj = vec![Vec::new(); nodes.len()];
    for (a, b) in edges {
        adj[id(a)].push(id(b));
    }
    struct T {
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        stack: Vec<usize>,
        on: Vec<bool>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(v: usize, adj: &[Vec<usize>], t: &mut T) {
        t.index[v] = Some(t.next);
        t.low[v] = t.next;
        t.next += 1;
        t.stack.push(v);
        t.on[v] = true;
        for &w in &adj[v] {
            match t.index[w] {
                None => {
                    visit(w, adj, t);
                    t.low[v] = t.low[v].min(t.low[w]);
                }
                Some(iw) if t.on[w] => t.low[v] = t.low[v].min(iw),
                _ => {}
            }
        }
        if Some(t.low[v]) == t.index[v] {
            let mut comp = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                t.on[w] = false;
                comp.push(w);
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                t.out.push(comp);
            }
        }
    }
    let n = nodes.len();
    let mut t = T {
        index: vec![None; n],
        low: vec![0; n],
        stack: Vec::new(),
        on: vec![false; n],
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if t.index[v].is_none() {
            visit(v, &adj, &mut t);
        }
    }
    t.out
        .into_iter()
        .map(|c| c.into_iter().map(|i| nodes[i].clone()).collect())
        .collect()
}

/// Layer of each top-level module from the table of `docs/architecture.md`.
fn layers() -> BTreeMap<String, usize> {
    let doc = std::fs::read_to_string("docs/architecture.md").unwrap();
    let mut out = BTreeMap::new();
    for line in doc.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() < 4 {
            continue;
        }
        if let Ok(layer) = cells[1].parse::<usize>() {
            for m in cells[2].split(',') {
                assert!(
                    out.insert(m.trim().to_string(), layer).is_none(),
                    "{m} listed twice"
                );
            }
        }
    }
    out
}

#[test]
fn the_module_graph_has_no_cycle() {
    let mods = modules();
    let e = edges(&mods);
    assert!(
        e.len() > 50,
        "too few edges found ({}): parser broken?",
        e.len()
    );
    let found = cycles(&e);
    let text: Vec<String> = found
        .iter()
        .map(|c| {
            c.iter()
                .map(|m| m.join("::"))
                .collect::<Vec<_>>()
                .join(" ⇄ ")
        })
        .collect();
    assert!(found.is_empty(), "import cycles: {text:#?}");
}

#[test]
fn top_level_imports_point_down_the_documented_layers() {
    let mods = modules();
    let layer = layers();
    let top: BTreeSet<&String> = mods.keys().map(|m| &m[0]).collect();
    for m in &top {
        assert!(
            layer.contains_key(*m),
            "module `{m}` is not in the layer table of docs/architecture.md"
        );
    }
    for m in layer.keys() {
        assert!(
            top.contains(m),
            "docs/architecture.md lists `{m}`, which is not a module of src/"
        );
    }
    let mut up = Vec::new();
    for (a, b) in edges(&mods) {
        if a.len() == 1 && layer[&a[0]] < layer[&b[0]] {
            up.push(format!(
                "{} (layer {}) imports {} (layer {})",
                a[0], layer[&a[0]], b[0], layer[&b[0]]
            ));
        }
    }
    assert!(up.is_empty(), "imports up the layers: {up:#?}");
}

/// The standard's arithmetic is usable with no file, run or recording in sight (the Python binding
/// and every reader call it with samples): `analysis` imports only the error type, the sampled
/// channels, the numerics and the stop flag (an atomic its long loops read, no I/O), whatever the
/// layer table says.
#[test]
fn analysis_depends_on_no_reader_run_or_recording() {
    let mods = modules();
    let allowed = ["analysis", "error", "signals", "numeric", "cancel"];
    let out: Vec<String> = edges(&mods)
        .into_iter()
        .filter(|(a, b)| a[0] == "analysis" && !allowed.contains(&b[0].as_str()))
        .map(|(a, b)| format!("{} imports {}", a.join("::"), b.join("::")))
        .collect();
    assert!(
        out.is_empty(),
        "analysis reaches outside the arithmetic: {out:#?}"
    );
    // The check sees analysis' edges at all (a parser that found none would pass).
    assert!(
        edges(&mods)
            .iter()
            .any(|(a, b)| a[0] == "analysis" && b[0] == "error"),
        "no edge from analysis to error found: parser broken?"
    );
}

#[test]
fn the_cycle_finder_finds_a_planted_cycle() {
    let m = |s: &str| -> Module { s.split("::").map(String::from).collect() };
    let mut e = BTreeSet::new();
    e.insert((m("a"), m("b")));
    e.insert((m("b"), m("c")));
    assert!(cycles(&e).is_empty());
    e.insert((m("c"), m("a")));
    assert_eq!(cycles(&e).len(), 1);
    let parsed = paths(
        "use crate::model::catalog::Model; let x = super::stream::f(); use super::{a::B, c};",
    );
    assert_eq!(parsed.len(), 4);
    assert_eq!(parsed[0].1, ["model", "catalog", "Model"]);
    assert_eq!(parsed[3].1, ["c"]);
}

#[test]
fn a_stage_calling_back_into_its_orchestrator_is_a_cycle() {
    let m = |s: &str| -> Module { s.split("::").map(String::from).collect() };
    let mods = BTreeMap::from([
        (
            m("diagnosis"),
            "mod stage;\nmod outcome;\npub use outcome::Out;\npub const K: f64 = 1.0;\n\
             pub fn run() { stage::go(); }"
                .to_string(),
        ),
        (m("diagnosis::outcome"), "pub struct Out;".to_string()),
        (
            m("diagnosis::stage"),
            "use super::Out;\npub fn go() -> Out { Out }".to_string(),
        ),
    ]);
    // The stage uses only a re-export: no cycle.
    assert!(cycles(&edges(&mods)).is_empty(), "{:?}", edges(&mods));
    // The stage uses a constant defined in the orchestrator's file: a cycle.
    let mut back = mods.clone();
    back.insert(
        m("diagnosis::stage"),
        "use super::{Out, K};\npub fn go() -> Out { let _ = K; Out }".to_string(),
    );
    assert_eq!(cycles(&edges(&back)).len(), 1, "{:?}", edges(&back));
    // A glob of the parent counts as its file.
    back.insert(
        m("diagnosis::stage"),
        "use super::*;\npub fn go() {}".to_string(),
    );
    assert_eq!(cycles(&edges(&back)).len(), 1, "{:?}", edges(&back));
}

/// The `.rs` files under `dir`, path → text.
fn files_under(dir: &str) -> BTreeMap<String, String> {
    fn walk(dir: &Path, out: &mut BTreeMap<String, String>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "rs") {
                let text = std::fs::read_to_string(&p).unwrap();
                out.insert(p.to_string_lossy().replace('\\', "/"), text);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(Path::new(dir), &mut out);
    out
}

/// The gap diagnosis's candidates, (static name, id, family file), read from the definitions
/// `pub static NAME: Definition = …` in `src/diagnosis/candidate/`: the id is the first string
/// literal of the definition.
fn candidates(files: &BTreeMap<String, String>) -> Vec<(String, String, String)> {
    let mut out = Vec::new();
    for (path, text) in files {
        if !path.starts_with("src/diagnosis/candidate/") {
            continue;
        }
        let code = code(text);
        let mut rest = code.as_str();
        while let Some(i) = rest.find("pub static ") {
            rest = &rest[i + "pub static ".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !rest[name.len()..].trim_start().starts_with(": Definition") {
                continue;
            }
            let id = rest.split('"').nth(1).unwrap_or_default().to_string();
            out.push((name, id, path.clone()));
        }
    }
    out
}

/// Whether `word` occurs in `code` as a whole identifier.
fn has_word(code: &str, word: &str) -> bool {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    code.match_indices(word).any(|(i, _)| {
        !code[..i].chars().last().is_some_and(ident)
            && !code[i + word.len()..].chars().next().is_some_and(ident)
    })
}

/// Where a candidate is named outside its family's file: by its definition's name anywhere in
/// `files` but the truth-form bench (`gap_bench/`, an independent scorer that joins on the JSON's
/// ids by design), or by its id as a string literal in the diagnosis and the code that shows it
/// (`diagnosis/`, `report/`, `cli/`; elsewhere `"backrest"` is a link role). Comments and test code
/// are not read.
fn candidates_named_outside(files: &BTreeMap<String, String>) -> Vec<String> {
    let cands = candidates(files);
    let mut out = Vec::new();
    for (path, text) in files {
        // A `tests.rs` file or a `tests/` folder under src is a split-out `#[cfg(test)] mod tests`.
        if path.starts_with("src/gap_bench/")
            || path.ends_with("/tests.rs")
            || path.contains("/tests/")
        {
            continue;
        }
        let code = code(text);
        let shows = ["src/diagnosis/", "src/report/", "src/cli/"]
            .iter()
            .any(|d| path.starts_with(d));
        for (name, id, home) in &cands {
            if path == home {
                continue;
            }
            if has_word(&code, name) {
                out.push(format!("{path} names {name} (defined in {home})"));
            }
            if shows && code.contains(&format!("\"{id}\"")) {
                out.push(format!("{path} names \"{id}\" (defined in {home})"));
            }
        }
    }
    out
}

#[test]
fn a_candidate_is_named_only_in_its_family_s_file() {
    let files = files_under("src");
    let cands = candidates(&files);
    assert!(
        cands.len() >= 20 && cands.iter().all(|(_, id, _)| !id.is_empty()),
        "too few candidates found ({cands:?}): parser broken?"
    );
    let named = candidates_named_outside(&files);
    assert!(
        named.is_empty(),
        "a candidate named outside its family's file (a stage asks the registry for a \
         behaviour, a field of the definition, instead): {named:#?}"
    );
    // A name or an id planted in a stage is found; in a comment or a test it is not.
    let (name, id, _) = &cands[0];
    for (planted, found) in [
        (format!("if c == &{name} {{}}"), true),
        (format!("let x = from_id(\"{id}\");"), true),
        (format!("// {name} \"{id}\""), false),
        (
            format!("#[cfg(test)]\nmod tests {{ fn f() {{ {name}; }} }}"),
            false,
        ),
    ] {
        let mut f = files.clone();
        f.insert("src/diagnosis/planted.rs".into(), planted.clone());
        assert_eq!(!candidates_named_outside(&f).is_empty(), found, "{planted}");
    }
}
