//! Calls and returns: FANUC G65/G66/M98/M99 with local levels and argument letters,
//! Siemens calls by name with PROC parameters (by value, VAR by reference), repetitions,
//! modal calls, and finding callees through a [`CalleeSource`] the caller provides.

use super::exec::{internal, Flow, Frame, FrameKind, Interp};
use super::expr;
use super::fault::Fault;
use super::flow::Code;
use super::paged::PagedSource;
use super::value::{convert_for, round_half_away, round_to, Value};
use super::vars::{zero_of, Level, Place, Slot};
use crate::diag::Diagnostic;
use crate::dialect::{Dialect, ParseOptions, Semantics};
use crate::ir::{Arg, Call, CallKind, CallTarget, ExprKind, ProgName, Unit};
use crate::span::{FileId, SourceDb, Span};
use std::collections::HashMap;
use std::path::Path;
use std::rc::Rc;

/// The program a call names.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum CalleeName {
    Number(u32),
    Name(String),
}

/// Finds called programs that are not in the file being run. The library does not
/// assume any file layout; [`DirCallees`] is the usual one.
pub trait CalleeSource {
    /// Loads and parses the program `name` called from file `caller`. `Ok(None)`: not
    /// found. `Err`: found but unusable (its diagnostics).
    fn find(
        &mut self,
        db: &mut SourceDb,
        caller: FileId,
        dialect: Dialect,
        name: &CalleeName,
    ) -> Result<Option<Unit>, Diagnostic>;
}

/// No callee outside the file being run.
pub struct NoCallees;

impl CalleeSource for NoCallees {
    fn find(
        &mut self,
        _db: &mut SourceDb,
        _caller: FileId,
        _dialect: Dialect,
        _name: &CalleeName,
    ) -> Result<Option<Unit>, Diagnostic> {
        Ok(None)
    }
}

/// Looks beside the caller's file (its name in the [`SourceDb`] is its path): FANUC
/// `O1234.*`, `1234.*`, `O01234.*` (any case, any extension); Siemens `NAME.SPF` /
/// `NAME.MPF` (any case).
pub struct DirCallees {
    pub semantics: Option<Semantics>,
}

impl CalleeSource for DirCallees {
    fn find(
        &mut self,
        db: &mut SourceDb,
        caller: FileId,
        dialect: Dialect,
        name: &CalleeName,
    ) -> Result<Option<Unit>, Diagnostic> {
        let caller_path = Path::new(&db.get(caller).name).to_path_buf();
        let dir = caller_path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or_else(|| Path::new("."));
        let hit = match name {
            // By file name, then name prefix, then the program number line inside any file.
            CalleeName::Number(n) => super::callee_files::find(dir, Some(&caller_path), *n, &|_| true),
            CalleeName::Name(s) => {
                let Ok(entries) = std::fs::read_dir(dir) else {
                    return Ok(None);
                };
                let mut files: Vec<std::path::PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
                files.sort();
                files.into_iter().find(|f| {
                    let st = f.file_stem().and_then(|s| s.to_str()).unwrap_or("");
                    let ext = f.extension().and_then(|s| s.to_str()).unwrap_or("").to_ascii_lowercase();
                    st.eq_ignore_ascii_case(s) && *f != caller_path && (ext == "spf" || ext == "mpf")
                })
            }
        };
        let Some(path) = hit else {
            return Ok(None);
        };
        let bytes = std::fs::read(&path)
            .map_err(|e| Diagnostic::error("NC401", format!("cannot read {}: {e}", path.display())))?;
        let loaded = crate::load(db, &path.display().to_string(), &bytes, None);
        let opts =
            ParseOptions { semantics: self.semantics.clone().unwrap_or_else(|| Semantics::default_for(dialect)) };
        let parsed = crate::parse(db, loaded.file, dialect, &opts);
        if let Some(first) = parsed.diags.iter().find(|d| d.is_error()) {
            let mut d = first.clone();
            d.notes.push(format!("while loading the called program {}", path.display()));
            return Err(d);
        }
        Ok(Some(parsed.unit))
    }
}

