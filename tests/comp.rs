//! Tool length and cutter radius compensation (issue 19, issue 17 item 6): the `comp`
//! events both evaluators write, the translation both ways through the H ↔ T/D offset map
//! (exact output, proven by verify), the refusals where a register cannot be proven, and
//! planted wrong translations (wrong H, wrong side, a missing G49 / D0) that the check
//! must catch.

use nctrans::check::{self, Side, Verdict};
use nctrans::dialect::{Dialect, ParseOptions, Semantics};
use nctrans::eval::{NoCallees, RunOptions, VecSink};
use nctrans::ir::Unit;
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::translate::to_sinumerik::{self as ts, Options};
use nctrans::translate::{self, to_fanuc::TranslateOptions};

const STEPS: u64 = 100_000;

fn parse(db: &mut SourceDb, name: &str, text: &str, d: Dialect) -> (nctrans::span::FileId, Unit) {
    let id = db.add(name, text);
    let p = nctrans::parse(db, id, d, &ParseOptions::for_dialect(d));
    assert!(!nctrans::diag::has_errors(&p.diags), "{name}:\n{}", nctrans::diag::render(db, &p.diags));
    (id, p.unit)
}

/// The text trace of a program.
fn trace(text: &str, d: Dialect) -> Vec<String> {
    let mut db = SourceDb::new();
    let (_, u) = parse(&mut db, "t", text, d);
    let mut sink = VecSink::default();
    let opts = RunOptions { max_steps: STEPS, ..RunOptions::default() };
    nctrans::eval::run(&mut db, &u, &mut NoCallees, &opts, &mut sink);
    sink.events.iter().map(|(e, _)| nctrans::eval::trace::text_line(e)).collect()
}

fn comp_events(text: &str, d: Dialect) -> Vec<String> {
    trace(text, d).into_iter().filter(|l| l.starts_with("comp")).collect()
}

/// The check of a Siemens program against a FANUC one.
fn check_pair(siemens: &str, fanuc: &str) -> (Verdict, String) {
    let mut db = SourceDb::new();
    let (_, s) = parse(&mut db, "a.mpf", siemens, Dialect::Sinumerik);
    let (_, f) = parse(&mut db, "b.nc", fanuc, Dialect::Fanuc);
    let side = |u: &Unit| Side {
        unit: u.clone(),
        callees: Box::new(NoCallees),
        run: RunOptions { max_steps: STEPS, ..RunOptions::default() },
    };
    let r = check::check(&db, side(&s), side(&f));
    (r.verdict, r.diff)
}

/// Siemens → FANUC: the program lines (no `%`, O line, header), after verify proved them.
fn to_fanuc(src: &str) -> Vec<String> {
    let mut db = SourceDb::new();
    let (_, u) = parse(&mut db, "in.mpf", src, Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], &TranslateOptions::default());
    assert!(t.ok(), "not translated:\n{}", nctrans::diag::render(&db, &t.diags));
    let v = translate::to_fanuc::verify(&mut db, &u, &[], &t.clone().into(), "out.nc", STEPS);
    assert!(v.equivalent, "{}\n{}\n{}", v.summary, v.rendered, t.text);
    t.text
        .lines()
        .filter(|l| *l != "%" && !l.starts_with('O') && !l.starts_with("(NCTRANS"))
        .map(str::to_string)
        .collect()
}

fn to_fanuc_codes(src: &str, opts: &TranslateOptions) -> Vec<&'static str> {
    let mut db = SourceDb::new();
    let (_, u) = parse(&mut db, "in.mpf", src, Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], opts);
    assert!(!t.ok(), "translated:\n{}", t.text);
    t.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect()
}

/// FANUC → Sinumerik: the program lines (header left out), after verify proved them.
fn to_sinumerik(src: &str) -> Vec<String> {
    let mut db = SourceDb::new();
    let (file, u) = parse(&mut db, "in.nc", src, Dialect::Fanuc);
    let tr = ts::translate(&[&u], &Options::default(), LineEnding::Lf);
    assert!(!tr.has_errors(), "not translated:\n{}", nctrans::diag::render(&db, &tr.diags));
    let rep = nctrans::translate::to_sinumerik::verify::verify_with(&db, file, &u, &tr, "out", STEPS);
    assert!(matches!(rep.verdict, Verdict::Equivalent { .. }), "{:?}\n{}", rep.verdict, rep.diff);
    let main = tr.main().expect("main file");
    main.text.lines().filter(|l| !l.starts_with("; Translated by")).map(str::to_string).collect()
}

