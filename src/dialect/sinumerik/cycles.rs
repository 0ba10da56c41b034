//! Sinumerik spelling of the drilling cycles: the standard cycle names and their parameter
//! lists, the classic 840D ones with the parameters 840D sl appended (`_GMODE`, `_DMODE`,
//! `_AMODE` …). The meaning is `ir::cycle`; the run is `eval::cycles::siemens`.

/// A Sinumerik drilling cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SieCycle {
    /// Drilling, centring.
    C81,
    /// Drilling, counterboring (dwell at the bottom).
    C82,
    /// Deep-hole drilling (chip breaking or chip removal).
    C83,
    /// Rigid tapping.
    C84,
    /// Tapping with a compensating (floating) chuck.
    C840,
    /// Boring 1: feed in, (dwell), feed out.
    C85,
    /// Boring 2: oriented spindle stop, lift-off, rapid out.
    C86,
    /// Boring 3: spindle stop, program stop, rapid out.
    C87,
    /// Boring 4: dwell, spindle stop, program stop, rapid out.
    C88,
    /// Boring 5: dwell, feed out.
    C89,
}

/// Whether `name` (upper case) is spelled as a cycle of the control's cycle package
/// (`CYCLE…`, `POCKET…`, `SLOT…`, `HOLES…`, `LONGHOLE`, `CONTPR…`): a program of the control,
/// not of the library, which only the drilling cycles above are modelled of.
pub fn is_package_name(name: &str) -> bool {
    ["CYCLE", "POCKET", "SLOT", "HOLES", "LONGHOLE", "CONTPR"].iter().any(|p| name.starts_with(p))
}

/// The cycle a called name is (upper case, as the parser gives it).
pub fn cycle_of(name: &str) -> Option<SieCycle> {
    Some(match name {
        "CYCLE81" => SieCycle::C81,
        "CYCLE82" => SieCycle::C82,
        "CYCLE83" => SieCycle::C83,
        "CYCLE84" => SieCycle::C84,
        "CYCLE840" => SieCycle::C840,
        "CYCLE85" => SieCycle::C85,
        "CYCLE86" => SieCycle::C86,
        "CYCLE87" => SieCycle::C87,
        "CYCLE88" => SieCycle::C88,
        "CYCLE89" => SieCycle::C89,
        _ => return None,
    })
}

impl SieCycle {
    pub fn name(self) -> &'static str {
        match self {
            SieCycle::C81 => "CYCLE81",
            SieCycle::C82 => "CYCLE82",
            SieCycle::C83 => "CYCLE83",
            SieCycle::C84 => "CYCLE84",
            SieCycle::C840 => "CYCLE840",
            SieCycle::C85 => "CYCLE85",
            SieCycle::C86 => "CYCLE86",
            SieCycle::C87 => "CYCLE87",
            SieCycle::C88 => "CYCLE88",
            SieCycle::C89 => "CYCLE89",
        }
    }

    /// The parameters in call order (Siemens 840D "Cycles" programming manual; the
    /// parameters after the classic list are those 840D sl added).
    pub fn params(self) -> &'static [&'static str] {
        match self {
            SieCycle::C81 => &["RTP", "RFP", "SDIS", "DP", "DPR", "_GMODE", "_DMODE", "_AMODE"],
            SieCycle::C82 => &["RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "_GMODE", "_DMODE", "_AMODE"],
            SieCycle::C83 => &[
                "RTP", "RFP", "SDIS", "DP", "DPR", "FDEP", "FDPR", "DAM", "DTB", "DTS", "FRF", "VARI", "_AXN", "_MDEP",
                "_VRT", "_DTD", "_DIS1", "_GMODE", "_DMODE", "_AMODE",
            ],
            SieCycle::C84 => &[
                "RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "SDAC", "MPIT", "PIT", "POSS", "SST", "SST1", "_AXN",
                "_PTAB", "_TECHNO", "_VARI", "_DAM", "_VRT",
            ],
            SieCycle::C840 => &[
                "RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "SDR", "SDAC", "ENC", "MPIT", "PIT", "_AXN", "_PTAB",
                "_TECHNO",
            ],
            SieCycle::C85 => &["RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "FFR", "RFF", "_GMODE", "_DMODE", "_AMODE"],
            SieCycle::C86 => &[
                "RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "SDIR", "RPA", "RPO", "RPAP", "POSS", "_GMODE", "_DMODE",
                "_AMODE",
            ],
            SieCycle::C87 => &["RTP", "RFP", "SDIS", "DP", "DPR", "SDIR", "_GMODE", "_DMODE", "_AMODE"],
            SieCycle::C88 => &["RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "SDIR", "_GMODE", "_DMODE", "_AMODE"],
            SieCycle::C89 => &["RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "_GMODE", "_DMODE", "_AMODE"],
        }
    }
}

/// The pitch of an ISO metric coarse thread M`size` (CYCLE84/CYCLE840 `MPIT`, 3 to 48).
pub fn metric_coarse_pitch(size: f64) -> Option<f64> {
    Some(match size as i64 {
        _ if size.fract() != 0.0 => return None,
        3 => 0.5,
        4 => 0.7,
        5 => 0.8,
        6 => 1.0,
        8 => 1.25,
        10 => 1.5,
        12 => 1.75,
        14 | 16 => 2.0,
        18 | 20 | 22 => 2.5,
        24 | 27 => 3.0,
        30 | 33 => 3.5,
        36 | 39 => 4.0,
        42 | 45 => 4.5,
        48 => 5.0,
        _ => return None,
    })
}
