//! `cargo xtask tidy`: the structure checks that keep the workspace from drifting back
//! (rust-analyzer's `tidy.rs` in spirit): each returns the problems it finds, one line each,
//! naming the file and what to do.
//!
//! - **Import cycles between files** of any crate's `src/`: a file's references to other
//!   modules (`use crate::...`, `super::...`, `self::...` and inline `crate::a::b` paths, after
//!   comments and inline `#[cfg(test)]` modules are left out) form a graph; a strongly
//!   connected set of two or more files is a cycle. A module file naming its own children
//!   does not count. [`ALLOWED_CYCLES`] lists the cycles a later issue removes (none today).
//! - **Layers:** a workspace crate depends only on the crates [`LAYERS`] allows it, and inside
//!   a crate a file names no higher layer of [`MODULE_LAYERS`].
//! - **Budgets:** the CLI's `src/` under [`CLI_MAX_LINES`] lines, README.md under
//!   [`README_MAX_LINES`], ARCHITECTURE.md under [`ARCHITECTURE_MAX_LINES`]; in both, prose
//!   lines at most [`PROSE_MAX_CHARS`] characters and table rows at most
//!   [`TABLE_ROW_MAX_CHARS`] (fenced code is not prose).
//! - **File size:** no file of `halfedge`, `driver` or `subcount`'s `src/` over
//!   [`FILE_MAX_LINES`] lines unless ARCHITECTURE.md names it with the reason.
//! - **No file under `src/` exists only for tests** (declared `#[cfg(test)] mod name;`).
//! - **The geometry kernel touches no process state:** no file of `halfedge`'s `src/` names
//!   one of [`PROCESS_MARKERS`] (system files, signals, renaming files, exiting): that is the
//!   `driver` crate's.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The CLI's `src/` holds fewer lines than this.
pub(crate) const CLI_MAX_LINES: usize = 3000;
/// A file of these crates' `src/` holds at most this many lines, unless ARCHITECTURE.md names
/// it (its path from the crate's `src/`, in backquotes) with the reason.
pub(crate) const FILE_MAX_LINES: usize = 800;
/// The crates whose files [`FILE_MAX_LINES`] bounds.
pub(crate) const FILE_BUDGET_CRATES: &[&str] = &["halfedge", "driver", "subcount"];
/// README.md holds fewer lines than this.
pub(crate) const README_MAX_LINES: usize = 200;
/// ARCHITECTURE.md holds fewer lines than this.
pub(crate) const ARCHITECTURE_MAX_LINES: usize = 250;
/// The longest prose line of README.md and ARCHITECTURE.md.
pub(crate) const PROSE_MAX_CHARS: usize = 100;
/// The longest table row of README.md and ARCHITECTURE.md.
pub(crate) const TABLE_ROW_MAX_CHARS: usize = 160;

/// Each workspace crate and the workspace crates its `[dependencies]` may name (lower layers
/// only): the counting crates under the mesh crate under the front ends.
pub(crate) const LAYERS: &[(&str, &[&str])] = &[
    ("decimal", &[]),
    ("chart", &[]),
    ("testdata", &[]),
    ("recurrence", &[]),
    ("schemes", &["recurrence", "decimal"]),
    ("halfedge", &["recurrence", "schemes"]),
    ("driver", &["recurrence", "schemes", "halfedge"]),
    (
        "subcount",
        &[
            "recurrence",
            "schemes",
            "halfedge",
            "driver",
            "decimal",
            "chart",
        ],
    ),
    ("xtask", &["recurrence", "schemes", "halfedge"]),
];

/// What only the `driver` crate may name: reading the system's state, signals, replacing
/// files, ending the process.
pub(crate) const PROCESS_MARKERS: &[&str] = &[
    "\"/proc/",
    "\"/sys/",
    "signal_hook",
    "rustix",
    "fs::rename",
    "process::exit",
];

