//! The documents are the repository's own: every section of
//! `docs/method.md` and `docs/api.md` a code comment cites exists, no
//! document is a diary of work sessions, and no committed text holds an
//! absolute path of a development machine. Reads files only; no server.

use std::fs;
use std::path::{Path, PathBuf};

/// ARCHITECTURE.md is a map, not a changelog: it must stay short.
const MAX_ARCHITECTURE_LINES: usize = 150;
/// Fewer citations than this means the scan missed them, not that the code
/// stopped citing: the test would pass vacuously.
const MIN_METHOD_CITATIONS: usize = 100;
const MIN_API_CITATIONS: usize = 15;
/// Text files whose content is checked for machine paths.
const TEXT_EXTENSIONS: [&str; 9] = ["rs", "md", "py", "sh", "toml", "yml", "yaml", "sql", "json"];
/// Folders of committed text (data sets under `calib/tests/data` are
/// third-party files with their own provenance and are not scanned).
const SCANNED: [&str; 12] = [
    "src",
    "calib/src",
    "calib/examples",
    "calib/tests",
    "tests",
    "docs",
    "bench",
    "examples",
    "migrations",
    "openapi",
    "docker",
    ".ci",
];

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(rel: &str) -> String {
    fs::read_to_string(repo().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// Every file under `dir` (recursively) with one of `extensions`, skipping
/// `calib/tests/data`.
fn files(dir: &Path, extensions: &[&str], out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.ends_with("calib/tests/data") {
            continue;
        }
        if path.is_dir() {
            files(&path, extensions, out);
        } else if path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| extensions.contains(&e))
        {
            out.push(path);
        }
    }
}

fn rust_sources() -> Vec<(PathBuf, String)> {
    let mut paths = Vec::new();
    for dir in [
        "src",
        "calib/src",
        "calib/examples",
        "calib/tests",
        "tests",
        "examples",
    ] {
        files(&repo().join(dir), &["rs"], &mut paths);
    }
    paths
        .into_iter()
        .map(|p| {
            let text = fs::read_to_string(&p).unwrap_or_default();
            (p, text)
        })
        .collect()
}

/// What follows `cited` in a comment, with line breaks, comment markers and
/// punctuation between them skipped: `method.md\n//! §6` reads as `§6`.
fn after_citation(text: &str, cited: &str) -> Vec<String> {
    text.match_indices(cited)
        .map(|(i, _)| {
            let rest = &text[i + cited.len()..];
            let trimmed = rest.trim_start_matches(|c: char| c.is_whitespace() || "/!,".contains(c));
            trimmed.chars().take(60).collect()
        })
        .collect()
}

/// The method sections one citation names: `§6`, `§2–4`, `§2–§4`, `§4.3`
/// (its section 4), or a heading's name `§"Uncertainty"`.
enum Cited {
    Number(u32),
    Name(String),
}

fn method_sections(tail: &str) -> Vec<Cited> {
    let Some(rest) = tail.strip_prefix('§') else {
        return Vec::new();
    };
    if let Some(named) = rest.strip_prefix('"') {
        let name = named.split('"').next().unwrap_or_default();
        return vec![Cited::Name(name.to_string())];
    }
    let digits = |s: &str| {
        s.chars()
            .take_while(char::is_ascii_digit)
            .collect::<String>()
    };
    let first = digits(rest);
    let Ok(n) = first.parse::<u32>() else {
        return Vec::new();
    };
    let mut out = vec![Cited::Number(n)];
    if let Some(range_end) = rest[first.len()..].strip_prefix('–') {
        if let Ok(m) = digits(range_end.trim_start_matches('§')).parse::<u32>() {
            out.push(Cited::Number(m));
        }
    }
    out
}

/// This file names the documents it checks; it cites nothing.
fn is_this_file(path: &Path) -> bool {
    path.ends_with("tests/it/docs.rs")
}