/// A pending G66 / MCALL modal call.
#[derive(Clone, Debug)]
pub struct ModalCall {
    pub code: usize,
    pub fanuc_args: Vec<(u8, Option<f64>)>,
    pub sie_args: Vec<Option<Value>>,
    pub repeat: u64,
    /// The frame depth that set it (kept for diagnostics; the call is modal at every level).
    pub depth: usize,
}

/// Siemens calls that only set up the HMI simulation: no-ops with a note.
const SIMULATION_ONLY: &[&str] = &["WORKPIECE", "SETMS", "TOOLDEF"];

/// Letters whose argument without a decimal point is in least increments (dimensional
/// addresses); D, E, F, H, M, S, T keep their value.
fn letter_scaled(letter: u8) -> Option<bool> {
    match letter {
        b'X' | b'Y' | b'Z' | b'U' | b'V' | b'W' | b'I' | b'J' | b'K' | b'R' | b'Q' => Some(false),
        b'A' | b'B' | b'C' => Some(true),
        _ => None,
    }
}

impl Interp<'_> {
    /// Flattens every program of `unit` and registers it by number/name; `fallback` names
    /// a nameless program (a Siemens file called by its file name).
    pub fn register_unit(&mut self, unit: &Unit, fallback: Option<&CalleeName>) -> Result<Vec<usize>, Diagnostic> {
        let mut ids = Vec::new();
        for p in &unit.programs {
            let code = Code::flatten(unit.file, p)?;
            let id = self.codes.len();
            self.codes.push(Rc::new(code));
            self.params.push(p.params.clone());
            self.save.push(p.save);
            let key = match &p.name {
                Some(ProgName::Number(n)) => Some(CalleeName::Number(*n)),
                Some(ProgName::Name(s)) => Some(CalleeName::Name(s.to_ascii_uppercase())),
                None => fallback.cloned(),
            };
            match key {
                Some(CalleeName::Number(n)) => {
                    self.by_number.entry(n).or_insert(id);
                }
                Some(CalleeName::Name(s)) => {
                    self.by_name.entry(s).or_insert(id);
                }
                None => {}
            }
            if let Some(CalleeName::Name(s)) = fallback {
                self.by_name.entry(s.clone()).or_insert(id);
            }
            ids.push(id);
        }
        Ok(ids)
    }

    /// Registers every program of a streamed file (paged code) like [`Self::register_unit`].
    pub fn register_stream(&mut self, pager: &Rc<dyn PagedSource>) -> Vec<usize> {
        let mut ids = Vec::new();
        for i in 0..pager.programs() {
            let p = pager.program(i);
            let id = self.codes.len();
            self.codes.push(Rc::new(Code::paged(pager.file(), Rc::clone(pager), i)));
            self.params.push(p.params.clone());
            self.save.push(p.save);
            match &p.name {
                Some(ProgName::Number(n)) => {
                    self.by_number.entry(*n).or_insert(id);
                }
                Some(ProgName::Name(s)) => {
                    self.by_name.entry(s.to_ascii_uppercase()).or_insert(id);
                }
                None => {}
            }
            ids.push(id);
        }
        ids
    }

    fn lookup(&self, name: &CalleeName) -> Option<usize> {
        match name {
            CalleeName::Number(n) => self.by_number.get(n).copied(),
            CalleeName::Name(s) => self.by_name.get(s).copied(),
        }
    }

    /// Finds a callee: programs already loaded (other `O` programs of the same file
    /// first), then the [`CalleeSource`].
    pub fn find_code(&mut self, name: &CalleeName, span: Span) -> Result<Option<usize>, Fault> {
        if let Some(id) = self.lookup(name) {
            return Ok(Some(id));
        }
        let caller = self.file();
        let found = self.callees.find(self.db, caller, self.dialect, name).map_err(|d| {
            // The callee's file holds no program: said at this call, which is what stops.
            match d.labels.first().filter(|_| d.code == "NC145") {
                Some(l) => {
                    let key = match name {
                        CalleeName::Number(n) => ProgName::Number(*n),
                        CalleeName::Name(s) => ProgName::Name(s.clone()),
                    };
                    Fault::error(crate::dialect::empty_call::diagnostic(self.db, (caller, span), &key, l.file))
                }
                None => Fault::error(d),
            }
        })?;
        let Some(unit) = found else {
            return Ok(None);
        };
        self.register_unit(&unit, Some(name)).map_err(Fault::error)?;
        Ok(self.lookup(name).or_else(|| {
            // A file found by name whose program carries another number: use its first.
            self.codes.len().checked_sub(unit.programs.len())
        }))
    }

    fn missing(&mut self, name: &CalleeName, span: Span) -> Fault {
        if matches!(name, CalleeName::Name(s) if ["REPOSA", "REPOSL", "REPOSQ", "REPOSQA", "REPOSH", "REPOSHA"].contains(&s.as_str()))
        {
            // Read as a bare name; it is the return to the interruption point of a routine.
            let d = Diagnostic::error(
                "NC639",
                "REPOS (back to the point where an interrupt stopped the axes) is not modelled",
            )
            .primary(self.file(), span, "here")
            .note("the evaluator runs an interrupt routine at the end of a block, where no move was cut short")
            .hint("end the routine with M17: the program goes on with the block after the interrupted one");
            return Fault::error(d);
        }
        if let CalleeName::Name(s) = name {
            if crate::dialect::sinumerik::is_predefined_procedure(s) {
                let d = Diagnostic::error(
                    "NC651",
                    format!("{s} is a predefined procedure of the control that the evaluator does not model"),
                )
                .primary(self.file(), span, "called here")
                .note("it is the control's own function, not a program of the library: no file of that name is looked for")
                .hint("nctrans cannot run or check a program through it; docs/semantics.md lists what is modelled");
                return Fault::error(d);
            }
        }
        let shown = self.note_callee(name);
        let cycle = matches!(name, CalleeName::Name(s) if crate::dialect::sinumerik::cycles::is_package_name(s));
        let d = if cycle {
            Diagnostic::error("NC402", format!("unknown cycle {shown}: the evaluator does not model it"))
                .primary(self.file(), span, "cycle called here")
                .hint("replace the cycle by explicit moves, or provide its program beside this file")
        } else {
            let where_ = match name {
                CalleeName::Number(n) => format!("O{n} in this file, or O{n}.nc / {n}.nc beside it"),
                CalleeName::Name(s) => format!("{s}.SPF or {s}.MPF beside this file (any case)"),
            };
            let d = Diagnostic::error("NC401", format!("called program {shown} not found"))
                .primary(self.file(), span, "called here")
                .note(format!("looked for {where_}"));
            match name {
                // `SH602` alone: a program name to the control; only an address if no program has it.
                CalleeName::Name(s) if numbered_name(s) => d
                    .note(format!(
                        "{s} is read as a call: a name of letters and digits written alone is a program name"
                    ))
                    .hint(format!(
                        "put {s}.SPF beside the main program; if {s} is an address, give it its value (`{s}=…`)"
                    )),
                _ => d.hint("put the subprogram beside the main program"),
            }
        };
        Fault::error(d)
    }

    fn repeat_count(&mut self, call: &Call) -> Result<u64, Fault> {
        match &call.repeat {
            Some(e) => {
                let cx = self.cx(false);
                let n = round_half_away(expr::eval_num(self, e, &cx)?);
                Ok(n.max(0.0) as u64)
            }
            None => Ok(1),
        }
    }

    fn target_name(&mut self, call: &Call) -> Result<CalleeName, Fault> {
        Ok(match &call.target {
            CallTarget::Number(n) => CalleeName::Number(*n),
            CallTarget::Name(s) => CalleeName::Name(s.to_ascii_uppercase()),
            CallTarget::Computed(e) => {
                let cx = self.cx(true);
                match expr::eval(self, e, &cx)? {
                    Value::Str(s) => CalleeName::Name(s.to_ascii_uppercase()),
                    v => CalleeName::Number(round_half_away(v.num().unwrap_or(0.0)).max(0.0) as u32),
                }
            }
        })
    }

    /// Evaluates FANUC argument letters (decimal-point rule per letter).
    fn fanuc_args(&mut self, call: &Call) -> Result<Vec<(u8, Option<f64>)>, Fault> {
        let mut out = Vec::new();
        for a in &call.args {
            if let Arg::Letter { letter, var, value } = a {
                let cx = self.cx(true);
                let v = expr::eval(self, value, &cx)?;
                let bare = match &value.kind {
                    ExprKind::Num(n) => !n.point,
                    ExprKind::Unary(crate::ir::UnOp::Neg, x) => {
                        matches!(&x.kind, ExprKind::Num(n) if !n.point)
                    }
                    _ => false,
                };
                let x = match v {
                    Value::Vacant => None,
                    other => {
                        let x = other.num().unwrap_or(0.0);
                        let scaling = self.sem.increment_scaling && !self.sem.calculator_input;
                        match (bare && scaling, letter_scaled(*letter)) {
                            (true, Some(rotary)) => {
                                let inc = self.sem.input_increment(self.m.modal.inch, rotary);
                                Some(round_to(x * inc, inc))
                            }
                            _ => Some(x),
                        }
                    }
                };
                out.push((*var, x));
            }
        }
        Ok(out)
    }

    /// Evaluates Siemens arguments: `Some(value)`, `None` for omitted.
    pub(crate) fn sie_args(&mut self, call: &Call) -> Result<Vec<Option<Value>>, Fault> {
        self.sie_args_beside(call, &[])
    }

    /// The argument values, leaving out those bound by reference (`refs[i]` is a place):
    /// a whole array passed to a VAR array parameter has no value of its own.
    fn sie_args_beside(&mut self, call: &Call, refs: &[Option<Place>]) -> Result<Vec<Option<Value>>, Fault> {
        let mut out = Vec::new();
        for (i, a) in call.args.iter().enumerate() {
            if matches!(refs.get(i), Some(Some(_))) {
                out.push(None);
                continue;
            }
            match a {
                Arg::Value(e) => {
                    let cx = self.cx(false);
                    out.push(Some(expr::eval(self, e, &cx)?));
                }
                Arg::Omitted(_) => out.push(None),
                Arg::Letter { value, .. } => {
                    let cx = self.cx(false);
                    out.push(Some(expr::eval(self, value, &cx)?));
                }
            }
        }
        Ok(out)
    }

    fn push_frame(&mut self, code: usize, kind: FrameKind, repeats: u64, span: Span, modal: bool) -> Result<(), Fault> {
        let (macros, subs) = self.frames.iter().fold((0u32, 0u32), |(m, s), f| match f.kind {
            FrameKind::Macro => (m + 1, s),
            FrameKind::Sub | FrameKind::Proc => (m, s + 1),
            FrameKind::Main => (m, s),
        });
        let over = match kind {
            FrameKind::Macro => macros + 1 > self.sem.max_call_depth,
            FrameKind::Sub => subs + 1 > self.sem.max_subprogram_depth,
            FrameKind::Proc => subs + 1 > self.sem.max_call_depth,
            FrameKind::Main => false,
        };
        if over {
            return Err(Fault::Limit {
                reason: format!(
                    "call nesting limit reached ({} levels of {})",
                    match kind {
                        FrameKind::Macro => self.sem.max_call_depth,
                        FrameKind::Proc => self.sem.max_call_depth,
                        _ => self.sem.max_subprogram_depth,
                    },
                    match kind {
                        FrameKind::Macro => "G65/G66 macro calls",
                        FrameKind::Sub => "M98 subprogram calls",
                        _ => "subprogram calls",
                    }
                ),
                span,
            });
        }
        let caller = self.frames.last().ok_or_else(internal)?;
        let mut level = caller.level;
        let mut sframe = caller.sframe;
        if kind == FrameKind::Macro {
            self.vars.levels.push(Level::default());
            level = self.vars.levels.len() - 1;
        }
        if kind == FrameKind::Proc {
            self.vars.frames.push(HashMap::new());
            sframe = self.vars.frames.len() - 1;
        }
        let saved =
            (kind == FrameKind::Proc && self.save.get(code) == Some(&true)).then(|| Box::new(Saved::of(&self.m)));
        self.frames.push(Frame {
            code,
            pc: 0,
            level,
            sframe,
            kind,
            repeats_left: repeats.saturating_sub(1),
            call_span: span,
            reps: Vec::new(),
            modal,
            saved,
            start: 0,
        });
        Ok(())
    }

    /// Binds PROC parameters in the new (top) frame.
    fn bind_params(
        &mut self,
        code: usize,
        args: &[Option<Value>],
        refs: &[Option<Place>],
        span: Span,
    ) -> Result<(), Fault> {
        let params = self.params.get(code).cloned().unwrap_or_default();
        if args.len() > params.len() {
            return Err(Fault::alarm(
                self.alarms.bad_index,
                format!("{} arguments passed, the subprogram has {} parameters", args.len(), params.len()),
                span,
            ));
        }
        let sf = self.frames.last().ok_or_else(internal)?.sframe;
        for (i, p) in params.iter().enumerate() {
            if p.by_ref {
                if let Some(Some(place)) = refs.get(i) {
                    self.vars.frames[sf].insert(p.name.clone(), Slot::Ref(place.clone()));
                    continue;
                }
            }
            let len = super::vars::array_len(&p.dims).ok_or_else(|| {
                Fault::alarm(self.alarms.bad_index, format!("array parameter {} too large", p.name), span)
            })?;
            let v = match args.get(i) {
                Some(Some(v)) => convert_for(p.ty, v.clone()).map_err(|_| {
                    Fault::alarm(
                        self.alarms.domain,
                        format!("argument {} has the wrong type for {}", i + 1, p.name),
                        span,
                    )
                })?,
                _ => zero_of(p.ty),
            };
            let mut data = vec![zero_of(p.ty); len];
            data[0] = v;
            self.vars.frames[sf].insert(p.name.clone(), Slot::Own { ty: p.ty, dims: p.dims.clone(), data });
        }
        Ok(())
    }

    pub fn call(&mut self, call: &Call, pc: usize, span: Span) -> Result<Flow, Fault> {
        if call.kind == CallKind::M97 {
            return self.local_call(call, pc, span);
        }
        if !self.fanuc
            && call.kind == CallKind::Named
            && matches!(&call.target, CallTarget::Name(n) if n == "EXECSTRING")
        {
            let as_call = self.execstring(call, span)?;
            return self.call(&as_call, pc, span);
        }
        let name = self.target_name(call)?;
        if let CalleeName::Name(s) = &name {
            // The standard drilling cycles are the control's own (eval::cycles::siemens).
            if let Some(c) = crate::dialect::sinumerik::cycles::cycle_of(s).filter(|_| !self.fanuc) {
                return self.siemens_cycle_call(call, c, span);
            }
            if s == "CYCLE832" && !self.fanuc {
                return self.cycle832(call, span);
            }
            if s == "FGROUP" && !self.fanuc {
                return self.fgroup(call, span);
            }
            if SIMULATION_ONLY.contains(&s.as_str()) {
                self.warn("NC406", format!("{s}(...) only sets up the HMI simulation: no effect on the trace"), span);
                return Ok(Flow::Next);
            }
        }
        let repeats = self.repeat_count(call)?;
        let mut resolved = self.find_code(&name, span)?;
        let mut repeats = repeats;
        if resolved.is_none() && call.kind == CallKind::M98 && call.repeat.is_none() {
            // `M98 P68003`: the count is packed in front of a four-digit number.
            if let CalleeName::Number(n) = name {
                if n > 9999 {
                    let unpacked = CalleeName::Number(n % 10000);
                    resolved = self.find_code(&unpacked, span)?;
                    repeats = u64::from(n / 10000);
                }
            }
        }
        let Some(code) = resolved else {
            return Err(self.missing(&name, span));
        };
        match call.kind {
            CallKind::G66 | CallKind::Mcall => {
                let fanuc_args = if self.fanuc { self.fanuc_args(call)? } else { vec![] };
                let sie_args = if self.fanuc { vec![] } else { self.sie_args(call)? };
                self.m.cycle.mcall = None;
                self.modal_call = Some(super::calls::ModalCall {
                    code,
                    fanuc_args,
                    sie_args,
                    repeat: repeats,
                    depth: self.frames.len(),
                });
                Ok(Flow::Next)
            }
            _ if repeats == 0 => Ok(Flow::Next),
            CallKind::G65 => {
                let args = self.fanuc_args(call)?;
                self.set_caller_pc(pc + 1)?;
                self.push_frame(code, FrameKind::Macro, repeats, span, false)?;
                self.set_args(&args);
                Ok(Flow::Switched)
            }
            CallKind::M98 | CallKind::M97 => {
                self.set_caller_pc(pc + 1)?;
                self.push_frame(code, FrameKind::Sub, repeats, span, false)?;
                Ok(Flow::Switched)
            }
            CallKind::Named | CallKind::LNumber => {
                let params = self.params.get(code).cloned().unwrap_or_default();
                let mut refs = Vec::new();
                for (i, a) in call.args.iter().enumerate() {
                    let by_ref = params.get(i).is_some_and(|p| p.by_ref);
                    refs.push(match a {
                        Arg::Value(e) if by_ref => self.place_of_arg(e)?,
                        _ => None,
                    });
                }
                let args = self.sie_args_beside(call, &refs)?;
                self.set_caller_pc(pc + 1)?;
                self.push_frame(code, FrameKind::Proc, repeats, span, false)?;
                self.bind_params(code, &args, &refs, span)?;
                Ok(Flow::Switched)
            }
        }
    }

    /// Siemens `EXECSTRING(text)` runs `text` as a part program line. Only the line that is
    /// a program name alone is modelled: that line calls the program without arguments (a
    /// name written alone in a block is a call), so `EXECSTRING(SHAPE)` with SHAPE =
    /// "D_TRIANGLE" is the call `D_TRIANGLE`. Any other line (empty, a move, a call with
    /// arguments) stops the run (NC553): what the control makes of it is not modelled.
    fn execstring(&mut self, call: &Call, span: Span) -> Result<Call, Fault> {
        let text = match call.args.as_slice() {
            [Arg::Value(e)] => {
                let cx = self.cx(false);
                match expr::eval(self, e, &cx)? {
                    Value::Str(s) => Some(s),
                    _ => None,
                }
            }
            _ => None,
        };
        let name = text.as_deref().map(str::trim).filter(|t| crate::dialect::sinumerik::is_program_name_line(t));
        let Some(name) = name else {
            let what = match &text {
                Some(t) if t.trim().is_empty() => "EXECSTRING of an empty line".to_string(),
                Some(t) => format!("EXECSTRING of the line \"{t}\""),
                None => "EXECSTRING without one STRING argument".to_string(),
            };
            let d = Diagnostic::error("NC553", format!("{what}: only a line that is a program name is run"))
                .primary(self.file(), span, "here")
                .note("EXECSTRING runs its text as a part program line; the evaluator models the line that is a program name alone (the call of that program)")
                .hint("call the program by name (`CALL \"NAME\"`), or write the line into the program");
            return Err(Fault::error(d));
        };
        Ok(Call {
            kind: CallKind::Named,
            target: CallTarget::Name(name.to_ascii_uppercase()),
            args: Vec::new(),
            repeat: None,
        })
    }

    /// Haas `M97 Pn Lm`: the blocks from Nn of this program, up to their M99, m times; like
    /// M98 it shares the caller's locals.
    fn local_call(&mut self, call: &Call, pc: usize, span: Span) -> Result<Flow, Fault> {
        let CallTarget::Number(n) = call.target else { return Err(internal()) };
        let repeats = self.repeat_count(call)?;
        if repeats == 0 {
            return Ok(Flow::Next);
        }
        let ci = self.frames.last().ok_or_else(internal)?.code;
        let code = Rc::clone(&self.codes[ci]);
        let Some(start) = code.find_number_from(pc + 1, n) else {
            return Err(Fault::alarm(self.alarms.no_target, format!("M97 P{n}: N{n} not found in this program"), span));
        };
        self.set_caller_pc(pc + 1)?;
        self.push_frame(ci, FrameKind::Sub, repeats, span, false)?;
        let top = self.frames.last_mut().ok_or_else(internal)?;
        top.pc = start;
        top.start = start;
        Ok(Flow::Switched)
    }

    fn set_caller_pc(&mut self, pc: usize) -> Result<(), Fault> {
        self.frames.last_mut().ok_or_else(internal)?.pc = pc;
        Ok(())
    }

    fn set_args(&mut self, args: &[(u8, Option<f64>)]) {
        let lv = self.frames.last().map_or(0, |f| f.level);
        let level = &mut self.vars.levels[lv];
        for (var, x) in args {
            if (1..=33).contains(var) {
                level.vals[*var as usize] = *x;
                level.written |= 1u64 << var;
            }
        }
    }

    /// The frame of an interrupt routine (`interrupt.rs`): one pass, not modal.
    pub(super) fn push_call_frame(&mut self, code: usize, kind: FrameKind, span: Span) -> Result<(), Fault> {
        self.push_frame(code, kind, 1, span, false)
    }

    /// An interrupt routine takes no arguments: its parameters start as a call without
    /// arguments gives them.
    pub(super) fn bind_no_args(&mut self, code: usize, span: Span) -> Result<(), Fault> {
        self.bind_params(code, &[], &[], span)
    }

    /// The fault of a routine not found.
    pub(super) fn missing_callee(&mut self, name: &CalleeName, span: Span) -> Fault {
        self.missing(name, span)
    }

    /// A G66/MCALL modal call after a block that moved.
    pub fn modal_trigger(&mut self, mc: &ModalCall, pc: usize, span: Span) -> Result<Flow, Fault> {
        if mc.repeat == 0 {
            return Ok(Flow::Next);
        }
        self.set_caller_pc(pc + 1)?;
        if self.fanuc {
            self.push_frame(mc.code, FrameKind::Macro, mc.repeat, span, true)?;
            self.set_args(&mc.fanuc_args);
        } else {
            self.push_frame(mc.code, FrameKind::Proc, mc.repeat, span, true)?;
            self.bind_params(mc.code, &mc.sie_args, &[], span)?;
        }
        Ok(Flow::Switched)
    }

    /// M99 [Pn] / RET / M17.
    pub fn do_return(&mut self, to: Option<&crate::ir::Expr>, span: Span) -> Result<Flow, Fault> {
        let target = match to {
            Some(e) => {
                let cx = self.cx(true);
                Some(round_half_away(expr::eval_num(self, e, &cx)?) as i64)
            }
            None => None,
        };
        let depth = self.frames.len();
        if depth <= 1 {
            if let Some(n) = target {
                // M99 Pn in a main program: continue at Nn.
                let ci = self.frames.last().ok_or_else(internal)?.code;
                let code = Rc::clone(&self.codes[ci]);
                let from = self.frames.last().map_or(0, |f| f.pc);
                return match u32::try_from(n).ok().and_then(|n| code.find_number_from(from + 1, n)) {
                    Some(d) => Ok(Flow::Goto(d)),
                    None => Err(Fault::alarm(self.alarms.no_target, format!("M99 P{n}: N{n} not found"), span)),
                };
            }
            let code = if self.fanuc { "M99" } else { "RET" };
            return Ok(Flow::Stop(self.end(code, span)));
        }
        let top = self.frames.last_mut().ok_or_else(internal)?;
        // Each pass of a SAVE subprogram ends in the modes it was called in.
        let reselected = top.saved.as_ref().is_some_and(|saved| saved.restore(&mut self.m));
        if reselected {
            // The subprogram selected an offset: the return selects the caller's again.
            self.emit(super::trace::Event::WorkOffset { n: self.m.wo as u32 }, span);
        }
        if let Some(ev) = self.m.comp_restored() {
            // G40/G41/G42 is a modal G group: restored too.
            self.emit(ev, span);
        }
        let top = self.frames.last_mut().ok_or_else(internal)?;
        if top.repeats_left > 0 {
            top.repeats_left -= 1;
            top.pc = top.start;
            top.reps.clear();
            return Ok(Flow::Switched);
        }
        let fr = self.frames.pop().ok_or_else(internal)?;
        if fr.kind == FrameKind::Macro {
            self.vars.levels.truncate(fr.level);
        }
        if fr.kind == FrameKind::Proc {
            self.vars.frames.truncate(fr.sframe);
        }
        if let Some(n) = target {
            let caller = self.frames.last().ok_or_else(internal)?;
            let code = Rc::clone(&self.codes[caller.code]);
            match u32::try_from(n).ok().and_then(|n| code.find_number_from(caller.pc, n)) {
                Some(d) => self.set_caller_pc(d)?,
                None => {
                    return Err(Fault::alarm(
                        self.alarms.no_target,
                        format!("M99 P{n}: N{n} not found in the calling program"),
                        span,
                    ))
                }
            }
        }
        Ok(Flow::Switched)
    }
}

