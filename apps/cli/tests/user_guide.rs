//! The user guide's examples run (issue 39 item 2): every fenced block of `docs/guide/**/*.md`
//!
//! * ` ```toml ` must parse as TOML. Marked with `<!-- check: flowmbd-<app> <study> -->` on the
//!   line before the fence, it is also read by that study (`--config block --print-config`,
//!   exit 0): every key exists and every value is valid. Marked with
//!   `<!-- file: NAME -->`, it is a file the chapter's commands use: a path that exists in the
//!   repository must hold exactly the block's text (the guide shows the shipped example as it
//!   is); any other name is written to a scratch folder and the chapter's commands get that path.
//! * ` ```sh ` lines starting with `flowmbd-` (continuation lines joined, a trailing `# comment`
//!   and anything after `|` dropped) are run with the binaries next to this test executable
//!   (`target/<profile>/flowmbd-*`), from the repository root, with `--quiet` and with `--out`
//!   pointed to a scratch folder (appended when absent, replaced when given), and must exit 0.
//!   A command whose binary has not been built is skipped with a message (`cargo test --release
//!   --workspace`, as the CI runs it, builds them all). In a debug build only the
//!   `--print-config` / `--help` commands run (the studies take minutes unoptimised); set
//!   `FLOWMBD_GUIDE_ALL=1` to run them all.
//!
//! Blocks that are not meant to run (long studies, Python) use ` ```text ` or ` ```python `.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// The binaries a guide command may call.
const APPS: &[&str] = &[
    "flowmbd-belt",
    "flowmbd-string",
    "flowmbd-tire",
    "flowmbd-reduce",
    "flowmbd-beam",
];

/// One fenced block: language, text, the marker comment before it, and where it starts.
#[derive(Debug)]
struct Block {
    lang: String,
    text: String,
    marker: Option<(String, String)>,
    line: usize,
}

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("repository root")
}

/// The Markdown files under `dir`, sorted.
fn markdown_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "md") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// `<!-- key: value -->` on a line.
fn marker(line: &str) -> Option<(String, String)> {
    let inner = line
        .trim()
        .strip_prefix("<!--")?
        .strip_suffix("-->")?
        .trim();
    let (k, v) = inner.split_once(':')?;
    Some((k.trim().to_string(), v.trim().to_string()))
}

/// The fenced blocks of a Markdown text.
fn blocks(text: &str) -> Vec<Block> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let t = lines[i].trim_start();
        if let Some(info) = t.strip_prefix("```") {
            let lang = info.split([' ', ',', '{']).next().unwrap_or("").to_string();
            let prev = lines[..i].iter().rev().find(|l| !l.trim().is_empty());
            let mk = prev.and_then(|l| marker(l));
            let start = i + 1;
            let mut j = start;
            while j < lines.len() && !lines[j].trim_start().starts_with("```") {
                j += 1;
            }
            assert!(j < lines.len(), "unclosed code fence at line {}", i + 1);
            let mut body = lines[start..j].join("\n");
            body.push('\n');
            out.push(Block {
                lang,
                text: body,
                marker: mk,
                line: i + 1,
            });
            i = j + 1;
        } else {
            i += 1;
        }
    }
    out
}

/// Shell-like words of a command line (single and double quotes, no expansions).
fn words(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut in_word = false;
    let mut quote: Option<char> = None;
    for c in line.chars() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => cur.push(c),
            None if c == '\'' || c == '"' => {
                quote = Some(c);
                in_word = true;
            }
            None if c.is_whitespace() => {
                if in_word {
                    out.push(std::mem::take(&mut cur));
                    in_word = false;
                }
            }
            None => {
                cur.push(c);
                in_word = true;
            }
        }
    }
    if in_word {
        out.push(cur);
    }
    out
}

/// The `flowmbd-*` commands of a `sh` block: continuation lines joined, a trailing comment and
/// a pipe dropped, white space collapsed (quoted arguments keep single spaces only).
fn commands(block: &str) -> Vec<String> {
    let mut joined = Vec::new();
    let mut cur = String::new();
    for l in block.lines() {
        let l = l.trim_end();
        if let Some(head) = l.strip_suffix('\\') {
            cur.push_str(head);
            cur.push(' ');
        } else {
            cur.push_str(l);
            joined.push(std::mem::take(&mut cur));
        }
    }
    joined
        .into_iter()
        .map(|l| l.trim().to_string())
        .filter(|l| l.starts_with("flowmbd-"))
        .map(|l| {
            let l = l.split(" #").next().unwrap_or(&l);
            let l = l.split(" | ").next().unwrap_or(l);
            l.split_whitespace().collect::<Vec<_>>().join(" ")
        })
        .collect()
}

