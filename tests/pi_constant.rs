//! Siemens `$PI` to FANUC: written as two 8-digit literals whose double is Siemens' `$PI`, so
//! every value computed from it is Siemens' to the last bit; the 8-digit rounding a programmer
//! might write (3.1415927, 4.6e-8 off) is caught by the check where that shows in a position.

#[path = "support/cli_run.rs"]
mod cli_run;

use cli_run::{nctrans, workdir};

/// A grinding-style computation: the wheel speed from the line speed, and a circle of
/// holes by arc length.
const SRC: &str = "DEF REAL WHEEL_D, RPM, ARC_ANG
WHEEL_D=400
RPM=35*60000/($PI*WHEEL_D)
S=ROUND(RPM) M3
ARC_ANG=250/(WHEEL_D/2)*180/$PI
G0 X=WHEEL_D/2*COS(ARC_ANG) Y=WHEEL_D/2*SIN(ARC_ANG)
G1 X=1000*$PI F200
G1 Y=$PI*100000
M30
";

#[test]
fn pi_is_written_exactly_and_proven() {
    let d = workdir("pi", "exact");
    std::fs::write(d.join("WHEEL.MPF"), SRC).unwrap();
    let (out, err, code) = nctrans(&d, &["--to", "fanuc", "WHEEL.MPF", "-o", "wheel.nc"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(err.contains("equivalent"), "{err}");
    let text = std::fs::read_to_string(d.join("wheel.nc")).unwrap();
    assert!(text.contains("[3.1415926+0.53589793/10000000.]"), "{text}");
    assert!(!text.contains("$PI") && !err.contains("NC342"), "{text}{err}");
    // Every number within FANUC's 8 digits: no rounding warning.
    assert!(!err.contains("NC350"), "{err}");
    // The rounded constant a programmer might write diverges where the 8th digit shows.
    std::fs::write(d.join("rounded.nc"), text.replace("[3.1415926+0.53589793/10000000.]", "3.1415927")).unwrap();
    let (out, err, code) = nctrans(&d, &["check", "WHEEL.MPF", "rounded.nc"]);
    assert_ne!(code, 0, "{out}{err}");
    assert!(format!("{out}{err}").contains("diverge"), "{out}{err}");
}
