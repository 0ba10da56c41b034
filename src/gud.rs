//! Global user data (GUD): the Siemens definition files (`.DEF`, e.g. `MGUD.DEF` with
//! `DEF NCK REAL INI[160]`) a library keeps beside its programs. They are found for a
//! program (the `[sinumerik] definitions` list, else the nearest folder holding `.DEF` files),
//! read once, and put into the profile (`Semantics::globals`), where the evaluator declares
//! them before a program runs and the translation maps them (`passes::varmap`).

use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::ir::{Def, DefScope, ItemKind, StmtKind};
use crate::span::SourceDb;
use std::path::{Path, PathBuf};

/// How many folders above a program's own are searched for definition files when the
/// search has no library root (a single-file command): the program's folder and its parent.
const LEVELS_WITHOUT_ROOT: usize = 2;

fn is_def_file(p: &Path) -> bool {
    p.is_file() && p.extension().is_some_and(|e| e.eq_ignore_ascii_case("def"))
}

/// The `.DEF` files directly in `dir` and in its `DEF` folder (any case; the control's
/// `_N_DEF_DIR`), sorted by path.
fn def_files_at(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(rd) = std::fs::read_dir(dir) else { return out };
    let mut sub = Vec::new();
    for e in rd.flatten() {
        let p = e.path();
        if is_def_file(&p) {
            out.push(p);
        } else if p.is_dir() && p.file_name().and_then(|n| n.to_str()).is_some_and(|n| n.eq_ignore_ascii_case("def")) {
            sub.push(p);
        }
    }
    for d in sub {
        if let Ok(rd) = std::fs::read_dir(&d) {
            out.extend(rd.flatten().map(|e| e.path()).filter(|p| is_def_file(p)));
        }
    }
    out.sort();
    out
}

/// The definition files that apply to `program`: those of the nearest folder, from the
/// program's own upwards, that holds `.DEF` files (directly or in a `DEF` folder): the
/// program's folder and its parent, and within a batch every folder up to its `root`. A
/// definition file itself has none.
pub fn discover(program: &Path, root: Option<&Path>) -> Vec<PathBuf> {
    if program.extension().is_some_and(|e| e.eq_ignore_ascii_case("def")) {
        return Vec::new();
    }
    // Relative paths are made absolute, so that the search can go above the current folder.
    let program = std::path::absolute(program).unwrap_or_else(|_| program.to_path_buf());
    let mut dir = program.parent();
    let mut level = 0;
    while let Some(d) = dir {
        let found = def_files_at(d);
        if !found.is_empty() {
            return found;
        }
        level += 1;
        // The program's folder and its parent always; within a batch, up to its root.
        let inside_root = root.is_some_and(|r| !same_dir(d, r) && inside(d, r));
        let at_root = level >= LEVELS_WITHOUT_ROOT && !inside_root;
        if at_root {
            break;
        }
        dir = d.parent().filter(|p| !p.as_os_str().is_empty());
    }
    Vec::new()
}

fn inside(dir: &Path, root: &Path) -> bool {
    match (dir.canonicalize(), root.canonicalize()) {
        (Ok(x), Ok(y)) => x.starts_with(y),
        _ => dir.starts_with(root),
    }
}

