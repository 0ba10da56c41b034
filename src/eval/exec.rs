//! The interpreter: runs flattened code frame by frame, one block at a time, through the
//! one choke point that counts steps and checks limits.

use super::calls::{CalleeName, ModalCall};
use super::expr::{self, Cx};
use super::fault::{AlarmNumbers, Fault};
use super::flow::{Code, Key, Op, OpRef};
use super::machine::{Machine, WordVal, WV};
use super::trace::{Event, Origin, TraceSink};
use super::value::{round_half_away, Value};
use super::vars::Vars;
use super::{CalleeSource, Ending, Input, RunOptions};
use crate::diag::Diagnostic;
use crate::dialect::lit::AbsInc;
use crate::dialect::{Dialect, Semantics};
use crate::eval::paged::Page;
use crate::ir::{Block, EndCode, Expr, ExprKind, Goto, Item, ItemKind, Search, Target, VarRef, WordValue};
use crate::span::{FileId, SourceDb, Span};
use std::collections::{HashMap, HashSet};
use std::rc::Rc;

mod corner_gate;
mod goto;
mod held;
mod lits;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameKind {
    Main,
    /// FANUC G65/G66: own local level.
    Macro,
    /// FANUC M98: shares the caller's locals.
    Sub,
    /// Siemens subprogram.
    Proc,
}

/// A section repetition in progress (Siemens `REPEAT`).
#[derive(Clone, Debug)]
pub struct Rep {
    pub restart: usize,
    pub end: usize,
    pub ret: usize,
    pub left: u64,
}

#[derive(Clone, Debug)]
pub struct Frame {
    pub code: usize,
    pub pc: usize,
    pub level: usize,
    pub sframe: usize,
    pub kind: FrameKind,
    pub repeats_left: u64,
    pub call_span: Span,
    pub reps: Vec<Rep>,
    /// This frame runs a modal (G66/MCALL) call: moves inside it do not trigger it.
    pub modal: bool,
    /// A Siemens `PROC … SAVE` subprogram: the modes at its call, restored at its end.
    pub saved: Option<Box<super::calls::Saved>>,
    /// Where each pass starts: 0, or the block Nn of a Haas `M97 Pn` local subprogram.
    pub start: usize,
}

/// What a block asks the loop to do next.
pub enum Flow {
    Next,
    Goto(usize),
    /// A frame was pushed or popped: continue with the new top frame.
    Switched,
    Stop(Ending),
}

pub struct Interp<'a> {
    pub sem: Semantics,
    pub fanuc: bool,
    pub dialect: Dialect,
    pub alarms: AlarmNumbers,
    pub codes: Vec<Rc<Code>>,
    /// Program number / name → code index.
    pub by_number: HashMap<u32, usize>,
    pub by_name: HashMap<String, usize>,
    /// Formal parameters per code index.
    pub params: Vec<Vec<crate::ir::Param>>,
    /// Whether each code index is a `PROC … SAVE` program.
    pub save: Vec<bool>,
    pub db: &'a mut SourceDb,
    pub callees: &'a mut dyn CalleeSource,
    pub sink: &'a mut dyn TraceSink,
    pub vars: Vars,
    pub m: Machine,
    pub frames: Vec<Frame>,
    pub steps: u64,
    pub max_steps: u64,
    pub diags: Vec<Diagnostic>,
    warned: HashSet<(&'static str, FileId, Span)>,
    pending_msg: Option<(String, Origin)>,
    /// The file of the block whose Siemens edge is held (`held.rs`).
    held_file: Option<(Span, FileId)>,
    pub modal_call: Option<ModalCall>,
    pub inputs: Vec<Input>,
    out_buf: Vec<(Event, Span)>,
    warn_buf: Vec<super::machine::Warn>,
    words_buf: Vec<WordVal>,
    /// The call depth of the block whose corner the machine holds (`machine::corners`).
    corner_depth: usize,
    pub sys_store: HashMap<String, f64>,
    /// [`super::machine::fast_path_on`] when the run began (asked once, not per block).
    fast_path: bool,
    /// Interrupt assignments and the test inputs that switch them (`interrupt.rs`).
    pub ints: super::interrupt::State,
}