/// Layers inside a crate: every file under the folder (first) but the exceptions (third)
/// must not name a module path containing the second entry, a higher layer. `halfedge`'s
/// subdivision engine is OpenSubdiv's three layers (ARCHITECTURE.md): the rules (`sdc/`:
/// masks, vertex rules, sharpness decay, no mesh and no level), the topology steps and the
/// rules' kernels (`subdivide/` but `refine/`), the refinement and evaluation (`refine/`);
/// `subdivide/mod.rs`, the one-shot API, is a loop over the refinement.
pub(crate) const MODULE_LAYERS: &[(&str, &str, &[&str])] = &[
    (
        "crates/halfedge/src/subdivide/",
        "refine::",
        &[
            "crates/halfedge/src/subdivide/mod.rs",
            "crates/halfedge/src/subdivide/refine/",
        ],
    ),
    ("crates/halfedge/src/subdivide/sdc/", "topo::", &[]),
    ("crates/halfedge/src/subdivide/sdc/", "mesh::", &[]),
    ("crates/halfedge/src/subdivide/sdc/", "HalfEdgeMesh", &[]),
    ("crates/halfedge/src/subdivide/sdc/", "weights::", &[]),
    ("crates/halfedge/src/subdivide/sdc/", "gather::", &[]),
];

/// Cycles allowed for now, by the folder (under the workspace root) holding all their files,
/// each with the issue that removes it.
pub(crate) const ALLOWED_CYCLES: &[(&str, &str)] = &[];

/// Every problem `tidy` finds under `root` (the workspace root).
pub(crate) fn check(root: &Path) -> Vec<String> {
    let mut problems = Vec::new();
    for src in crate_sources(root) {
        problems.extend(cycles(root, &src));
        problems.extend(test_only_files(root, &src));
    }
    problems.extend(layers(root));
    problems.extend(budgets(root));
    problems.extend(process_in_kernel(root));
    problems.extend(module_layers(root));
    problems
}

/// The files that name a higher layer of their crate ([`MODULE_LAYERS`]).
fn module_layers(root: &Path) -> Vec<String> {
    let mut problems = Vec::new();
    for (dir, higher, exceptions) in MODULE_LAYERS {
        for file in rust_files(&root.join(dir)) {
            let name = file
                .strip_prefix(root)
                .unwrap_or(&file)
                .display()
                .to_string();
            if exceptions.iter().any(|e| name.starts_with(e)) {
                continue;
            }
            let text = std::fs::read_to_string(&file).unwrap_or_default();
            let code = code_without_tests(&text);
            let names_higher = code
                .match_indices(higher)
                .any(|(i, _)| !code[..i].ends_with(|c: char| c.is_alphanumeric() || c == '_'));
            if names_higher {
                problems.push(format!(
                    "{name} names `{higher}`, a higher layer (MODULE_LAYERS): move what it needs below"
                ));
            }
        }
    }
    problems
}

/// The files of `halfedge`'s `src/` that name a [`PROCESS_MARKERS`] entry.
fn process_in_kernel(root: &Path) -> Vec<String> {
    let mut problems = Vec::new();
    for file in rust_files(&root.join("crates/halfedge/src")) {
        let text = std::fs::read_to_string(&file).unwrap_or_default();
        for marker in PROCESS_MARKERS.iter().filter(|m| text.contains(*m)) {
            problems.push(format!(
                "{} names `{marker}`: process state is the driver crate's, not the geometry kernel's",
                file.strip_prefix(root).unwrap_or(&file).display()
            ));
        }
    }
    problems
}

/// `cargo xtask tidy`: prints each problem and fails when there is one.
pub(crate) fn run(root: &Path) -> anyhow::Result<()> {
    let problems = check(root);
    for p in &problems {
        println!("tidy: {p}");
    }
    if problems.is_empty() {
        println!("tidy: ok");
        Ok(())
    } else {
        anyhow::bail!("tidy: {} problem(s)", problems.len())
    }
}

