//! The configuration of a translation (one file or a folder): the defaults, then
//! `nctrans.toml` (or `--config`), then the flags given, which win.

use super::batch::BatchArgs;
use super::translate::TranslateArgs;
use clap::parser::ValueSource;
use clap::ArgMatches;
use nctrans::config::{self, Config};
use nctrans::dialect::Dialect;
use std::path::Path;

fn given(m: &ArgMatches, id: &str) -> bool {
    matches!(m.value_source(id), Some(ValueSource::CommandLine))
}

/// The configuration: defaults, then `nctrans.toml`, then the flags given.
pub fn configure(t: &TranslateArgs, b: &BatchArgs, m: &ArgMatches) -> Result<Config, String> {
    let mut c = match &b.config {
        Some(p) => Config::load(p)?,
        None if Path::new(config::FILE_NAME).is_file() => Config::load(Path::new(config::FILE_NAME))?,
        None => Config::default(),
    };
    let flag =
        |c: &mut Config, key: &str, text: &str, name: &str| c.set_flag(key, text).map_err(|e| format!("{name}: {e}"));
    if let Some(d) = t.to {
        c.to = Some(d);
    }
    if let Some(o) = &t.output {
        c.output = Some(o.clone());
    }
    if t.no_verify {
        c.verify = false;
    }
    if given(m, "unsupported") {
        flag(&mut c, "translate.unsupported", &t.unsupported, "--unsupported")?;
    }
    if given(m, "comments") {
        flag(&mut c, "translate.comments", &t.comments, "--comments")?;
    }
    if let Some(n) = t.number_blocks {
        flag(&mut c, "translate.number_blocks", &n.to_string(), "--number-blocks")?;
    }
    if t.compound_conditions {
        c.fanuc.compound_conditions = true;
    }
    if t.specialise_callers {
        c.specialise_callers = true;
    }
    if t.l_numbers {
        c.l_numbers = true;
    }
    if given(m, "max_steps") {
        flag(&mut c, "verify.max_steps", &t.max_steps.to_string(), "--max-steps")?;
    }
    if let Some(e) = t.input_encoding {
        c.input_encoding = Some(e);
    }
    if let Some(n) = t.program_number {
        flag(&mut c, "translate.program_number", &n.to_string(), "--program-number")?;
        c.check_program_number().map_err(|e| format!("--program-number: {e}"))?;
    }
    let to = c.to.ok_or("a translation needs a target: --to fanuc or --to sinumerik (or `to` in nctrans.toml)")?;
    let dir = if to == Dialect::Fanuc { "to_fanuc" } else { "to_sinumerik" };
    // The first rule that covers a variable places it, so flag rules go before the file's.
    let before = if to == Dialect::Fanuc { c.var_map_to_fanuc.len() } else { c.var_map_to_sinumerik.len() };
    for r in &t.var_map {
        flag(&mut c, &format!("variables.{dir}"), r, "--var-map")?;
    }
    let rules = if to == Dialect::Fanuc { &mut c.var_map_to_fanuc } else { &mut c.var_map_to_sinumerik };
    rules.rotate_left(before);
    for r in &t.tool_map {
        flag(&mut c, "tools", r, "--tool-map")?;
    }
    for r in &t.fixed {
        flag(&mut c, "variables.fixed", r, "--fixed")?;
    }
    for r in &t.program_map {
        flag(&mut c, &format!("programs.{dir}"), r, "--program-map")?;
    }
    if let Some(p) = &t.offset_map {
        let m = config::load_offset_map(p).map_err(|e| format!("--offset-map: {e}"))?;
        if !c.offsets.edges.is_empty() && c.offsets != m {
            // The map is one whole: a tool named in it has only the edges given there.
            eprintln!("note: --offset-map {} replaces the [offsets] of the configuration", p.display());
        }
        c.offsets = m;
    }
    if let Some(j) = b.jobs {
        flag(&mut c, "batch.jobs", &j.to_string(), "-j")?;
    }
    if b.force {
        c.force = true;
    }
    if let Some(r) = &b.report {
        flag(&mut c, "batch.report", &r.display().to_string(), "--report")?;
    }
    if let Some(p) = &b.map {
        c.map = Some(p.clone());
    }
    Ok(c)
}
