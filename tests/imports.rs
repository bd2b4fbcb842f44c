//! No import circle between the files of src/: read from their `use` lines and the paths
//! they name in code (`super::load::read(…)`, `crate::scene::Scene`), their tests left out,
//! file A imports file B when A names B's module or something declared in it, and no chain
//! of imports leads from a file back to itself. A circle is what makes a file impossible to
//! read, test or move without the other; what two files both need belongs in a file below
//! them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

type Module = Vec<String>;

/// Every source file's module path (src/a/b.rs and src/a/b/mod.rs are a::b; lib.rs and
/// main.rs are the crate root) and its text without its tests.
fn sources() -> BTreeMap<Module, String> {
    fn walk(dir: &Path, root: &Path, out: &mut BTreeMap<Module, String>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, root, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let relative = path.strip_prefix(root).unwrap().with_extension("");
                let mut module: Module = relative
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                if ["mod", "lib", "main"].contains(&module.last().unwrap().as_str()) {
                    module.pop();
                }
                let text = std::fs::read_to_string(&path).unwrap();
                let code = match text.find("#[cfg(test)]\nmod tests") {
                    Some(at) => text[..at].to_string(),
                    None => text,
                };
                // lib.rs and main.rs are both the root: one module of both texts.
                out.entry(module).or_default().push_str(&code);
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = BTreeMap::new();
    walk(&root, &root, &mut out);
    out
}

/// The `use` declarations of `code`, each as its path and, for a `{…}` list, the first
/// name of each item in it.
fn uses(code: &str) -> Vec<(Vec<String>, Vec<String>)> {
    let mut out = Vec::new();
    let mut lines = code.lines();
    while let Some(line) = lines.next() {
        // A declaration starts a line: `use`, or `pub` / `pub(…)` then `use`.
        let line = line.trim_start();
        let after_pub = match line.strip_prefix("pub") {
            Some(rest) if rest.starts_with('(') => rest.find(')').map(|i| &rest[i + 1..]),
            Some(rest) => Some(rest),
            None => Some(line),
        };
        let Some(decl) = after_pub.and_then(|r| r.trim_start().strip_prefix("use ")) else {
            continue;
        };
        let mut decl = decl.to_string();
        while !decl.contains(';') {
            match lines.next() {
                Some(more) => decl.push_str(more),
                None => break,
            }
        }
        let decl = &decl[..decl.find(';').unwrap_or(decl.len())];
        let body: String = decl.split_whitespace().collect::<Vec<_>>().join(" ");
        let (path, list) = match body.find('{') {
            Some(brace) => (&body[..brace], Some(&body[brace + 1..])),
            None => (body.as_str(), None),
        };
        let path: Vec<String> = path
            .split("::")
            .filter(|s| !s.is_empty())
            .map(|s| s.split(" as ").next().unwrap().trim().to_string())
            .collect();
        let mut names = Vec::new();
        if let Some(list) = list {
            // The first segment of each item at the list's top level.
            let mut depth = 0;
            let mut item = String::new();
            for c in list.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        names.push(std::mem::take(&mut item));
                        continue;
                    }
                    _ => {}
                }
                if depth == 0 {
                    item.push(c);
                }
            }
            names.push(item);
            names = names
                .into_iter()
                .map(|n| {
                    let first = n.trim().split("::").next().unwrap_or("");
                    first.split(" as ").next().unwrap_or("").trim().to_string()
                })
                .filter(|n| !n.is_empty())
                .collect();
        }
        out.push((path, names));
    }
    out.extend(inline_paths(code));
    out
}

/// The paths from `crate` or `super` that code names outside `use` lines and comments
/// (`super::assets::read_text_file(…)`), each with no list.
fn inline_paths(code: &str) -> Vec<(Vec<String>, Vec<String>)> {
    let mut out = Vec::new();
    for line in code.lines() {
        let line = line.trim_start();
        if line.starts_with("//") || line.starts_with("use ") || line.starts_with("pub use ") {
            continue;
        }
        for root in ["crate::", "super::"] {
            let mut from = 0;
            while let Some(found) = line[from..].find(root) {
                let start = from + found;
                from = start + root.len();
                let before = line[..start].chars().next_back();
                if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                    continue;
                }
                let path: String = line[start..]
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                    .collect();
                let segments: Vec<String> = path
                    .split("::")
                    .filter(|s| !s.is_empty())
                    .map(String::from)
                    .collect();
                out.push((segments, Vec::new()));
            }
        }
    }
    out
}

