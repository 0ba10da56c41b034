//! Unit-style tests of the Sinumerik reader: the fast path gives the grammar's IR, the
//! Siemens precedence table, keyword guards, header/PROC handling, one error per bad block,
//! and robustness against deep nesting and mutated input.

use nctrans::dialect::sinumerik::{block_via_fast_path, block_via_grammar};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::span::SourceDb;
use nctrans::{diag, ir};

fn parse(text: &str) -> (String, Vec<nctrans::diag::Diagnostic>, String) {
    let mut db = SourceDb::new();
    let file = db.add("t.mpf", text);
    let p = nctrans::parse(&db, file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
    let problems = ir::visit::check_spans(&p.unit, text.len() as u32);
    assert!(problems.is_empty(), "{problems:?}");
    let rendered = diag::render(&db, &p.diags);
    (ir::dump::dump(&p.unit), p.diags, rendered)
}

fn ok(text: &str) -> String {
    let (dump, diags, rendered) = parse(text);
    assert!(!diag::has_errors(&diags), "{text:?} rejected:\n{rendered}");
    dump
}

fn codes(text: &str) -> Vec<&'static str> {
    parse(text).1.iter().filter(|d| d.is_error()).map(|d| d.code).collect()
}

/// The expression of `R1=<e>` in dump form.
fn value(e: &str) -> String {
    let d = ok(&format!("R1={e}\n"));
    let line = d.lines().find(|l| l.trim_start().starts_with("assign")).unwrap_or_default().trim().to_string();
    let v = line.trim_start_matches("assign R1 = ");
    v[..v.rfind(" @").unwrap_or(v.len())].to_string()
}

#[path = "support/rng.rs"]
mod rng;
use rng::Rng;

fn number(r: &mut Rng) -> String {
    let sign = r.pick(&["", "-", "+", ""]);
    let int = (r.next() % 5000).to_string();
    match r.next() % 5 {
        0 => format!("{sign}{int}"),
        1 => format!("{sign}{int}."),
        2 => format!("{sign}.{}", r.next() % 1000),
        _ => format!("{sign}{int}.{}", r.next() % 100000),
    }
}

#[test]
fn fast_path_gives_the_grammar_ir_on_generated_blocks() {
    let mut r = Rng(0x9e3779b97f4a7c15);
    let mut taken = 0;
    for _ in 0..20000 {
        let mut b = String::new();
        if r.next().is_multiple_of(3) {
            b.push_str(&format!("N{} ", r.next() % 100000));
        }
        for _ in 0..(1 + r.next() % 6) {
            let letter =
                r.pick(&["G", "X", "Y", "Z", "F", "S", "M", "T", "D", "I", "J", "K", "A", "x", "g", "E", "R", "H"]);
            let sep = r.pick(&[" ", " ", "\t", "", "  "]);
            b.push_str(&format!("{letter}{}{sep}", number(&mut r)));
        }
        if r.next().is_multiple_of(4) {
            b.push_str(r.pick(&[";", "; comment", ";注释 X1", " ;"]));
        }
        let grammar = block_via_grammar(&b);
        if let Some(fast) = block_via_fast_path(&b) {
            taken += 1;
            assert_eq!(Some(fast), grammar, "block {b:?}");
        }
    }
    assert!(taken > 10000, "fast path took only {taken} blocks");
}

#[test]
fn fast_path_declines_what_it_does_not_know() {
    for b in [
        "X=1",
        "X1=10",
        "G1 X1EX3",
        "L123",
        "N10 LABEL: X1",
        "X1.2.3",
        "R1=5",
        "P3",
        "G1 X",
        "IF R1 GOTOF A",
        "X1 [",
        "/X1",
    ] {
        assert_eq!(block_via_fast_path(b), None, "{b}");
    }
}

#[test]
fn siemens_precedence_table() {
    assert_eq!(value("R2==1 AND R3==2"), "(eq~ (eq~ R2 (and 1 R3)) 2)");
    assert_eq!(value("1 OR 0 AND 0"), "(or 1 (and 0 0))");
    assert_eq!(value("1 XOR 1 OR 1"), "(or (xor 1 1) 1)");
    assert_eq!(value("1 B_OR 2 B_XOR 3 B_AND 4"), "(bor 1 (bxor 2 (band 3 4)))");
    assert_eq!(value("1+2 B_AND 3"), "(band (+ 1 2) 3)");
    assert_eq!(value("\"A\" << 1 == \"A1\""), "(eq~ (concat \"A\" 1) \"A1\")");
    assert_eq!(value("2+3*4-6/2"), "(- (+ 2 (* 3 4)) (/ 6 2))");
    assert_eq!(value("7 DIV 2 MOD 3"), "(mod (div 7 2) 3)");
    assert_eq!(value("NOT R2 AND R3"), "(and (not R2) R3)");
    assert_eq!(value("B_NOT 5 B_AND 3"), "(band (bnot 5) 3)");
    assert_eq!(value("-R2*3"), "(* (neg R2) 3)");
    assert_eq!(value("2*-3"), "(* 2 (neg 3))");
    assert_eq!(value("1 < 2 <> 0"), "(ne~ (lt~ 1 2) 0)");
}