fn to_sinumerik_codes(src: &str) -> Vec<&'static str> {
    let mut db = SourceDb::new();
    let (_, u) = parse(&mut db, "in.nc", src, Dialect::Fanuc);
    let tr = ts::translate(&[&u], &Options::default(), LineEnding::Lf);
    assert!(tr.has_errors(), "translated:\n{}", tr.main().map_or(String::new(), |f| f.text.clone()));
    tr.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect()
}

#[test]
fn fanuc_comp_events_follow_g43_g49_g41_g40_and_the_modal_registers() {
    let p = "%\nO1\nT1 M6\nG43 H1 Z50.\nG43 H1 Z40.\nH2\nG41 D11 X1. F100.\nG41 X2.\nD0 X3.\nG40 X4.\nG43 H0\nG43 H3\n\
             G91 G28 Z0.\nG49\nM30\n%\n";
    assert_eq!(
        comp_events(p, Dialect::Fanuc),
        [
            "comp length=1 radius=off",
            "comp length=2 radius=off",
            "comp length=2 radius=left:11",
            "comp length=2 radius=off", // D0: offset 0
            "comp length=off radius=off",
            "comp length=3 radius=off",
            // G28 keeps G43 modal (the vector is restored with the next Z move).
            "comp length=off radius=off",
        ]
    );
    // The event stands before the block's motion.
    let t = trace("%\nO1\nT1 M6\nG43 H1 Z50. M8\nM30\n%\n", Dialect::Fanuc);
    assert_eq!(t[1..4], ["comp length=1 radius=off", "coolant on", "move rapid Z=50 f=-"]);
}

#[test]
fn siemens_edges_carry_length_and_radius_and_a_tool_change_selects_d1() {
    let p = "T2 M6\nD2 G0 Z50\nG41 G1 X1 F100\nD0 X2\nG40 X3\nT=\"MILL\" M6\nD0\nM6 D3\nM30\n";
    assert_eq!(
        comp_events(p, Dialect::Sinumerik),
        [
            "comp length=\"2.1\" radius=off", // MD20270 = 1
            "comp length=\"2.2\" radius=off",
            "comp length=\"2.2\" radius=left:\"2.2\"",
            "comp length=off radius=off",
            "comp length=\"MILL.1\" radius=off",
            "comp length=off radius=off",
            "comp length=\"MILL.3\" radius=off",
        ]
    );
}

#[test]
fn g44_runs_with_a_warning_that_keeps_check_from_calling_it_equivalent() {
    let mut db = SourceDb::new();
    let (_, u) = parse(&mut db, "t.nc", "%\nO1\nT1 M6\nG44 H1 Z50.\nM30\n%\n", Dialect::Fanuc);
    let mut sink = VecSink::default();
    let out = nctrans::eval::run(&mut db, &u, &mut NoCallees, &RunOptions::default(), &mut sink);
    assert!(out.diags.iter().any(|d| d.code == nctrans::eval::machine::COMPENSATION_NOTE), "{:?}", out.diags);
}

#[test]
fn registers_pair_by_first_appearance_so_a_reused_register_is_a_divergence() {
    let siemens = "T1 M6 D1\nG0 Z50\nT2 M6 D1\nG0 Z50\nM30\n";
    // Renamed consistently: equivalent (the check does not know the setup sheet).
    let renamed = "%\nO1\nT1 M6\nG43 H11\nG0 Z50.\nT2 M6\nG43 H12\nG0 Z50.\nM30\n%\n";
    assert!(matches!(check_pair(siemens, renamed).0, Verdict::Equivalent { .. }));
    // One H for two tools: the second tool would run with the first one's length.
    let wrong = "%\nO1\nT1 M6\nG43 H1\nG0 Z50.\nT2 M6\nG43 H1\nG0 Z50.\nM30\n%\n";
    let (v, diff) = check_pair(siemens, wrong);
    assert!(matches!(v, Verdict::Diverged { .. }), "{v:?}");
    assert!(diff.contains("comp"), "{diff}");
}

