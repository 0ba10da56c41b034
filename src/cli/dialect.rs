//! The source dialect of a single-file translation and how it was decided (`--from`, the
//! file's extension, else its content), so a file is never read as the dialect its
//! extension denies, and a file already in the target dialect is told as such.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use std::io::Read;
use std::path::Path;
use std::process::ExitCode;

/// How the source dialect was decided.
pub enum How {
    Flag,
    Extension(String),
    Content,
}

impl How {
    fn says(&self) -> String {
        match self {
            How::Flag => "as given by --from".into(),
            How::Extension(e) => format!("from its extension .{e}"),
            How::Content => "judged from its content, as its extension does not tell".into(),
        }
    }
}

/// The readable name of a dialect in messages.
pub fn title(d: Dialect) -> &'static str {
    match d {
        Dialect::Sinumerik => "Sinumerik",
        Dialect::Fanuc => "FANUC",
    }
}

/// How much of a file the content guess reads (`Dialect::sniff` looks at 400 lines).
const SNIFF_BYTES: u64 = 64 * 1024;

/// The dialect of `path`: `from`, else its extension, else a guess from its first lines.
pub fn source_dialect(path: &Path, from: Option<Dialect>) -> (Dialect, How) {
    if let Some(d) = from {
        return (d, How::Flag);
    }
    if let Some(ext) = path.extension().and_then(|e| e.to_str()) {
        if let Some(d) = Dialect::from_extension(ext) {
            return (d, How::Extension(ext.to_string()));
        }
    }
    let mut head = Vec::new();
    if let Ok(f) = std::fs::File::open(path) {
        let _ = f.take(SNIFF_BYTES).read_to_end(&mut head);
    }
    (Dialect::sniff(&String::from_utf8_lossy(&head)), How::Content)
}

/// Checks that `input` may be translated to `to`: its dialect (decided as
/// [`source_dialect`] says) is the other one. `Err` is the exit code after the message:
/// a program-less file gets its NC145 like every command gives it; else the file's
/// dialect, how that was decided, and the direction asked for.
pub fn check_direction(input: &Path, from: Option<Dialect>, to: Dialect) -> Result<(), ExitCode> {
    let (d, how) = source_dialect(input, from);
    if d != to {
        return Ok(());
    }
    if nctrans::dialect::empty::may_be_program_less(input) {
        if let Ok(bytes) = std::fs::read(input) {
            let mut db = SourceDb::new();
            let l = nctrans::load(&mut db, &input.display().to_string(), &bytes, None);
            let p = nctrans::parse(&db, l.file, d, &ParseOptions::for_dialect(d));
            if p.diags.iter().any(|x| x.code == "NC145") {
                eprint!("{}", nctrans::diag::render(&db, &p.diags));
                return Err(ExitCode::from(1));
            }
        }
    }
    let other = if to == Dialect::Fanuc { Dialect::Sinumerik } else { Dialect::Fanuc };
    eprintln!(
        "error: {} is a {} program ({}), and --to {} translates {} → {}: it is already in the target dialect",
        input.display(),
        title(d),
        how.says(),
        to.name(),
        title(other),
        title(to),
    );
    let hint = match how {
        How::Flag => format!("to translate it to {}: nctrans --to {} {}", title(other), other.name(), input.display()),
        _ => format!(
            "to translate it to {}: nctrans --to {} {}; if it is in fact a {} program, say so: --from {}",
            title(other),
            other.name(),
            input.display(),
            title(other),
            other.name()
        ),
    };
    eprintln!("  = hint: {hint}");
    Err(ExitCode::from(2))
}
