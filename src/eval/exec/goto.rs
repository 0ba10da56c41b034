//! Jumps: GOTO/GOTOF/GOTOB/GOTOC and FANUC GOTO n, to a block number, a label or a
//! computed target, searched as the dialect searches.

use super::*;

impl Interp<'_> {
    pub(super) fn goto(&mut self, code: &Rc<Code>, g: &Goto, pc: usize, span: Span) -> Result<Flow, Fault> {
        if let Some(c) = &g.cond {
            let cx = self.cx(false);
            if !expr::eval(self, c, &cx)?.truthy() {
                return Ok(Flow::Next);
            }
        }
        let (key, shown) = match &g.target {
            Target::Number(n) => (Some(Key::Number(n.value)), format!("N{}", n.value)),
            Target::Label(l) => (code.label_id(&l.name).map(Key::Label), l.name.clone()),
            Target::Computed(e) => {
                let cx = self.cx(true);
                match expr::eval(self, e, &cx)? {
                    Value::Str(s) => {
                        let up = s.to_ascii_uppercase();
                        (code.label_id(&up).map(Key::Label), up)
                    }
                    v => {
                        let n = round_half_away(v.num().unwrap_or(0.0));
                        if !(0.0..=99999.0).contains(&n) {
                            (None, format!("N{n}"))
                        } else {
                            (Some(Key::Number(n as u32)), format!("N{n}"))
                        }
                    }
                }
            }
        };
        let dest = key.and_then(|k| code.find(pc, g.search, k));
        match dest {
            Some(d) => Ok(Flow::Goto(d)),
            None if g.missing_continues => Ok(Flow::Next),
            None => Err(Fault::alarm(
                self.alarms.no_target,
                format!(
                    "jump target {shown} not found ({})",
                    match g.search {
                        Search::Forward => "searched forward",
                        Search::Backward => "searched backward",
                        Search::ForwardThenBackward => "searched forward, then backward",
                        Search::ForwardThenWrap => "searched to the end, then from the top",
                    }
                ),
                span,
            )),
        }
    }
}