const SIEMENS_PART: &str = "; two tools, a contour\nG17 G40 G90 G71\nT1 M6\nD1\nG54 G0 X0 Y0 S1000 M3\nZ50\n\
G1 Z-2 F100\nG41 X10 Y0\nY10\nG2 X20 Y20 CR=10\nG40 G1 X30 Y30\nG0 Z50\nT2 D1 M6\nG0 X5 Y5\nZ20\nD0\nM30\n";

#[test]
fn sinumerik_edges_translate_to_g43_h_and_g41_d_and_verify() {
    assert_eq!(
        to_fanuc(SIEMENS_PART),
        [
            "( two tools, a contour)",
            "G17 G40 G90 G21",
            "T1 M06",
            "G43 H1",
            "G54 G00 X0. Y0. S1000 M03",
            "Z50.",
            "G01 Z-2. F100.",
            "G41 D1 X10. Y0.",
            "Y10.",
            "G02 X20. Y20. R10.",
            "G40 G01 X30. Y30.",
            "G00 Z50.",
            "T2 M06",
            "G43 H2",
            "G00 X5. Y5.",
            "Z20.",
            "G49",
            "M30",
        ]
    );
    // The edge in the approach block: the G43 goes with the Z move.
    assert_eq!(to_fanuc("T3 M6\nG0 D1 Z50\nM30\n")[..2], ["T3 M06", "G00 G43 H3 Z50."]);
}

const FANUC_PART: &str = "%\nO2\nG17 G40 G49 G80 G90\nT1 M06\nG54 G00 X0. Y0. S1000 M03\nG43 H01 Z50. M08\n\
G01 Z-2. F100.\nG41 D01 X10. Y0.\nY10.\nG40 X0. Y0.\nG00 Z50. M09\nG49\nT#20 M06\nG43 H#20 Z50.\nG49\nM30\n%\n";

#[test]
fn fanuc_g43_and_g41_translate_to_the_edge_of_the_tool_in_the_spindle_and_verify() {
    let p = FANUC_PART.replace("T#20", "#20=2\nT#20");
    assert_eq!(
        to_sinumerik(&p),
        [
            "; FANUC variable map:",
            ";   #20 = LOC20",
            "DEF REAL LOC20",
            "G17 G40 G90",
            "T1 M6 D0",
            "G54 G0 X0 Y0 S1000 M3",
            "D1 Z50 M8",
            "G1 Z-2 F100",
            "G41 X10 Y0",
            "Y10",
            "G40 X0 Y0",
            "G0 Z50 M9",
            "D0",
            "LOC20=2",
            "T=LOC20 M6 D0",
            "D1 Z50",
            "D0",
            "M30",
        ]
    );
}

#[test]
fn registers_that_cannot_be_proven_are_refused_precisely() {
    let d = TranslateOptions::default();
    // The edge of a tool change without D is machine data, and a move comes before any D.
    assert_eq!(to_fanuc_codes("T1 M6\nG0 Z50\nD1\nM30\n", &d), ["NC470"]);
    // An edge without a tool in the spindle; an edge the map has no registers for.
    assert_eq!(to_fanuc_codes("D1\nG0 Z50\nM30\n", &d), ["NC470"]);
    assert_eq!(to_fanuc_codes("T1 M6 D2\nM30\n", &d), ["NC472"]);
    // A tool change or D0 under G41.
    assert_eq!(to_fanuc_codes("T1 M6 D1\nG41 G1 X1 F100\nT2 M6 D1\nM30\n", &d), ["NC473"]);
    assert_eq!(to_fanuc_codes("T1 M6 D1\nG41 G1 X1 F100\nD0 X2\nM30\n", &d), ["NC470"]);
    // A profile that states MD20270 makes the tool change's edge known.
    let mut stated = TranslateOptions::default();
    stated.source.cutting_edge_default = Some(1);
    let mut db = SourceDb::new();
    let (_, u) = parse(&mut db, "in.mpf", "T1 M6\nG0 Z50\nM30\n", Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], &stated);
    assert!(t.ok() && t.text.contains("T1 M06\nG43 H1\n"), "{}", t.text);

    // FANUC: an H that is not the tool's, G44, a tool change under G43, G41 under G49.
    assert_eq!(to_sinumerik_codes("%\nO1\nT1 M6\nG43 H2 Z50.\nM30\n%\n"), ["NC472"]);
    assert_eq!(to_sinumerik_codes("%\nO1\nT1 M6\nG44 H1 Z50.\nM30\n%\n"), ["NC474"]);
    assert_eq!(to_sinumerik_codes("%\nO1\nT1 M6\nG43 H1 Z50.\nT2 M6\nM30\n%\n"), ["NC473"]);
    assert_eq!(to_sinumerik_codes("%\nO1\nT1 M6\nG41 D1 X1. F100.\nM30\n%\n"), ["NC472"]);
    assert_eq!(to_sinumerik_codes("%\nO1\nG43 H1 Z50.\nM30\n%\n"), ["NC472"]);
}

