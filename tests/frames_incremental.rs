//! Sinumerik `TRANS` (FANUC `G52`) in programs with incremental moves. Siemens travels a
//! frame change with the first incremental move of the axis after it (MD42440), FANUC after
//! G52 only the increment; once the axis is programmed absolutely in the new frame they agree.
//! So only an incremental move (or a call that may make one) of an axis not programmed since
//! its shift changed is refused (NC445, at the move, the TRANS beside it), followed through
//! branches, loops, jumps and called programs; everything else translates and is proven, and
//! a translation that moves the shift with the increment is caught by the check.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};

/// A shifted pocket: every axis absolute again after the TRANS, then an incremental step.
const POCKET: &str = "G17 G90 G54 G71\nT1 D1 M6\nS2500 M3\nG0 X0 Y0 Z100\nTRANS X50 Y40\n\
G0 X0 Y0 Z5\nG1 Z-2 F200\nG91 G1 X10 F600\nG90 G1 Y10\nG0 Z50\nTRANS\nG0 X0 Y0 Z100\nM30\n";

fn translated(d: &std::path::Path, name: &str, text: &str) -> (String, String) {
    let src = write(d, name, text);
    let (code, out, err) = nctrans(&["--to", "fanuc", &src]);
    assert_eq!(code, 0, "{name}: {err}\n{out}");
    assert!(err.contains("equivalent"), "{name}: {err}");
    (src, out)
}

fn refused(d: &std::path::Path, name: &str, text: &str) -> String {
    let src = write(d, name, text);
    let (code, out, err) = nctrans(&["--to", "fanuc", &src]);
    assert_ne!(code, 0, "{name}: {out}");
    assert!(err.contains("error[NC445]"), "{name}: {err}");
    err
}

fn caught(d: &std::path::Path, src: &str, bad: &str) {
    let b = write(d, "BAD.nc", bad);
    let (code, verdict, err) = nctrans(&["check", src, &b]);
    assert_ne!(code, 0, "{verdict}{err}");
    assert!(format!("{verdict}{err}").contains("diverge"), "{verdict}{err}");
}

#[test]
fn a_shifted_pocket_with_an_incremental_step_translates_and_is_proven() {
    let d = scratch_dir("frames_incremental", "pocket");
    let (src, out) = translated(&d, "P.MPF", POCKET);
    assert!(out.contains("G52 X50. Y40. Z0.") && out.contains("G91 G01 X10."), "{out}");
    // The step with the shift travelled too (what Siemens would do right after the TRANS).
    caught(&d, &src, &out.replace("G91 G01 X10.", "G91 G01 X60."));
    // An axis whose shift the TRANS leaves as it was (Z: 0 before and after) may step at once.
    let z = POCKET.replace("G0 X0 Y0 Z5\nG1 Z-2 F200\n", "G91 G1 Z-95 F200\nG90 G0 X0 Y0\n");
    translated(&d, "Z.MPF", &z);
}

#[test]
fn an_incremental_move_right_after_trans_is_refused_at_that_move() {
    let d = scratch_dir("frames_incremental", "right_after");
    let text = "G17 G90 G54 G71\nT1 D1 M6\nG0 X0 Y0 Z100\nTRANS X50\nG91 G1 X10 F600\nG90 G0 Z50\nTRANS\nM30\n";
    let err = refused(&d, "R.MPF", text);
    assert!(err.contains("R.MPF:5:"), "points at the move: {err}");
    assert!(err.contains("the shift of X changes here"), "the TRANS beside it: {err}");
    assert_eq!(err.matches("error[NC445]").count(), 1, "{err}");
    // IC() in G90 alike.
    refused(&d, "IC.MPF", &text.replace("G91 G1 X10 F600", "G1 X=IC(10) F600"));
    // What a translation without the rule writes diverges: Siemens travels the shift too.
    let good = "G17 G90 G54 G71\nT1 D1 M6\nG0 X0 Y0 Z100\nTRANS X50\nG0 X0\nG91 G1 X10 F600\nG90 G0 Z50\nTRANS\nM30\n";
    let (_, out) = translated(&d, "GOOD.MPF", good);
    let src = write(&d, "R.MPF", text);
    caught(&d, &src, &out.replace("G00 X0.\n", ""));
}

#[test]
fn the_flow_decides_branches_loops_and_jumps() {
    let d = scratch_dir("frames_incremental", "flow");
    let head = "G17 G90 G54 G71\nT1 D1 M6\nG0 X0 Y0 Z5\n";
    // Both branches program X again: the step after them translates.
    let both = format!("{head}R1=2\nTRANS X50\nIF R1>1\nG0 X0\nELSE\nG0 X5\nENDIF\nG91 G1 X10 F300\nG90\nTRANS\nM30\n");
    translated(&d, "BOTH.MPF", &both);
    // One branch does not: refused.
    let one = format!("{head}R1=2\nTRANS X50\nIF R1>1\nG0 X0\nENDIF\nG91 G1 X10 F300\nG90\nTRANS\nM30\n");
    refused(&d, "ONE.MPF", &one);
    // A loop whose body steps incrementally and changes the TRANS: the second pass steps
    // right after the change.
    let lp = format!("{head}FOR R1=1 TO 3\nG91 G1 X10 F300\nG90\nTRANS X=R1*20\nENDFOR\nTRANS\nM30\n");
    let err = refused(&d, "LOOP.MPF", &lp);
    assert!(err.contains("LOOP.MPF:5:"), "{err}");
    // The same loop programming X at the top of each pass translates.
    let ok = lp.replace("G91 G1 X10 F300\n", "G0 X0\nG91 G1 X10 F300\n");
    translated(&d, "LOOPOK.MPF", &ok);
    // A jump over the absolute move lands with X not programmed again.
    let jump = format!("{head}R1=2\nTRANS X50\nIF R1>1 GOTOF STEP\nG0 X0\nSTEP:\nG91 G1 X10 F300\nG90\nTRANS\nM30\n");
    refused(&d, "JUMP.MPF", &jump);
}

