//! The proof of a Sinumerik → FANUC translation: the output read back as FANUC and run beside
//! the Siemens programs, with the profiles and inputs each side needs (its own file so that
//! the translation's `mod.rs` holds the writing).

use super::*;

/// Parses the translation back as FANUC (proving it is valid FANUC syntax); the text is
/// added to `db` under `out_name`.
pub fn reparse(
    db: &mut crate::span::SourceDb,
    t: &crate::translate::Translation,
    out_name: &str,
) -> crate::dialect::Parsed {
    let file = db.add(out_name, t.text().to_string());
    let mut opts = crate::dialect::ParseOptions::for_dialect(Dialect::Fanuc);
    opts.semantics.macro_interrupt = t.symbols.fanuc().macro_interrupt;
    opts.semantics.haas_ngc = t.symbols.fanuc().haas_ngc;
    crate::parse(db, file, Dialect::Fanuc, &opts)
}

/// Verifies a translation to FANUC (see [`crate::translate::verify`]): parses it back as FANUC, then
/// runs the Siemens program and the translation in the evaluator and compares their traces
/// (`check`): once with the program's own inputs, and once per argument vector the
/// library's callers pass it (`opts.library`). The Siemens side is aligned with the symbol
/// map first: `T="NAME"` reads as the mapped tool number. A `MSG` that became a comment
/// (FANUC shows no message without stopping) is left out of the comparison by the check
/// ([`EXCLUDE`]), which counts it for the verdict. The R parameters the translation maps
/// start at 0 on both sides (Siemens' power-on value); FANUC's would otherwise be vacant.
/// Parameters not passed are 0 on Siemens; the argument locals get the same value.
pub fn verify<'a>(
    db: &mut crate::span::SourceDb,
    main: &Unit,
    subs: &[&Unit],
    t: &crate::translate::Translation,
    out_name: &str,
    opts: impl Into<crate::translate::VerifyOptions<'a>>,
) -> Verification {
    let opts = opts.into();
    use crate::check::{self, Side};
    use crate::eval::{NoCallees, RunOptions};
    let parsed = reparse(db, t, out_name);
    let mut rendered = diag::render(db, &parsed.diags);
    if diag::has_errors(&parsed.diags) {
        let mut v = Verification::none("not verified: the output does not parse as FANUC (a bug in nctrans)");
        v.rendered = rendered;
        v.unreadable = parsed.diags;
        return v;
    }
    let map = t.symbols.fanuc();
    let fanuc_inputs: Vec<String> = proof_homes(map);
    let (sinumerik, fanuc) = match &opts.profiles {
        Some(p) => (source_semantics(t, Some(&p.sinumerik)).or(Some(p.sinumerik.clone())), Some(p.fanuc.clone())),
        None => (source_semantics(t, None), None),
    };
    let sinumerik = proof_source(sinumerik, map);
    let fanuc = target_semantics(fanuc, map);
    // Both programs meet the source's probe inputs (`nctrans: probe`); a bad line is
    // reported by `run` on the source, here it gives none.
    let probes = crate::eval::header_probes(&db.get(main.file).text).unwrap_or_default();
    // And its interrupt inputs (`nctrans: interrupt`): the proof covers those switches.
    let interrupts = crate::eval::header_interrupts(&db.get(main.file).text).unwrap_or_default();
    // The source's `nctrans: set` lines, then `--set` (which overrides them), as `run` takes them.
    let sets: Vec<String> = crate::eval::input::header_words(&db.get(main.file).text, "nctrans: set", false)
        .map(str::to_string)
        .chain(opts.set.iter().cloned())
        .collect();
    // Less those that name a main-program DEF, which the FANUC program starts itself.
    let (sets, unused) = proof_sets(&sets, map);
    let params = main.programs.first().map(|p| p.params.clone()).unwrap_or_default();
    let letters = passes::words::param_letters(params.len()).unwrap_or_default();
    let mut cases: Vec<(String, Vec<(usize, String)>)> = vec![(String::new(), vec![])];
    if let Some(lib) = &opts.library {
        let key = match main.programs.first().and_then(|p| p.name.as_ref()) {
            Some(ProgName::Name(n)) => n.to_ascii_uppercase(),
            _ => lib.main_name.to_string(),
        };
        for (k, v) in lib.library.arg_vectors(&crate::translate::library::ProgKey::Name(key)).iter().enumerate() {
            let vals = v
                .iter()
                .filter_map(|a| {
                    params.iter().position(|p| p.name.eq_ignore_ascii_case(&a.var)).map(|i| (i, a.to_set()))
                })
                .collect();
            cases.push((format!(" (with the arguments of call site {})", k + 1), vals));
        }
    }
    let parse_all = |v: &[String]| v.iter().filter_map(|s| crate::eval::parse_input(s).ok()).collect::<Vec<_>>();
    let mut runs = Vec::new();
    for (label, vals) in cases {
        let mut a_in = Vec::new();
        let mut b_in = fanuc_inputs.clone();
        for (i, (_, var)) in letters.iter().enumerate() {
            if params.get(i).is_some_and(|p| p.by_ref) {
                continue;
            }
            let given = vals.iter().find(|(j, _)| *j == i);
            let value = given.map_or("0".to_string(), |(_, s)| s.split_once('=').map_or("0", |x| x.1).to_string());
            b_in.push(format!("#{var}={value}"));
            if let Some((_, s)) = given {
                a_in.push(s.clone());
            }
        }
        b_in.extend(var_param_inputs(&params, map));
        a_in.extend(sets.iter().cloned());
        b_in.extend(fanuc_set_inputs(&sets, map));
        let run = |inputs, semantics| RunOptions {
            max_steps: opts.max_steps,
            inputs,
            semantics,
            probes: probes.clone(),
            interrupts: interrupts.clone(),
            ..RunOptions::default()
        };
        let callees = crate::translate::called::MemCallees(subs.iter().map(|u| align_source(u, map)).collect());
        let reached = crate::translate::called::Reached::default();
        let a = Side {
            unit: align_source(main, map),
            callees: reached.wrap(Box::new(callees)),
            run: run(parse_all(&a_in), sinumerik.clone()),
        };
        let b =
            Side { unit: parsed.unit.clone(), callees: Box::new(NoCallees), run: run(parse_all(&b_in), fanuc.clone()) };
        let mut report = check::check_excluding(db, a, b, EXCLUDE);
        report.called = reached.names();
        report.excluded.unused_inputs = unused.clone();
        runs.push((label, report));
    }
    let mut v = Verification::of_runs(runs);
    rendered.push_str(&v.rendered);
    v.rendered = rendered;
    v.reparsed = Some(parsed.unit);
    v
}

