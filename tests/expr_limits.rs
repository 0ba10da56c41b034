//! Expressions at and beyond the readers' limits (`dialect::limits`: 256 nested operations,
//! 64 levels of brackets; FANUC's profile allows 5): long flat chains of every operator,
//! unary chains and deep nesting of every form, in both dialects. Beyond a limit every
//! command gives one diagnostic with its code and line (NC130; FANUC bracket nesting NC163)
//! and nothing aborts; at the limit parse, dump, span check, run and translation both ways
//! work and compute the right value. The library runs on a thread with half the stack of a
//! batch worker (the checker inside it too), the CLI binary with its own threads (main
//! thread, the checker's second program, batch workers). To measure a form's stack:
//! `CASES=s_eq STK=<bytes> cargo test --test expr_limits at_the_limit`.

use nctrans::check;
use nctrans::dialect::limits::{MAX_EXPR_DEPTH, MAX_NESTING, THREAD_STACK};
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::eval::{self, NoCallees, RunOptions, VecSink};
use nctrans::span::SourceDb;
use nctrans::translate::{self, to_sinumerik as translate_sinumerik, to_sinumerik::verify as verify_sinumerik};
use nctrans::{diag, ir};
use std::path::{Path, PathBuf};
use std::process::Command;

const N: usize = MAX_EXPR_DEPTH as usize;
const NEST: usize = MAX_NESTING as usize;

