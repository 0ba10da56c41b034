//! Forms real program libraries use (issue 21): Haas conditional blocks, sign runs, nested
//! comments and separator lines in the FANUC reader; CASE without parentheses, numbered
//! program names, AX[…], rotary words, GUD definitions and synchronized actions in the
//! Siemens reader. Each pins what the construct becomes in the IR.

use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::ir::dump::dump;
use nctrans::span::SourceDb;

/// The dump without spans, and the diagnostic codes.
fn read(text: &str, dialect: Dialect) -> (String, Vec<&'static str>) {
    let mut db = SourceDb::new();
    let name = if dialect == Dialect::Fanuc { "t.nc" } else { "t.mpf" };
    let loaded = nctrans::load(&mut db, name, text.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, dialect, &ParseOptions::for_dialect(dialect));
    let problems = nctrans::ir::visit::check_spans(&parsed.unit, text.len() as u32);
    assert!(problems.is_empty(), "{problems:?}");
    let mut out = String::new();
    for line in dump(&parsed.unit).lines() {
        let words: Vec<&str> = line.split(' ').filter(|w| !w.starts_with('@')).collect();
        out.push_str(words.join(" ").trim());
        out.push('\n');
    }
    (out, parsed.diags.iter().map(|d| d.code).collect())
}

fn fanuc(text: &str) -> (String, Vec<&'static str>) {
    read(text, Dialect::Fanuc)
}

fn siemens(text: &str) -> (String, Vec<&'static str>) {
    read(text, Dialect::Sinumerik)
}

