//! The FANUC reader on small inputs: what each construct becomes in the IR, and that bad
//! blocks give exactly one diagnostic each while reading continues.

use nctrans::dialect::{Dialect, ParseOptions, Parsed};
use nctrans::ir::dump::dump;
use nctrans::span::SourceDb;

fn parse_with(text: &str, opts: &ParseOptions) -> (Parsed, String) {
    let mut db = SourceDb::new();
    let loaded = nctrans::load(&mut db, "t.nc", text.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, Dialect::Fanuc, opts);
    let problems = nctrans::ir::visit::check_spans(&parsed.unit, text.len() as u32);
    assert!(problems.is_empty(), "{problems:?}");
    let rendered = nctrans::diag::render(&db, &parsed.diags);
    (parsed, rendered)
}

fn parse(text: &str) -> (Parsed, String) {
    parse_with(text, &ParseOptions::for_dialect(Dialect::Fanuc))
}

/// The dump of an error-free program, without spans (they are checked by the corpus).
fn ir(text: &str) -> String {
    let (p, rendered) = parse(text);
    assert!(!nctrans::diag::has_errors(&p.diags), "{rendered}");
    let d = dump(&p.unit);
    let mut out = String::new();
    for line in d.lines() {
        let words: Vec<&str> = line.split(' ').filter(|w| !w.starts_with('@')).collect();
        out.push_str(words.join(" ").trim_end());
        out.push('\n');
    }
    out
}

fn codes(text: &str) -> Vec<&'static str> {
    parse(text).0.diags.iter().filter(|d| d.is_error()).map(|d| d.code).collect()
}

#[test]
fn keywords_split_out_of_letter_runs() {
    let a = ir("IF[#513AND8EQ8]GOTO110\nN110M30\n");
    assert!(a.contains("goto forward-then-wrap N110 if (eq (band.f #513 8) 8)"), "{a}");
    let b = ir("#1=1\nWHILE [ #1 LE 147 ] DO1\n#1=#1+1\nEND1\n");
    assert!(b.contains("do1 while (le #1 147)"), "{b}");
    let c = ir("G65H01P#101Q#102\n");
    assert!(c.contains("assign #101 = #102"), "{c}");
}

#[test]
fn precedence_and_logical_versus_bitwise() {
    let a = ir("#1=1+2*3-4 OR 5 AND 6 MOD 7\n");
    assert!(a.contains("assign #1 = (bor.f (- (+ 1 (* 2 3)) 4) (mod (band.f 5 6) 7))"), "{a}");
    let b = ir("IF[[#1 EQ 1] AND [#2 GT 3]]GOTO5\nN5M30\n");
    assert!(b.contains("if (and (eq #1 1) (gt #2 3))"), "{b}");
    assert_eq!(codes("IF[[#1 EQ 1] AND 3]GOTO5\nN5M30\n"), vec!["NC171"]);
    assert_eq!(codes("#2=[1 LT 2]\n"), vec!["NC171"]);
    assert_eq!(codes("IF[#1]GOTO5\nN5M30\n"), vec!["NC171"]);
}

#[test]
fn atan_forms_and_division_after_atan() {
    let a = ir("#1=ATAN[1]/[2]\n#2=ATAN[1,2]\n#3=ATAN[3]\n#4=ATAN[1]/2\n");
    assert!(a.contains("assign #1 = (atan2.f 1 2)"), "{a}");
    assert!(a.contains("assign #2 = (atan2.f 1 2)"), "{a}");
    assert!(a.contains("assign #3 = (atan.f 3)"), "{a}");
    assert!(a.contains("assign #4 = (/ (atan.f 1) 2)"), "{a}");
}

#[test]
fn variables_and_vacant() {
    let a = ir("#1=#0\n#[#1+2]=#100+#500+#1000\nG0 X#[#1] Y-#2 Z-[SIN[#1]]\n");
    assert!(a.contains("assign #1 = vacant"), "{a}");
    assert!(a.contains("assign #[(+ #1 2)] = (+ (+ #100 #500) #1000)"), "{a}");
    assert!(a.contains("word X #[#1]"), "{a}");
    assert!(a.contains("word Y (neg #2)"), "{a}");
    assert!(a.contains("word Z (neg (sin #1))"), "{a}");
    assert_eq!(codes("#0=1\n"), vec!["NC170"]);
    assert_eq!(codes("#1=##2\n"), vec!["NC164"]);
    assert_eq!(codes("#60=1\n"), vec!["NC177"]);
}

#[test]
fn numbers_keep_their_decimal_point() {
    let a = ir("G1 X10 Y10. Z.5 F-2\n");
    assert!(a.contains("word X 10\n") && a.contains("word Y 10.\n"), "{a}");
    assert!(a.contains("word Z 0.5\n") && a.contains("word F -2\n"), "{a}");
}

