//! Every command-line example in the README and the user's guide runs, so that the docs cannot
//! drift from the program: each line of a ```sh block that starts with `irradiant ` (or
//! `./run render`) is run in order, in one folder a document, shrunk to a size the software
//! adapter renders in moments — the image, the samples, the frames and the light-field bakes
//! made small, `bench` in its smoke mode — but with every flag and technique spec as written.
//! A flag or spec the program no longer takes fails here, naming the document and the line.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::*;

/// The image every example renders: the smallest that still has a G-buffer pyramid of a few
/// levels for SSIL.
const TINY_SIZE: &str = "32x24";

/// A light-field bake the software adapter affords in a second: 2×2×2 probes of 32² maps (the
/// smallest the min-mip's factor of 16 allows twice), one bounce.
const TINY_BAKE: [(&str, i64); 6] = [
    ("resolution", 32),
    ("prefilter_resolution", 8),
    ("irradiance_texels", 8),
    ("distance_texels", 8),
    ("bounces", 1),
    ("emitter_samples", 1),
];

/// The runnable example lines of a Markdown file, with their line numbers.
fn examples(markdown: &str) -> Vec<(usize, String)> {
    let mut in_sh = false;
    let mut found = Vec::new();
    for (number, line) in markdown.lines().enumerate() {
        let trimmed = line.trim();
        if let Some(info) = trimmed.strip_prefix("```") {
            in_sh = !in_sh && matches!(info.trim(), "sh" | "bash" | "shell");
            continue;
        }
        if in_sh && (trimmed.starts_with("irradiant ") || trimmed.starts_with("./run render")) {
            found.push((number + 1, without_comment(trimmed).to_owned()));
        }
    }
    found
}

/// The line up to a `#` that starts a shell comment (outside quotes, after a space).
fn without_comment(line: &str) -> &str {
    let (mut single, mut double) = (false, false);
    let mut previous = ' ';
    for (i, c) in line.char_indices() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            '#' if !single && !double && previous.is_whitespace() => return line[..i].trim_end(),
            _ => {}
        }
        previous = c;
    }
    line
}

/// A spec with the light field's bake made tiny (other techniques unchanged).
fn shrink_spec(spec: &str) -> String {
    let (name, inner) = match spec.split_once('{') {
        Some((name, rest)) => (name.trim(), rest.trim_end().trim_end_matches('}')),
        None => (spec.trim(), ""),
    };
    if !name.starts_with("lightfield") {
        return spec.to_owned();
    }
    let mut table: toml::Table = toml::from_str(&format!("v = {{{inner}}}"))
        .ok()
        .and_then(|t: toml::Table| t.get("v").and_then(|v| v.as_table()).cloned())
        .unwrap_or_default();
    let bake = table
        .entry("bake")
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    if let toml::Value::Table(bake) = bake {
        for (key, value) in TINY_BAKE {
            bake.insert(key.into(), value.into());
        }
        let probes = toml::Value::Array(vec![2.into(), 2.into(), 2.into()]);
        bake.insert("probe_counts".into(), probes);
    }
    format!("{name}{}", toml::Value::Table(table))
}

