//! The interpreter's route for compact literal blocks (`dialect/lit.rs`, nearly every block of
//! CAM output): one block through `Machine::apply_lit` or the general words, and a stretch of
//! them run without going back to the main loop for each.

use super::{internal, Flow, Interp, LETTERS};
use crate::dialect::lit::LitBlock;
use crate::eval::fault::Fault;
use crate::eval::flow::{Code, Op};
use crate::eval::machine::{BlockEffect, WordVal, WV};
use crate::eval::paged::Page;
use crate::eval::trace::Origin;
use crate::eval::Ending;
use std::rc::Rc;

impl Interp<'_> {
    /// Runs the literal op `op` at `pc` of `code` and the literal ops after it (in `page`,
    /// the streamed page it is in, or in `code`'s ops), each exactly as `run_loop` runs
    /// an op, while each gives [`Flow::Next`] and leaves the frames as they were; returns
    /// the flow of the last op run and its pc. The top frame has no section repetition
    /// (its end is not looked for here) and no sink wants `block_done`.
    pub(super) fn run_lits(
        &mut self,
        code: &Rc<Code>,
        page: Option<&Page>,
        op: &Op,
        pc: usize,
    ) -> Result<(Flow, usize), Fault> {
        let depth = self.frames.len();
        let (mut op, mut pc) = (op, pc);
        loop {
            // Entered with a literal op and continued with literal ops only.
            let Op::Lit(l) = op else { return Err(internal()) };
            // What a frame reads of its own pc during the op (M99 Pn) is this op's.
            if let Some(fr) = self.frames.last_mut() {
                fr.pc = pc;
            }
            self.steps += 1;
            if self.steps > self.max_steps {
                return Err(self.step_limit(op));
            }
            if self.sink.wants_stop() {
                return Ok((Flow::Stop(Ending::Stopped), pc));
            }
            let flow = self.exec_lit(code, l, pc)?;
            // A held corner: `run_loop` checks what follows it.
            if !matches!(flow, Flow::Next) || self.frames.len() != depth || self.m.corners.held.is_some() {
                return Ok((flow, pc));
            }
            let next = match page {
                Some(p) => p.get(pc + 1),
                None => code.mem_op(pc + 1),
            };
            match next {
                Some(n @ Op::Lit(_)) => (op, pc) = (n, pc + 1),
                _ => return Ok((Flow::Next, pc)),
            }
        }
    }

    /// [`Interp::exec_block`] for a block of literal words: the same words, without the
    /// expression walker.
    pub(super) fn exec_lit(&mut self, code: &Rc<Code>, b: &LitBlock, pc: usize) -> Result<Flow, Fault> {
        if let Some(n) = b.number {
            self.m.last_n = f64::from(n);
        }
        if self.fast_path {
            if let Some(done) = self.m.apply_lit(b) {
                let Some(span) = done else { return Ok(Flow::Next) };
                // The machine's own move, written in place.
                // A held Siemens edge goes out before the move (`Interp::emit_ref`).
                let direct = self.pending_msg.is_none() && self.m.comp.held.is_none();
                match self.m.grid_move() {
                    Some(g) if direct => {
                        g.line = b.line;
                        // `code` is the running frame's: its file is `self.file()`.
                        let origin = Origin { file: code.file, span };
                        self.ints.motions += 1;
                        self.sink.grid_move(g, origin);
                    }
                    _ => {
                        let ev = self.m.move_event();
                        self.emit_ref(&ev, span);
                    }
                }
                // `block_end` of a block that moved and neither ends nor returns: only a
                // modal call can follow.
                if self.modal_call.is_none() && !self.ints.active() {
                    return Ok(Flow::Next);
                }
                let eff = BlockEffect { moved: true, ..Default::default() };
                return self.block_end(eff, b.span, pc);
            }
        }
        let mut words = std::mem::take(&mut self.words_buf);
        words.clear();
        // `extend` writes each word in place (a `push` per word built it on the stack
        // first and copied it, which stalled on the copy).
        let fanuc = self.fanuc;
        words.extend(b.words().iter().map(|w| {
            let i = usize::from(w.letter - b'A');
            WordVal {
                addr: std::borrow::Cow::Borrowed(&LETTERS[i..i + 1]),
                val: WV::Num(w.value),
                mode: w.mode,
                bare: fanuc && !w.point,
                literal: true,
                span: w.span,
            }
        }));
        self.finish_block(code, words, None, Vec::new(), b.span, pc)
    }
}
