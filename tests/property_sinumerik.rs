//! Property test of the FANUC → Sinumerik translation: random small FANUC programs (vacant
//! variables, G65 calls with omitted arguments, GOTO webs with duplicate N numbers, nested
//! DO loops, IF-THEN, bitwise and rounding functions) must translate, read back as
//! Sinumerik, and give the same trace. 200 programs per run; `NCTRANS_PROPTEST_CASES=n` runs
//! more, `NCTRANS_PROPTEST_SEED=s` picks the first seed. A failure prints the seed and the
//! program.

use nctrans::check::Verdict;
use nctrans::dialect::{Dialect, ParseOptions};
use nctrans::read::LineEnding;
use nctrans::span::SourceDb;
use nctrans::translate::to_sinumerik::{translate, Options};
use std::fmt::Write;

#[path = "support/rng.rs"]
mod rng;
use rng::Rng;

const CONSTS: &[&str] = &["1.", "2.5", "-3.", "0.25", "10.", "-1.2", "7", "12", "0"];
const VARS: &[&str] = &["#1", "#2", "#3", "#4", "#5", "#100", "#500"];

fn operand(r: &mut Rng) -> String {
    match r.below(10) {
        0 => "#0".into(),
        1..=4 => r.pick(VARS).into(),
        _ => r.pick(CONSTS).into(),
    }
}

fn expr(r: &mut Rng, depth: u32) -> String {
    if depth == 0 || r.chance(35) {
        return operand(r);
    }
    match r.below(8) {
        0 => format!("[{}+{}]", expr(r, depth - 1), expr(r, depth - 1)),
        1 => format!("[{}-{}]", expr(r, depth - 1), expr(r, depth - 1)),
        2 => format!("[{}*{}]", expr(r, depth - 1), operand(r)),
        3 => format!("[{}/{}]", expr(r, depth - 1), r.pick(&["2.", "-4.", "0.5", "3."])),
        4 => format!("{}[{}]", r.pick(&["FIX", "FUP", "ROUND", "ABS"]), expr(r, depth - 1)),
        5 => format!("[{} {} {}]", operand(r), r.pick(&["AND", "OR", "XOR"]), r.pick(&["3", "12", "5"])),
        6 => format!("ATAN[{}]/[{}]", r.pick(&["1.", "-1.", "0.5"]), r.pick(&["1.", "-2.", "-0.5"])),
        _ => format!("SIN[{}]", expr(r, depth - 1)),
    }
}

fn cond(r: &mut Rng) -> String {
    let op = r.pick(&["EQ", "NE", "GT", "GE", "LT", "LE"]);
    let a = r.pick(VARS);
    let b = if r.chance(30) { "#0".to_string() } else { operand(r) };
    if r.chance(20) {
        format!("[[{a} {op} {b}] AND [{} GT 0]]", r.pick(VARS))
    } else {
        format!("[{a} {op} {b}]")
    }
}

struct Gen {
    r: Rng,
    out: String,
    /// N numbers of top-level blocks written so far (backward targets).
    earlier: Vec<u32>,
    /// Forward targets promised: written later at top level.
    pending: Vec<u32>,
    depth: u32,
    loops: u32,
}

impl Gen {
    fn line(&mut self, s: &str) {
        self.out.push_str(s);
        self.out.push('\n');
    }