#[test]
fn an_offset_map_names_the_registers_of_other_edges() {
    let mut sem = Semantics::default_for(Dialect::Fanuc);
    let (k, v) = nctrans::dialect::offsets::OffsetMap::parse_entry("6.2", "H26,D46").expect("entry");
    sem.offsets.edges.insert(k, v);
    let opts = TranslateOptions { target: sem, ..TranslateOptions::default() };
    let mut db = SourceDb::new();
    let (_, u) = parse(&mut db, "in.mpf", "T6 M6 D2\nG41 G1 X1 F100\nG40 X2\nM30\n", Dialect::Sinumerik);
    let t = translate::to_fanuc::to_fanuc(&u, &[], &opts);
    assert!(t.ok(), "{:?}", t.diags.iter().map(|d| &d.message).collect::<Vec<_>>());
    assert!(t.text.contains("T6 M06\nG43 H26\nG41 G01 D46 X1. F100.\n"), "{}", t.text);
    let v = translate::to_fanuc::verify(&mut db, &u, &[], &t.clone().into(), "out.nc", STEPS);
    assert!(v.equivalent, "{}", v.summary);
}

#[test]
fn planted_wrong_translations_are_caught() {
    let right: Vec<String> = to_fanuc(SIEMENS_PART);
    let fanuc = |lines: &[String]| format!("%\nO1\n{}\n%\n", lines.join("\n"));
    assert!(matches!(check_pair(SIEMENS_PART, &fanuc(&right)).0, Verdict::Equivalent { .. }));
    let planted = |from: &str, to: &str| -> Vec<String> {
        let mut hit = false;
        let v = right
            .iter()
            .filter_map(|l| {
                if !hit && l == from {
                    hit = true;
                    (!to.is_empty()).then(|| to.to_string())
                } else {
                    Some(l.clone())
                }
            })
            .collect();
        assert!(hit, "{from} not in the translation");
        v
    };
    for (what, from, to) in [
        ("wrong H for the second tool", "G43 H2", "G43 H1"),
        ("wrong side", "G41 D1 X10. Y0.", "G42 D1 X10. Y0."),
        ("missing G49", "G49", ""),
        ("missing G40", "G40 G01 X30. Y30.", "G01 X30. Y30."),
        ("missing G43 after the tool change", "G43 H2", ""),
    ] {
        let (v, _) = check_pair(SIEMENS_PART, &fanuc(&planted(from, to)));
        assert!(matches!(v, Verdict::Diverged { .. }), "{what}: {v:?}");
    }
    // The other way: a Siemens translation without its D0, and with the wrong side.
    let s_wrong = SIEMENS_PART.replace("D0\nM30", "M30");
    assert!(matches!(check_pair(&s_wrong, &fanuc(&right)).0, Verdict::Diverged { .. }));
    let s_side = SIEMENS_PART.replace("G41 X10", "G42 X10");
    assert!(matches!(check_pair(&s_side, &fanuc(&right)).0, Verdict::Diverged { .. }));
}

#[test]
fn the_profile_reads_the_offset_map_and_md20270() {
    use nctrans::config::Config;
    let c =
        Config::from_toml("[sinumerik]\ncutting_edge_default = 1\n[offsets]\n\"6.2\" = \"H26,D46\"\n").expect("read");
    assert_eq!(c.sinumerik_semantics().cutting_edge_default, Some(1));
    assert_eq!(c.fanuc_semantics().offsets.registers(6, 2), Some((26, 46)));
    assert_eq!(Config::default().sinumerik_semantics().cutting_edge_default, None);
    assert!(Config::from_toml("[offsets]\n\"6\" = \"H1,D1\"\n").is_err());
    assert!(Config::from_toml("[sinumerik]\ncutting_edge_default = 12\n").is_err());
}