/// Which files each file imports.
fn imports(sources: &BTreeMap<Module, String>) -> BTreeMap<Module, BTreeSet<Module>> {
    let mut graph = BTreeMap::new();
    for (module, code) in sources {
        let mut targets = BTreeSet::new();
        for (path, names) in uses(code) {
            let Some(first) = path.first() else { continue };
            let (mut at, rest): (Module, &[String]) = match first.as_str() {
                "crate" => (Vec::new(), &path[1..]),
                "super" => (
                    module[..module.len().saturating_sub(1)].to_vec(),
                    &path[1..],
                ),
                "self" => (module.clone(), &path[1..]),
                child => {
                    let mut m = module.clone();
                    m.push(child.to_string());
                    if !sources.contains_key(&m) {
                        continue; // another crate
                    }
                    (module.clone(), &path[..])
                }
            };
            let mut rest = rest;
            while rest.first().is_some_and(|s| s == "super") {
                at.pop();
                rest = &rest[1..];
            }
            for segment in rest {
                let mut deeper = at.clone();
                deeper.push(segment.clone());
                if !sources.contains_key(&deeper) {
                    break;
                }
                at = deeper;
            }
            for name in &names {
                let mut deeper = at.clone();
                deeper.push(name.clone());
                if sources.contains_key(&deeper) {
                    targets.insert(deeper);
                }
            }
            targets.insert(at);
        }
        targets.remove(module);
        targets.retain(|t| sources.contains_key(t));
        graph.insert(module.clone(), targets);
    }
    graph
}

/// Every circle: the strongly connected components of more than one file (Tarjan).
fn circles(graph: &BTreeMap<Module, BTreeSet<Module>>) -> Vec<Vec<Module>> {
    struct State<'g> {
        graph: &'g BTreeMap<Module, BTreeSet<Module>>,
        index: BTreeMap<&'g Module, usize>,
        low: BTreeMap<&'g Module, usize>,
        stack: Vec<&'g Module>,
        found: Vec<Vec<Module>>,
    }
    fn visit<'g>(s: &mut State<'g>, v: &'g Module) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        for w in &s.graph[v] {
            if !s.index.contains_key(w) {
                visit(s, w);
                let low = s.low[v].min(s.low[w]);
                s.low.insert(v, low);
            } else if s.stack.contains(&w) {
                let low = s.low[v].min(s.index[w]);
                s.low.insert(v, low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            loop {
                let w = s.stack.pop().unwrap();
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
    let mut s = State {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        found: Vec::new(),
    };
    for v in graph.keys() {
        if !s.index.contains_key(v) {
            visit(&mut s, v);
        }
    }
    s.found
}

#[test]
fn no_file_of_src_imports_itself_through_others() {
    let sources = sources();
    assert!(sources.len() > 50, "read {} files", sources.len());
    let graph = imports(&sources);
    // The reading sees real imports: the integrator uses the accelerator, which uses the BVH.
    let m = |s: &str| -> Module { s.split('/').map(String::from).collect() };
    assert!(graph[&m("integrator")].contains(&m("accel")));
    assert!(graph[&m("accel/instance")].contains(&m("accel/bvh")));
    assert!(graph[&m("accel/bvh")].contains(&m("simd")));
    let found = circles(&graph);
    let shown: Vec<String> = found
        .iter()
        .map(|c| {
            c.iter()
                .map(|m| m.join("/"))
                .collect::<Vec<_>>()
                .join(" ↔ ")
        })
        .collect();
    assert!(found.is_empty(), "import circles: {shown:#?}");
}

/// The reader finds a circle where there is one, and paths named in code.
#[test]
fn a_circle_is_found() {
    let m = |s: &str| -> Module { s.split('/').map(String::from).collect() };
    let mut sources = BTreeMap::new();
    sources.insert(m("a"), "use crate::b::{Thing, c};\n".to_string());
    sources.insert(m("b"), "pub use super::a::Other;\n".to_string());
    sources.insert(m("b/c"), String::new());
    sources.insert(m("d"), "use crate::a;".to_string());
    let graph = imports(&sources);
    assert_eq!(graph[&m("a")], BTreeSet::from([m("b"), m("b/c")]));
    let found = circles(&graph);
    assert_eq!(found.len(), 1);
    assert_eq!(
        found[0].iter().cloned().collect::<BTreeSet<_>>(),
        BTreeSet::from([m("a"), m("b")])
    );
    // A path named in code counts as a `use` does; one in a comment does not.
    sources.insert(
        m("d"),
        "// crate::a::x\nfn f() { crate::a::x(); }\n".to_string(),
    );
    let graph = imports(&sources);
    assert!(graph[&m("d")].contains(&m("a")));
    sources.insert(m("d"), "// crate::a::x\n".to_string());
    assert!(!imports(&sources)[&m("d")].contains(&m("a")));
}