#[test]
fn haas_if_runs_the_nc_words_of_its_block() {
    let (ir, codes) = fanuc("O1\nIF [#1 EQ 2] S800 M03\nM30\n");
    // Read the same with any profile; without the Haas one a warning says FANUC alarms.
    assert_eq!(codes, vec!["NC255"]);
    assert!(ir.contains("if-block (eq #1 2)\nword S 800\nword M 3\n"), "{ir}");
    let (trace, codes) = run_haas("O1\n#1=2\nIF [#1 EQ 2] S800 M03\nIF [#1 NE 2] S900\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    assert!(trace.iter().any(|l| l.contains("800")) && !trace.iter().any(|l| l.contains("900")), "{trace:?}");
}

#[test]
fn haas_if_without_then_assigns() {
    let (ir, codes) = fanuc("O1\nIF [#9 EQ #0] #9=250.\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ir.contains("if-then (eq #9 vacant)\nassign #9 = 250.\n"), "{ir}");
}

#[test]
fn haas_then_assignment_with_words_is_one_conditional_block() {
    let (ir, codes) = fanuc("O1\nIF [#1 EQ 2] THEN #7=[#9*0.9] F[#9*0.85]\nM30\n");
    assert_eq!(codes, vec!["NC255"]);
    assert!(ir.contains("if-block (eq #1 2)\nassign #7 = (* #9 0.9)\nword F (* #9 0.85)\n"), "{ir}");
}

#[test]
fn an_if_with_nothing_after_it_is_a_warning() {
    let (ir, codes) = fanuc("O1\nIF [#1 EQ #2]\nM30\n");
    assert_eq!(codes, vec!["NC251"]);
    assert!(ir.contains("if-block (eq #1 #2)\n"), "{ir}");
}

#[test]
fn sign_runs_fold_to_one_sign() {
    let (ir, codes) = fanuc("O1\n#1=[+-2.]\n#2=[--#1]\n#3=[-+-#1]\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ir.contains("assign #1 = -2.\n"), "{ir}");
    assert!(ir.contains("assign #2 = #1\n"), "{ir}");
    assert!(ir.contains("assign #3 = #1\n"), "{ir}");
}

#[test]
fn balanced_inner_parentheses_stay_in_the_comment() {
    let (ir, codes) = fanuc("O1 (POCKET (D8) LEFT)\nG0 X1. (A (B))\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ir.contains("comment \"POCKET (D8) LEFT\""), "{ir}");
    assert!(ir.contains("comment \"A (B)\""), "{ir}");
}

#[test]
fn an_unbalanced_inner_parenthesis_ends_the_comment_at_the_first_close() {
    // As before nested comments were read: `(DIA (5MM)` is the comment `DIA (5MM`.
    let (ir, codes) = fanuc("O1\nG0 X1. (DIA (5MM)\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ir.contains("comment \"DIA (5MM\""), "{ir}");
}

#[test]
fn separator_lines_are_comments_with_a_warning() {
    let (ir, codes) = fanuc("O1\n* * * * *\n=====\nG0 X1.\nM30\n");
    assert_eq!(codes, vec!["NC250", "NC250"]);
    assert!(ir.contains("comment \"* * * * *\""), "{ir}");
    // Not a separator: a word, or marks with a value.
    assert_eq!(fanuc("O1\n--5\nM30\n").1.iter().filter(|c| **c == "NC250").count(), 0);
}

#[test]
fn case_without_parentheses_reads_as_with_them() {
    let with = siemens("DEF INT MODE=1\nCASE (MODE) OF 1 GOTOF AA DEFAULT GOTOF BB\nAA: M30\nBB: M30\n");
    let without = siemens("DEF INT MODE=1\nCASE MODE OF 1 GOTOF AA DEFAULT GOTOF BB\nAA: M30\nBB: M30\n");
    assert!(with.1.is_empty() && without.1.is_empty(), "{:?} {:?}", with.1, without.1);
    assert_eq!(with.0, without.0);
    assert!(without.0.contains("case MODE | 1 -> "), "{}", without.0);
}

#[test]
fn a_numbered_name_alone_is_a_program_call_a_letter_with_digits_an_address() {
    let (ir, codes) = siemens("SH602\nPLCASUP1 P2\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ir.contains("call SH602"), "{ir}");
    assert!(ir.contains("call PLCASUP1"), "{ir}");
    assert_eq!(siemens("X\nM30\n").1, vec!["NC127"]);
}

#[test]
fn ax_with_an_axis_letter_is_that_axis_and_with_a_variable_an_axis_chosen_at_run_time() {
    let (ir, codes) = siemens("DEF AXIS A_W\nA_W=AXNAME(\"Z\")\nG1 AX[X]=5 AX[A_W]=IC(2) F10\nTRANS AX[A_W]=1\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ir.contains("word X 5\n"), "{ir}");
    assert!(ir.contains("word AX[A_W] ic(2)\n"), "{ir}");
    assert!(ir.contains("frame TRANS AX[A_W] 1\n"), "{ir}");
    assert!(ir.contains("assign A_W = (axname \"Z\")\n"), "{ir}");
}

#[test]
fn rotary_positioning_keeps_its_direction() {
    let (ir, codes) = siemens("G1 C=ACP(90) F100\nC=ACN(0)\nC=DC(10)\nC=CAC(2)\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    for w in ["word C acp(90)", "word C acn(0)", "word C dc(10)", "word C cac(2)"] {
        assert!(ir.contains(w), "{w} in {ir}");
    }
    assert_eq!(siemens("R1=ACP(5)\nM30\n").1, vec!["NC125"]);
}

#[test]
fn global_user_data_keeps_its_scope() {
    let (ir, codes) = siemens("DEF NCK REAL WHEEL[50]\nDef Chan Int STAGE\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ir.contains("def nck REAL WHEEL[50]"), "{ir}");
    assert!(ir.contains("def chan INT STAGE"), "{ir}");
}

#[test]
fn synchronized_actions_are_read_with_condition_and_actions() {
    let (ir, codes) =
        siemens("ID=1 WHEN ($A_IN[1]==1) AND (R1==0) DO DELDTG(X)\nWHEN $A_DBB[2]==1 DO POS[X]=0.2 FA[X]=30\nM30\n");
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ir.contains("sync-action id=1 when"), "{ir}");
    assert!(ir.contains("call DELDTG (X)"), "{ir}");
    assert!(ir.contains("assign POS['X] = 0.2\nassign FA['X] = 30\n"), "{ir}");
}

/// Parses and runs a FANUC program with the Haas profile; the trace lines.
fn run_haas(text: &str) -> (Vec<String>, Vec<&'static str>) {
    use nctrans::dialect::Semantics;
    use nctrans::eval::{self, RunOptions, VecSink};
    let mut sem = Semantics::default_for(Dialect::Fanuc);
    sem.haas = true;
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, "haas.nc", text.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Fanuc, &ParseOptions { semantics: sem.clone() });
    assert!(!nctrans::diag::has_errors(&parsed.diags), "{:?}", parsed.diags);
    let opts = RunOptions { semantics: Some(sem.clone()), ..RunOptions::default() };
    let mut sink = VecSink::default();
    let mut callees = eval::DirCallees { semantics: Some(sem) };
    let out = eval::run(&mut db, &parsed.unit, &mut callees, &opts, &mut sink);
    let lines = sink.events.iter().map(|(e, _)| nctrans::eval::trace::text_line(e)).collect();
    (lines, out.diags.iter().map(|d| d.code).collect())
}

#[test]
fn haas_m97_runs_the_local_subprogram_l_times_and_returns_after_the_call() {
    let src = "O1\nG00 G90 X0 Y0\nM97 P1000 L2\nG00 X50.\nM30\nN1000 G91 G01 X10. F300.\nG90\nM99\n";
    let (trace, codes) = run_haas(src);
    assert!(codes.is_empty(), "{codes:?}");
    let moves: Vec<&String> = trace.iter().filter(|l| l.starts_with("move")).collect();
    assert_eq!(moves.len(), 4, "{trace:?}");
    assert!(moves[1].contains("X=10"), "{trace:?}");
    assert!(moves[2].contains("X=20"), "{trace:?}");
    assert!(moves[3].contains("X=50"), "{trace:?}");
    // Without the Haas profile M97 is a plain M code, with a warning saying why.
    assert!(fanuc(src).1.contains(&"NC253"));
}

#[test]
fn haas_m97_to_a_missing_block_is_the_controls_alarm() {
    let (trace, codes) = run_haas("O1\nM97 P2000\nM30\n");
    assert!(trace.iter().any(|l| l.contains("alarm")), "{trace:?} {codes:?}");
}

#[test]
fn extern_declares_and_call_forms_name_the_program() {
    let (ir, codes) = siemens(
        "EXTERN CYC(REAL, VAR INT[3])\nDEF STRING[8] P_NAME\nCALL \"cyc\"\nCALL P_NAME\nPCALL CYC(1, R2)\nM30\n",
    );
    assert!(codes.is_empty(), "{codes:?}");
    assert!(ir.contains("extern CYC (REAL[], var INT[3])"), "{ir}");
    assert!(ir.contains("call CYC\n"), "{ir}");
    assert!(ir.contains("call P_NAME\n"), "{ir}");
    assert!(ir.contains("call CYC (1, R2)\n"), "{ir}");
}