/// A subprogram starts in its caller's compensation: its safety line (`G40 G49`, `G40`)
/// is known whatever the registers, so it translates; a register after it still needs a tool.
#[test]
fn a_subprograms_safety_line_translates() {
    let mut db = SourceDb::new();
    let (file, u) = parse(&mut db, "in.nc", "%\nO20\nG00 G17 G40 G49 G90\nG00 X1.\nM99\n%\n", Dialect::Fanuc);
    let tr = ts::translate(&[&u], &Options::default(), LineEnding::Lf);
    assert!(!tr.has_errors(), "{}", nctrans::diag::render(&db, &tr.diags));
    let text = &tr.main().expect("main").text;
    assert!(text.contains("G0 G17 G40 G90 D0\n"), "{text}");
    let rep = nctrans::translate::to_sinumerik::verify::verify_with(&db, file, &u, &tr, "out", STEPS);
    assert!(matches!(rep.verdict, Verdict::Equivalent { .. }), "{:?}", rep.verdict);
    let mut db = SourceDb::new();
    let (_, u) = parse(&mut db, "sub.spf", "PROC SUB\nG17 G40 G90\nG0 X1\nRET\n", Dialect::Sinumerik);
    let opts = TranslateOptions { main_is_sub: true, ..TranslateOptions::default() };
    let t = translate::to_fanuc::to_fanuc(&u, &[], &opts);
    assert!(t.ok() && t.text.contains("G17 G40 G90"), "{:?}", t.diags.iter().map(|d| &d.message).collect::<Vec<_>>());
}

