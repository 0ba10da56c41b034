//! FANUC drilling cycles in loops and in called macros, to Sinumerik: a WHILE pass that
//! starts with its full cycle block and leaves the cycle active (the `G80` after the loop
//! cancels it) becomes one `MCALL … MCALL` per pass; a macro called in G90 (G00) by every
//! caller reads its cycle's R and Z in G90 and gets its motion mode back after `G80`.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

const LOOP: &str = "%\nO3000 (ROW OF HOLES)\nG21 G17 G90\nG00 X0. Y0. Z50.\n#26=-10.\n#9=100.\n#10=0\n\
WHILE [#10 LT 3] DO1\n#13=#10*10.\nG98 G81 X#13 Y0. Z#26 R2. F#9\n#10=#10+1\nEND1\nG80\nG00 X50.\nM30\n%\n";

#[test]
fn a_pass_that_leaves_its_cycle_active_ends_its_mcall() {
    let d = scratch_dir("cycles-in-loops-fanuc", "loop");
    let src = write(&d, "O3000.nc", LOOP);
    let (code, out, err) = nctrans(&["--to", "sinumerik", &src]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let lines: Vec<&str> = out.lines().map(str::trim).collect();
    let end = lines.iter().position(|l| *l == "ENDWHILE").expect("ENDWHILE");
    assert!(out.contains("MCALL CYCLE81") && lines[end - 1] == "MCALL", "{out}");
}

#[test]
fn a_move_before_the_pass_cycle_or_no_cancel_after_the_loop_is_refused() {
    let d = scratch_dir("cycles-in-loops-fanuc", "refused");
    // A move before the cycle block: on FANUC the previous pass's cycle drills there.
    let moved = LOOP.replace("#13=#10*10.\n", "#13=#10*10.\nX#13 Y5.\n");
    // The loop is followed by a move: the last pass's cycle would drill at it.
    let uncancelled = LOOP.replace("END1\nG80\nG00 X50.\n", "END1\nX50.\nG80\n");
    for (name, text) in [("MOVED.nc", moved), ("OPEN.nc", uncancelled)] {
        let src = write(&d, name, &text);
        let (code, _, err) = nctrans(&["--to", "sinumerik", &src]);
        assert_ne!(code, 0, "{name}: {err}");
        assert!(err.contains("NC428"), "{name}: {err}");
    }
}

const MAIN: &str = "%\nO2000\nG21 G17 G40 G49 G80 G90\nG00 X0. Y0. Z50.\nM98 P9200\nG00 Z100.\nM30\n%\n";
const MACRO: &str = "%\nO9200 (TWO HOLES)\nG98 G81 X10. Y10. Z-5. R2. F100.\nX20.\nG80\nX0. Y0.\nM99\n%\n";

#[test]
fn a_called_program_takes_g90_and_the_motion_mode_from_its_callers() {
    let d = scratch_dir("cycles-in-loops-fanuc", "called");
    let src = write(&d, "O2000.nc", MAIN);
    write(&d, "O9200.nc", MACRO);
    let out = d.join("out");
    let (code, _, err) = nctrans(&["--to", "sinumerik", &src, "-o", &format!("{}/", out.display())]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    // Called where G91 is in force, the R and Z read otherwise: no one mode, refused.
    let d2 = scratch_dir("cycles-in-loops-fanuc", "called-g91");
    let src2 = write(&d2, "O2000.nc", &MAIN.replace("M98 P9200\n", "M98 P9200\nG91 M98 P9200\nG90\n"));
    write(&d2, "O9200.nc", MACRO);
    let out2 = d2.join("out");
    let (code, _, err) = nctrans(&["--to", "sinumerik", &src2, "-o", &format!("{}/", out2.display())]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("G90/G91 depends on the path taken or on the caller"), "{err}");
}