#[test]
fn every_method_section_the_code_cites_exists() {
    let method = read("docs/method.md");
    let headings: Vec<&str> = method.lines().filter(|l| l.starts_with('#')).collect();
    let has_number = |n: u32| headings.iter().any(|h| h.starts_with(&format!("## {n}. ")));
    let has_name = |name: &str| headings.iter().any(|h| h.contains(name));
    let mut cited = 0;
    for (path, text) in rust_sources().into_iter().filter(|(p, _)| !is_this_file(p)) {
        for tail in after_citation(&text, "method.md") {
            for section in method_sections(&tail) {
                cited += 1;
                match section {
                    Cited::Number(n) => {
                        assert!(
                            has_number(n),
                            "{}: method.md §{n} has no section",
                            path.display()
                        )
                    }
                    Cited::Name(name) => assert!(
                        has_name(&name),
                        "{}: method.md §\"{name}\" has no heading",
                        path.display()
                    ),
                }
            }
        }
    }
    assert!(
        cited >= MIN_METHOD_CITATIONS,
        "only {cited} method.md citations found"
    );
}

#[test]
fn every_api_guide_section_the_code_cites_exists() {
    let api = read("docs/api.md").to_lowercase();
    let headings: Vec<&str> = api.lines().filter(|l| l.starts_with('#')).collect();
    let mut cited = 0;
    for (path, text) in rust_sources().into_iter().filter(|(p, _)| !is_this_file(p)) {
        for tail in after_citation(&text, "api.md") {
            let Some(quoted) = tail.strip_prefix('"') else {
                continue;
            };
            let name = quoted.split('"').next().unwrap_or_default().to_lowercase();
            cited += 1;
            assert!(
                headings.iter().any(|h| h.contains(&name)),
                "{}: api.md \"{name}\" has no heading",
                path.display()
            );
        }
    }
    assert!(
        cited >= MIN_API_CITATIONS,
        "only {cited} api.md citations found"
    );
}

#[test]
fn no_document_is_a_session_diary() {
    assert!(!repo().join("docs/notes").exists(), "docs/notes/ is back");
    let mut docs = Vec::new();
    files(&repo().join("docs"), &["md", "py", "txt"], &mut docs);
    for doc in &docs {
        let name = doc
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default()
            .to_lowercase();
        let after_session = name.split("session").skip(1);
        let numbered = after_session
            .into_iter()
            .any(|s| s.starts_with(|c: char| c.is_ascii_digit()));
        assert!(!numbered, "{name} is named after a work session");
    }
    let is_date = |w: &str| {
        let b = w.as_bytes();
        b.len() >= 10 && b[..4].iter().all(u8::is_ascii_digit) && b[4] == b'-' && b[7] == b'-'
    };
    for doc in ["ARCHITECTURE.md", "BENCHMARKS.md"] {
        for heading in read(doc)
            .lines()
            .filter(|l| l.starts_with("## ") || l.starts_with("### "))
        {
            let dated = heading
                .split(|c: char| c.is_whitespace() || c == '(')
                .any(is_date);
            assert!(
                !heading.contains("Session") && !dated,
                "{doc}: section by session or date: {heading}"
            );
        }
    }
    let lines = read("ARCHITECTURE.md").lines().count();
    assert!(
        lines <= MAX_ARCHITECTURE_LINES,
        "ARCHITECTURE.md is {lines} lines"
    );
}

#[test]
fn no_committed_text_holds_a_machine_path() {
    // Built from parts so that this file does not match itself.
    let machine_roots: Vec<String> = ["work", "home", "root"]
        .iter()
        .map(|r| format!("/{r}/"))
        .collect();
    let mut paths = vec![
        repo().join("README.md"),
        repo().join("ARCHITECTURE.md"),
        repo().join("BENCHMARKS.md"),
    ];
    for dir in SCANNED {
        files(&repo().join(dir), &TEXT_EXTENSIONS, &mut paths);
    }
    assert!(paths.len() > 500, "only {} files scanned", paths.len());
    for path in paths {
        let text = fs::read_to_string(&path).unwrap_or_default();
        for root in &machine_roots {
            assert!(
                !text.contains(root.as_str()),
                "{} holds a machine path ({root}…)",
                path.display()
            );
        }
    }
}