/// The folder of the binaries: this test runs from `target/<profile>/deps/`.
fn bin_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable");
    exe.parent()
        .and_then(Path::parent)
        .expect("target/<profile>")
        .to_path_buf()
}

fn scratch(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("user-guide-{}", std::process::id()))
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The relative file paths of a block's `[tire.import]` table (empty without one).
fn import_files(table: &toml::Table) -> Vec<String> {
    let import = table
        .get("tire")
        .and_then(|t| t.get("import"))
        .and_then(|t| t.as_table());
    import
        .map(|t| {
            t.iter()
                .filter(|(k, _)| k.as_str() != "format")
                .filter_map(|(_, v)| v.as_str())
                .filter(|p| Path::new(p).is_relative() && !p.contains(".."))
                .map(str::to_string)
                .collect()
        })
        .unwrap_or_default()
}

/// Run `args` of the binary `app` from the repository root with the cache folder in `home`;
/// `Err(message)` on a non-zero exit.
fn run(app: &str, args: &[String], home: &Path) -> Result<std::time::Duration, String> {
    run_in(app, args, home, &repo_root())
}

/// [`run`] from the folder `cwd`.
fn run_in(
    app: &str, args: &[String], home: &Path, cwd: &Path,
) -> Result<std::time::Duration, String> {
    let exe = bin_dir().join(format!("{app}{}", std::env::consts::EXE_SUFFIX));
    let t0 = Instant::now();
    let out = Command::new(&exe)
        .args(args)
        .current_dir(cwd)
        .env("XDG_CACHE_HOME", home)
        .output()
        .map_err(|e| format!("{}: {e}", exe.display()))?;
    if out.status.success() {
        Ok(t0.elapsed())
    } else {
        Err(format!(
            "exit {:?}\n{}",
            out.status.code(),
            String::from_utf8_lossy(&out.stderr)
        ))
    }
}

fn have(app: &str) -> bool {
    bin_dir()
        .join(format!("{app}{}", std::env::consts::EXE_SUFFIX))
        .is_file()
}

