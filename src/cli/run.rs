//! `nctrans run FILE`: runs a program in the bundled evaluator and prints its canonical
//! trace (text or JSON lines); a large file is run as a stream in constant memory.

use super::args::{load_for_run, EvalOpts, InputOpts};
use super::stream::{self, ProgressLine, Source};
use nctrans::diag;
use nctrans::dialect::Dialect;
use nctrans::span::SourceDb;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

/// Runs `nctrans run`.
pub fn run(
    path: &PathBuf,
    from: Option<Dialect>,
    eval: &EvalOpts,
    format: nctrans::eval::Format,
    (quiet, expand_cycles): (bool, bool),
    input: &InputOpts,
) -> ExitCode {
    use nctrans::eval::{self, Ending};
    // The streamed run writes `cycle` events only; an expanded run reads the whole file.
    if !expand_cycles && stream::wanted(path, input) {
        if let Some(code) = run_streamed(path, from, eval, format, quiet, input.encoding) {
            return code;
        }
    }
    let mut db = SourceDb::new();
    let (unit, mut opts) = match load_for_run(&mut db, path, from, eval, input) {
        Ok(x) => x,
        Err(code) => return code,
    };
    if expand_cycles {
        // The retract amounts are machine data: the profile's, when the folder has one.
        let project = std::path::Path::new(nctrans::config::FILE_NAME);
        let config = if project.is_file() {
            match nctrans::config::Config::load(project) {
                Ok(c) => c,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            }
        } else {
            nctrans::config::Config::default()
        };
        opts.expand_cycles = Some(config.cycle_retracts(unit.dialect));
    }
    let main_file = db.get(unit.file).clone();
    let main_id = unit.file;
    let line_of = move |o: eval::Origin| (o.file == main_id).then(|| main_file.line_col(o.span.lo).0);
    let out = std::io::BufWriter::new(std::io::stdout().lock());
    let mut callees = eval::DirCallees { semantics: opts.semantics.clone() };
    let (outcome, write_error) = if quiet {
        (eval::run(&mut db, &unit, &mut callees, &opts, &mut eval::NullSink), None)
    } else {
        let mut sink = eval::WriterSink::new(out, format, Box::new(line_of));
        let o = eval::run(&mut db, &unit, &mut callees, &opts, &mut sink);
        let err = sink.error.take().or_else(|| sink.out.flush().err());
        (o, err)
    };
    eprint!("{}", diag::render(&db, &outcome.diags));
    if let Some(e) = write_error {
        eprintln!("error: writing the trace: {e}");
        return ExitCode::from(2);
    }
    match outcome.ending {
        Ending::End(_) | Ending::Stopped => ExitCode::SUCCESS,
        Ending::Error => ExitCode::from(1),
        Ending::Alarm { .. } => ExitCode::from(3),
        Ending::Limit { .. } => ExitCode::from(4),
    }
}

/// `nctrans run` streamed.
fn run_streamed(
    path: &Path,
    from: Option<Dialect>,
    eval: &EvalOpts,
    format: nctrans::eval::Format,
    quiet: bool,
    forced: Option<&'static encoding_rs::Encoding>,
) -> Option<ExitCode> {
    use nctrans::eval::{self, Ending};
    let mut src = Source::new(path, forced)?;
    let ix = match stream::scan(&mut src, from, 0)? {
        Ok(ix) => ix,
        Err(code) => return Some(code),
    };
    let mut opts = match stream::run_options(&ix, path, eval) {
        Ok(o) => o,
        Err(code) => return Some(code),
    };
    // The profile the file was read with (the library's global user data with it), as the
    // whole-file run has it (`args::load_for_run`).
    opts.semantics = Some(ix.opts.semantics.clone());
    let mut db = SourceDb::new();
    let main_id = db.add(path.display().to_string(), String::new());
    let size = ix.size;
    let pager = std::rc::Rc::new(nctrans::stream::paged::Pager::new(Arc::new(ix)));
    let progress_on = ProgressLine::new("running", size).on;
    if progress_on {
        let mut l = ProgressLine::new("running", size);
        pager.set_progress(Box::new(move |p| l.update(p)));
    }
    let p2 = std::rc::Rc::clone(&pager);
    let line_of = move |o: eval::Origin| (o.file == main_id).then(|| p2.line_of(o.span.lo)).flatten();
    let mut callees = eval::DirCallees { semantics: opts.semantics.clone() };
    let (outcome, write_error) = if quiet {
        (eval::run_stream(&mut db, pager, &mut callees, &opts, &mut eval::NullSink), None)
    } else {
        let out = std::io::BufWriter::with_capacity(1 << 16, std::io::stdout().lock());
        let mut sink = eval::WriterSink::new(out, format, Box::new(line_of));
        sink.block_lines = Some(main_id);
        let o = eval::run_stream(&mut db, pager, &mut callees, &opts, &mut sink);
        let err = sink.error.take().or_else(|| sink.out.flush().err());
        (o, err)
    };
    if progress_on {
        eprint!("\r{:70}\r", "");
    }
    eprint!("{}", nctrans::excerpt::render(&db, &outcome.diags, &[(main_id, src.path())]));
    if let Some(e) = write_error {
        eprintln!("error: writing the trace: {e}");
        return Some(ExitCode::from(2));
    }
    Some(match outcome.ending {
        Ending::End(_) | Ending::Stopped => ExitCode::SUCCESS,
        Ending::Error => ExitCode::from(1),
        Ending::Alarm { .. } => ExitCode::from(3),
        Ending::Limit { .. } => ExitCode::from(4),
    })
}