#[test]
fn long_operator_chains_do_not_recurse() {
    // The tree is built without recursion; its depth is capped because later phases recurse.
    let chain = vec!["1"; 200].join("+");
    assert!(ok(&format!("R1={chain}\n")).contains("assign R1"));
    let chain = vec!["1"; 50000].join("+");
    assert_eq!(codes(&format!("R1={chain}\n")), vec!["NC130"]);
    let negs = "-".repeat(2000);
    assert_eq!(codes(&format!("R1={negs}1\n")), vec!["NC130"]);
    let mixed = format!("R1={}", vec!["(1+2*3)"; 5000].join(" AND "));
    assert_eq!(codes(&mixed), vec!["NC130"]);
}

#[test]
fn keywords_are_guarded_against_names() {
    let d = ok("DEF REAL HANDLE=1, GOTOFX=2, ORDER=3, REPEATER=4\nR1=HANDLE AND GOTOFX OR ORDER\nM30\n");
    assert!(d.contains("(or (and HANDLE GOTOFX) ORDER)"), "{d}");
    let d = ok("RET\n");
    assert!(d.contains("return"), "{d}");
    let d = ok("R1=1\nREPEAT\nR1=R1+1\nUNTIL R1>3\nM30\n");
    assert!(d.contains("repeat @"), "{d}");
    let d = ok("RETRACT\nM30\n");
    assert!(d.contains("call RETRACT"), "{d}");
}

#[test]
fn names_and_keywords_are_case_insensitive_but_strings_keep_case() {
    let d = ok("def real depth=1\nt=\"BallNose\"\nr1=Depth\nm30\n");
    assert!(d.contains("def REAL DEPTH = 1"), "{d}");
    assert!(d.contains("word T \"BallNose\""), "{d}");
    assert!(d.contains("assign R1 = DEPTH"), "{d}");
}

#[test]
fn address_or_variable() {
    let d = ok("DEF REAL TAG=1\nTAG=2\nELX=3\nU_LAYER=4\nCR=5\nX1=6\nLAYERS=7\nM30\n");
    assert!(d.contains("assign TAG = 2"), "{d}");
    assert!(d.contains("word ELX 3"), "{d}");
    assert!(d.contains("assign U_LAYER = 4"), "{d}");
    assert!(d.contains("word CR 5"), "{d}");
    assert!(d.contains("word X1 6"), "{d}");
    assert!(d.contains("assign LAYERS = 7"), "{d}");
}

#[test]
fn header_and_proc_name_the_program() {
    let d = ok("%_N_PART7_MPF\n;$PATH=/_N_MPF_DIR\nG0 X0\nM30\n");
    assert!(d.contains("program PART7"), "{d}");
    let d = ok("PROC SUB1(REAL P_A, VAR INT P_B) SAVE\nRET\n");
    assert!(d.contains("program SUB1 save"), "{d}");
    assert!(d.contains("param var INT P_B"), "{d}");
}

#[test]
fn one_error_per_bad_block_and_reading_goes_on() {
    assert_eq!(codes("R1=FOO(1)+BAR(2)\nR2=(\nR300=1\nM30\n"), vec!["NC123", "NC121", "NC208"]);
}

#[test]
fn r_count_follows_the_profile() {
    let mut db = SourceDb::new();
    let file = db.add("t.mpf", "R299=1\nR300=1\n");
    let mut opts = ParseOptions::for_dialect(Dialect::Sinumerik);
    opts.semantics.r_param_count = 1000;
    let p = nctrans::parse(&db, file, Dialect::Sinumerik, &opts);
    assert!(!diag::has_errors(&p.diags));
    assert_eq!(codes("R299=1\nR300=1\n"), vec!["NC208"]);
}

#[test]
fn structure_errors() {
    assert_eq!(codes("IF R1\nWHILE R2\nENDIF\nM30\n"), vec!["NC202"]);
    assert_eq!(codes("WHILE R1\nIF R2\nENDWHILE\nM30\n"), vec!["NC202"]);
    assert_eq!(codes("IF R1\nELSE\nELSE\nENDIF\n"), vec!["NC209"]);
    assert_eq!(codes("ENDLOOP\n"), vec!["NC201"]);
    assert_eq!(codes("LOOP\n"), vec!["NC200"]);
    assert_eq!(codes("A1: X1\nGOTOB A1\nGOTOF A1\n"), vec!["NC126", "NC210"]);
    assert_eq!(codes("GOTOC NOWHERE\nGOTO N5\n"), vec!["NC206"]);
    assert_eq!(codes("REPEAT LATER P=2\nLATER: X1\n"), vec!["NC205"]);
}