/// A comma-separated list of specs, each shrunk (`all` spelled out first).
fn shrink_spec_list(list: &str) -> String {
    let mut specs = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (i, c) in list.char_indices() {
        match c {
            '{' | '[' => depth += 1,
            '}' | ']' => depth -= 1,
            ',' if depth == 0 => {
                specs.push(&list[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    specs.push(&list[start..]);
    let names = irradiant::registry::names();
    let specs: Vec<&str> = if specs.iter().any(|s| s.trim() == "all") {
        names
    } else {
        specs
    };
    specs
        .iter()
        .map(|s| shrink_spec(s))
        .collect::<Vec<_>>()
        .join(",")
}

/// Flags naming a file or folder a command writes: relative ones go to the test's scratch
/// folder instead of the repository (`--dump-atlas .` included).
const OUTPUT_FLAGS: [&str; 5] = [
    "--out",
    "--json",
    "--save-camera",
    "--dump-atlas",
    "--cache",
];

/// Flags naming a file a command reads, which an earlier example may have written: relative
/// ones that are not in the repository (a manifest read as a camera file is) are read from the
/// scratch folder.
const READ_BACK_FLAGS: [&str; 2] = ["--camera-from", "--settings"];

/// The arguments with every relative output under `scratch`; a render with no --out writes
/// there too.
fn redirect_outputs(mut args: Vec<String>, root: &Path, scratch: &Path) -> Vec<String> {
    for i in 1..args.len() {
        let flag = args[i - 1].as_str();
        let relative = Path::new(&args[i]).is_relative();
        let written = OUTPUT_FLAGS.contains(&flag);
        let read_back = READ_BACK_FLAGS.contains(&flag) && !root.join(&args[i]).exists();
        if relative && (written || read_back) {
            args[i] = scratch.join(&args[i]).to_string_lossy().into_owned();
        }
    }
    if args.first().is_some_and(|c| c == "render") && !args.iter().any(|a| a == "--out") {
        args.extend([
            "--out".into(),
            scratch.join("irradiant.png").to_string_lossy().into_owned(),
        ]);
    }
    args
}

/// The example's arguments as the test runs them: tiny sizes, few samples and frames.
fn shrink(words: Vec<String>) -> Vec<String> {
    let command = words.first().cloned().unwrap_or_default();
    let mut out = Vec::new();
    let mut words = words.into_iter().peekable();
    let mut has_size = false;
    while let Some(word) = words.next() {
        let (flag, inline) = match word.split_once('=').filter(|_| word.starts_with("--")) {
            Some((f, v)) => (f.to_owned(), Some(v.to_owned())),
            _ => (word.clone(), None),
        };
        let takes_value = matches!(
            flag.as_str(),
            "--size"
                | "--spp"
                | "--reference-spp"
                | "--sequence-spp"
                | "--frames"
                | "--every"
                | "--over-time"
                | "--probe-samples"
                | "--query-samples"
                | "--average"
                | "--rays"
                | "--iterations"
                | "--settle"
                | "--technique"
                | "--techniques"
                | "--difference-from"
        );
        if !takes_value {
            out.push(word);
            continue;
        }
        let value = inline.or_else(|| words.next()).unwrap_or_default();
        let small = match (command.as_str(), flag.as_str()) {
            (_, "--size") => {
                has_size = true;
                TINY_SIZE.into()
            }
            (_, "--spp" | "--sequence-spp") => "2".into(),
            (_, "--reference-spp") => "4".into(),
            ("soak", "--frames") => "4".into(),
            (_, "--frames") => "2".into(),
            ("soak", "--every" | "--settle") => "2".into(),
            (_, "--every") => "1".into(),
            (_, "--over-time") => "3".into(),
            (_, "--probe-samples" | "--query-samples" | "--average") => "1".into(),
            (_, "--rays") => "256".into(),
            (_, "--iterations") => "1".into(),
            (_, "--technique") => shrink_spec(&value),
            (_, "--techniques" | "--difference-from") => shrink_spec_list(&value),
            _ => value,
        };
        out.extend([flag, small]);
    }
    let renders = matches!(
        command.as_str(),
        "render" | "compare" | "soak" | "oracle" | "agreement" | "view"
    );
    // The viewer draws one frame into a texture: the test has no display.
    if command == "view" && !out.iter().any(|w| w == "--offscreen") {
        out.push("--offscreen".into());
    }
    if renders && !has_size {
        out.extend(["--size".into(), TINY_SIZE.into()]);
    }
    // The commands that simulate frames run 2 (soak 4), whatever their default.
    if matches!(command.as_str(), "render" | "compare" | "oracle")
        && !out.iter().any(|w| w == "--frames")
    {
        out.extend(["--frames".into(), "2".into()]);
    }
    if command == "oracle" {
        for flag in ["--average", "--probe-samples", "--query-samples"] {
            if !out.iter().any(|w| w == flag) {
                out.extend([flag.into(), "1".into()]);
            }
        }
    }
    if command == "compare" && !out.iter().any(|w| w == "--reference-spp") {
        out.extend(["--reference-spp".into(), "4".into()]);
    }
    // Four frames do not converge: a still soak's drift check is the soak test's, not this one's.
    if command == "soak" && out.iter().any(|w| w == "--still") {
        out.extend(["--drift".into(), "1000".into()]);
    }
    if command == "soak" && !out.iter().any(|w| w == "--settle") {
        out.extend(["--settle".into(), "2".into()]);
    }
    if command == "soak" && !out.iter().any(|w| w == "--frames") {
        out.extend(["--frames".into(), "4".into(), "--every".into(), "2".into()]);
    }
    if command == "bench" && !out.iter().any(|w| w == "--smoke") {
        out.push("--smoke".into());
    }
    if command == "render" && !out.iter().any(|w| w == "--technique" || w == "--spp") {
        // A render without --technique is DDGI's unless a manifest names another; --spp only
        // reaches the path tracer, so it may stand in either case.
        out.extend(["--spp".into(), "2".into()]);
    }
    out
}

/// The folder Mesa keeps its compiled shaders under for this process, as MESA_SHADER_CACHE_DIR
/// names one (Mesa adds `mesa_shader_cache` itself): MESA_SHADER_CACHE_DIR, else
/// $XDG_CACHE_HOME, else ~/.cache. The examples' XDG_CACHE_HOME moves irradiant's caches into
/// the scratch folder, and would move Mesa's with them: each document then compiled every
/// pipeline cold, which on lavapipe is most of a run (`render --preset quality` at 32×24: 53 s
/// cold against 5 s from the cache the other tests fill).
fn mesa_shader_cache() -> Option<PathBuf> {
    let var = |name| {
        std::env::var_os(name)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    // Absolute, as the examples run from the repository's root rather than this folder.
    var("MESA_SHADER_CACHE_DIR")
        .or_else(|| var("XDG_CACHE_HOME"))
        .or_else(|| var("HOME").map(|home| home.join(".cache")))
        .and_then(|folder| std::path::absolute(folder).ok())
}

/// Runs every example of one document, in order, from the repository's root, its outputs in a
/// folder of its own.
fn run_examples_of(document: &str) {
    run_examples_between(document, None, None);
}

/// The line number of the heading of `document` that starts with `heading`.
fn heading_line(document: &str, text: &str, heading: &str) -> usize {
    text.lines()
        .position(|line| line.starts_with(heading))
        .map(|index| index + 1)
        .unwrap_or_else(|| panic!("{document} has no heading `{heading}…`: the test splits there"))
}

/// Runs the examples of `document` from the heading that starts with `from` (else the start) to
/// the one that starts with `to` (else the end): a part of a long document, so that its parts
/// run side by side on the test threads. No example of a part may read another part's output.
fn run_examples_between(document: &str, from: Option<&str>, to: Option<&str>) {
    // Run from the repository's root, as a reader would: scene paths are relative to it.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap();
    let path = root.join(document);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{document}: {e}"));
    let first = from.map_or(0, |h| heading_line(document, &text, h));
    let last = to.map_or(usize::MAX, |h| heading_line(document, &text, h));
    let lines: Vec<_> = examples(&text)
        .into_iter()
        .filter(|(number, _)| (first..last).contains(number))
        .collect();
    assert!(
        lines.len() >= 3,
        "{document} shows {} command-line examples here: the test reads ```sh blocks",
        lines.len()
    );
    let dir = scratch(&format!("docs-{}-{first}", document.replace('/', "-")));
    // The reference and bake caches go into the scratch folder, not the user's.
    let cache: PathBuf = dir.join("cache");
    let shader_cache = mesa_shader_cache();
    for (number, line) in lines {
        let words = shlex::split(&line)
            .unwrap_or_else(|| panic!("{document}:{number}: unbalanced quotes in `{line}`"));
        // `irradiant render …` and `./run render …` alike: the command and its flags.
        let args = redirect_outputs(shrink(words[1..].to_vec()), &root, &dir);
        let start = std::time::Instant::now();
        let mut command = Command::new(env!("CARGO_BIN_EXE_irradiant"));
        command
            .args(&args)
            .current_dir(&root)
            .env("XDG_RUNTIME_DIR", "/tmp")
            .env("XDG_CACHE_HOME", &cache);
        if let Some(shaders) = &shader_cache {
            command.env("MESA_SHADER_CACHE_DIR", shaders);
        }
        let output = command.output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        eprintln!(
            "{document}:{number}: {:.1} s",
            start.elapsed().as_secs_f64()
        );
        if !has_adapter(output.status.success(), &stderr) {
            return;
        }
        assert!(
            output.status.success() && !stderr.contains("panicked"),
            "{document}:{number}: `{line}` failed (run as {args:?}):\n{stderr}"
        );
        // An example that warns of an unknown key shows a setting the program does not have.
        assert!(
            !stderr.contains("unknown setting"),
            "{document}:{number}: `{line}` names a setting the program does not know:\n{stderr}"
        );
    }
}

#[test]
fn every_example_in_the_readme_runs() {
    run_examples_of("README.md");
}

/// The guide in two parts that run side by side (their examples took 196 s one after another
/// on lavapipe, most of it one process at a time on one of two cores). No example from section
/// 9 on reads an earlier one's output: the camera file and the saved probes are read within
/// their own sections (7 and 3).
const GUIDE_SPLIT: &str = "## 9. Timing";

#[test]
fn every_example_in_the_guide_up_to_timing_runs() {
    run_examples_between("docs/guide.md", None, Some(GUIDE_SPLIT));
}

#[test]
fn every_example_in_the_guide_from_timing_on_runs() {
    run_examples_between("docs/guide.md", Some(GUIDE_SPLIT), None);
}

#[test]
fn examples_are_found_and_shrunk_as_the_docs_write_them() {
    let markdown = "text\n```sh\nirradiant render --scene cornell --size 640x480 # a comment\n\
                    ./run test\n```\n```toml\nirradiant = 1\n```\n```sh\n./run render\n```\n";
    let found = examples(markdown);
    assert_eq!(
        found,
        [
            (
                3,
                "irradiant render --scene cornell --size 640x480".to_owned()
            ),
            (10, "./run render".to_owned())
        ]
    );
    let words = |s: &str| shlex::split(s).unwrap()[1..].to_vec();
    let shrunk = shrink(words(
        "irradiant render --technique 'lightfield{bake.resolution = 256}' --size=640x480 --spp 99",
    ));
    assert_eq!(shrunk[0], "render");
    let spec = &shrunk[2];
    assert!(
        spec.starts_with("lightfield{") && spec.contains("resolution = 32"),
        "{spec}"
    );
    assert_eq!(&shrunk[3..7], ["--size", TINY_SIZE, "--spp", "2"]);
    let soak = shrink(words("irradiant soak --techniques all --frames 10000"));
    assert!(soak.contains(&"--settle".to_owned()), "{soak:?}");
    let list = &soak[2];
    assert!(
        list.starts_with("none,") && list.contains("lightfield-naive{"),
        "{list}"
    );
    assert!(shrink(words("irradiant bench")).contains(&"--smoke".to_owned()));
    assert_eq!(without_comment("a 'b # c' # d"), "a 'b # c'");
}
