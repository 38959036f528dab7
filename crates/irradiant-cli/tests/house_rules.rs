//! The house rules that a reader of the repository would otherwise check by hand (issue 37):
//! no source file over 700 lines, no numbered work sessions in what the project says of itself,
//! every relative link of the docs resolving, and the technique trait below the registry.

use std::path::{Path, PathBuf};

/// Longest source file the house allows: past it a file is split along the seams it has.
const MAX_SOURCE_LINES: usize = 700;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

/// Every file under `dir` whose name ends in one of `extensions`, build outputs left out.
fn files(dir: &Path, extensions: &[&str], found: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        if path.is_dir() {
            if !matches!(name.as_str(), "target" | ".git" | "corpus" | "artifacts") {
                files(&path, extensions, found);
            }
        } else if extensions.iter().any(|e| name.ends_with(e)) {
            found.push(path);
        }
    }
}

fn relative(path: &Path) -> String {
    path.strip_prefix(root())
        .unwrap_or(path)
        .display()
        .to_string()
}

#[test]
fn no_source_file_is_longer_than_700_lines() {
    let root = root();
    let mut sources = Vec::new();
    for dir in ["crates", "tools", "fuzz"] {
        files(
            &root.join(dir),
            &[".rs", ".wgsl", ".sh", ".py"],
            &mut sources,
        );
    }
    assert!(sources.len() > 50, "found only {} sources", sources.len());
    let long: Vec<String> = sources
        .iter()
        .filter_map(|path| {
            let lines = std::fs::read_to_string(path).ok()?.lines().count();
            (lines > MAX_SOURCE_LINES).then(|| format!("{} ({lines} lines)", relative(path)))
        })
        .collect();
    assert!(
        long.is_empty(),
        "split these along their seams: {}",
        long.join(", ")
    );
}

/// "session" followed by a number, case aside: how the project must not speak of itself.
fn names_a_numbered_session(line: &str) -> bool {
    let lower = line.to_lowercase();
    lower.match_indices("session").any(|(i, word)| {
        let after = &lower[i + word.len()..];
        let rest = after.trim_start_matches(' ');
        rest.len() < after.len() && rest.starts_with(|c: char| c.is_ascii_digit())
    })
}

#[test]
fn the_project_speaks_of_commits_dates_and_issues_never_numbered_sessions() {
    // Built at run time, so that this file does not name one itself.
    assert!(names_a_numbered_session(&format!(
        "until Session {}, the",
        17
    )));
    assert!(!names_a_numbered_session(
        "a session 's frame; sessions; session.rs"
    ));
    let root = root();
    let mut texts = vec![root.join("README.md"), root.join("BENCHMARKS.md")];
    for dir in ["docs", "crates", "tools", "scenes", "fuzz"] {
        files(
            &root.join(dir),
            &[".md", ".rs", ".wgsl", ".sh", ".py", ".toml"],
            &mut texts,
        );
    }
    let mut found = Vec::new();
    for path in &texts {
        let Ok(text) = std::fs::read_to_string(path) else {
            continue;
        };
        for (number, line) in text.lines().enumerate() {
            if names_a_numbered_session(line) {
                found.push(format!(
                    "{}:{}: {}",
                    relative(path),
                    number + 1,
                    line.trim()
                ));
            }
        }
    }
    assert!(
        found.is_empty(),
        "name a commit, a date or an issue instead:\n{}",
        found.join("\n")
    );
}

/// The targets of a Markdown file's inline links and images: `[text](target)`.
fn link_targets(markdown: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut rest = markdown;
    while let Some(i) = rest.find("](") {
        rest = &rest[i + 2..];
        if let Some(end) = rest.find(')') {
            let target = rest[..end].split_whitespace().next().unwrap_or("");
            targets.push(target.to_owned());
        }
    }
    targets
}

/// Whether git would leave this file out of a commit (false where git is absent).
fn ignored_by_git(path: &Path) -> bool {
    std::process::Command::new("git")
        .arg("-C")
        .arg(root())
        .args(["check-ignore", "-q"])
        .arg(path)
        .status()
        .is_ok_and(|status| status.success())
}

#[test]
fn every_relative_link_in_the_docs_resolves() {
    let root = root();
    let mut pages = vec![root.join("README.md"), root.join("BENCHMARKS.md")];
    files(&root.join("docs"), &[".md"], &mut pages);
    files(&root.join("scenes"), &[".md"], &mut pages);
    let mut broken = Vec::new();
    for page in &pages {
        let text = std::fs::read_to_string(page).unwrap();
        for target in link_targets(&text) {
            let external = target.contains("://") || target.starts_with("mailto:");
            let path = target.split('#').next().unwrap_or("");
            if external || path.is_empty() {
                continue;
            }
            let resolved = page.parent().unwrap().join(path);
            // The papers and scenes beside the repository (../shared) are CI's too.
            if !resolved.exists() {
                broken.push(format!("{}: {target}", relative(page)));
            } else if ignored_by_git(&resolved) {
                // Here on disk, absent from a clean clone.
                broken.push(format!(
                    "{}: {target} (ignored by .gitignore)",
                    relative(page)
                ));
            }
        }
    }
    assert!(pages.len() > 10, "found only {} pages", pages.len());
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_technique_trait_imports_no_technique_and_the_registry_sits_above() {
    let src = root().join("crates/irradiant/src");
    for below in ["technique.rs", "settings.rs"] {
        // Code only: a doc comment may point up to the registry.
        let text: String = std::fs::read_to_string(src.join(below))
            .unwrap()
            .lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect();
        for above in [
            "crate::registry",
            "crate::ddgi",
            "crate::ssil",
            "crate::lightfield",
            "crate::none",
        ] {
            assert!(
                !text.contains(above),
                "{below} imports {above}: the trait and the settings sit below the techniques"
            );
        }
    }
    let registry = std::fs::read_to_string(src.join("registry.rs")).unwrap();
    assert!(
        registry.contains("crate::ddgi::DDGI"),
        "the registry lists the techniques"
    );
}
