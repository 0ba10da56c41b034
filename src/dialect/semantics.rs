//! The facts where the two controls differ, as documented flags in one place. Parsers,
//! passes and the evaluator read them from here instead of hard-coding a dialect's rule.

use super::Dialect;

/// How a control behaves, per dialect and machine configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Semantics {
    /// FANUC has a vacant ("null") value distinct from 0; Siemens does not.
    pub has_vacant: bool,
    /// FANUC: an address value written without a decimal point is in least input
    /// increments (`X10` = 0.010 mm on IS-B metric). Siemens: always in units.
    pub increment_scaling: bool,
    /// Least input increment in mm for dimensional words without a decimal point
    /// (IS-B metric 0.001). Ignored when `increment_scaling` is false.
    pub least_increment_mm: f64,
    /// FANUC parameter 3401#0 DPI: calculator-type input (`X10` = 10 mm).
    pub calculator_input: bool,
    /// FANUC parameter 6004#0 NAT: false gives ATAN 0..360 and ASIN 270..90.
    pub nat: bool,
    /// Siemens relative-equality tolerance for comparisons (1e-12); 0 for exact.
    pub cmp_tolerance: f64,
    /// Highest R parameter number plus one (828D default 300, MD28050).
    pub r_param_count: u32,
    /// FANUC bracket nesting limit (5, alarm 118).
    pub max_bracket_depth: u32,
    /// Nested DO loops per program level (FANUC 3).
    pub max_loop_nesting: u32,
    /// Call nesting limit: FANUC 4 macro levels (G65/G66), Siemens 15 program levels below main.
    pub max_call_depth: u32,
    /// FANUC M98 nesting (independent of G65 levels).
    pub max_subprogram_depth: u32,
    /// Siemens MD42440 FRAME_OFFSET_INCR_PROG = 1 (default): the first incremental move
    /// after a frame / work-offset change also travels the offset change (the increment
    /// applies to the programmed workpiece position). FANUC: an incremental move travels
    /// only the increment. Used by the evaluator; the translator must keep it in mind when
    /// it emits G91 after an offset change.
    pub incremental_travels_offset: bool,
    /// FANUC parameter 5400#0 RIN (0i-A connection manual: "0: Specified by an absolute
    /// method, 1: Specified by G90 or G91"): the G68 angle R is added to the angle in force
    /// under G91. Default 0; the evaluator reads it, the translation refuses a G68 under
    /// G91 either way.
    pub rotation_angle_incremental: bool,
    /// A Haas control (`[fanuc] series = "haas"` / `"haas-ngc"`): `M97 Pn` calls the local
    /// subprogram at block Nn of the same program (Haas mill operator's manual 96-8000,
    /// M97). On a FANUC, M97 is a machine builder's M code. Also the dwell: a Haas `G04 P`
    /// written with a decimal point is seconds, without one milliseconds (`G04 P0.5` is
    /// 0.5 s, `G04 P500` 0.5 s); a FANUC `G04 P` is whole milliseconds (the evaluator refuses
    /// a written point there, NC513, and a computed P on a Haas, NC512: not settled).
    pub haas: bool,
    /// FANUC: the machine has the custom macro interrupt (`[fanuc] macro_interrupt`): `M96
    /// P…` enables the interrupt program P for the one interrupt signal (UINT), `M97`
    /// disables it, the program returns with M99 to the block after the interrupted one and
    /// runs with its own local variables. The signal's wiring and parameter 6003 (which type,
    /// local variables) are machine data the program does not show, so it is off unless the
    /// profile states it; off, M96/M97 are machine-specific M codes (docs/semantics.md,
    /// "Interrupts"). Not on a Haas, where M97 calls a local subprogram.
    pub macro_interrupt: bool,
    /// The FANUC length and radius registers of each Siemens cutting edge (the setup's
    /// offset table; by default edge D1 of tool n is H n and D n): `[offsets]`.
    pub offsets: crate::dialect::offsets::OffsetMap,
    /// Siemens MD20270 `$MC_CUTTING_EDGE_DEFAULT` as the profile states it: the edge a tool
    /// change without D selects (0: none). `None`: not stated; the evaluator runs with the
    /// factory setting 1 (D1), and the Sinumerik → FANUC translation refuses a tool change
    /// whose edge depends on it (840D sl function manual W1, 2.1).
    pub cutting_edge_default: Option<u32>,
    /// A Haas NGC control (`[fanuc] series = "haas-ngc"`): `#10000..#10999` are the general
    /// purpose variables, those with a legacy number read as it (`dialect::fanuc::haas_vars`).
    pub haas_ngc: bool,
    /// Siemens global user data (GUD): the `DEF NCK …` / `DEF CHAN …` definitions of the
    /// library's `.DEF` files (`crate::gud`), declared on the control before any program runs,
    /// so every program and subprogram sees them. Empty when no definition file applies.
    pub globals: std::sync::Arc<Vec<crate::ir::Def>>,
    /// Siemens macros (`DEFINE NAME AS text` in the library's `.DEF` files): the reader
    /// replaces every NAME in program code by its text (`dialect::sinumerik::macros`).
    /// Names upper case; empty when no definition file applies.
    pub macros: std::sync::Arc<Vec<(String, String)>>,
    /// Siemens master spindle (MD20090 `$MC_SPIND_DEF_MASTER_SPIND`, default 1): `M1=3` and
    /// `S1=1000` address it by number and mean what `M3` and `S1000` mean; the one FANUC
    /// spindle is it. Words of another spindle (`M2=3`) have no FANUC counterpart. `SETMS`
    /// is not modelled, so this stays the master spindle. 0 on FANUC (no numbered spindles).
    pub master_spindle: u32,
    /// Siemens tool management as the set-up's tool map knows it (`[tools]`, `--tool-map`):
    /// the T number of each tool name, which `GETT("NAME")` returns. Empty: not known, and
    /// `GETT` is refused (NC508). Names as written.
    pub tools: std::sync::Arc<std::collections::BTreeMap<String, u32>>,
    /// The file a FANUC `DPRNT` line is written to when translated to Siemens `WRITE`
    /// (`[sinumerik] write_file`): FANUC prints to the I/O channel, `WRITE` needs a file.
    pub write_file: String,
    /// Siemens values the machine's set-up fixes and no program writes (`[variables] fixed`):
    /// STRING global user data such as the axis letters a library's `.DEF` file declares
    /// (`AXIS_HORI = "Z"`), upper-case names. The evaluator starts them at these values and
    /// refuses a write to one (NC544); the translation to FANUC folds `AXNAME(AXIS_HORI)`
    /// to that axis (`lower::to_fanuc::axis_vars`). Empty: nothing is assumed.
    pub fixed: std::sync::Arc<std::collections::BTreeMap<String, String>>,
    /// The machine's signal wiring (`[signals]`): which FANUC interface signal each Siemens
    /// PLC datum or NCK input/output is (`dialect::signals`). Empty: none is known, and a
    /// translation refuses signals naming the key.
    pub signals: std::sync::Arc<crate::dialect::signals::SignalMap>,
}