#[test]
fn pockets_in_a_subprogram_called_after_trans_translate() {
    let d = scratch_dir("frames_incremental", "pockets");
    let main = "G17 G90 G54 G71\nT1 D1 M6\nS2500 M3\nG0 X0 Y0 Z100\nTRANS X50 Y40\nPOCKETS\nTRANS X120 Y40\n\
                POCKETS\nTRANS\nG0 Z100\nM30\n";
    write(
        &d,
        "POCKETS.SPF",
        "PROC POCKETS\nG90 G0 X0 Y0 Z5\nG1 Z-2 F200\nFOR R1=1 TO 3\nG91 G1 X20 F600\nG1 Y4\nG1 X-20\nG1 Y4\nENDFOR\n\
         G90 G0 Z5\nRET\n",
    );
    let (src, out) = translated(&d, "MAIN.MPF", main);
    assert!(out.contains("G52 X120. Y40. Z0."), "{out}");
    caught(&d, &src, &out.replace("G52 X120. Y40. Z0.", "G52 X100. Y40. Z0."));
    // A subprogram that steps before positioning: refused at its call, naming the TRANS.
    write(&d, "STEPS.SPF", "PROC STEPS\nG91 G1 X20 F600\nG90 G0 Z5\nRET\n");
    let err = refused(&d, "STEPS.MPF", &main.replace("POCKETS", "STEPS"));
    assert!(err.contains("a call of STEPS") && err.contains("STEPS.MPF:6:"), "{err}");
    assert!(err.contains("the shift of X changes here"), "{err}");
}

#[test]
fn a_subprogram_with_its_own_trans_leaves_its_caller_to_program_again() {
    let d = scratch_dir("frames_incremental", "callee_trans");
    write(&d, "SHIFTED.SPF", "PROC SHIFTED\nG90\nTRANS X20\nG0 X0 Y0\nG1 X5 F300\nTRANS\nRET\n");
    let main = "G17 G90 G54 G71\nT1 D1 M6\nG0 X0 Y0 Z5\nSHIFTED\nG91 G1 X10 F300\nG90\nM30\n";
    let err = refused(&d, "MAIN.MPF", main);
    assert!(err.contains("MAIN.MPF:5:") && err.contains("this call may leave the shift of X changed"), "{err}");
    translated(&d, "AGAIN.MPF", &main.replace("SHIFTED\n", "SHIFTED\nG0 X0\n"));
}

#[test]
fn a_streamed_translation_proves_it_too() {
    let d = scratch_dir("frames_incremental", "stream");
    let src = write(&d, "P.MPF", POCKET);
    let out = d.join("P.nc").display().to_string();
    let (code, _, err) = nctrans(&["--to", "fanuc", "--stream", &src, "-o", &out]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("equivalent"), "{err}");
    let bad = write(&d, "R.MPF", &POCKET.replace("G0 X0 Y0 Z5\n", "G0 Z5\n"));
    let (code, _, err) = nctrans(&["--to", "fanuc", "--stream", &bad, "-o", &out, "--force"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("error[NC445]"), "{err}");
}

#[test]
fn a_trans_under_g91_is_written_under_g90_and_the_mode_selected_again() {
    let d = scratch_dir("frames_incremental", "under_g91");
    let text = "G17 G90 G54 G71\nT1 D1 M6\nG0 X0 Y0 Z5\nG91\nTRANS X50\nG90 G0 X0\nG91 G1 X10 F300\nG90\nTRANS\nM30\n";
    let (src, out) = translated(&d, "G91.MPF", text);
    assert!(out.contains("G90 G52 X50. Y0. Z0.\nG91\n"), "{out}");
    // G52 read under G91 (an incremental local shift): not what TRANS does.
    let bad = out.replace("G90 G52 X50. Y0. Z0.\nG91\n", "G52 X50. Y0. Z0.\n");
    let b = write(&d, "BAD.nc", &bad);
    let (code, verdict, err) = nctrans(&["check", &src, &b]);
    assert_ne!(code, 0, "{verdict}{err}");
    // In a called program the caller's mode is read and selected again.
    write(&d, "SUBT.SPF", "PROC SUBT\nTRANS X50\nG90 G0 X0 Y0\nG91 G1 X5 F100\nTRANS\nRET\n");
    let (_, out) = translated(&d, "CALLT.MPF", "G17 G90 G54 G71\nT1 D1 M6\nG91\nSUBT\nG90 G0 X0\nM30\n");
    assert!(out.contains("=#4003\nG90 G52 X50. Y0. Z0.\nG#"), "{out}");
}
