//! What a check knowingly leaves out of the comparison ([`Exclude`]) and what it counted
//! leaving out ([`Excluded`]), so that a verdict can say what was not compared.

/// Trace events a translation knowingly does not carry: a check of it leaves them out of the
/// comparison and counts them ([`Excluded`]), so that its verdict says what was not compared.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Exclude {
    /// The first run's messages shown without a stop (Siemens `MSG`), and the message of a
    /// first-run stop that the second run makes without one: FANUC shows no message without
    /// stopping, so the Sinumerik → FANUC translation keeps such a `MSG` as a comment.
    pub messages: bool,
}

/// What a check left out of the comparison ([`Exclude`]), counted as the first run made it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Excluded {
    pub messages: u64,
    /// Look-ahead and high-speed settings of the first run (`G05.1 Q1`, `FFWON`,
    /// `CYCLE832`, …: warning NC560, once per place): they have no trace event, so the two
    /// programs' settings were not compared.
    pub modes: u64,
    /// Interrupt routines of the first run whose input never switched while they were
    /// enabled (warning NC566, once per assigning instruction): they did not run, so
    /// what they do was not compared.
    pub interrupts: u64,
    /// Machine signal writes of the first run (`$A_OUT[n]=…`, `#1100=…`: warning NC579, once
    /// per place): the trace has no event for signals, so the two programs' writes were not
    /// compared.
    pub signals: u64,
    /// Inputs of the Siemens side that name a main-program DEF variable, left out because
    /// the FANUC program assigns the DEF's start value itself (warning NC661,
    /// `translate::to_fanuc::proof_sets`).
    pub unused_inputs: Vec<String>,
    /// The set-up values the runs read (`[variables] fixed`: `AXIS_HORI = "Z"`, from the
    /// runs' NC543 notes): compared, but true only on a machine set up so. Not "left out",
    /// so not in [`Excluded::describe`]; every verdict line ([`Excluded::equivalent`]) names them.
    pub assumed: Option<String>,
}

impl Excluded {
    pub fn is_empty(&self) -> bool {
        self.messages == 0
            && self.modes == 0
            && self.interrupts == 0
            && self.signals == 0
            && self.unused_inputs.is_empty()
    }

    pub fn add(&mut self, other: Excluded) {
        self.messages += other.messages;
        self.modes += other.modes;
        self.interrupts += other.interrupts;
        self.signals += other.signals;
        for i in other.unused_inputs {
            if !self.unused_inputs.contains(&i) {
                self.unused_inputs.push(i);
            }
        }
        self.assumed = crate::dialect::fixed::joined(self.assumed.take(), other.assumed);
    }

    /// What was not compared, for people: `2 messages kept as comments`, `1 look-ahead
    /// setting not compared`, both joined by a comma; `None` for nothing.
    pub fn describe(&self) -> Option<String> {
        let mut parts = Vec::new();
        match self.messages {
            0 => {}
            1 => parts.push("1 message kept as a comment".to_string()),
            n => parts.push(format!("{n} messages kept as comments")),
        }
        match self.modes {
            0 => {}
            1 => parts.push("1 look-ahead setting not compared".to_string()),
            n => parts.push(format!("{n} look-ahead settings not compared")),
        }
        match self.interrupts {
            0 => {}
            1 => parts.push("1 interrupt routine not compared (its input never switched)".to_string()),
            n => parts.push(format!("{n} interrupt routines not compared (their inputs never switched)")),
        }
        match self.signals {
            0 => {}
            1 => parts.push("1 signal write not compared".to_string()),
            n => parts.push(format!("{n} signal writes not compared")),
        }
        if !self.unused_inputs.is_empty() {
            let what = if self.unused_inputs.len() == 1 { "input" } else { "inputs" };
            parts.push(format!(
                "not used: the {what} {}, as the FANUC program assigns the DEF's start value (NC661)",
                self.unused_inputs.join(" ")
            ));
        }
        (!parts.is_empty()).then(|| parts.join(", "))
    }

    /// The verdict line of an equivalence: `equivalent (12 events)`,
    /// `equivalent (12 events; 2 messages kept as comments)`; `detail` is what was compared.
    pub fn equivalent(&self, detail: &str) -> String {
        let mut parts: Vec<String> = vec![detail.to_string()];
        parts.extend(self.describe());
        parts.extend(self.assumed.as_ref().map(|a| format!("assumed from the set-up (variables.fixed): {a}")));
        format!("equivalent ({})", parts.join("; "))
    }
}
