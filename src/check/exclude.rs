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
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Excluded {
    pub messages: u64,
}

impl Excluded {
    pub fn is_empty(&self) -> bool {
        self.messages == 0
    }

    pub fn add(&mut self, other: Excluded) {
        self.messages += other.messages;
    }

    /// What was not compared, for people: `2 messages kept as comments`; `None` for nothing.
    pub fn describe(&self) -> Option<String> {
        match self.messages {
            0 => None,
            1 => Some("1 message kept as a comment".into()),
            n => Some(format!("{n} messages kept as comments")),
        }
    }

    /// The verdict line of an equivalence: `equivalent (12 events)`,
    /// `equivalent (12 events; 2 messages kept as comments)`; `detail` is what was compared.
    pub fn equivalent(&self, detail: &str) -> String {
        match self.describe() {
            Some(d) => format!("equivalent ({detail}; {d})"),
            None => format!("equivalent ({detail})"),
        }
    }
}