/// The `src/` folders of the workspace's crates.
fn crate_sources(root: &Path) -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
        .map(|rd| rd.flatten().map(|e| e.path().join("src")).collect())
        .unwrap_or_default();
    dirs.push(root.join("xtask/src"));
    dirs.push(root.join("tests/src"));
    dirs.retain(|d| d.is_dir());
    dirs.sort();
    dirs
}

/// The `.rs` files under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = entry.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The module path of `file` under `src` (`lib.rs`/`main.rs` the root, `a/mod.rs` is `a`).
fn module_path(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap_or(file);
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().into_owned())
        .collect();
    if let Some(last) = parts.pop() {
        let stem = last.trim_end_matches(".rs").to_owned();
        let root_file = parts.is_empty() && (stem == "lib" || stem == "main");
        if stem != "mod" && !root_file {
            parts.push(stem);
        }
    }
    parts
}

/// The code of a file: comments and inline `#[cfg(test)]` modules left out.
pub(crate) fn code_without_tests(text: &str) -> String {
    let mut out = String::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        let t = line.trim();
        if t == "#[cfg(test)]" {
            let next = lines
                .peek()
                .map(|l| l.trim().to_owned())
                .unwrap_or_default();
            if next.starts_with("mod ") && next.ends_with('{') {
                // Skip the module to its closing brace.
                let mut depth = 0i64;
                for l in lines.by_ref() {
                    depth += l.matches('{').count() as i64 - l.matches('}').count() as i64;
                    if depth <= 0 && l.contains('}') {
                        break;
                    }
                }
                continue;
            }
        }
        if t.starts_with("//") {
            continue;
        }
        let code = match line.find("//") {
            Some(i) if !line[..i].contains('"') => &line[..i],
            _ => line,
        };
        out.push_str(code);
        out.push('\n');
    }
    out
}

/// The module paths `code` refers to, resolved against `module` (the file's own module).
pub(crate) fn references(code: &str, module: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    // `use` statements, with their braces expanded.
    for stmt in use_statements(code) {
        for path in expand(&stmt) {
            if let Some(p) = resolve(&path, module) {
                out.push(p);
            }
        }
    }
    // Inline paths: `crate::a::b`, `super::a`, `self::a` outside `use` statements.
    let bytes = code.as_bytes();
    for start in ["crate::", "super::", "self::"] {
        let mut from = 0;
        while let Some(i) = code[from..].find(start) {
            let at = from + i;
            from = at + start.len();
            let before = at.checked_sub(1).map(|b| bytes[b]);
            if before.is_some_and(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b':') {
                continue;
            }
            let end = code[at..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == ':'))
                .map_or(code.len(), |e| at + e);
            let path: Vec<String> = code[at..end]
                .split("::")
                .filter(|s| !s.is_empty())
                .map(str::to_owned)
                .collect();
            if let Some(p) = resolve(&path, module) {
                out.push(p);
            }
        }
    }
    out
}

/// The text of every `use ...;` statement of `code` (without `use` and `;`).
fn use_statements(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("use ") {
        let ok = i == 0 || {
            let b = rest.as_bytes()[i - 1];
            !(b.is_ascii_alphanumeric() || b == b'_')
        };
        let after = &rest[i + 4..];
        let Some(end) = after.find(';') else { break };
        if ok {
            out.push(after[..end].split_whitespace().collect::<Vec<_>>().join(""));
        }
        rest = &after[end..];
    }
    out
}