    fn stmt(&mut self) {
        let k = self.r.below(19);
        match k {
            0..=2 => {
                let v = self.r.pick(VARS);
                let e = expr(&mut self.r, 3);
                self.line(&format!("{v}={e}"));
            }
            3 => {
                let v = self.r.pick(VARS);
                let s = if self.r.chance(50) { "#0".to_string() } else { self.r.pick(VARS).to_string() };
                self.line(&format!("{v}={s}"));
            }
            4 | 5 => {
                let x = self.r.pick(VARS);
                let y = expr(&mut self.r, 1);
                let z = if self.r.chance(50) {
                    let v = self.r.pick(&["10", "-5", "#3", "2."]);
                    format!(" Z{v}")
                } else {
                    String::new()
                };
                self.line(&format!("G1 X{x} Y[{y}]{z} F100."));
            }
            6 => {
                let c = cond(&mut self.r);
                let v = self.r.pick(VARS);
                let e = expr(&mut self.r, 2);
                self.line(&format!("IF{c}THEN {v}={e}"));
            }
            7 | 8 => {
                // Forward jump to a top-level block written later (out of loops is fine).
                let n = 10 * (self.r.below(9) + 1) as u32;
                self.pending.push(n);
                let c = cond(&mut self.r);
                self.line(&format!("IF{c}GOTO{n}"));
            }
            9 if self.depth < 3 && self.loops < 4 => {
                self.depth += 1;
                self.loops += 1;
                let id = self.depth;
                let ctr = format!("#{}", 29 + id);
                self.line(&format!("{ctr}=0"));
                let times = self.r.below(3) + 1;
                self.line(&format!("WHILE[{ctr} LT {times}]DO{id}"));
                let body = self.r.below(3) + 1;
                for _ in 0..body {
                    self.stmt();
                }
                self.line(&format!("{ctr}={ctr}+1"));
                self.line(&format!("END{id}"));
                self.depth -= 1;
            }
            10 => {
                let mut args = String::new();
                for (letter, p) in [('A', 70), ('X', 60), ('Z', 50), ('B', 30)] {
                    if self.r.chance(p) {
                        let v = operand(&mut self.r);
                        let _ = write!(args, " {letter}{v}");
                    }
                }
                self.line(&format!("G65 P9001{args}"));
            }
            12 => {
                let v = self.r.pick(VARS);
                let w = self.r.pick(VARS);
                self.line(&format!("{v}=-{w}"));
            }
            13 => {
                let v = self.r.pick(VARS);
                let w = self.r.pick(VARS);
                self.line(&format!("G0 X-{v} Y[-{w}]"));
            }
            14 => {
                let g = self.r.pick(&["G91", "G90"]);
                let d = self.r.pick(&["G04 P200", "G04 X0.5", "G04 X15"]);
                self.line(&format!("{g} G0 X1. Y-2"));
                self.line(d);
                self.line("G90");
            }
            15 => {
                self.line("G1 X0 Y0 F80.");
                let r = self.r.pick(&["R5.", "R-5.", "R5"]);
                self.line(&format!("G2 X5. Y5. {r}"));
            }
            16 => {
                // M98 shares the locals: the subprogram changes #1 and tests #2.
                let l = self.r.below(3) + 1;
                self.line(&format!("M98 P9002 L{l}"));
            }
            17 => {
                let n = self.r.pick(&["#[3]", "#[100]", "#[250*2]"]);
                let e = expr(&mut self.r, 1);
                self.line(&format!("{n}={e}"));
            }
            _ => {
                if self.depth == 0 && !self.earlier.is_empty() && self.r.chance(50) {
                    // Backward jump, bounded by a counter so every program ends.
                    let i = self.r.below(self.earlier.len() as u64) as usize;
                    let n = self.earlier[i];
                    self.line("#33=#33+1");
                    self.line(&format!("IF[#33 LT 3]GOTO{n}"));
                } else {
                    let v = self.r.pick(VARS);
                    self.line(&format!("G0 X{v}"));
                }
            }
        }
    }

    fn program(seed: u64) -> String {
        let mut g = Gen {
            r: Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1),
            out: String::new(),
            earlier: vec![],
            pending: vec![],
            depth: 0,
            loops: 0,
        };
        g.line("O1000");
        g.line("#33=0");
        let blocks = g.r.below(10) + 4;
        for _ in 0..blocks {
            if g.r.chance(30) {
                // A numbered top-level block: a target for jumps (numbers may repeat).
                let n = 10 * (g.r.below(9) + 1) as u32;
                let v = g.r.pick(VARS);
                g.line(&format!("N{n} G0 Y{v}"));
                g.earlier.push(n);
                g.pending.retain(|p| *p != n);
            }
            g.stmt();
        }
        // Every promised forward target exists at the end.
        let mut pending = std::mem::take(&mut g.pending);
        pending.sort();
        pending.dedup();
        for n in pending {
            g.line(&format!("N{n} G0 Z1."));
        }
        g.line("M30");
        g.line("O9001");
        g.line("IF[#26 EQ #0]GOTO 5");
        g.line("G1 X#24 Z#26 F50.");
        g.line("N5 #100=#1");
        g.line("IF[#2 NE #0]THEN #500=#2");
        g.line("M99");
        g.line("O9002");
        g.line("#1=#1+1");
        g.line("IF[#2 EQ #0]THEN #2=-#1");
        g.line("G0 X#2");
        g.line("M99");
        g.out
    }
}