#[test]
fn deep_structures_and_parens_are_bounded() {
    let mut t = String::new();
    for _ in 0..5000 {
        t.push_str("WHILE R1\n");
    }
    for _ in 0..5000 {
        t.push_str("ENDWHILE\n");
    }
    assert_eq!(codes(&t), vec!["NC211"]);
    let deep = format!("R1={}1{}\n", "(".repeat(100000), ")".repeat(100000));
    assert_eq!(codes(&deep), vec!["NC130"]);
    let deep = format!("R1=R[{}1{}]\n", "R[".repeat(70), "]".repeat(70));
    assert_eq!(codes(&deep), vec!["NC130"]);
}

#[test]
fn mutations_never_panic() {
    let seeds = [
        "N10 DEF REAL A[2,3]=SET(1,,3) ; c\nIF (R1==1) AND R2 GOTOF L1\nCASE(R1) OF 1 GOTOF L1 DEFAULT GOTOB L1\n",
        "L1: G1 X=IC(R1+SIN(30)) Y='H1F' T=\"x\" $P_UIFR[1,X,TR]=2 R[R1]=3 CONTOUR(1,,2) P3\n",
        "PROC P(VAR REAL A[3]) SAVE\nFOR R1=0 TO 3\nREPEAT\nUNTIL 1\nENDFOR\nMSG(\"a\"<<1)\nREPEAT L1 P=2\nRET\n",
    ];
    let mut r = Rng(7);
    for s in seeds {
        let bytes = s.as_bytes();
        for _ in 0..3000 {
            let mut m = bytes.to_vec();
            match r.next() % 3 {
                0 => m.truncate((r.next() % (bytes.len() as u64 + 1)) as usize),
                1 => {
                    let i = (r.next() % bytes.len() as u64) as usize;
                    let alphabet = b"()[]=;:\"'$,/-+ \nXRNGOTOFIFAND0129.E";
                    m[i] = alphabet[(r.next() % alphabet.len() as u64) as usize];
                }
                _ => {
                    let a = (r.next() % bytes.len() as u64) as usize;
                    let b = (r.next() % bytes.len() as u64) as usize;
                    let (lo, hi) = (a.min(b), a.max(b));
                    let piece = m[lo..hi].to_vec();
                    let at = (r.next() % (m.len() as u64 + 1)) as usize;
                    m.splice(at..at, piece);
                }
            }
            let text = String::from_utf8_lossy(&m).to_string();
            let _ = parse(&text);
        }
    }
}

/// Not a benchmark, a floor: even a debug build must read plain motion blocks quickly. The
/// release measurement is reported by `cargo test --release -- --ignored --nocapture speed`.
#[test]
fn plain_motion_blocks_are_fast() {
    let n = 20000;
    let text: String = (0..n).map(|i| format!("N{i} G1 X{}.234 Y-2.5 Z0.1 F1000\n", i % 100)).collect();
    let t = std::time::Instant::now();
    let d = ok(&text);
    let secs = t.elapsed().as_secs_f64();
    assert!(d.lines().count() > n);
    assert!(secs < 10.0, "{secs} s for {n} blocks");
}

#[test]
#[ignore]
fn speed() {
    let n = 1_000_000;
    let plain: String = (0..n).map(|i| format!("G1 X{}.234 Y-2.5 Z0.1 F1000\n", i % 1000)).collect();
    for (what, text) in [("fast path", plain.clone()), ("grammar only", String::new())] {
        if text.is_empty() {
            let t = std::time::Instant::now();
            let m = 200_000;
            for i in 0..m {
                let _ = block_via_grammar(&format!("G1 X{}.234 Y-2.5 Z0.1 F1000", i % 1000));
            }
            let s = t.elapsed().as_secs_f64();
            println!("{what}: {m} blocks in {s:.3} s = {:.0} blocks/s", m as f64 / s);
            continue;
        }
        let mut db = SourceDb::new();
        let file = db.add("t.mpf", text);
        let t = std::time::Instant::now();
        let p = nctrans::parse(&db, file, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
        let s = t.elapsed().as_secs_f64();
        assert!(p.diags.is_empty());
        println!("{what}: {n} blocks in {s:.3} s = {:.0} blocks/s", n as f64 / s);
    }
}