impl<'a> Interp<'a> {
    pub fn new(
        dialect: Dialect,
        opts: &RunOptions,
        db: &'a mut SourceDb,
        callees: &'a mut dyn CalleeSource,
        sink: &'a mut dyn TraceSink,
    ) -> Interp<'a> {
        let sem = opts.semantics.clone().unwrap_or_else(|| Semantics::default_for(dialect));
        let fanuc = dialect == Dialect::Fanuc;
        let alarms = if fanuc { AlarmNumbers::FANUC } else { AlarmNumbers::SINUMERIK };
        let scaling = sem.increment_scaling && !sem.calculator_input;
        let mut m = Machine::new(fanuc, alarms, scaling, sem.least_increment_mm);
        m.master_spindle = (!fanuc && sem.master_spindle > 0).then(|| sem.master_spindle.to_string());
        m.haas = fanuc && sem.haas;
        m.incr_travels_offset = sem.incremental_travels_offset;
        m.comp.edge_default = sem.cutting_edge_default.unwrap_or(super::machine::comp::CUTTING_EDGE_DEFAULT);
        m.rotation_angle_incremental = sem.rotation_angle_incremental;
        m.probe_contact = opts.probe_contact;
        m.probe.inputs = opts.probes.clone();
        m.expand = opts.expand_cycles;
        let r_count = sem.r_param_count as usize;
        Interp {
            fanuc,
            dialect,
            alarms,
            codes: Vec::new(),
            by_number: HashMap::new(),
            by_name: HashMap::new(),
            params: Vec::new(),
            save: Vec::new(),
            db,
            callees,
            sink,
            vars: Vars::new(r_count),
            m,
            frames: Vec::new(),
            steps: 0,
            max_steps: opts.max_steps,
            diags: Vec::new(),
            warned: HashSet::new(),
            pending_msg: None,
            held_file: None,
            modal_call: None,
            inputs: opts.inputs.clone(),
            out_buf: Vec::new(),
            warn_buf: Vec::new(),
            words_buf: Vec::new(),
            corner_depth: 0,
            sys_store: HashMap::new(),
            fast_path: super::machine::fast_path_on(),
            ints: super::interrupt::State::new(opts.interrupts.clone()),
            sem,
        }
    }

    pub fn file(&self) -> FileId {
        self.frames.last().map_or(0, |f| self.codes[f.code].file)
    }

    pub fn cx(&self, in_address: bool) -> Cx {
        Cx {
            file: self.file(),
            fanuc: self.fanuc,
            nat: self.sem.nat,
            rel_tol: self.sem.cmp_tolerance,
            alarms: if self.fanuc { &AlarmNumbers::FANUC } else { &AlarmNumbers::SINUMERIK },
            in_address,
            increment: self.sem.input_increment(self.m.modal.inch, false),
        }
    }

    /// A warning, once per place.
    pub fn warn(&mut self, code: &'static str, msg: String, span: Span) {
        let file = self.file();
        if self.warned.insert((code, file, span)) {
            self.diags.push(Diagnostic::warning(code, msg).primary(file, span, "here"));
        }
    }

    /// Sends an event, merging a Siemens MSG with the M0/M1 right after it.
    pub fn emit(&mut self, ev: Event, span: Span) {
        self.release_held(&ev);
        let origin = Origin { file: self.file(), span };
        self.emit_at(ev, origin);
    }

    /// [`Interp::emit`] from a given place.
    pub(super) fn emit_at(&mut self, ev: Event, origin: Origin) {
        self.ints.motions += u64::from(super::interrupt::is_motion(&ev));
        if let Some((text, o)) = self.pending_msg.take() {
            if let Event::Stop { optional, message: None } = ev {
                self.sink.event(&Event::Stop { optional, message: Some(text) }, origin);
                return;
            }
            self.sink.event(&Event::Message { text }, o);
        }
        if let Event::Message { text } = ev {
            self.pending_msg = Some((text, origin));
            return;
        }
        self.sink.event(&ev, origin);
    }

    /// [`Interp::emit`] of a borrowed event: passed on as it is unless a message waits
    /// to be merged, or it is one.
    fn emit_ref(&mut self, ev: &Event, span: Span) {
        self.release_held(ev);
        if self.pending_msg.is_none() && !matches!(ev, Event::Message { .. }) {
            self.ints.motions += u64::from(super::interrupt::is_motion(ev));
            let origin = Origin { file: self.file(), span };
            self.sink.event(ev, origin);
        } else {
            self.emit(ev.clone(), span);
        }
    }

    pub fn flush(&mut self) {
        if let Some((text, o)) = self.pending_msg.take() {
            self.sink.event(&Event::Message { text }, o);
        }
    }

    /// The main loop. Returns how the run ended.
    pub fn run_loop(&mut self) -> Result<Ending, Fault> {
        // The page of a streamed program the last op came from (with its code's index):
        // the next op is nearly always in it, found without asking the pager (which
        // would give this same page: pages do not change once read).
        let mut page: Option<(usize, Rc<Page>)> = None;
        // Asked once: a sink wants every block or none (see `TraceSink::wants_blocks`).
        let wants_blocks = self.sink.wants_blocks();
        loop {
            let Some(fr) = self.frames.last() else {
                return Ok(Ending::End("M30"));
            };
            let (ci, pc) = (fr.code, fr.pc);
            let no_reps = fr.reps.is_empty();
            let code = Rc::clone(&self.codes[ci]);
            // A streamed program's op lives in a page that `page` or `held` keeps alive.
            let in_page = matches!(&page, Some((c, p)) if *c == ci && p.get(pc).is_some());
            let op = if in_page {
                page.as_ref().and_then(|(_, p)| p.get(pc))
            } else {
                match code.op_at(pc).map_err(Fault::error)? {
                    Some(OpRef::Mem(op)) => Some(op),
                    Some(OpRef::Page(p, _)) => {
                        page = Some((ci, p));
                        page.as_ref().and_then(|(_, p)| p.get(pc))
                    }
                    None => None,
                }
            };
            if self.m.corners.held.is_some() {
                self.corner_gate(op)?;
            }
            let Some(op) = op else {
                // Past the last block.
                if self.frames.len() == 1 {
                    let span = code.last_span();
                    return Err(Fault::alarm(0, "end of the main program reached without M30/M2/M99/RET", span));
                }
                let span = code.last_span();
                self.warn("NC410", "subprogram ends without M99/M17/RET; returning to the caller".into(), span);
                match self.do_return(None, span)? {
                    Flow::Stop(e) => return Ok(e),
                    _ => continue,
                }
            };
            let (flow, pc) = if matches!(op, Op::Lit(_)) && !wants_blocks && no_reps {
                // A run of literal blocks (CAM output): one after the other, without
                // coming back here for each.
                let page = page.as_ref().and_then(|(c, p)| (*c == ci).then_some(&**p));
                self.run_lits(&code, page, op, pc)?
            } else {
                // The choke point: every executed block passes here (or `run_lits`).
                self.steps += 1;
                if self.steps > self.max_steps {
                    return Err(self.step_limit(op));
                }
                if self.sink.wants_stop() {
                    return Ok(Ending::Stopped);
                }
                let flow = self.exec_op(&code, op, pc)?;
                if wants_blocks && matches!(op, Op::Block(_) | Op::Lit(_)) {
                    let origin = Origin { file: code.file, span: op.span() };
                    let pos = self.m.trace_pos();
                    self.sink.block_done(origin, &pos);
                }
                (flow, pc)
            };
            match flow {
                Flow::Next => {
                    let fr = self.frames.last_mut().ok_or_else(internal)?;
                    // Section repetition ends: a finished repetition continues after
                    // its REPEAT block, which may itself end an enclosing section.
                    let mut done = pc;
                    loop {
                        fr.pc = done + 1;
                        match fr.reps.last_mut() {
                            Some(rep) if rep.end == done => {
                                if rep.left > 0 {
                                    rep.left -= 1;
                                    fr.pc = rep.restart;
                                    break;
                                }
                                done = rep.ret - 1;
                                fr.reps.pop();
                            }
                            _ => break,
                        }
                    }
                }
                Flow::Goto(t) => {
                    let fr = self.frames.last_mut().ok_or_else(internal)?;
                    fr.pc = t;
                }
                Flow::Switched => {}
                Flow::Stop(e) => return Ok(e),
            }
        }
    }

    /// The fault of the step limit, reached at `op`.
    fn step_limit(&self, op: &Op) -> Fault {
        Fault::Limit { reason: format!("step limit of {} blocks reached", self.max_steps), span: op.span() }
    }

    fn exec_op(&mut self, code: &Rc<Code>, op: &Op, pc: usize) -> Result<Flow, Fault> {
        match op {
            Op::Block(b) => self.exec_block(code, b, pc),
            Op::Lit(l) => self.exec_lit(code, l, pc),
            Op::Nop(_) => Ok(Flow::Next),
            Op::Test { cond, target, .. } => {
                let cx = self.cx(false);
                let v = expr::eval(self, cond, &cx)?;
                Ok(if v.truthy() { Flow::Next } else { Flow::Goto(*target) })
            }
            Op::Jump { target, .. } => Ok(Flow::Goto(*target)),
            Op::Until { cond, target, .. } => {
                let cx = self.cx(false);
                let v = expr::eval(self, cond, &cx)?;
                Ok(if v.truthy() { Flow::Next } else { Flow::Goto(*target) })
            }
            Op::ForHead { var, from, to, exit, .. } => {
                let cx = self.cx(false);
                let v = expr::eval(self, from, &cx)?;
                self.write_var(var, v)?;
                if self.for_continues(var, to)? {
                    Ok(Flow::Next)
                } else {
                    Ok(Flow::Goto(*exit))
                }
            }
            Op::ForEnd { var, to, body, .. } => {
                let cx = self.cx(false);
                let cur = expr::eval_num(self, &var_expr(var), &cx)?;
                self.write_var(var, Value::Num(cur + 1.0))?;
                if self.for_continues(var, to)? {
                    Ok(Flow::Goto(*body))
                } else {
                    Ok(Flow::Next)
                }
            }
        }
    }

    fn for_continues(&mut self, var: &VarRef, to: &Expr) -> Result<bool, Fault> {
        let cx = self.cx(false);
        let cur = expr::eval(self, &var_expr(var), &cx)?;
        let end = expr::eval(self, to, &cx)?;
        Ok(expr::compare(crate::ir::CmpOp::Le, crate::ir::Tolerance::Relative, &cur, &end, &cx))
    }

    fn exec_block(&mut self, code: &Rc<Code>, b: &Block, pc: usize) -> Result<Flow, Fault> {
        // The words' buffer is reused from block to block (an early error return only
        // drops it: the next block starts a new one).
        let mut words = std::mem::take(&mut self.words_buf);
        words.clear();
        let mut stop_message: Option<String> = None;
        let mut control: Vec<&Item> = Vec::new();
        if let Some(n) = &b.meta.number {
            self.m.last_n = f64::from(n.value);
        }
        for item in &b.items {
            match &item.kind {
                ItemKind::Word(w) => {
                    if let Some(wv) = self.eval_word(w)? {
                        words.push(wv);
                    }
                }
                ItemKind::StopMessage { text } => stop_message = Some(text.clone().unwrap_or_default()),
                // SUPA: suppress the frames for this block, like G53.
                ItemKind::Instruction { name } if name == "SUPA" || name == "G153" => words.push(WordVal {
                    addr: std::borrow::Cow::Borrowed("G"),
                    val: WV::Num(53.0),
                    mode: AbsInc::Plain,
                    bare: false,
                    literal: false,
                    span: item.span,
                }),
                ItemKind::Goto(_)
                | ItemKind::Case(_)
                | ItemKind::Call(_)
                | ItemKind::Return { .. }
                | ItemKind::End { .. }
                | ItemKind::RepeatSection(_) => control.push(item),
                ItemKind::IfBlock { cond, items } => {
                    let cx = self.cx(false);
                    if expr::eval(self, cond, &cx)?.truthy() {
                        for inner in items {
                            match &inner.kind {
                                ItemKind::Word(w) => {
                                    if let Some(wv) = self.eval_word(w)? {
                                        words.push(wv);
                                    }
                                }
                                ItemKind::Goto(_)
                                | ItemKind::Call(_)
                                | ItemKind::Return { .. }
                                | ItemKind::End { .. } => control.push(inner),
                                _ => self.exec_simple(inner, &mut stop_message)?,
                            }
                        }
                    }
                }
                ItemKind::IfThen { cond, then } => {
                    let cx = self.cx(false);
                    if expr::eval(self, cond, &cx)?.truthy() {
                        match &then.kind {
                            ItemKind::Goto(_) | ItemKind::Call(_) | ItemKind::Return { .. } => control.push(then),
                            _ => self.exec_simple(then, &mut stop_message)?,
                        }
                    }
                }
                _ => self.exec_simple(item, &mut stop_message)?,
            }
        }
        self.finish_block(code, words, stop_message, control, b.meta.span, pc)
    }

    /// The rest of a block once its words are evaluated: the NC words, then the control
    /// items, then what the words ask (end, return, modal call).
    fn finish_block(
        &mut self,
        code: &Rc<Code>,
        mut words: Vec<WordVal>,
        stop_message: Option<String>,
        control: Vec<&Item>,
        span: Span,
        pc: usize,
    ) -> Result<Flow, Fault> {
        let has_stop = stop_message.is_some();
        let mut eff = super::machine::BlockEffect::default();
        if !words.is_empty() || has_stop {
            let mut out = std::mem::take(&mut self.out_buf);
            let mut warns = std::mem::take(&mut self.warn_buf);
            let r = self.m.apply(&words, stop_message, &mut out, &mut warns);
            self.note_held();
            if self.m.corners.held.is_some() {
                self.corner_depth = self.frames.len();
            }
            for (code_, msg, span) in warns.drain(..) {
                self.warn(code_, msg, span);
            }
            for (ev, span) in &out {
                self.emit_ref(ev, *span);
            }
            out.clear();
            self.out_buf = out;
            self.warn_buf = warns;
            eff = r.map_err(|f| self.fix_file(f))?;
        }
        words.clear();
        self.words_buf = words;
        if !control.is_empty() {
            self.interrupt_clash("jumps, calls, returns or ends", span)?;
        }
        for item in control {
            let flow = self.exec_control(code, item, pc)?;
            if !matches!(flow, Flow::Next) {
                return Ok(flow);
            }
        }
        self.block_end(eff, span, pc)
    }

    /// What a block's words ask once its control items ran: end, return, modal call.
    fn block_end(&mut self, eff: super::machine::BlockEffect, span: Span, pc: usize) -> Result<Flow, Fault> {
        if let Some(code_) = eff.end {
            self.interrupt_clash("ends the program", span)?;
            return Ok(Flow::Stop(self.end(code_, span)));
        }
        if eff.ret {
            self.interrupt_clash("returns", span)?;
            return self.do_return(None, span);
        }
        if eff.moved && self.m.cycle.mcall.is_some() {
            self.mcall_hole(span)?;
        }
        if self.ints.due() {
            if eff.moved && self.modal_call.is_some() && !self.frames.iter().any(|f| f.modal) {
                self.interrupt_clash("triggers a modal call", span)?;
            }
            return self.interrupt_fire(pc, span);
        }
        if eff.moved {
            if let Some(mc) = self.modal_call.clone() {
                // Modal at every program level (M98 subprograms included), except inside
                // the modal macro itself and what it calls.
                let in_modal = self.frames.iter().any(|f| f.modal);
                if !in_modal {
                    return self.modal_trigger(&mc, pc, span);
                }
            }
        }
        Ok(Flow::Next)
    }

    /// Machine faults carry no file; give them the current one.
    pub fn fix_file(&self, f: Fault) -> Fault {
        match f {
            Fault::Error(mut d) => {
                let file = self.file();
                for l in &mut d.labels {
                    if l.file == usize::MAX {
                        l.file = file;
                    }
                }
                Fault::Error(d)
            }
            other => other,
        }
    }

    pub fn end(&mut self, code: &'static str, span: Span) -> Ending {
        let steps = self.steps;
        self.emit(Event::End { code, steps }, span);
        Ending::End(code)
    }

    fn exec_simple(&mut self, item: &Item, stop_message: &mut Option<String>) -> Result<(), Fault> {
        match &item.kind {
            ItemKind::Assign { target, value } => {
                let cx = self.cx(false);
                let v = expr::eval(self, value, &cx)?;
                self.write_var(target, v)
            }
            ItemKind::Def(def) => self.define(def),
            ItemKind::Alarm { style, number, text } => {
                let cx = self.cx(false);
                let n = round_half_away(expr::eval_num(self, number, &cx)?) as i64;
                let number = match style {
                    crate::ir::AlarmStyle::FanucMacro => 3000 + n,
                    crate::ir::AlarmStyle::Setal => n,
                };
                Err(Fault::alarm(number, text.clone().unwrap_or_default(), item.span))
            }
            ItemKind::StopMessage { text } => {
                *stop_message = Some(text.clone().unwrap_or_default());
                Ok(())
            }
            ItemKind::Message { text } => {
                if let Some(e) = text {
                    let cx = self.cx(false);
                    let v = expr::eval(self, e, &cx)?;
                    let t = match v {
                        Value::Str(s) => s,
                        Value::Num(x) => super::value::fmt_num(x),
                        Value::Vacant => String::new(),
                    };
                    self.emit(Event::Message { text: t }, item.span);
                }
                Ok(())
            }
            ItemKind::Print(p) => self.print(p, item.span),
            // Declarations: nothing runs (`EXTERN`).
            ItemKind::Stopre | ItemKind::Extern(_) => Ok(()),
            ItemKind::Instruction { name } => match name.as_str() {
                "CIP" | "CT" | "ASPLINE" | "BSPLINE" | "CSPLINE" | "POLY" | "G2" | "G3" => Err(Fault::error(
                    Diagnostic::error(
                        "NC403",
                        format!("{name} (circle/spline motion) is not modelled by the evaluator"),
                    )
                    .primary(self.file(), item.span, "here")
                    .hint("this motion cannot be proven equivalent; rewrite it with G1/G2/G3 moves"),
                )),
                // No stored Siemens manual page gives RET's parameter list, where the control
                // searches the target in the caller or how many levels it leaves, so the run
                // stops here instead of guessing where the machine goes on.
                _ if crate::dialect::sinumerik::is_ret_with_target(name) => Err(Fault::error(
                    Diagnostic::error("NC507", format!("{name}: a return that resumes elsewhere is not modelled"))
                        .primary(self.file(), item.span, "a return with a jump target")
                        .note("RET with a jump target resumes at a label or block of a calling program, levels up")
                        .note(crate::dialect::sinumerik::RET_TARGET_UNSOURCED)
                        .hint("return with RET and jump in the caller (GOTOF/GOTOB) where it resumes"),
                )),
                // Interrupts, feed-forward, the rest (instructions.rs).
                _ => self.warn_instruction(name, item.span),
            },
            ItemKind::ModalCallOff => {
                self.modal_call = None;
                self.m.cycle.mcall = None;
                Ok(())
            }
            ItemKind::ParamWrite(_) => {
                self.warn("NC405", "parameter write (G10 L50) has no effect on the trace".into(), item.span);
                Ok(())
            }
            ItemKind::Frame { op, words } => {
                let mut ws = Vec::new();
                for w in words {
                    if let Some(v) = self.eval_word(w)? {
                        ws.push(v);
                    }
                }
                let r = self.m.frame_op(op, &ws, item.span);
                r.map_err(|f| self.fix_file(f))
            }
            ItemKind::IfThen { .. } | ItemKind::IfBlock { .. } | ItemKind::Word(_) => Ok(()),
            ItemKind::SyncAction(a) => Err(super::refuse::sync_action(self.file(), item.span, a)),
            ItemKind::Goto(_)
            | ItemKind::Case(_)
            | ItemKind::Call(_)
            | ItemKind::Return { .. }
            | ItemKind::End { .. }
            | ItemKind::RepeatSection(_) => Ok(()),
        }
    }

    fn exec_control(&mut self, code: &Rc<Code>, item: &Item, pc: usize) -> Result<Flow, Fault> {
        match &item.kind {
            ItemKind::Goto(g) => self.goto(code, g, pc, item.span),
            ItemKind::Case(c) => {
                let cx = self.cx(false);
                let sel = expr::eval(self, &c.selector, &cx)?;
                for arm in &c.arms {
                    let v = expr::eval(self, &arm.value, &cx)?;
                    if expr::compare(crate::ir::CmpOp::Eq, crate::ir::Tolerance::Relative, &sel, &v, &cx) {
                        return self.goto(code, &arm.goto, pc, item.span);
                    }
                }
                match &c.default {
                    Some(g) => self.goto(code, g, pc, item.span),
                    None => Ok(Flow::Next),
                }
            }
            ItemKind::Call(call) => self.call(call, pc, item.span),
            ItemKind::Return { to } => self.do_return(to.as_ref(), item.span),
            ItemKind::End { code: c } => {
                let name = match c {
                    EndCode::M30 => "M30",
                    EndCode::M2 => "M2",
                };
                if !self.fanuc && self.frames.len() > 1 {
                    // Siemens M2/M30 in a subprogram end the subprogram (like M17).
                    return self.do_return(None, item.span);
                }
                Ok(Flow::Stop(self.end(name, item.span)))
            }
            ItemKind::RepeatSection(rs) => {
                let crate::ir::RepeatSection { count, single, .. } = &**rs;
                let n = match count {
                    Some(e) => {
                        let cx = self.cx(false);
                        round_half_away(expr::eval_num(self, e, &cx)?).max(0.0) as u64
                    }
                    None => 1,
                };
                let Some((s, e)) = code.section(pc, rs).map_err(|name| {
                    let place = if *single { "" } else { " before this block" };
                    Fault::alarm(self.alarms.no_target, format!("REPEAT: label {name} not found{place}"), item.span)
                })?
                else {
                    return Ok(Flow::Next);
                };
                if n == 0 {
                    return Ok(Flow::Next);
                }
                let left = n - 1;
                let fr = self.frames.last_mut().ok_or_else(internal)?;
                fr.reps.push(Rep { restart: s, end: e, ret: pc + 1, left });
                Ok(Flow::Goto(s))
            }
            _ => Ok(Flow::Next),
        }
    }

    /// Evaluates a word's value. `None`: the word vanished (FANUC vacant variable).
    pub fn eval_word(&mut self, w: &crate::ir::Word) -> Result<Option<WordVal>, Fault> {
        let (e, mode) = match &w.value {
            WordValue::Expr(e) => (e, AbsInc::Plain),
            WordValue::Ac(e) => (e, AbsInc::Ac),
            WordValue::Ic(e) => (e, AbsInc::Ic),
            WordValue::Rotary(m, _) => return Err(super::refuse::rotary(self.file(), w, *m)),
        };
        let bare = self.fanuc && is_bare_literal(e);
        // A literal (nearly every word of CAM code) is its value: skip the walker.
        let lit = match &e.kind {
            ExprKind::Num(n) => Some(n.value),
            ExprKind::Unary(crate::ir::UnOp::Neg, a) => match &a.kind {
                ExprKind::Num(n) => Some(-n.value),
                _ => None,
            },
            _ => None,
        };
        let v = match lit {
            Some(x) => Value::Num(x),
            None => {
                let cx = self.cx(true);
                expr::eval(self, e, &cx)?
            }
        };
        let val = match v {
            Value::Vacant => return Ok(None),
            Value::Num(x) => WV::Num(x),
            Value::Str(s) => WV::Str(s),
        };
        let addr = match &w.addr {
            crate::ir::Addr::Letter(b) if b.is_ascii_uppercase() => {
                let i = (b - b'A') as usize;
                std::borrow::Cow::Borrowed(&LETTERS[i..i + 1])
            }
            crate::ir::Addr::Axis(e) => std::borrow::Cow::Owned(self.axis_name(e)?),
            a => std::borrow::Cow::Owned(a.as_str().to_ascii_uppercase()),
        };
        Ok(Some(WordVal { addr, val, mode, bare, literal: lit.is_some(), span: w.span }))
    }

    pub fn note_callee(&mut self, name: &CalleeName) -> String {
        match name {
            CalleeName::Number(n) => format!("O{n}"),
            CalleeName::Name(s) => s.clone(),
        }
    }
}

fn var_expr(v: &VarRef) -> Expr {
    Expr::new(ExprKind::Var(Box::new(v.clone())), v.span)
}

/// A FANUC literal without a decimal point (`X10`, `X-10`): the decimal-point rule applies.
fn is_bare_literal(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Num(n) => !n.point,
        ExprKind::Unary(crate::ir::UnOp::Neg, a) => {
            matches!(&a.kind, ExprKind::Num(n) if !n.point)
        }
        _ => false,
    }
}

const LETTERS: &str = "ABCDEFGHIJKLMNOPQRSTUVWXYZ";

pub fn internal() -> Fault {
    Fault::error(Diagnostic::error("NC499", "internal evaluator inconsistency (please report this program)"))
}