/// The paths of a `use` tree (`a::{b, c::{d, e}}` is `a::b`, `a::c::d`, `a::c::e`).
fn expand(tree: &str) -> Vec<Vec<String>> {
    let Some(open) = tree.find('{') else {
        let path = tree.split(" as ").next().unwrap_or(tree);
        return vec![path
            .split("::")
            .filter(|s| !s.is_empty())
            .map(str::to_owned)
            .collect()];
    };
    let prefix: Vec<String> = tree[..open]
        .split("::")
        .filter(|s| !s.is_empty())
        .map(str::to_owned)
        .collect();
    let inner = tree[open + 1..]
        .strip_suffix('}')
        .unwrap_or(&tree[open + 1..]);
    let mut out = Vec::new();
    let (mut depth, mut start) = (0, 0);
    let mut parts = Vec::new();
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
    for part in parts.into_iter().filter(|p| !p.is_empty()) {
        for tail in expand(part) {
            let mut p = prefix.clone();
            p.extend(tail.into_iter().filter(|s| s != "self"));
            out.push(p);
        }
    }
    out
}

/// An absolute module path for `path` (starting with `crate`, `super` or `self`) seen from
/// `module` (a file `a/b.rs` and a folder `a/b/mod.rs` are both module `a::b`); `None` for
/// other crates' paths.
fn resolve(path: &[String], module: &[String]) -> Option<Vec<String>> {
    let mut base: Vec<String> = match path.first()?.as_str() {
        "crate" => Vec::new(),
        "self" | "super" => module.to_vec(),
        _ => return None,
    };
    let mut rest = path;
    if rest[0] == "crate" || rest[0] == "self" {
        rest = &rest[1..];
    }
    while rest.first().is_some_and(|s| s == "super") {
        base.pop();
        rest = &rest[1..];
    }
    base.extend(rest.iter().cloned());
    Some(base)
}

/// The import cycles between the files of the crate whose sources are `src`.
fn cycles(root: &Path, src: &Path) -> Vec<String> {
    let files = rust_files(src);
    let modules: BTreeMap<Vec<String>, usize> = files
        .iter()
        .enumerate()
        .map(|(i, f)| (module_path(src, f), i))
        .collect();
    let mut edges: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); files.len()];
    for (i, file) in files.iter().enumerate() {
        let Ok(text) = std::fs::read_to_string(file) else {
            continue;
        };
        let own = module_path(src, file);
        for path in references(&code_without_tests(&text), &own) {
            // The deepest module file the path names.
            let target = (0..=path.len())
                .rev()
                .find_map(|n| modules.get(&path[..n]).copied());
            if let Some(t) = target {
                let descendant = module_path(src, &files[t]).starts_with(&own);
                if t != i && !descendant {
                    edges[i].insert(t);
                }
            }
        }
    }
    let mut out = Vec::new();
    for scc in strongly_connected(&edges) {
        if scc.len() < 2 {
            continue;
        }
        let names: Vec<String> = scc
            .iter()
            .map(|&i| {
                files[i]
                    .strip_prefix(root)
                    .unwrap_or(&files[i])
                    .display()
                    .to_string()
            })
            .collect();
        let allowed = ALLOWED_CYCLES
            .iter()
            .any(|(dir, _)| names.iter().all(|n| n.starts_with(dir)));
        if !allowed {
            out.push(format!(
                "import cycle between files: {} (move what they share into a module below both)",
                names.join(", ")
            ));
        }
    }
    out
}

