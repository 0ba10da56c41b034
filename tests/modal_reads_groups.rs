//! Siemens `$P_GG[6]` (the plane G17/G18/G19 as 1..3) and `$P_GG[7]` (the radius
//! compensation G40/G41/G42 as 1..3), numbered by the SINUMERIK ONE programming manual's G
//! group tables (docs/semantics.md, Modal information): run, a read in a block that changes
//! the mode seeing the mode before it, the groups without a source refused by name.

mod eval_support;

use eval_support::{nctrans, scratch_dir, write};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    scratch_dir("modal-reads-groups-tests", name)
}

fn run(file: &str) -> (String, String) {
    let (_, out, err) = nctrans(&["run", file]);
    let lines: Vec<&str> = out.lines().map(|l| l.split("  @").next().unwrap_or("")).collect();
    (lines.join("\n"), err)
}

/// Each value of groups 6 and 7, and the read in `G19 R3=$P_GG[6]` / `G42 … R7=$P_GG[7]`
/// seeing the plane and side before the block (as group 1 does).
#[test]
fn plane_and_radius_compensation_groups_run_with_their_list_numbers() {
    let d = scratch("eval");
    let f = write(
        &d,
        "A.MPF",
        "G90 G71\nG0 X0\nR1=$P_GG[6]\nG18\nR2=$P_GG[6]\nG19 R3=$P_GG[6]\nR4=$P_GG[6]\nG17\nR5=$P_GG[7]\n\
         T1 D1\nG41 G1 X10 Y0 F100\nR6=$P_GG[7]\nG42 X20 R7=$P_GG[7]\nR8=$P_GG[7]\nG40 X30\nR9=$P_GG[7]\n\
         G0 X=R1 Y=R2 Z=R3\nG0 X=R4 Y=R5 Z=R6\nG0 X=R7 Y=R8 Z=R9\nM30\n",
    );
    let (out, err) = run(&f);
    for want in ["move rapid X=1 Y=2 Z=2 f=-", "move rapid X=3 Y=1 Z=2 f=-", "move rapid X=2 Y=3 Z=1 f=-"] {
        assert!(out.contains(want), "{want}: {out}{err}");
    }
    // Not a wrong value where the run meets a group without a source: NC656 naming it.
    for (n, what) in [(14, "group 14: G90/G91"), (15, "group 15: the feed type"), (10, "")] {
        let f = write(&d, "B.MPF", &format!("G90 G71\nG0 X0\nR1=$P_GG[{n}]\nM30\n"));
        let (_, err) = run(&f);
        assert!(err.contains("NC656") && err.contains(&format!("$P_GG[{n}]")) && err.contains(what), "{n}: {err}");
        assert!(err.contains("group 6 G17/G18/G19 = 1..3"), "{n}: {err}");
    }
}