#[test]
fn g65_argument_specifications() {
    let a = ir("G65 P9010 L2 A1. B2. I-3. I4. D5. X6.\n");
    assert!(a.contains("g65 O9010 (A=#1:1., B=#2:2., I=#4:-3., I=#7:4., D=#7:5., X=#24:6.) times 2"), "{a}");
    let b = ir("G65 P9010 I1 K3 J4 I5\n");
    assert!(b.contains("(I=#4:1, K=#6:3, J=#8:4, I=#10:5)"), "{b}");
    let c = ir("G66 P9011 Z-1.\nX1.\nG67\n");
    assert!(c.contains("g66 O9011 (Z=#26:-1.)") && c.contains("modal-call-off"), "{c}");
    assert_eq!(codes("G65 P9010 G1 X1.\n"), vec!["NC174"]);
    assert_eq!(codes("G65 X1.\n"), vec!["NC174"]);
}

#[test]
fn m98_m99_and_ends() {
    let a = ir("M98 P68003\nM98 P0003 L2\nM98 P#1\nM99 P20\nM99\nM02\nM2\nM30\n");
    assert!(a.contains("m98 O8003 times 6"), "{a}");
    assert!(a.contains("m98 O3 times 2"), "{a}");
    assert!(a.contains("m98 #1"), "{a}");
    assert!(a.contains("return to 20\n") && a.contains("return\n"), "{a}");
    assert_eq!(a.matches("end M2").count(), 2, "{a}");
    assert!(a.contains("end M30"), "{a}");
}

#[test]
fn macro_a_is_lowered() {
    let a = ir("G65 H05 P#101 Q#102 R10\nG65 H23 P#103 Q7 R2\nG65 H84 P10 Q#1 R5\nN10 G65 H99 P3\n");
    assert!(a.contains("assign #101 = (trunc (/ #102 10))"), "{a}");
    assert!(a.contains("assign #103 = (- 7 (* (trunc (/ 7 2)) 2))"), "{a}");
    assert!(a.contains("goto forward-then-wrap N10 if (lt #1 5)"), "{a}");
    assert!(a.contains("alarm setal (+ 500 3)"), "{a}");
    assert_eq!(codes("G65 H07 P#101 Q1 R2\n"), vec!["NC175"]);
}

#[test]
fn alarms_and_messages_take_their_comment() {
    let a = ir("#3000=1(PROBE NO CONTACT)\n#3006=1(CHECK)\n");
    assert!(a.contains("alarm fanuc-3000 1 \"PROBE NO CONTACT\""), "{a}");
    assert!(a.contains("stop-message \"CHECK\""), "{a}");
    assert!(!a.contains("comment \"PROBE"), "the alarm text is not also a comment: {a}");
}

#[test]
fn parameter_write_mode() {
    let a = ir("N150G10L50\nN160N6200R11000000\nN2060P2R2184\nN180G11\nN190 G0 X0\n");
    assert!(a.contains("block N160\n      param-write n=6200 r=11000000"), "{a}");
    assert!(a.contains("param-write n=2060 p=2 r=2184"), "{a}");
    assert!(a.contains("block N180"), "{a}");
    // N inside G10 L50 is not a GOTO target.
    assert_eq!(codes("G10L50\nN6200R1\nG11\nGOTO6200\n"), vec!["NC236"]);
    assert_eq!(codes("G10L50\nN6200X1\nG11\n"), vec!["NC181"]);
}

#[test]
fn programs_tape_marks_and_numbers() {
    let (p, _) = parse("%\nO1(A)\nM30\n:2\nM99\n%\nGARBAGE\n");
    let names: Vec<String> = p.unit.programs.iter().map(|p| format!("{:?}", p.name)).collect();
    assert_eq!(names, vec!["Some(Number(1))", "Some(Number(2))"]);
    assert_eq!(p.diags.iter().map(|d| d.code).collect::<Vec<_>>(), vec!["NC237"]);
    let (p, _) = parse("G0 X1\nM30\n");
    assert_eq!(p.unit.programs.len(), 1);
    assert_eq!(p.unit.programs[0].name, None);
    assert_eq!(codes("O0\nM30\n"), vec!["NC169"]);
    assert_eq!(codes("N0 G0\n"), vec!["NC168"]);
    assert_eq!(codes("N100000 G0\n"), vec!["NC168"]);
    assert_eq!(codes("G0 N10\n"), vec!["NC168"]);
    let b = ir("/N10 G0\n/3 G1\n");
    assert!(b.contains("block skip/0 N10") && b.contains("block skip/3"), "{b}");
}

