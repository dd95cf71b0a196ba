//! The module layering of ARCHITECTURE.md ("each module depends only on the modules above
//! it") checked against the sources: the layer list is read from the document's `## Layers`
//! block, and every `crate::` path in the non-test code of `src/` must name a module of an
//! earlier layer or of its own layer. Both a wrong edge and a module missing from the list
//! fail, so the document and the code cannot drift apart.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The layers of ARCHITECTURE.md, top first: a line of the `## Layers` code block that
/// starts with a module name opens a layer; a name indented by exactly two spaces joins the
/// layer above it; other lines continue a description.
fn layers() -> Vec<Vec<String>> {
    let doc = fs::read_to_string(root().join("ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let section = doc
        .split("## Layers")
        .nth(1)
        .expect("a `## Layers` section");
    let block = section
        .split("```")
        .nth(1)
        .expect("a code block under `## Layers`");
    let mut layers: Vec<Vec<String>> = Vec::new();
    for line in block.lines().skip(1) {
        let name: String = line
            .trim_start()
            .chars()
            .take_while(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '_')
            .collect();
        let indent = line.len() - line.trim_start().len();
        if name.is_empty() {
            continue;
        }
        match indent {
            0 => layers.push(vec![name]),
            2 => layers
                .last_mut()
                .expect("an indented module follows a layer")
                .push(name),
            _ => {}
        }
    }
    layers
}

/// Every `.rs` file under `dir`.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("src/") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level module a file of `src/` belongs to (`src/models/ward.rs` → `models`).
fn module_of(file: &Path) -> String {
    let rel = file.strip_prefix(root().join("src")).expect("under src/");
    let first = rel.components().next().expect("a path");
    let first = first.as_os_str().to_str().expect("UTF-8");
    first.trim_end_matches(".rs").to_string()
}

/// The code of a file without comments (line comments, doc comments included) and without
/// its `#[cfg(test)]` unit tests.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]\nmod tests").next().unwrap_or(text);
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The first path segment of every `crate::…` path in `code`, through `crate::{a, b::c}`
/// groups (nested groups included).
fn crate_paths(code: &str) -> Vec<String> {
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect()
    };
    let mut out = Vec::new();
    for (i, _) in code.match_indices("crate::") {
        let rest = &code[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            // Top-level items of the group: split on commas at depth 0.
            let (mut depth, mut start) = (0usize, 0usize);
            for (j, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => {
                        out.push(ident(group[start..j].trim()));
                        break;
                    }
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        out.push(ident(group[start..j].trim()));
                        start = j + 1;
                    }
                    _ => {}
                }
            }
        } else {
            out.push(ident(rest));
        }
    }
    out.retain(|s| !s.is_empty() && s != "self");
    out
}

/// The crate root's re-exports (`pub use real::{Real, Scalar};` → `Real ↦ real`, …).
fn root_reexports() -> BTreeMap<String, String> {
    let lib = fs::read_to_string(root().join("src/lib.rs")).expect("src/lib.rs");
    let mut map = BTreeMap::new();
    for stmt in code(&lib).split(';') {
        let Some(path) = stmt.trim().strip_prefix("pub use ") else {
            continue;
        };
        let Some((module, items)) = path.split_once("::") else {
            continue;
        };
        let items = items.trim_start_matches('{').trim_end_matches('}');
        for item in items.split(',') {
            let item = item.trim();
            if !item.is_empty() {
                map.insert(item.to_string(), module.trim().to_string());
            }
        }
    }
    map
}

/// A file's text without its `pub(crate) mod desc { … }` block, and that block (empty if
/// none), matched by braces.
fn split_desc(text: &str) -> (String, String) {
    let Some(start) = text.find("pub(crate) mod desc {") else {
        return (text.to_string(), String::new());
    };
    let open = start + "pub(crate) mod desc ".len();
    let mut depth = 0usize;
    for (j, c) in text[open..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    let end = open + j + 1;
                    let rest = format!("{}{}", &text[..start], &text[end..]);
                    return (rest, text[start..end].to_string());
                }
            }
            _ => {}
        }
    }
    panic!("unbalanced `mod desc` block");
}

#[test]
fn every_module_depends_only_on_the_layers_above_it() {
    let layers = layers();
    let layer_of: BTreeMap<String, usize> = layers
        .iter()
        .enumerate()
        .flat_map(|(i, l)| l.iter().map(move |m| (m.clone(), i)))
        .collect();
    assert!(
        layer_of.contains_key("ior") && layer_of.contains_key("material"),
        "the layer list was not read: {layers:?}"
    );
    let reexports = root_reexports();
    let mut files = Vec::new();
    sources(&root().join("src"), &mut files);
    files.sort();
    let mut problems = Vec::new();
    for file in &files {
        let module = module_of(file);
        if module == "lib" {
            continue;
        }
        let Some(&own) = layer_of.get(&module) else {
            problems.push(format!(
                "module `{module}` is not in the layer list of ARCHITECTURE.md"
            ));
            continue;
        };
        let text = fs::read_to_string(file).expect("a source file");
        // A model file's description (`mod desc`, feature `serde`) is the `material`
        // layer's code kept beside its model: checked as `material`.
        let (text, desc) = split_desc(&code(&text));
        let parts = [
            (module.clone(), own, text),
            ("material".to_string(), layer_of["material"], desc),
        ];
        for (module, own, text) in &parts {
            let (module, own) = (module.clone(), *own);
            for first in crate_paths(&code(text)) {
                let target = match reexports.get(&first) {
                    Some(m) => m.clone(),
                    None => first.clone(),
                };
                if target == module {
                    continue;
                }
                match layer_of.get(&target) {
                Some(&t) if t <= own => {}
                Some(_) => problems.push(format!(
                    "{}: `{module}` uses `crate::{first}` (module `{target}`, a layer below it)",
                    file.display()
                )),
                None if target.chars().next().is_some_and(char::is_uppercase) => {
                    problems.push(format!(
                        "{}: `crate::{first}` is neither a module nor a root re-export",
                        file.display()
                    ))
                }
                None => problems.push(format!(
                    "{}: `{module}` uses `crate::{first}`, a module missing from the layer list",
                    file.display()
                )),
            }
            }
        }
    }
    problems.sort();
    problems.dedup();
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The checker itself: group parsing, comments and the layering of a known edge.
#[test]
fn the_checker_reads_paths_groups_and_layers() {
    assert_eq!(
        crate_paths("use crate::{Real, ndf::{Ggx, Ndf}, self};\nlet x = crate::fast::pow(a);"),
        ["Real", "ndf", "fast"]
    );
    assert!(crate_paths(&code("/// see [`crate::material`]\nfn f() {}")).is_empty());
    let layers = layers();
    let pos = |m: &str| layers.iter().position(|l| l.iter().any(|x| x == m));
    assert!(pos("ior") < pos("fresnel"), "ior is data below fresnel");
    assert!(pos("math") < pos("real"));
    assert_eq!(pos("sampling"), pos("models"));
    assert_eq!(
        root_reexports().get("Real").map(String::as_str),
        Some("real")
    );
}