fn same_dir(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

/// What the definition files of a program hold.
#[derive(Debug, Default)]
pub struct Definitions {
    /// Global user data, in file order.
    pub defs: Vec<Def>,
    /// `DEFINE NAME AS text` macros (names upper case), in file order.
    pub macros: Vec<(String, String)>,
    pub diags: Vec<Diagnostic>,
}

/// The global definitions of `files`, read as Sinumerik into `db`: every `DEF` of a
/// definition file is global user data (`NCK` or `CHAN`; one channel is modelled, so both
/// are one value), every `DEFINE NAME AS text` a macro, which applies to the definition
/// files too (`DEF NCK REAL DEPTH[MAXSTAGE]`). A name defined twice the same way is one
/// variable or macro; defined two ways it is an error (NC503), as is a macro whose text
/// uses another (macros do not nest). Parse errors of a file are returned as they are.
pub fn load(db: &mut SourceDb, files: &[PathBuf], encoding: Option<&'static encoding_rs::Encoding>) -> Definitions {
    let mut out = Definitions::default();
    let mut seen: std::collections::HashMap<String, (crate::ir::DataType, Vec<u32>, String)> = Default::default();
    // The files' texts first: macros apply to every file, wherever they are defined.
    let mut texts = Vec::new();
    for path in files {
        match std::fs::read(path) {
            Ok(bytes) => {
                let name = path.display().to_string();
                let loaded = crate::load(db, &name, &bytes, encoding);
                texts.push((name, loaded.file));
            }
            Err(e) => out.diags.push(
                Diagnostic::error("NC503", format!("cannot read the definition file {}: {e}", path.display()))
                    .hint("check the [sinumerik] definitions list in nctrans.toml"),
            ),
        }
    }
    let mut blanked = Vec::new();
    for (_, file) in &texts {
        let mut text = db.get(*file).text.clone();
        for (name, body, range) in crate::dialect::sinumerik::macros::defines(&text) {
            let span = crate::span::Span::new(range.start as u32, range.end as u32);
            match out.macros.iter().find(|(n, _)| *n == name) {
                Some((_, b)) if *b == body => {}
                Some((_, b)) => out.diags.push(
                    Diagnostic::error("NC503", format!("macro {name} is defined twice, differently"))
                        .primary(*file, span, "defined here")
                        .note(format!("the other definition is `{b}`"))
                        .hint("keep one definition of each macro"),
                ),
                None => out.macros.push((name, body)),
            }
            // The DEFINE line is a definition, not code: blanked, so offsets stay the file's.
            text.replace_range(range.clone(), &" ".repeat(range.len()));
        }
        blanked.push(text);
    }
    for (name, body) in &out.macros {
        let words = body.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'));
        if let Some(inner) = words.into_iter().find(|w| out.macros.iter().any(|(n, _)| n.eq_ignore_ascii_case(w))) {
            out.diags.push(
                Diagnostic::error(
                    "NC503",
                    format!("macro {name} uses macro {}: Sinumerik macros do not nest", inner.to_ascii_uppercase()),
                )
                .hint(format!("write the text of {} into {name}'s definition", inner.to_ascii_uppercase())),
            );
        }
    }
    let mut sem = Semantics::default_for(Dialect::Sinumerik);
    sem.macros = std::sync::Arc::new(out.macros.clone());
    let opts = ParseOptions { semantics: sem };
    for ((name, file), text) in texts.iter().zip(blanked) {
        let src = crate::span::SourceFile::new(name.clone(), text);
        let parsed = crate::dialect::parse(&src, *file, Dialect::Sinumerik, &opts);
        let errors = crate::diag::has_errors(&parsed.diags);
        out.diags.extend(parsed.diags.into_iter().filter(|d| d.is_error()));
        if errors {
            continue;
        }
        for p in &parsed.unit.programs {
            crate::ir::visit::walk_stmts(&p.body, &mut |s| {
                let StmtKind::Block(b) = &s.kind else { return };
                for it in &b.items {
                    let ItemKind::Def(d) = &it.kind else { continue };
                    let mut d = (**d).clone();
                    d.scope = Some(d.scope.unwrap_or(DefScope::Chan));
                    d.vars.retain(|v| match seen.get(&v.name) {
                        None => {
                            seen.insert(v.name.clone(), (d.ty, v.dims.clone(), name.clone()));
                            true
                        }
                        Some((ty, dims, _)) if *ty == d.ty && *dims == v.dims => false,
                        Some((ty, dims, other)) => {
                            let was = if dims.is_empty() { format!("{ty}") } else { format!("{ty} {dims:?}") };
                            out.diags.push(
                                Diagnostic::error("NC503", format!("global user data {} is defined twice, differently", v.name))
                                    .primary(*file, v.span, "defined here")
                                    .note(format!("{other} defines it as {was}"))
                                    .hint("keep one definition file per control, or list the right one in [sinumerik] definitions"),
                            );
                            false
                        }
                    });
                    if !d.vars.is_empty() {
                        out.defs.push(d);
                    }
                }
            });
        }
    }
    out
}

/// Puts the global definitions that apply to `program` into `sem`: `configured` (the
/// `[sinumerik] definitions` list) when it is not empty, else the files [`discover`] finds.
/// Returns the errors met (the caller renders them and stops).
pub fn apply(
    sem: &mut Semantics,
    db: &mut SourceDb,
    program: &Path,
    root: Option<&Path>,
    configured: &[PathBuf],
) -> Vec<Diagnostic> {
    let files = if configured.is_empty() { discover(program, root) } else { configured.to_vec() };
    if files.is_empty() {
        return Vec::new();
    }
    let d = load(db, &files, None);
    sem.globals = std::sync::Arc::new(d.defs);
    sem.macros = std::sync::Arc::new(d.macros);
    d.diags
}

/// The batch root of a file given by its absolute path and its path relative to the root.
pub fn root_of(abs: &Path, rel: &Path) -> Option<PathBuf> {
    let mut root = abs.to_path_buf();
    for _ in rel.components() {
        root = root.parent()?.to_path_buf();
    }
    Some(root)
}