#[test]
fn user_guide_blocks_parse_and_commands_run() {
    let root = repo_root();
    let guide = root.join("docs/guide");
    let files = markdown_files(&guide);
    assert!(!files.is_empty(), "no Markdown under {}", guide.display());
    let all = std::env::var_os("FLOWMBD_GUIDE_ALL").is_some() || !cfg!(debug_assertions);
    let work = scratch("work");
    let mut failures: Vec<String> = Vec::new();
    let (mut ran, mut tomls, mut skipped) = (0usize, 0usize, 0usize);
    for md in &files {
        let rel = md.strip_prefix(&root).unwrap().display().to_string();
        let text = std::fs::read_to_string(md).unwrap();
        // files the chapter declares, by the name its commands use
        let mut declared: HashMap<String, PathBuf> = HashMap::new();
        for (k, b) in blocks(&text).into_iter().enumerate() {
            let at = format!("{rel}:{}", b.line);
            match b.lang.as_str() {
                "toml" => {
                    tomls += 1;
                    if let Err(e) = toml::from_str::<toml::Table>(&b.text) {
                        failures.push(format!("{at}: the toml block does not parse: {e}"));
                        continue;
                    }
                    let block_file = work.join(format!("block-{}-{k}.toml", md_stem(md)));
                    std::fs::write(&block_file, b.text.as_str()).unwrap();
                    match &b.marker {
                        Some((key, name)) if key == "file" => {
                            let in_repo = root.join(name);
                            if in_repo.is_file() {
                                let shipped = std::fs::read_to_string(&in_repo).unwrap();
                                if shipped.trim_end() != b.text.trim_end() {
                                    failures.push(format!(
                                        "{at}: the block differs from {name} (the guide shows the shipped file as it is)"
                                    ));
                                }
                            } else {
                                let p = work.join(name);
                                if let Some(d) = p.parent() {
                                    std::fs::create_dir_all(d).unwrap();
                                }
                                std::fs::write(&p, b.text.as_str()).unwrap();
                                declared.insert(name.clone(), p);
                            }
                        }
                        Some((key, study)) if key == "check" => {
                            let w = words(study);
                            let (app, rest) = w.split_first().expect("check: app study");
                            if !APPS.contains(&app.as_str()) {
                                failures.push(format!("{at}: check names no flowmbd app: {study}"));
                                continue;
                            }
                            if !have(app) {
                                eprintln!(
                                    "SKIP {at}: {app} is not built ({})",
                                    bin_dir().display()
                                );
                                skipped += 1;
                                continue;
                            }
                            let mut args: Vec<String> = rest.to_vec();
                            args.extend([
                                "--config".into(),
                                block_file.display().to_string(),
                                "--print-config".into(),
                            ]);
                            // an imported tire's files need only exist for --print-config:
                            // empty stand-ins in a folder of the block's own
                            let dir = scratch(&format!("check-{}-{k}", md_stem(md)));
                            let table: toml::Table = toml::from_str(&b.text).unwrap();
                            for f in import_files(&table) {
                                let p = dir.join(f);
                                if let Some(d) = p.parent() {
                                    std::fs::create_dir_all(d).unwrap();
                                }
                                std::fs::write(p, "").unwrap();
                            }
                            match run_in(app, &args, &work, &dir) {
                                Ok(_) => ran += 1,
                                Err(e) => failures.push(format!(
                                    "{at}: `{study} --config <block> --print-config` failed: {e}"
                                )),
                            }
                        }
                        _ => {}
                    }
                }
                "sh" => {
                    for (c, cmd) in commands(&b.text).into_iter().enumerate() {
                        let w = words(&cmd);
                        let app = w[0].clone();
                        if !APPS.contains(&app.as_str()) {
                            failures.push(format!("{at}: `{cmd}`: no such flowmbd binary"));
                            continue;
                        }
                        if !have(&app) {
                            eprintln!(
                                "SKIP {at}: `{cmd}`: {app} is not built ({})",
                                bin_dir().display()
                            );
                            skipped += 1;
                            continue;
                        }
                        let quick = w.iter().any(|a| a == "--print-config" || a == "--help");
                        if !quick && !all {
                            eprintln!(
                                "SKIP {at}: `{cmd}`: debug build (run with --release or FLOWMBD_GUIDE_ALL=1)"
                            );
                            skipped += 1;
                            continue;
                        }
                        let out = scratch(&format!("out-{}-{k}-{c}", md_stem(md)));
                        let mut args: Vec<String> = Vec::new();
                        let mut it = w[1..].iter();
                        let mut has_out = false;
                        while let Some(a) = it.next() {
                            if a == "--out" {
                                it.next();
                                has_out = true;
                                args.extend(["--out".into(), out.display().to_string()]);
                            } else if let Some(p) = declared.get(a) {
                                args.push(p.display().to_string());
                            } else {
                                args.push(a.clone());
                            }
                        }
                        if !has_out {
                            args.extend(["--out".into(), out.display().to_string()]);
                        }
                        if !args.iter().any(|a| a == "--quiet") && !quick {
                            args.push("--quiet".into());
                        }
                        match run(&app, &args, &work) {
                            Ok(dt) => {
                                ran += 1;
                                eprintln!("ok {at}: `{cmd}` ({:.1} s)", dt.as_secs_f64());
                            }
                            Err(e) => failures.push(format!("{at}: `{cmd}` failed: {e}")),
                        }
                    }
                }
                _ => {}
            }
        }
    }
    eprintln!(
        "user guide: {} files, {tomls} toml blocks, {ran} commands and checks run, {skipped} skipped",
        files.len()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// mdBook's anchor of a heading: lower case, spaces to `-`, other punctuation dropped.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The relative links `](target)` of a Markdown text outside code blocks.
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_code = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            continue;
        }
        let mut rest = line;
        while let Some(k) = rest.find("](") {
            rest = &rest[k + 2..];
            let Some(end) = rest.find(')') else { break };
            let target = &rest[..end];
            if !target.contains("://") && !target.starts_with("mailto:") {
                out.push(target.to_string());
            }
            rest = &rest[end..];
        }
    }
    out
}