/// One generated program. `x`: the X the first move must reach when it is within the limit.
struct Case {
    name: String,
    dialect: Dialect,
    text: String,
    /// The diagnostic it must give (beyond a limit), with the line it is on.
    refused: Option<(&'static str, usize)>,
    x: Option<i64>,
    /// A code the translation may refuse with (a construct the target cannot express).
    untranslatable: Option<&'static str>,
}

/// `1 op 1 op …` with `ops` operators, and its value.
fn chain(op: &str, ops: usize) -> (String, Option<i64>) {
    let text = vec!["1"; ops + 1].join(op);
    let mut v: i64 = 1;
    for _ in 0..ops {
        v = match op.trim() {
            "+" => v + 1,
            "-" => v - 1,
            "*" | "/" | "AND" | "OR" | "B_AND" | "B_OR" | "DIV" => v,
            "MOD" => 0,
            "XOR" | "B_XOR" | "<>" => (v != 1) as i64,
            "==" | ">=" | "<=" => (v == 1) as i64,
            ">" => (v > 1) as i64,
            "<" => (v < 1) as i64,
            _ => return (text, None),
        };
    }
    (text, Some(v))
}

const FANUC_OPS: &[(&str, &str)] = &[
    ("add", "+"),
    ("sub", "-"),
    ("mul", "*"),
    ("div", "/"),
    ("and", " AND "),
    ("or", " OR "),
    ("xor", " XOR "),
    ("mod", " MOD "),
];

const SIEMENS_OPS: &[(&str, &str)] = &[
    ("add", "+"),
    ("sub", "-"),
    ("mul", "*"),
    ("div", "/"),
    ("idiv", " DIV "),
    ("mod", " MOD "),
    ("band", " B_AND "),
    ("bor", " B_OR "),
    ("bxor", " B_XOR "),
    ("and", " AND "),
    ("or", " OR "),
    ("xor", " XOR "),
    ("eq", "=="),
    ("ne", "<>"),
    ("gt", ">"),
    ("ge", ">="),
    ("lt", "<"),
    ("le", "<="),
    ("cat", "<<"),
];

fn fanuc(name: &str, body: &str, line: usize, refused: Option<&'static str>, x: Option<i64>) -> Case {
    Case {
        name: format!("f_{name}"),
        dialect: Dialect::Fanuc,
        text: format!("O1\n#1=1\n{body}\nM30\n"),
        refused: refused.map(|c| (c, line)),
        x: if refused.is_some() { None } else { x },
        untranslatable: None,
    }
}

fn siemens(name: &str, body: &str, refused: Option<&'static str>, x: Option<i64>) -> Case {
    Case {
        name: format!("s_{name}"),
        dialect: Dialect::Sinumerik,
        text: format!("R1=1\n{body}\nM30\n"),
        refused: refused.map(|c| (c, 2)),
        x: if refused.is_some() { None } else { x },
        untranslatable: None,
    }
}

/// Every form at the limit (`over == 0`) or `over` beyond it.
fn cases(over: usize) -> Vec<Case> {
    let only = std::env::var("CASES").ok();
    let bad = |code| (over > 0).then_some(code);
    let n = N + over;
    let mut v = Vec::new();
    for (name, op) in FANUC_OPS {
        let (c, x) = chain(op, n);
        v.push(fanuc(name, &format!("G1 X[{c}] F100."), 3, bad("NC130"), x));
        // The same chain assigned, in a condition and a G65 argument.
        v.push(fanuc(&format!("{name}_assign"), &format!("#2={c}\nG1 X#2 F100."), 3, bad("NC130"), x));
    }
    let (c, _) = chain("+", n - 1);
    v.push(fanuc("if", &format!("IF [{c} GT 0] GOTO 10\nG1 X9. F100.\nN10 G1 X1. F100."), 3, bad("NC130"), Some(1)));
    v.push(fanuc("while", &format!("WHILE [{c} LT 0] DO1\nEND1\nG1 X1. F100."), 3, bad("NC130"), Some(1)));
    let conds = vec!["[#1 EQ 1]"; n].join(" AND ");
    let mut c =
        fanuc("conds", &format!("IF [{conds}] GOTO 10\nG1 X9. F100.\nN10 G1 X1. F100."), 3, bad("NC130"), Some(1));
    // Siemens compares with a tolerance, so each exact FANUC `EQ` becomes `a-b==0`, one
    // operation more: at the limit the translation is refused, at the source line.
    c.untranslatable = Some("NC130");
    v.push(c);
    // Brackets inside the chain: five levels (the FANUC default), each with its share.
    let mut deep = "1".to_string();
    for _ in 0..4 {
        deep = format!("[{deep}{}]", "+1".repeat(N / 4));
    }
    deep.push_str(&"+1".repeat(over));
    v.push(fanuc("deepmix", &format!("G1 X[{deep}] F100."), 3, bad("NC130"), Some(N as i64 + 1 + over as i64)));
    // Nesting: the profile's five levels, then one more (FANUC alarm 118: NC163).
    let k = 5 + over.min(1);
    let bad_nest = (over > 0).then_some("NC163");
    let mut nests = vec![
        ("nest", format!("G1 X{}1{} F100.", "[".repeat(k), "]".repeat(k)), 1),
        ("sin", format!("#2={}90{}\nG1 X#2 F100.", "SIN[".repeat(k), "]".repeat(k)), 1),
        (
            "neg",
            format!("G1 X-{}1{} F100.", "[-".repeat(k - 1) + "[", "]".repeat(k)),
            if k.is_multiple_of(2) { 1 } else { -1 },
        ),
        ("ind", format!("G1 X#{}1{} F100.", "[#".repeat(k - 1) + "[", "]".repeat(k)), 1),
    ];
    for (name, body, x) in nests.drain(..) {
        let mut c = fanuc(name, &body, 3, bad_nest, Some(x));
        if name == "sin" {
            // SIN[90] = 1, SIN[1] is not an integer: only the deepest one is checked.
            c.x = None;
        }
        v.push(c);
    }
    for (name, op) in SIEMENS_OPS {
        let (c, x) = chain(op, n);
        let mut case = siemens(name, &format!("G1 X={c} F100"), bad("NC130"), x);
        if *name == "cat" {
            case = siemens(name, &format!("MSG({})", vec!["\"A\""; n + 1].join("<<")), bad("NC130"), None);
            case.untranslatable = Some("NC314");
        }
        v.push(case);
        if *name != "cat" {
            v.push(siemens(&format!("{name}_assign"), &format!("R2={c}\nG1 X=R2 F100"), bad("NC130"), x));
        }
    }
    let (c, _) = chain("+", n - 1);
    v.push(siemens("if", &format!("IF {c} > 0 GOTOF LBL1\nG1 X9 F100\nLBL1: G1 X1 F100"), bad("NC130"), Some(1)));
    v.push(siemens("while", &format!("WHILE {c} < 0\nENDWHILE\nG1 X1 F100"), bad("NC130"), Some(1)));
    for (name, op, x) in
        [("neg", "-", if n.is_multiple_of(2) { 1 } else { -1 }), ("not", "NOT ", n.is_multiple_of(2) as i64)]
    {
        v.push(siemens(name, &format!("G1 X={}1 F100", op.repeat(n)), bad("NC130"), Some(x)));
    }
    let mut bnot = siemens("bnot", &format!("R2={}1", "B_NOT ".repeat(n)), bad("NC130"), None);
    bnot.untranslatable = Some("NC330");
    v.push(bnot);
    // Parentheses inside the chain: 64 levels of 4 operations each.
    let mut deep = "1".to_string();
    for _ in 0..NEST {
        deep = format!("({deep}{})", "+1".repeat(N / NEST));
    }
    deep.push_str(&"+1".repeat(over));
    v.push(siemens("deepmix", &format!("G1 X={deep} F100"), bad("NC130"), Some(N as i64 + 1 + over as i64)));
    // Nesting: 64 levels, then one more.
    let k = NEST + over.min(1);
    v.push(siemens("nest", &format!("G1 X={}1{} F100", "(".repeat(k), ")".repeat(k)), bad("NC130"), Some(1)));
    v.push(siemens("negnest", &format!("G1 X={}1{} F100", "-(".repeat(k), ")".repeat(k)), bad("NC130"), Some(1)));
    let mut sin = siemens("sin", &format!("R2={}90{}", "SIN(".repeat(k), ")".repeat(k)), bad("NC130"), None);
    sin.text = sin.text.replace("M30", "G1 X=ROUND(R2*0) F100\nM30");
    sin.x = if over > 0 { None } else { Some(0) };
    v.push(sin);
    v.push(siemens("minval", &format!("G1 X={}1{} F100", "MINVAL(1,".repeat(k), ")".repeat(k)), bad("NC130"), Some(1)));
    v.push(siemens(
        "ind",
        &format!("G1 X=R[{}1{}] F100", "R[".repeat(k - 1), "]".repeat(k - 1)),
        bad("NC130"),
        Some(1),
    ));
    // The deepest walks together: a comparison chain (the costliest to lower for FANUC)
    // inside 64 nested structures, the most the Siemens structurer takes.
    let (c, x) = chain("==", n);
    let ifs = format!("{}G1 X={c} F100\n{}", "IF R1==1\n".repeat(64), "ENDIF\n".repeat(64));
    let mut nested = siemens("in_structures", ifs.trim_end(), bad("NC130"), x);
    nested.refused = nested.refused.map(|(code, _)| (code, 66));
    v.push(nested);
    v.retain(|c| only.as_ref().is_none_or(|o| o.split(',').any(|n| n == c.name)));
    v
}

/// The first move's X in the trace of `text` run as `dialect`.
fn first_x(db: &mut SourceDb, unit: &ir::Unit) -> Result<Option<String>, String> {
    let mut sink = VecSink::default();
    let out = eval::run(db, unit, &mut NoCallees, &RunOptions::default(), &mut sink);
    if diag::has_errors(&out.diags) {
        return Err(diag::render(db, &out.diags));
    }
    Ok(sink
        .events
        .iter()
        .map(|(e, _)| eval::trace::text_line(e))
        .find(|l| l.starts_with("move"))
        .and_then(|l| l.split_whitespace().find(|w| w.starts_with("X=")).map(str::to_string)))
}

/// Everything the library does with one case; the errors found.
fn library(c: &Case) -> Vec<String> {
    let mut errs = Vec::new();
    let mut db = SourceDb::new();
    let name = format!("{}.{}", c.name, if c.dialect == Dialect::Fanuc { "nc" } else { "mpf" });
    let loaded = nctrans::load(&mut db, &name, c.text.as_bytes(), None);
    let parsed = nctrans::parse(&db, loaded.file, c.dialect, &ParseOptions::for_dialect(c.dialect));
    let codes: Vec<&str> =
        parsed.diags.iter().filter(|d| d.severity == diag::Severity::Error).map(|d| d.code).collect();
    if let Some((code, line)) = c.refused {
        let rendered = diag::render(&db, &parsed.diags);
        // One diagnostic for the expression. (A refused `WHILE[…]DO1` leaves its END1
        // without a loop, which the FANUC structurer reports as for any unreadable WHILE.)
        let one = codes.first() == Some(&code) && codes.iter().filter(|&&c| c == code).count() == 1;
        let rest_ok = codes.len() == 1 || c.name == "f_while";
        if !one || !rest_ok || !rendered.contains(&format!("{name}:{line}:")) {
            errs.push(format!("{}: want one {code} on line {line}, got {codes:?}\n{rendered}", c.name));
        }
        return errs;
    }
    if !codes.is_empty() {
        return vec![format!("{}: {}", c.name, diag::render(&db, &parsed.diags))];
    }
    let unit = parsed.unit;
    let dump = ir::dump::dump(&unit);
    if dump.len() < c.text.len() / 4 {
        errs.push(format!("{}: dump too short", c.name));
    }
    let spans = ir::visit::check_spans(&unit, c.text.len() as u32);
    if !spans.is_empty() {
        errs.push(format!("{}: spans {spans:?}", c.name));
    }
    match first_x(&mut db, &unit) {
        Err(e) => errs.push(format!("{}: run: {e}", c.name)),
        Ok(x) => {
            if let Some(want) = c.x {
                if x != Some(format!("X={want}")) {
                    errs.push(format!("{}: first move {x:?}, want X={want}", c.name));
                }
            }
        }
    }
    let verdict = check::in_one_thread(|| match c.dialect {
        Dialect::Sinumerik => {
            let t = translate::to_fanuc::to_fanuc(&unit, &[], &translate::to_fanuc::TranslateOptions::default());
            if !t.ok() {
                return Err(diag::render(&db, &t.diags));
            }
            let v =
                translate::to_fanuc::verify(&mut db, &unit, &[], &t.clone().into(), "out.nc", eval::DEFAULT_MAX_STEPS);
            if v.equivalent {
                Ok(())
            } else {
                Err(format!("{}\n{}", v.summary, v.rendered))
            }
        }
        Dialect::Fanuc => {
            let o = translate_sinumerik::Options { main_name: "MAIN".into(), ..Default::default() };
            let t = translate_sinumerik::translate(&[&unit], &o, loaded.line_ending);
            if t.has_errors() {
                return Err(diag::render(&db, &t.diags));
            }
            let r = verify_sinumerik::verify(&db, loaded.file, &unit, &t, "out");
            match r.verdict {
                check::Verdict::Equivalent { .. } => Ok(()),
                other => Err(format!("{other:?}\n{}", diag::render(&r.db, &r.diags))),
            }
        }
    });
    if let Err(e) = verdict {
        match c.untranslatable {
            // Refused at the source, before an output is written and read back (NC372).
            Some(code) if e.contains(&format!("error[{code}]")) && !e.contains("NC372") => {}
            _ => errs.push(format!("{}: translation: {e}", c.name)),
        }
    }
    errs
}

/// Runs `f` on a thread with half the stack nctrans gives its own threads (and the main
/// thread has), so the limits hold with a margin of two.
fn on_small_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let stack = std::env::var("STK").ok().and_then(|s| s.parse().ok()).unwrap_or(THREAD_STACK / 2);
    std::thread::Builder::new().stack_size(stack).spawn(f).expect("spawn").join().expect("no panic")
}