/// The strongly connected components of a graph (Tarjan's algorithm, iterative), each sorted.
pub(crate) fn strongly_connected(edges: &[BTreeSet<usize>]) -> Vec<Vec<usize>> {
    let n = edges.len();
    let (mut index, mut low) = (vec![usize::MAX; n], vec![0; n]);
    let (mut on_stack, mut stack) = (vec![false; n], Vec::new());
    let mut next = 0;
    let mut out = Vec::new();
    for start in 0..n {
        if index[start] != usize::MAX {
            continue;
        }
        // (node, its successors not yet visited)
        let mut work: Vec<(usize, Vec<usize>)> = Vec::new();
        // The node to visit next: it gets the next index and goes on both stacks.
        let mut enter = Some(start);
        loop {
            if let Some(v) = enter.take() {
                index[v] = next;
                low[v] = next;
                next += 1;
                stack.push(v);
                on_stack[v] = true;
                work.push((v, edges[v].iter().copied().collect()));
            }
            let Some((v, succ)) = work.last_mut() else {
                break;
            };
            let v = *v;
            if let Some(w) = succ.pop() {
                if index[w] == usize::MAX {
                    enter = Some(w);
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
            } else {
                work.pop();
                if let Some((parent, _)) = work.last() {
                    low[*parent] = low[*parent].min(low[v]);
                }
                if low[v] == index[v] {
                    let mut scc = Vec::new();
                    while let Some(w) = stack.pop() {
                        on_stack[w] = false;
                        scc.push(w);
                        if w == v {
                            break;
                        }
                    }
                    scc.sort_unstable();
                    out.push(scc);
                }
            }
        }
    }
    out
}

/// Files of `src` declared only for tests (`#[cfg(test)] mod name;`): tests live in `tests/`
/// or in an inline `#[cfg(test)] mod tests { ... }`.
fn test_only_files(root: &Path, src: &Path) -> Vec<String> {
    let mut out = Vec::new();
    for file in rust_files(src) {
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue;
        };
        let lines: Vec<&str> = text.lines().map(str::trim).collect();
        for w in lines.windows(2) {
            if w[0] == "#[cfg(test)]" && w[1].starts_with("mod ") && w[1].ends_with(';') {
                let name = w[1].trim_start_matches("mod ").trim_end_matches(';');
                out.push(format!(
                    "{}: `mod {name};` is a file under src/ that exists only for tests: move it to the crate's tests/",
                    file.strip_prefix(root).unwrap_or(&file).display()
                ));
            }
        }
    }
    out
}

/// Workspace crates depending on crates their layer does not allow.
fn layers(root: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let workspace: BTreeSet<&str> = LAYERS.iter().map(|(c, _)| *c).collect();
    for (name, allowed) in LAYERS {
        let manifest = if *name == "xtask" {
            root.join("xtask/Cargo.toml")
        } else {
            root.join("crates").join(name).join("Cargo.toml")
        };
        let Ok(text) = std::fs::read_to_string(&manifest) else {
            out.push(format!("{}: not found", manifest.display()));
            continue;
        };
        let mut in_deps = false;
        for line in text.lines() {
            let t = line.trim();
            if t.starts_with('[') {
                in_deps = t == "[dependencies]";
                continue;
            }
            if !in_deps || t.starts_with('#') {
                continue;
            }
            let dep = t.split(['=', '.', ' ']).next().unwrap_or("").trim();
            if workspace.contains(dep) && !allowed.contains(&dep) {
                out.push(format!(
                    "{}: `{name}` depends on `{dep}`, a crate of its own layer or above (allowed: {})",
                    manifest.strip_prefix(root).unwrap_or(&manifest).display(),
                    if allowed.is_empty() { "none".to_owned() } else { allowed.join(", ") }
                ));
            }
        }
    }
    out
}

/// The size budgets.
fn budgets(root: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let cli: usize = rust_files(&root.join("crates/subcount/src"))
        .iter()
        .filter_map(|f| std::fs::read_to_string(f).ok())
        .map(|t| t.lines().count())
        .sum();
    if cli >= CLI_MAX_LINES {
        out.push(format!(
            "crates/subcount/src is {cli} lines, the budget {CLI_MAX_LINES}: move logic into the libraries"
        ));
    }
    let architecture = std::fs::read_to_string(root.join("ARCHITECTURE.md")).unwrap_or_default();
    for krate in FILE_BUDGET_CRATES {
        let src = root.join("crates").join(krate).join("src");
        for file in rust_files(&src) {
            let n = std::fs::read_to_string(&file).map_or(0, |t| t.lines().count());
            let inner = file
                .strip_prefix(&src)
                .unwrap_or(&file)
                .display()
                .to_string();
            if n > FILE_MAX_LINES && !architecture.contains(&format!("`{inner}`")) {
                out.push(format!(
                    "crates/{krate}/src/{inner} is {n} lines, over {FILE_MAX_LINES}: split it, or name it in ARCHITECTURE.md with the reason"
                ));
            }
        }
    }
    for (doc, max) in [
        ("README.md", README_MAX_LINES),
        ("ARCHITECTURE.md", ARCHITECTURE_MAX_LINES),
    ] {
        let Ok(text) = std::fs::read_to_string(root.join(doc)) else {
            out.push(format!("{doc}: not found"));
            continue;
        };
        out.extend(doc_problems(doc, &text, max));
    }
    out
}

