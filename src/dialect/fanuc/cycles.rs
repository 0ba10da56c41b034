//! FANUC spelling of the drilling cycles (group 09): which G code is which
//! [`CycleKind`], and which of them read P as a dwell at the bottom. The meaning and the
//! run live in `ir::cycle` and `eval::cycles`.

use crate::ir::cycle::CycleKind;

/// The cycle of a G code given as ten times its value (`g_index`: G81 = 810).
pub fn cycle_of(gi: i64) -> Option<CycleKind> {
    Some(match gi {
        730 => CycleKind::ChipBreak,
        740 => CycleKind::TapLeft,
        760 => CycleKind::FineBore,
        810 => CycleKind::Drill,
        820 => CycleKind::DwellDrill,
        830 => CycleKind::Peck,
        840 => CycleKind::Tap,
        850 => CycleKind::Bore,
        860 => CycleKind::BoreStop,
        870 => CycleKind::BackBore,
        // G88: feed in, dwell, spindle stop, then the operator retracts by hand: a stop.
        880 => CycleKind::BoreStop,
        890 => CycleKind::BoreDwell,
        _ => return None,
    })
}

/// G88: the spindle stops at the bottom and the control halts for the operator to
/// retract by hand (a `stop` after the hole), unlike G86 whose retract is a rapid.
pub fn is_manual_retract(gi: i64) -> bool {
    gi == 880
}

/// Whether the cycle's block format has P (dwell at the bottom, in milliseconds): G76,
/// G82, G74/G84, G87, G88, G89. G73, G81, G83, G85 and G86 have none.
pub fn takes_dwell(gi: i64) -> bool {
    matches!(gi, 740 | 760 | 820 | 840 | 870 | 880 | 890)
}