// The book's structure, as `mdbook build` checks it (issue 39 item 1: the guide built in CI,
// without installing mdBook): SUMMARY.md lists every chapter of src/ once and only existing
// files, and every relative link of a chapter reaches an existing chapter and, with an
// anchor, one of its headings.
#[test]
fn the_books_summary_and_links_hold() {
    let src = repo_root().join("docs/guide/src");
    let summary = std::fs::read_to_string(src.join("SUMMARY.md")).unwrap();
    let listed: Vec<String> = links(&summary);
    let chapters: Vec<String> = markdown_files(&src)
        .iter()
        .map(|p| p.strip_prefix(&src).unwrap().to_string_lossy().into_owned())
        .filter(|n| n != "SUMMARY.md")
        .collect();
    for c in &chapters {
        let n = listed.iter().filter(|l| *l == c).count();
        assert_eq!(n, 1, "{c} is listed {n} times in SUMMARY.md");
    }
    for l in &listed {
        assert!(
            chapters.contains(l),
            "SUMMARY.md lists {l}, which is not in docs/guide/src"
        );
    }
    let headings = |name: &str| -> Vec<String> {
        std::fs::read_to_string(src.join(name))
            .unwrap()
            .lines()
            .filter(|l| l.starts_with('#'))
            .map(|l| slug(l.trim_start_matches('#')))
            .collect()
    };
    for c in &chapters {
        let text = std::fs::read_to_string(src.join(c)).unwrap();
        for l in links(&text) {
            let (file, anchor) = l.split_once('#').unwrap_or((&l, ""));
            let file = if file.is_empty() { c.as_str() } else { file };
            if !file.ends_with(".md") {
                continue;
            }
            assert!(
                chapters.iter().any(|x| x == file),
                "{c}: link to {file}, no such chapter"
            );
            if !anchor.is_empty() {
                assert!(
                    headings(file).iter().any(|h| h == anchor),
                    "{c}: link to {file}#{anchor}, no such heading"
                );
            }
        }
    }
}

// The guide builds with mdBook (issue 39 item 1), as `mdbook build docs/guide` does, through
// mdBook's own library (no binary to install), into a scratch folder: every chapter of
// SUMMARY.md becomes a page (README.md: index.html), and every heading of a chapter gets the
// anchor our link check above expects (mdBook's slugs, not ours, decide).
#[test]
fn the_book_builds_with_mdbook() {
    let root = repo_root().join("docs/guide");
    let out = scratch("book");
    let mut book = mdbook_driver::MDBook::load(&root)
        .unwrap_or_else(|e| panic!("docs/guide: mdBook cannot load the book: {e:#}"));
    book.config.build.build_dir = out.clone();
    book.build()
        .unwrap_or_else(|e| panic!("docs/guide: mdBook cannot build the book: {e:#}"));
    let src = root.join("src");
    let summary = std::fs::read_to_string(src.join("SUMMARY.md")).unwrap();
    let listed = links(&summary);
    assert!(
        listed.len() >= 5,
        "SUMMARY.md lists {} chapters",
        listed.len()
    );
    for chapter in &listed {
        let page = match chapter.as_str() {
            "README.md" => "index.html".to_string(),
            c => c.replace(".md", ".html"),
        };
        let html = std::fs::read_to_string(out.join(&page))
            .unwrap_or_else(|e| panic!("{chapter}: no page {page} in the built book: {e}"));
        let text = std::fs::read_to_string(src.join(chapter)).unwrap();
        let mut fenced = false;
        for line in text.lines() {
            if line.trim_start().starts_with("```") {
                fenced = !fenced;
            }
            if fenced || !line.starts_with('#') {
                continue;
            }
            let id = slug(line.trim_start_matches('#'));
            assert!(
                html.contains(&format!("id=\"{id}\"")),
                "{chapter}: heading {line:?} has no anchor #{id} in the built {page}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&out);
}

fn md_stem(p: &Path) -> String {
    p.file_stem().unwrap().to_string_lossy().into_owned()
}

#[test]
fn block_and_command_extraction() {
    let md = "text\n<!-- check: flowmbd-belt fead -->\n```toml\n[drive]\ntension = 300.0\n```\n\
              ```sh\nflowmbd-belt fead --rpm 1500 \\\n  --out x   # comment\ncargo build\n\
              flowmbd-tire cleat --print-config | head\n```\n";
    let b = blocks(md);
    assert_eq!(b.len(), 2);
    assert_eq!(b[0].lang, "toml");
    assert_eq!(
        b[0].marker,
        Some(("check".to_string(), "flowmbd-belt fead".to_string()))
    );
    assert_eq!(b[0].text, "[drive]\ntension = 300.0\n");
    let c = commands(&b[1].text);
    assert_eq!(
        c,
        vec![
            "flowmbd-belt fead --rpm 1500 --out x".to_string(),
            "flowmbd-tire cleat --print-config".to_string()
        ]
    );
    assert_eq!(words("a 'b c' \"d\" e"), vec!["a", "b c", "d", "e"]);
}