fn check_one(seed: u64) -> Result<(), String> {
    let src = Gen::program(seed);
    let mut db = SourceDb::new();
    let file = db.add(format!("random-{seed}.nc"), src.clone());
    let parsed = nctrans::parse(&db, file, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
    if nctrans::diag::has_errors(&parsed.diags) {
        return Err(format!("generator wrote an invalid program:\n{}", nctrans::diag::render(&db, &parsed.diags)));
    }
    let tr = translate(&[&parsed.unit], &Options::default(), LineEnding::Lf);
    if tr.has_errors() {
        return Err(format!("not translated:\n{}", nctrans::diag::render(&db, &tr.diags)));
    }
    let rep = nctrans::translate::to_sinumerik::verify::verify_with(&db, file, &parsed.unit, &tr, "out", 200_000);
    match rep.verdict {
        Verdict::Equivalent { .. } => Ok(()),
        v => {
            let out: String = tr.files.iter().map(|f| format!("==== {}\n{}", f.name, f.text)).collect();
            Err(format!("{v:?}\n{}\n{}\n{out}", nctrans::diag::render(&rep.db, &rep.diags), rep.diff))
        }
    }
}

#[test]
fn random_fanuc_programs_translate_and_verify() {
    let n: u64 = std::env::var("NCTRANS_PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(200);
    let first: u64 = std::env::var("NCTRANS_PROPTEST_SEED").ok().and_then(|v| v.parse().ok()).unwrap_or(1);
    for seed in first..first + n {
        if let Err(e) = check_one(seed) {
            panic!(
                "seed {seed} (rerun with NCTRANS_PROPTEST_SEED={seed} NCTRANS_PROPTEST_CASES=1):\n{}\n{e}",
                Gen::program(seed)
            );
        }
    }
}

/// Truncations, byte flips and splices of every FANUC corpus program: whatever still parses
/// must translate without panicking or hanging, and a translation without errors must read
/// back as Sinumerik. `NCTRANS_FUZZ_ROUNDS` raises the mutations per file (default 20).
#[test]
fn mutated_corpus_programs_never_panic_the_translation() {
    let rounds: u64 = std::env::var("NCTRANS_FUZZ_ROUNDS").ok().and_then(|v| v.parse().ok()).unwrap_or(20);
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/in/fanuc");
    let mut files: Vec<_> = std::fs::read_dir(&dir).expect("corpus").filter_map(|e| e.ok()).map(|e| e.path()).collect();
    files.sort();
    let texts: Vec<String> = files.iter().filter_map(|p| std::fs::read_to_string(p).ok()).collect();
    let mut r = Rng(0x5eed);
    for (i, text) in texts.iter().enumerate() {
        for round in 0..rounds {
            let mut bytes = text.as_bytes().to_vec();
            match r.below(3) {
                0 => bytes.truncate(r.below(bytes.len() as u64 + 1) as usize),
                1 => {
                    for _ in 0..3 {
                        if !bytes.is_empty() {
                            let at = r.below(bytes.len() as u64) as usize;
                            bytes[at] = b"#[]=-+0123456789XYZGNOPLM ;()\nEQNEGOTOWHILEDOEND"[r.below(48) as usize];
                        }
                    }
                }
                _ => {
                    let other = texts[r.below(texts.len() as u64) as usize].as_bytes();
                    let cut = r.below(bytes.len() as u64 + 1) as usize;
                    let from = r.below(other.len() as u64 + 1) as usize;
                    bytes.truncate(cut);
                    bytes.extend_from_slice(&other[from..]);
                }
            }
            let src = String::from_utf8_lossy(&bytes).into_owned();
            let mut db = SourceDb::new();
            let file = db.add(format!("mutant-{i}-{round}.nc"), src.clone());
            let parsed = nctrans::parse(&db, file, Dialect::Fanuc, &ParseOptions::for_dialect(Dialect::Fanuc));
            if nctrans::diag::has_errors(&parsed.diags) {
                continue;
            }
            let tr = translate(&[&parsed.unit], &Options::default(), LineEnding::Lf);
            // Every diagnostic renders (its labels lie in the file).
            let _ = nctrans::diag::render(&db, &tr.diags);
            if tr.has_errors() {
                continue;
            }
            for f in &tr.files {
                let mut db2 = SourceDb::new();
                let id = db2.add(f.name.clone(), f.text.clone());
                let back = nctrans::parse(&db2, id, Dialect::Sinumerik, &ParseOptions::for_dialect(Dialect::Sinumerik));
                assert!(
                    !nctrans::diag::has_errors(&back.diags),
                    "mutant {i}-{round}: {} does not read back:\n{src}\n----\n{}\n{}",
                    f.name,
                    f.text,
                    nctrans::diag::render(&db2, &back.diags)
                );
            }
        }
    }
}