/// The default of [`Semantics::write_file`].
pub const DEFAULT_WRITE_FILE: &str = "NCTRANS_PRINT";

/// The FANUC least input increment of a word written without a decimal point, in the unit
/// it is read in: `inc_mm` (the profile's metric increment, [`Semantics::least_increment_mm`])
/// for metric lengths, angles (`rotary`) and dwell seconds; a tenth of it in inch for
/// lengths under G20 (IS-B: 0.001 mm, 0.0001 in; IS-C: 0.0001 mm, 0.00001 in). The one
/// rule for the evaluator (`eval::machine`, G65 arguments) and the FANUC → Sinumerik
/// lowering (`lower::to_sinumerik::words::scale`), so both read `Z1000` alike.
#[inline(always)]
pub fn input_increment(inc_mm: f64, inch: bool, rotary: bool) -> f64 {
    if inch && !rotary {
        inc_mm / 10.0
    } else {
        inc_mm
    }
}

impl Semantics {
    /// [`input_increment`] of this profile.
    pub fn input_increment(&self, inch: bool, rotary: bool) -> f64 {
        input_increment(self.least_increment_mm, inch, rotary)
    }

    /// The default profile of each control (FANUC 0i/16i-class IS-B metric mill with NAT=0;
    /// Siemens 828D).
    pub fn default_for(dialect: Dialect) -> Semantics {
        match dialect {
            Dialect::Fanuc => Semantics {
                has_vacant: true,
                increment_scaling: true,
                least_increment_mm: 0.001,
                calculator_input: false,
                nat: false,
                cmp_tolerance: 0.0,
                r_param_count: 0,
                max_bracket_depth: 5,
                max_loop_nesting: 3,
                max_call_depth: 4,
                max_subprogram_depth: 10,
                incremental_travels_offset: false,
                rotation_angle_incremental: false,
                haas: false,
                macro_interrupt: false,
                offsets: Default::default(),
                cutting_edge_default: None,
                haas_ngc: false,
                globals: Default::default(),
                macros: Default::default(),
                master_spindle: 0,
                tools: Default::default(),
                write_file: DEFAULT_WRITE_FILE.into(),
                fixed: Default::default(),
                signals: Default::default(),
            },
            Dialect::Sinumerik => Semantics {
                has_vacant: false,
                increment_scaling: false,
                least_increment_mm: 0.001,
                calculator_input: true,
                nat: false,
                cmp_tolerance: 1e-12,
                r_param_count: 300,
                max_bracket_depth: u32::MAX,
                max_loop_nesting: u32::MAX,
                max_call_depth: 15,
                max_subprogram_depth: 15,
                incremental_travels_offset: true,
                rotation_angle_incremental: false,
                haas: false,
                macro_interrupt: false,
                offsets: Default::default(),
                cutting_edge_default: None,
                haas_ngc: false,
                globals: Default::default(),
                macros: Default::default(),
                master_spindle: 1,
                tools: Default::default(),
                write_file: DEFAULT_WRITE_FILE.into(),
                fixed: Default::default(),
                signals: Default::default(),
            },
        }
    }
}