/// The problems of one doc: its length and its long lines (fenced code left out).
pub(crate) fn doc_problems(doc: &str, text: &str, max_lines: usize) -> Vec<String> {
    let mut out = Vec::new();
    let n = text.lines().count();
    if n >= max_lines {
        out.push(format!(
            "{doc} is {n} lines, the budget {max_lines}: the reference belongs in docs/"
        ));
    }
    let mut fenced = false;
    for (i, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        let chars = line.chars().count();
        let (limit, what) = if line.trim_start().starts_with('|') {
            (TABLE_ROW_MAX_CHARS, "table row")
        } else {
            (PROSE_MAX_CHARS, "line")
        };
        if !fenced && chars > limit {
            out.push(format!(
                "{doc}:{}: {what} of {chars} characters, over {limit}",
                i + 1
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cycles_are_strongly_connected_components() {
        // 0 -> 1 -> 2 -> 0 and 3 -> 0, 4 alone.
        let edges: Vec<BTreeSet<usize>> = vec![
            [1].into(),
            [2].into(),
            [0].into(),
            [0].into(),
            BTreeSet::new(),
        ];
        let mut sccs = strongly_connected(&edges);
        sccs.sort();
        assert_eq!(sccs, [vec![0, 1, 2], vec![3], vec![4]]);
    }

    #[test]
    fn references_resolve_use_trees_and_inline_paths() {
        let code = "use crate::{a::B, c::{d, e::F}};\nuse super::g;\nfn f() { crate::h::i(); }\n";
        let module = ["x".to_owned(), "y".to_owned()];
        let refs = references(code, &module);
        for want in [
            vec!["a", "B"],
            vec!["c", "d"],
            vec!["c", "e", "F"],
            vec!["x", "g"],
            vec!["h", "i"],
        ] {
            let want: Vec<String> = want.into_iter().map(str::to_owned).collect();
            assert!(refs.contains(&want), "{want:?} in {refs:?}");
        }
    }

    #[test]
    fn inline_test_modules_and_comments_are_left_out() {
        let text = "use crate::a;\n// crate::b\n#[cfg(test)]\nmod tests {\n    use crate::c;\n}\n";
        let code = code_without_tests(text);
        assert!(code.contains("crate::a"));
        assert!(
            !code.contains("crate::b") && !code.contains("crate::c"),
            "{code}"
        );
    }

    #[test]
    fn docs_over_budget_or_with_long_lines_are_problems() {
        let long = "x".repeat(PROSE_MAX_CHARS + 1);
        let text = format!("# t\n{long}\n```\n{long}\n```\n| {} |\n", "y".repeat(150));
        let problems = doc_problems("README.md", &text, 200);
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert!(problems[0].starts_with("README.md:2: line of 101"));
        assert_eq!(doc_problems("README.md", &"a\n".repeat(200), 200).len(), 1);
    }

    /// The workspace holds every check but the CLI's size, which issue 25 brings under its
    /// budget (`.ci/run` runs `cargo xtask tidy` from then on): a new import cycle, a crate
    /// above its layer, a file only for tests or README.md / ARCHITECTURE.md over budget fails
    /// `cargo test` now.
    #[test]
    fn the_workspace_is_tidy() {
        let problems = check(&crate::project_root());
        assert!(problems.is_empty(), "{}", problems.join("\n"));
    }
}