/// A `PROC … SAVE` restores G40/G41/G42 with the other modal G groups: the return is a
/// `comp` event when it changes the radius compensation.
#[test]
fn a_save_subprogram_restores_the_radius_side() {
    let dir = std::env::temp_dir().join(format!("nctrans-comp-save-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch");
    std::fs::write(dir.join("MAIN.MPF"), "T1 M6 D1\nG0 X0 Y0\nSUBG\nG1 X5 F100\nM30\n").expect("write");
    std::fs::write(dir.join("SUBG.SPF"), "PROC SUBG SAVE\nG41 G1 X1 Y1 F100\nRET\n").expect("write");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_nctrans"))
        .args(["run", "MAIN.MPF"])
        .current_dir(&dir)
        .output()
        .expect("run nctrans");
    let text = String::from_utf8_lossy(&out.stdout);
    let comps: Vec<&str> =
        text.lines().filter(|l| l.starts_with("comp")).map(|l| l.split("  @").next().unwrap_or(l)).collect();
    assert_eq!(
        comps,
        [
            "comp length=\"1.1\" radius=off",
            "comp length=\"1.1\" radius=left:\"1.1\"",
            "comp length=\"1.1\" radius=off", // the return restores G40
        ],
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A Haas-style program: a G65 macro and an M98 subprogram that only move, then G43 H and
/// G41 D, and a tool change after them.
const FANUC_CALLS: &str = "%\nO1\nG17 G40 G49 G80 G90\nT1 M06\nG54 G00 X0. Y0. S1000 M03\nG43 H01 Z50.\n\
G65 P2001 A5.\nM98 P2002\nG01 Z-2. F100.\nG41 D01 X10. Y0.\nY10.\nG40 X0. Y0.\nM98 P2002\nG49\nT2 M06\n\
M98 P2002\nG43 H02 Z50.\nG49\nM30\nO2001\nG91 G01 X#1 F300.\nG90\nM99\nO2002\nG00 Z20.\nM99\n%\n";

#[test]
fn a_call_of_a_program_that_keeps_the_tool_keeps_the_compensation_known() {
    // The edge after both calls, the radius compensation, the tool change after a call;
    // proven equivalent by `to_sinumerik`.
    assert_eq!(
        to_sinumerik(FANUC_CALLS),
        [
            "G17 G40 G90",
            "T1 M6 D0",
            "G54 G0 X0 Y0 S1000 M3",
            "D1 Z50",
            "O_2001(5,1)",
            "O_2002",
            "G1 Z-2 F100",
            "G41 X10 Y0",
            "Y10",
            "G40 X0 Y0",
            "O_2002",
            "D0",
            "T2 M6 D0",
            "O_2002",
            "D1 Z50", // H2 is edge D1 of tool 2
            "D0",
            "M30",
        ]
    );
}

#[test]
fn a_call_of_a_program_that_changes_the_tool_or_is_unknown_is_refused_by_name() {
    // The callee cancels the length (a G49 safety line) or changes the tool.
    for callee in ["G49\nG00 Z20.", "T3 M06", "M98 P2003"] {
        let p = FANUC_CALLS.replace("O2002\nG00 Z20.", &format!("O2002\n{callee}"));
        let mut db = SourceDb::new();
        let (_, u) = parse(&mut db, "in.nc", &p, Dialect::Fanuc);
        let tr = ts::translate(&[&u], &Options::default(), LineEnding::Lf);
        let errors: Vec<_> = tr.diags.iter().filter(|d| d.is_error()).collect();
        let codes: Vec<&str> = errors.iter().map(|d| d.code).collect();
        if callee.starts_with("M98") {
            // O2003 is not in the job: the call itself is refused first.
            assert!(codes.contains(&"NC353") && codes.contains(&"NC520"), "{callee}: {codes:?}");
        } else {
            assert_eq!(codes.first(), Some(&"NC520"), "{callee}: {}", nctrans::diag::render(&db, &tr.diags));
        }
        let d = errors.iter().find(|d| d.code == "NC520").expect("NC520");
        assert!(d.message.contains("after the call of O2002"), "{}", d.message);
        let text = nctrans::diag::render(&db, &tr.diags);
        assert!(text.contains("this call may change the tool or the compensation"), "{text}");
    }
    // A variable read before the call may be changed by it: `G43 H#20` is no longer the tool's.
    let p = "%\nO1\n#20=1\nT#20 M06\nM98 P2002\nG43 H#20 Z50.\nM30\nO2002\nG00 Z20.\nM99\n%\n";
    assert_eq!(to_sinumerik_codes(p), ["NC472"]);
    // A G66 modal call of a program that changes the tool runs after every move.
    let p = "%\nO1\nT1 M06\nG43 H1 Z50.\nG66 P2002\nX1.\nG67\nM30\nO2002\nT3 M06\nM99\n%\n";
    assert!(to_sinumerik_codes(p).contains(&"NC521"));
}

/// A CAM post's tool change: the new tool is positioned in XY (spindle, work offset,
/// coolant) before its `G43 Z.. H..`.
const CAM_TOOL_CHANGE: &str =
    "%\nO1\nG90 G17 G94\nT1 M6\nS6000 M3\nG54\nM8\nG0 X-40. Y-10.\nG43 Z15. H1\nG1 Z-1. F500.\n\
X40.\nG0 Z15.\nM9\nG53 G0 Z0.\nT2 M6\nS2500 M3\nG54\nM8\nG0 X10. Y10.\nG43 Z15. H2\nG1 Z-3. F200.\nG0 Z15.\n\
G91 G28 Z0.\nT3 M6\nG90 G0 X5. Y5. S900 M3\nG43 Z20. H3\nG1 Z0. F100.\nM30\n%\n";

#[test]
fn a_tool_positioned_in_xy_before_its_g43_translates_and_verifies() {
    let out = to_sinumerik(CAM_TOOL_CHANGE);
    for (i, line) in ["T2 M6 D1", "S2500 M3", "G54", "M8", "G0 X10 Y10", "Z15"].iter().enumerate() {
        let at = out.iter().position(|l| l == "T2 M6 D1").expect("the second tool change") + i;
        assert_eq!(out[at], *line, "{out:#?}");
    }
    assert!(out.contains(&"T3 M6 D1".to_string()), "{out:#?}");
    // A move along Z under the old H, a position read or a call before the G43: refused.
    for between in ["G0 X10. Y10. Z50.", "G91 Z0.", "#1=#5003", "G0 X#5001", "G28 Z0.", "G81 Z-1. R1."] {
        let src = format!("%\nO1\nT1 M6\nG43 H1 Z50.\nT2 M6\n{between}\nG43 Z15. H2\nM30\n%\n");
        assert!(to_sinumerik_codes(&src).contains(&"NC473"), "{between}");
    }
    // So is a structure there, even one without compensation words (its blocks run in
    // between; a loop that moves only X would still be refused rather than followed).
    let looped =
        "%\nO1\nT1 M6\nG43 H1 Z50.\nT2 M6\nWHILE[#1 LT 2]DO1\n#1=#1+1\nG0 Z[40.+#1]\nEND1\nG43 Z15. H2\nM30\n%\n";
    assert!(to_sinumerik_codes(looped).contains(&"NC473"), "{looped}");
    // A call there (here of a program not in the job) is refused too.
    to_sinumerik_codes("%\nO1\nT1 M6\nG43 H1 Z50.\nT2 M6\nM98 P100\nG43 Z15. H2\nM30\n%\n");
}

#[test]
fn the_check_compares_a_deferred_length_where_z_first_moves() {
    // The same tool change, FANUC and Siemens: equivalent.
    let fanuc = "%\nO1\nT1 M6\nG43 H1 Z50.\nG53 Z0.\nT2 M6\nM8\nG0 X10. Y10.\nG43 Z15. H2\nM30\n%\n";
    let siemens = "T1 M6 D1\nZ50\nG53 Z0\nT2 M6 D1\nM8\nG0 X10 Y10\nZ15\nM30\n";
    let (v, diff) = check_pair(siemens, fanuc);
    assert!(matches!(v, Verdict::Equivalent { .. }), "{v:?}\n{diff}");
    // The Siemens program moves Z under the new edge where FANUC still has H1 (the same
    // programmed positions): a divergence, not an equivalence.
    let fanuc_z = "%\nO1\nT1 M6\nG43 H1 Z50.\nG53 Z0.\nT2 M6\nG0 X10. Y10. Z40.\nG43 Z15. H2\nM30\n%\n";
    let siemens_z = "T1 M6 D1\nZ50\nG53 Z0\nT2 M6 D1\nG0 X10 Y10 Z40\nZ15\nM30\n";
    let (v, diff) = check_pair(siemens_z, fanuc_z);
    assert!(matches!(v, Verdict::Diverged { .. }), "{v:?}\n{diff}");
    // The FANUC length selected blocks after the tool change (a spindle start between, the
    // G43 block's Z where Z already is) is held to the same event as the Siemens one.
    let fanuc_later = "%\nO1\nT2 M6\nG43 H2 Z25.\nG0 X50. Y30.\nT3 M6\nS800 M3\nG43 H3 Z25.\n\
G0 X10. Y10.\nG1 Z-5. F90.\nM30\n%\n";
    let siemens_at_m6 = "T2 M6 D1\nZ25\nG0 X50 Y30\nT3 M6 D1\nS800 M3\nZ25\nG0 X10 Y10\nG1 Z-5 F90\nM30\n";
    let (v, diff) = check_pair(siemens_at_m6, fanuc_later);
    assert!(matches!(v, Verdict::Equivalent { .. }), "{v:?}\n{diff}");
    // A Z move between the tool change and the G43 runs under H2 on FANUC and under the
    // new edge on Siemens, at the same programmed positions: a divergence.
    let fanuc_z_first = "%\nO1\nT2 M6\nG43 H2 Z25.\nG0 X50. Y30.\nT3 M6\nS800 M3\nG0 Z40.\nG43 H3 Z25.\n\
G0 X10. Y10.\nG1 Z-5. F90.\nM30\n%\n";
    let siemens_z_first = "T2 M6 D1\nZ25\nG0 X50 Y30\nT3 M6 D1\nS800 M3\nG0 Z40\nZ25\nG0 X10 Y10\nG1 Z-5 F90\nM30\n";
    let (v, diff) = check_pair(siemens_z_first, fanuc_z_first);
    assert!(matches!(v, Verdict::Diverged { .. }), "{v:?}\n{diff}");
    // A radius change is never deferred; nor is a length change that is not at a tool change.
    let (v, _) = check_pair(
        "T1 M6 D1\nG0 X10 Y10\nD2\nG0 X20\nM30\n",
        "%\nO1\nT1 M6\nG43 H1\nG0 X10. Y10.\nG0 X20.\nG43 H2\nM30\n%\n",
    );
    assert!(!matches!(v, Verdict::Equivalent { .. }), "{v:?}");
}