/// The semantics a check reads the translation back with: `base` (the profile's) with what
/// the output was written for — a Haas control (its G187, G103 and settings; on an NGC its
/// variables) and the custom macro interrupt (the interrupts run as the source's did); `None`
/// (the plain FANUC profile) where there is neither a base nor any of these.
pub fn target_semantics(base: Option<crate::dialect::Semantics>, map: &SymbolMap) -> Option<crate::dialect::Semantics> {
    if base.is_none() && !map.haas && !map.macro_interrupt {
        return None;
    }
    let mut s = base.unwrap_or_else(|| crate::dialect::Semantics::default_for(Dialect::Fanuc));
    s.haas |= map.haas;
    s.haas_ngc |= map.haas && map.haas_ngc;
    s.macro_interrupt |= map.macro_interrupt;
    Some(s)
}

/// The Siemens profile of a check's source side: `base` (or the default) with the
/// translation's global user data; `None` when there is neither.
pub fn source_semantics(
    t: &crate::translate::Translation,
    base: Option<&crate::dialect::Semantics>,
) -> Option<crate::dialect::Semantics> {
    with_globals(base, t.symbols.fanuc())
}

/// [`source_semantics`] of a translation's symbol map (a streamed translation has no
/// `Translation`).
pub fn with_globals(base: Option<&Semantics>, map: &SymbolMap) -> Option<Semantics> {
    if map.globals.is_empty() {
        return base.cloned();
    }
    let mut s = base.cloned().unwrap_or_else(|| Semantics::default_for(Dialect::Sinumerik));
    s.globals = std::sync::Arc::new(map.globals.clone());
    Some(s)
}

/// What a Sinumerik → FANUC check leaves out of the comparison: the messages the translation
/// keeps as comments (`words` pass, NC320), counted in the verdict.
pub const EXCLUDE: crate::check::Exclude = crate::check::Exclude { messages: true };

/// The Siemens programs a translation is compared against, aligned with its symbol map
/// (tool names read as their numbers).
pub fn align_source(unit: &Unit, map: &SymbolMap) -> Unit {
    let mut u = unit.clone();
    for p in &mut u.programs {
        align_body(&mut p.body, map);
    }
    u
}

fn align_body(body: &mut [Stmt], map: &SymbolMap) {
    for s in body.iter_mut() {
        match &mut s.kind {
            StmtKind::Block(b) => {
                for it in &mut b.items {
                    if let ItemKind::Word(w) = &mut it.kind {
                        if let WordValue::Expr(Expr { kind: kind @ ExprKind::Str(_), span }) = &mut w.value {
                            if let ExprKind::Str(name) = &*kind {
                                if let Some(&n) = map.tools.get(name) {
                                    *kind = ExprKind::Num(Number { value: n as f64, point: false });
                                    let _ = span;
                                }
                            }
                        }
                    }
                }
            }
            other => {
                for child in crate::ir::visit::child_bodies_mut(other) {
                    align_body(child, map);
                }
            }
        }
    }
}