#[test]
fn expressions_at_the_limit_work_everywhere_in_the_library() {
    let errs = on_small_stack(|| cases(0).iter().flat_map(library).collect::<Vec<_>>());
    assert!(errs.is_empty(), "{}", errs.join("\n"));
}

#[test]
fn expressions_beyond_the_limit_are_one_diagnostic_each() {
    for over in [1, 2_000] {
        let errs = on_small_stack(move || cases(over).iter().flat_map(library).collect::<Vec<_>>());
        assert!(errs.is_empty(), "{}", errs.join("\n"));
    }
}

#[test]
fn a_profile_that_allows_deep_brackets_is_still_bounded() {
    let errs = on_small_stack(|| {
        let mut opts = ParseOptions::for_dialect(Dialect::Fanuc);
        opts.semantics.max_bracket_depth = u32::MAX;
        let mut errs = Vec::new();
        for (k, want) in [(NEST, None), (NEST + 1, Some("NC163")), (50_000, Some("NC163"))] {
            for body in [
                format!("#2={}1{}", "[".repeat(k), "]".repeat(k)),
                format!("#2={}1{}", "SIN[".repeat(k), "]".repeat(k)),
                format!("#2=-{}1{}", "[-".repeat(k - 1) + "[", "]".repeat(k)),
                format!("#2=#{}1{}", "[#".repeat(k - 1) + "[", "]".repeat(k)),
            ] {
                let mut db = SourceDb::new();
                let f = db.add("deep.nc", format!("O1\n#1=1\n{body}\nM30\n"));
                let p = nctrans::parse(&db, f, Dialect::Fanuc, &opts);
                let codes: Vec<&str> = p.diags.iter().map(|d| d.code).collect();
                if codes != want.into_iter().collect::<Vec<_>>() {
                    errs.push(format!("{k} levels: {codes:?}"));
                    continue;
                }
                ir::dump::dump(&p.unit);
                let out = eval::run(&mut db, &p.unit, &mut NoCallees, &RunOptions::default(), &mut VecSink::default());
                if diag::has_errors(&out.diags) {
                    errs.push(format!("{k} levels: {}", diag::render(&db, &out.diags)));
                }
            }
        }
        errs
    });
    assert!(errs.is_empty(), "{}", errs.join("\n"));
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("expr-limits").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

fn write(dir: &Path, cases: &[Case]) -> Vec<(PathBuf, &'static str, &'static str)> {
    cases
        .iter()
        .map(|c| {
            let (ext, to) = if c.dialect == Dialect::Fanuc { ("nc", "sinumerik") } else { ("mpf", "fanuc") };
            let p = dir.join(format!("{}.{ext}", c.name));
            std::fs::write(&p, &c.text).expect("write");
            (p, ext, to)
        })
        .collect()
}

struct Ran {
    code: i32,
    stderr: String,
}

fn nctrans(dir: &Path, args: &[&str]) -> Ran {
    let out = Command::new(env!("CARGO_BIN_EXE_nctrans")).current_dir(dir).args(args).output().expect("run nctrans");
    // A signal (a stack overflow aborts) has no exit code.
    let code = out.status.code().unwrap_or_else(|| panic!("nctrans {args:?} died: {:?}", out.status));
    Ran { code, stderr: String::from_utf8_lossy(&out.stderr).into_owned() }
}

/// The forms the CLI is run on one by one (the library and the batches take every form).
const CLI_FORMS: &[&str] =
    &["f_add", "f_mul_assign", "f_if", "f_conds", "f_deepmix", "s_add", "s_eq", "s_if", "s_deepmix", "s_nest"];

#[test]
fn the_cli_refuses_long_and_deep_expressions_with_their_line() {
    let dir = scratch("over");
    let mut cs: Vec<Case> = cases(1).into_iter().filter(|c| CLI_FORMS.contains(&c.name.as_str())).collect();
    // The line of the issue, 50 000 terms long, and its other forms 10 000 long.
    let long = vec!["1"; 10_000].join("+");
    let vars = vec!["#1"; 10_000].join("+");
    for (name, body) in [
        ("issue_assign", format!("#1={}", vec!["1"; 50_000].join("+"))),
        ("issue_if", format!("IF [{vars} GT 0] GOTO 10\nN10")),
        ("issue_word", format!("G0 X[{long}]")),
        ("issue_nest", format!("#2={}1{}", "[".repeat(10_000), "]".repeat(10_000))),
    ] {
        let code = if name == "issue_nest" { "NC163" } else { "NC130" };
        cs.push(fanuc(name, &body, 3, Some(code), None));
    }
    cs.push(siemens("issue_assign", &format!("R2={long}"), Some("NC130"), None));
    cs.push(siemens("issue_nest", &format!("R2={}1{}", "(".repeat(10_000), ")".repeat(10_000)), Some("NC130"), None));
    let files = write(&dir, &cs);
    let mut errs = Vec::new();
    for (c, (path, _, to)) in cs.iter().zip(&files) {
        let f = path.file_name().and_then(|n| n.to_str()).expect("name");
        let (code, line) = c.refused.expect("refused");
        let mut runs = vec![vec!["parse", f], vec!["run", f], vec!["--to", to, f]];
        if c.name.contains("issue_assign") {
            runs.extend([vec!["run", "--stream", f], vec!["--to", to, "--stream", f], vec!["check", f, f]]);
        }
        for args in runs {
            let r = nctrans(&dir, &args);
            let at = format!("{f}:{line}:");
            if r.code != 1 && r.code != 2 || !r.stderr.contains(&format!("error[{code}]")) || !r.stderr.contains(&at) {
                errs.push(format!("{args:?}: exit {}, want {code} at line {line}:\n{}", r.code, cut(&r.stderr)));
            }
        }
    }
    // A batch of every form each way: the same diagnostic in its report, nothing aborts.
    for (ext, to) in [("nc", "sinumerik"), ("mpf", "fanuc")] {
        let sub = dir.join(ext);
        let all = cases(1).into_iter().filter(|c| (c.dialect == Dialect::Fanuc) == (ext == "nc")).collect::<Vec<_>>();
        std::fs::create_dir_all(&sub).expect("dir");
        write(&sub, &all);
        let report = dir.join(format!("{ext}.json"));
        let report = report.to_str().expect("path");
        let r = nctrans(&dir, &["--to", to, "-o", &format!("out-{ext}/"), ext, "-j", "2", "--report", report]);
        let json = std::fs::read_to_string(report).unwrap_or_default();
        let refused = json.matches("\"code\": \"NC130\"").count() + json.matches("\"code\": \"NC163\"").count();
        if r.code != 1 || json.matches("\"status\": \"parse-error\"").count() != all.len() || refused < all.len() {
            errs.push(format!("batch to {to}: exit {}\n{}", r.code, cut(&r.stderr)));
        }
    }
    assert!(errs.is_empty(), "{}", errs.join("\n"));
}

fn cut(s: &str) -> String {
    s.lines().map(|l| l.chars().take(160).collect::<String>()).take(12).collect::<Vec<_>>().join("\n")
}

#[test]
fn the_cli_runs_and_translates_expressions_at_the_limit() {
    let dir = scratch("at");
    let cs = cases(0);
    let files = write(&dir, &cs);
    let mut errs = Vec::new();
    for (c, (path, _, to)) in cs.iter().zip(&files).filter(|(c, _)| CLI_FORMS.contains(&c.name.as_str())) {
        let f = path.file_name().and_then(|n| n.to_str()).expect("name");
        // A translation runs its output on the checker's own thread.
        for args in [vec!["parse", f], vec!["run", f], vec!["--to", to, f], vec!["--to", to, "--stream", f]] {
            let r = nctrans(&dir, &args);
            let refused = c.untranslatable.is_some_and(|code| r.stderr.contains(&format!("error[{code}]")));
            if r.code != 0 && !(refused && args[0] == "--to") {
                errs.push(format!("{args:?}: exit {}\n{}", r.code, cut(&r.stderr)));
            }
        }
    }
    // A batch of every form each way: parse, translation and both runs on worker threads.
    for (ext, to) in [("nc", "sinumerik"), ("mpf", "fanuc")] {
        let sub = dir.join(ext);
        std::fs::create_dir_all(&sub).expect("dir");
        for (p, e, _) in &files {
            if e == &ext {
                std::fs::copy(p, sub.join(p.file_name().expect("name"))).expect("copy");
            }
        }
        let out = format!("out-{ext}/");
        let r = nctrans(&dir, &["--to", to, "-o", &out, ext, "-j", "2"]);
        let known = |l: &str| cs.iter().any(|c| c.untranslatable.is_some_and(|u| l.contains(&c.name) && l.contains(u)));
        for l in r.stderr.lines().filter(|l| l.contains(" NC") && !known(l)) {
            errs.push(format!("batch to {to}: {l}"));
        }
        if !r.stderr.contains("verified") {
            errs.push(format!("batch to {to}: exit {}\n{}", r.code, cut(&r.stderr)));
        }
    }
    // `check` on a program at the limit and its translation.
    let r = nctrans(&dir, &["check", "s_eq.mpf", "out-mpf/s_eq.nc"]);
    if r.code != 0 {
        errs.push(format!("check: exit {}\n{}", r.code, cut(&r.stderr)));
    }
    assert!(errs.is_empty(), "{}", errs.join("\n"));
}