#[test]
fn semicolons_comments_and_case() {
    let a = ir("g0 x1.;g1 y2.(Üñí (CODE;X)\n");
    assert!(a.contains("word G 0") && a.contains("word Y 2."), "{a}");
    assert!(a.contains("comment \"Üñí (CODE;X\""), "{a}");
    assert_eq!(codes("G0 X1 (OPEN\n"), vec!["NC161"]);
}

#[test]
fn loops_and_jumps() {
    assert_eq!(codes("DO4\nEND4\n"), vec!["NC230"]);
    assert_eq!(codes("DO1\nEND2\n"), vec!["NC231"]);
    assert_eq!(codes("DO1\nDO2\nEND1\nEND2\n"), vec!["NC232"]);
    assert_eq!(codes("DO1\n"), vec!["NC233"]);
    assert_eq!(codes("END1\n"), vec!["NC234"]);
    assert_eq!(codes("DO1\nDO2\nDO3\nDO1\nEND1\nEND3\nEND2\nEND1\n"), vec!["NC235"]);
    assert_eq!(codes("GOTO5\n"), vec!["NC236"]);
    assert_eq!(codes("GOTO0\n"), vec!["NC173"]);
    let a = ir("#1=5\nGOTO#1\nGOTO[#1+1]\nN5\nN6 M30\n");
    assert!(a.contains("goto forward-then-wrap #1") && a.contains("goto forward-then-wrap (+ #1 1)"), "{a}");
}

#[test]
fn the_bracket_limit_follows_the_profile() {
    let text = "#1=[[[[[[1]]]]]]\n";
    assert_eq!(codes(text), vec!["NC163"]);
    let mut opts = ParseOptions::for_dialect(Dialect::Fanuc);
    opts.semantics.max_bracket_depth = 6;
    assert!(!nctrans::diag::has_errors(&parse_with(text, &opts).0.diags));
    // Absurd nesting is refused before the grammar whatever the profile says.
    opts.semantics.max_bracket_depth = u32::MAX;
    let deep = format!("#1={}1{}\n", "[".repeat(100_000), "]".repeat(100_000));
    assert_eq!(parse_with(&deep, &opts).0.diags.iter().map(|d| d.code).collect::<Vec<_>>(), vec!["NC163"]);
}

#[test]
fn one_diagnostic_per_bad_block_and_reading_continues() {
    let text = "#1=[#2+\n#1=FOO[1]\n#1=SIN[1,2]\nIF[#1<2]GOTO5\n#1=5 X#1\n#1=1 #2=2\nN5 G0 X#1\n";
    let (p, rendered) = parse(text);
    let got: Vec<&str> = p.diags.iter().map(|d| d.code).collect();
    assert_eq!(got, vec!["NC162", "NC165", "NC166", "NC172", "NC167", "NC167"], "{rendered}");
    // The good block after them is still read.
    assert!(dump(&p.unit).contains("N5"));
    // Every diagnostic says what to do.
    for d in &p.diags {
        assert!(d.notes.iter().any(|n| n.starts_with("hint: ")), "{}: no hint", d.message);
    }
}

#[test]
fn grammar_errors_say_what_was_expected() {
    // `IF[..]` alone is the Haas conditional block with no words (issue 21): a warning.
    let (_, r) = parse("IF[#1 EQ 2]\n");
    assert!(r.contains("warning[NC251]"), "{r}");
    let (_, r) = parse("WHILE[#1 LT 2]\n");
    assert!(r.contains("expected `DO`"), "{r}");
    let (_, r) = parse("#1=#2 EQ 3\n");
    assert!(r.contains("comparison `EQ` outside brackets"), "{r}");
    let (_, r) = parse("IF[#1 = 2]GOTO5\nN5\n");
    assert!(r.contains("compare with EQ"), "{r}");
}

#[test]
fn chamfering_and_corner_r_read_as_the_words_of_their_meaning() {
    // `,R` is the corner radius, `,C` the chamfer's leg (Siemens RND=, CHR=); a blank may
    // follow the comma.
    let a = ir("G01 X100. ,R5. F100.\nY80. , C2.\nX0 ,C#1\n");
    assert!(a.contains("word RND 5.\n") && a.contains("word CHR 2.\n"), "{a}");
    assert!(a.contains("word CHR #1\n"), "{a}");
    // A comma before any other letter is still an error.
    assert_eq!(codes("G01 X100. ,A5.\n"), ["NC160"]);
}

#[test]
fn a_bracketed_constant_in_an_address_counts_as_having_a_point() {
    let a = ir("G0 X[1] Y1 Z[1+1]\n");
    assert!(a.contains("word X 1.\n") && a.contains("word Y 1\n"), "{a}");
    assert!(a.contains("word Z (+ 1 1)\n"), "{a}");
}
