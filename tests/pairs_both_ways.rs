//! The Siemens ↔ FANUC pair table, checked in both directions. Each row is a Siemens program
//! and a FANUC program that mean the same (the checker proves the row itself first); then
//! the Siemens one is translated to FANUC and the FANUC one to Siemens, and each translation
//! must verify against its source. Rows that only make sense one way say why. The exact
//! texts of each direction are pinned in `transpile_fanuc.rs` and `transpile_sinumerik.rs`.

use nctrans::check::{self, Side, Verdict};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{NoCallees, RunOptions};
use nctrans::ir::Unit;
use nctrans::read::LineEnding;
use nctrans::span::{FileId, SourceDb};
use nctrans::translate::to_sinumerik::{translate as to_sinumerik, Options};
use nctrans::translate::{self, to_fanuc::TranslateOptions};

const STEPS: u64 = 200_000;

#[derive(Clone, Copy, PartialEq)]
enum Way {
    Both,
    /// Only Siemens → FANUC, with the reason.
    SToF(&'static str),
    /// Only FANUC → Siemens, with the reason.
    FToS(&'static str),
}

struct Row {
    what: &'static str,
    siemens: &'static str,
    fanuc: &'static str,
    way: Way,
}

const ROWS: &[Row] = &[
    Row {
        what: "words, decimal point",
        siemens: "G1 X1 Y2.5 Z-0.01 F250\nM30\n",
        fanuc: "O1\nG01 X1. Y2.5 Z-10 F250.\nM30\n",
        way: Way::Both,
    },
    Row { what: "dwell", siemens: "G4 F0.5\nM30\n", fanuc: "O1\nG04 P500\nM30\n", way: Way::Both },
    Row { what: "inch units", siemens: "G700 G1 X1 F10\nM30\n", fanuc: "O1\nG20 G01 X1. F10.\nM30\n", way: Way::Both },
    // FANUC G20/G21 set lengths and feeds, as G700/G710 do (not G70/G71, which read F in
    // the basic system, mm/min): so no F is converted FANUC → Siemens.
    Row {
        what: "inch then metric units, feeds with them",
        siemens: "G700 G1 X1 F10\nG710 G1 X10 F500\nM30\n",
        fanuc: "O1\nG20 G01 X1. F10.\nG21 G01 X10. F500.\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "lengths inch, feeds metric (G70 after G700)",
        siemens: "G700 G1 X1 F10\nG70 G1 X2 F254\nM30\n",
        fanuc: "O1\nG20 G01 X1. F10.\nG01 X2. F10.\nM30\n",
        way: Way::SToF("G70 is written only where feeds are metric and lengths inch; FANUC → Siemens keeps G700"),
    },
    Row {
        what: "arc radius",
        siemens: "G1 X0 Y0 F100\nG2 X10 Y10 CR=10\nM30\n",
        fanuc: "O1\nG01 X0 Y0 F100.\nG02 X10. Y10. R10.\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "R parameters / common variables",
        siemens: "R1=2.5\nR2=R1*2\nG0 X=R2\nM30\n",
        fanuc: "O1\n#501=2.5\n#502=#501*2\nG00 X#502\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "IF/ELSE / IF-GOTO",
        siemens: "R1=3\nIF R1>2\nG0 X1\nELSE\nG0 X2\nENDIF\nM30\n",
        fanuc: "O1\n#501=3\nIF[#501 LE 2]GOTO 10\nG00 X1.\nGOTO 20\nN10 G00 X2.\nN20 M30\n",
        way: Way::Both,
    },
    Row {
        what: "WHILE",
        siemens: "R1=0\nWHILE R1<3\nG1 X=R1 F100\nR1=R1+1\nENDWHILE\nM30\n",
        fanuc: "O1\n#501=0\nWHILE[#501 LT 3]DO1\nG01 X#501 F100.\n#501=#501+1\nEND1\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "LOOP / bare DO",
        siemens: "R1=0\nLOOP\nR1=R1+1\nIF R1>=3 GOTOF OUT\nENDLOOP\nOUT: G0 X=R1\nM30\n",
        fanuc: "O1\n#501=0\nDO1\n#501=#501+1\nIF[#501 GE 3]GOTO 9\nEND1\nN9 G00 X#501\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "bitwise AND",
        siemens: "R1=12\nR2=R1 B_AND 10\nG0 X=R2\nM30\n",
        fanuc: "O1\n#501=12\n#502=#501 AND 10\nG00 X#502\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "rounding away from zero / ceiling",
        siemens: "R1=-1.2\nR2=ROUNDUP(R1)\nG0 X=R2\nM30\n",
        fanuc: "O1\n#501=-1.2\n#502=FIX[#501]\nG00 X#502\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "angle ranges",
        siemens: "R1=ATAN2(-1,-1)\nG0 X=R1\nM30\n",
        fanuc: "O1\n#501=ATAN[-1]/[-1]-360\nG00 X#501\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "exact comparison",
        siemens: "R1=0.1*3\nIF R1-0.3==0 GOTOF AA\nG0 X1\nAA: M30\n",
        fanuc: "O1\n#501=0.1*3\nIF[#501 EQ 0.3]GOTO 5\nG00 X1.\nN5 M30\n",
        way: Way::Both,
    },
    Row {
        what: "stop with message",
        siemens: "MSG(\"CHECK\")\nM0\nM30\n",
        fanuc: "O1\n#3006=1(CHECK)\nM30\n",
        way: Way::Both,
    },
    Row { what: "user alarm", siemens: "SETAL(65001)\nM30\n", fanuc: "O1\n#3000=1(STOP)\nM30\n", way: Way::Both },
    Row {
        what: "work offset write",
        siemens: "$P_UIFR[1,X,TR]=-100\nG54\nG0 X0\nM30\n",
        fanuc: "O1\nG10 L2 P1 X-100.\nG54 G00 X0\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "vacancy test of an argument",
        siemens: "R1=0\nIF R1==0 GOTOF AA\nG0 X1\nAA: M30\n",
        fanuc: "O1\nIF[#1 EQ #0]GOTO 5\nG00 X1.\nN5 M30\n",
        way: Way::FToS("Siemens has no vacant value: the Siemens side of the row can only emulate it"),
    },
    Row {
        what: "M98 sharing the caller's locals",
        siemens: "R1=1\nR1=R1*2\nG0 X=R1\nM30\n",
        fanuc: "O1\n#1=1.\nM98 P2\nG00 X#1\nM30\nO2\n#1=#1*2\nM99\n",
        way: Way::FToS("Siemens → FANUC refuses VAR parameters; the Siemens side here is the inlined meaning"),
    },
    Row {
        what: "FOR loop",
        siemens: "DEF INT CNT\nFOR CNT=1 TO 3\nG1 X=CNT F100\nENDFOR\nM30\n",
        fanuc: "O1\n#1=1\nWHILE[#1 LE 3]DO1\nG01 X#1 F100.\n#1=#1+1\nEND1\nM30\n",
        way: Way::Both,
    },
    Row {
        what: "string tool names",
        siemens: "T=\"DRILL\"\nM6 D1\nM30\n",
        fanuc: "O1\nT1 M06\nG43 H1\nM30\n",
        way: Way::SToF("FANUC has no tool names; the row needs --tool-map DRILL=1 and the trace compares names"),
    },
];

fn load(db: &mut SourceDb, name: &str, text: &str, d: Dialect) -> (FileId, Unit) {
    let id = db.add(name, text);
    let p = nctrans::parse(db, id, d, &ParseOptions::for_dialect(d));
    assert!(!nctrans::diag::has_errors(&p.diags), "{name} does not parse:\n{}", nctrans::diag::render(db, &p.diags));
    (id, p.unit)
}

fn same(db: &SourceDb, a: &Unit, b: &Unit) -> (Verdict, String) {
    let side = |u: &Unit| Side {
        unit: u.clone(),
        callees: Box::new(NoCallees),
        run: RunOptions { max_steps: STEPS, ..RunOptions::default() },
    };
    let r = check::check(db, side(a), side(b));
    let text = format!("{}\n{}", nctrans::diag::render(&r.db, &r.diags), r.diff);
    (r.verdict, text)
}

#[test]
fn pair_table_rows_are_equivalent_and_translate_both_ways() {
    let mut failures = Vec::new();
    for row in ROWS {
        let mut db = SourceDb::new();
        let (_, s) = load(&mut db, "row.mpf", row.siemens, Dialect::Sinumerik);
        let (ffile, f) = load(&mut db, "row.nc", row.fanuc, Dialect::Fanuc);
        if !matches!(row.way, Way::FToS(_) | Way::SToF(_)) {
            let (v, text) = same(&db, &s, &f);
            if !matches!(v, Verdict::Equivalent { .. }) {
                failures.push(format!("{}: the row's two programs differ ({v:?})\n{text}", row.what));
                continue;
            }
        }
        if matches!(row.way, Way::Both | Way::SToF(_)) {
            let mut opts = TranslateOptions::default();
            opts.tool_map.insert("DRILL".into(), 1);
            let t = translate::to_fanuc::to_fanuc(&s, &[], &opts);
            if !t.ok() {
                failures.push(format!(
                    "{}: S→F not translated: {:?}",
                    row.what,
                    t.diags.iter().map(|d| &d.message).collect::<Vec<_>>()
                ));
            } else {
                let v = translate::to_fanuc::verify(&mut db, &s, &[], &t.clone().into(), "out.nc", STEPS);
                if !v.equivalent {
                    failures
                        .push(format!("{}: S→F does not verify: {}\n{}\n{}", row.what, v.summary, v.rendered, t.text));
                }
            }
        }
        if matches!(row.way, Way::Both | Way::FToS(_)) {
            let t = to_sinumerik(&[&f], &Options::default(), LineEnding::Lf);
            if t.has_errors() {
                failures.push(format!(
                    "{}: F→S not translated: {:?}",
                    row.what,
                    t.diags.iter().map(|d| &d.message).collect::<Vec<_>>()
                ));
            } else {
                let r = nctrans::translate::to_sinumerik::verify::verify_with(&db, ffile, &f, &t, "out", STEPS);
                if !matches!(r.verdict, Verdict::Equivalent { .. }) {
                    let out: String = t.files.iter().map(|x| x.text.clone()).collect();
                    failures.push(format!(
                        "{}: F→S does not verify ({:?})\n{}\n{}\n{out}",
                        row.what,
                        r.verdict,
                        nctrans::diag::render(&r.db, &r.diags),
                        r.diff
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn one_way_rows_say_why() {
    for row in ROWS {
        if let Way::SToF(why) | Way::FToS(why) = row.way {
            assert!(why.len() > 20, "{}: a one-way row needs its reason", row.what);
        }
    }
}
