//! The G codes that only change modal state (motion mode, plane, units, G90/G91, feed
//! type): one definition for the general block path and the literal fast path.

use super::Motion;
use crate::eval::trace::Plane;

/// The modal state a G code of [`Modal::g`] may change (`Machine::modal`).
///
/// `inch`: lengths in inch (FANUC G20, Siemens G70/G700); `inch_feed`: feeds in inch/min
/// (FANUC G20, Siemens G700). Siemens G70/G71 leave feeds in the basic system (MD10240,
/// metric in every profile here), whatever G700/G710 came before: only G700/G710 make F
/// inch/metric (828D function manual G2, 7.3; docs/semantics.md "Units"). The feed in force
/// is stored in mm/min, so it stays physically the same across any switch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Modal {
    pub motion: Motion,
    pub plane: Plane,
    pub absolute: bool,
    pub inch: bool,
    pub inch_feed: bool,
    pub per_rev: bool,
}

/// A G word's value as the machine reads it: ten times the code, rounded (G1 = 10,
/// G64.1 = 641, G700 = 7000).
#[inline]
pub fn g_index(g: f64) -> i64 {
    crate::eval::value::round(g * 10.0) as i64
}

impl Modal {
    /// The unit system variables with lengths (and feeds) are read and written in: FANUC
    /// G20; Siemens only under G700 (G70/G71 read and write in the basic system, metric:
    /// 828D function manual G2, 7.3), the feeds' unit in both.
    #[inline]
    pub fn sys_inch(&self) -> bool {
        self.inch_feed
    }

    /// Applies the G code `gi` ([`g_index`]) when all it does is change this state;
    /// `false` (nothing changed) for every other code, which the general path decides.
    #[inline]
    pub fn g(&mut self, fanuc: bool, gi: i64) -> bool {
        match gi {
            0 => self.motion = Motion::Rapid,
            10 => self.motion = Motion::Linear,
            20 => self.motion = Motion::Cw,
            30 => self.motion = Motion::Ccw,
            110 => {}
            170 => self.plane = Plane::XY,
            180 => self.plane = Plane::ZX,
            190 => self.plane = Plane::YZ,
            200 if fanuc => {
                self.inch = true;
                self.inch_feed = true;
            }
            210 if fanuc => {
                self.inch = false;
                self.inch_feed = false;
            }
            700 if !fanuc => {
                self.inch = true;
                self.inch_feed = false;
            }
            710 if !fanuc => {
                self.inch = false;
                self.inch_feed = false;
            }
            7000 if !fanuc => {
                self.inch = true;
                self.inch_feed = true;
            }
            7100 if !fanuc => {
                self.inch = false;
                self.inch_feed = false;
            }
            900 => self.absolute = true,
            910 => self.absolute = false,
            940 => self.per_rev = false,
            950 => self.per_rev = true,
            _ => return false,
        }
        true
    }
}