/// What a Siemens `PROC … SAVE` subprogram restores at its end: the modal G functions
/// (every group the machine models), the settable frame (G54.. and the values selected
/// with it, where the subprogram selected another) and the programmable frame (TRANS).
/// The feed, spindle, tool and position are not modal G functions and stay.
#[derive(Clone, Debug)]
pub struct Saved {
    modal: super::machine::Modal,
    wo: usize,
    frame: [f64; 9],
    trans: [f64; 9],
    /// The rotation, scaling and mirroring of the programmable frame.
    xf: super::machine::Xform,
    /// [`Machine::wo_selections`](super::machine::Machine::wo_selections) at the call.
    selections: u64,
    /// The cutter radius compensation side (group 07).
    side: Option<super::trace::Side>,
}

impl Saved {
    fn of(m: &super::machine::Machine) -> Saved {
        Saved {
            modal: m.modal,
            wo: m.wo,
            frame: m.frame,
            trans: m.trans,
            xf: m.xf,
            selections: m.wo_selections,
            side: m.comp.side,
        }
    }

    /// Restores the modes; `true` when the subprogram selected a work offset (the restore
    /// is then a selection, a `work_offset` event, as FANUC's translation re-selects it).
    fn restore(&self, m: &mut super::machine::Machine) -> bool {
        let selected = m.wo_selections != self.selections;
        m.wo_selections = self.selections;
        m.modal = self.modal;
        if m.wo != self.wo {
            m.wo = self.wo;
            m.frame = self.frame;
        }
        m.set_trans(self.trans);
        m.set_xform(self.xf);
        m.comp.side = self.side;
        selected
    }
}

/// `SH602`, `PLCASUP1`: two or more letters, then digits (one letter and digits is an address).
fn numbered_name(s: &str) -> bool {
    let letters = s.bytes().take_while(u8::is_ascii_alphabetic).count();
    letters >= 2 && letters < s.len() && s.bytes().skip(letters).all(|c| c.is_ascii_digit())
}
