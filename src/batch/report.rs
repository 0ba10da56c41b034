//! What a batch tells the user: the summary table (counts per status, the worst files) and
//! the per-file report as JSON or CSV. Written by hand: the formats are small, and the
//! field order stays fixed for diffing reports between runs.

use super::{BatchResult, FileRecord, Status};
use std::fmt::Write as _;

/// How bad a status is, for listing the worst files first: a divergence is a wrong
/// translation caught, the most important thing to look at.
pub fn rank(s: Status) -> u8 {
    match s {
        Status::Diverged => 7,
        Status::Error => 6,
        Status::ParseError => 5,
        Status::Unsupported => 4,
        Status::Inconclusive => 3,
        Status::TranslatedUnverified => 2,
        Status::Skipped => 1,
        Status::Verified => 0,
    }
}

/// Why a failed file failed, for its "worst files" line: its first error, else what its
/// status says (a run that hit the step limit, a divergence without a diagnostic), never
/// a warning the file also had, which did not stop it.
fn blocking(f: &FileRecord) -> String {
    match f.diagnostics.iter().find(|d| d.severity == "error") {
        Some(d) => match d.line {
            Some(l) => format!("{} line {l}: {}", d.code, d.message),
            None if !d.code.is_empty() => format!("{}: {}", d.code, d.message),
            None => d.message.clone(),
        },
        None if !f.summary.is_empty() => f.summary.clone(),
        None => f.diagnostics.first().map_or_else(String::new, |d| format!("{}: {}", d.code, d.message)),
    }
}

/// The most files listed under "worst files".
pub const WORST: usize = 10;

/// The summary table printed at the end of a batch.
pub fn summary(r: &BatchResult, target: &str) -> String {
    let mut s = String::new();
    let run = r.files.iter().filter(|f| f.status != Status::Skipped).count();
    let _ = writeln!(
        s,
        "nctrans batch to {target}: {run} file(s) in {:.1} s with -j {}{}",
        r.elapsed.as_secs_f64(),
        r.jobs,
        if r.cancelled { " (stopped by Ctrl-C: the files not run are listed as error)" } else { "" }
    );
    for st in Status::ALL {
        let n = r.count(st);
        if n > 0 || !matches!(st, Status::Skipped | Status::Error | Status::TranslatedUnverified) {
            let _ = writeln!(s, "  {:<22} {n:>6}", st.as_str());
        }
    }
    // What verification knowingly left out (the verdicts say it per file).
    let mut excluded = crate::check::Excluded::default();
    let mut with = 0;
    for f in r.files.iter().filter(|f| f.status == Status::Verified && !f.excluded.is_empty()) {
        excluded.add(f.excluded.clone());
        with += 1;
    }
    if let Some(d) = excluded.describe() {
        let _ = writeln!(s, "  not compared: {d} (in {with} verified file(s))");
    }
    let mut worst: Vec<&FileRecord> = r.files.iter().filter(|f| f.status.is_failure()).collect();
    worst.sort_by(|a, b| rank(b.status).cmp(&rank(a.status)).then_with(|| a.path.cmp(&b.path)));
    if !worst.is_empty() {
        let _ = writeln!(s, "worst files:");
        for f in worst.iter().take(WORST) {
            let _ = writeln!(s, "  {:<22} {}  {}", f.status.as_str(), f.path, blocking(f));
        }
        if worst.len() > WORST {
            let _ = writeln!(s, "  … and {} more (see --report)", worst.len() - WORST);
        }
    }
    if r.all_verified() {
        let _ = writeln!(s, "every file verified");
    }
    s
}

/// A JSON string literal: the same escapes as a TOML basic string.
fn js(s: &str) -> String {
    super::maps::quote(s)
}

fn opt_num<T: std::fmt::Display>(v: Option<T>) -> String {
    v.map_or("null".to_string(), |v| v.to_string())
}

/// The report as JSON: run facts, counts per status, one record per file.
pub fn json(r: &BatchResult, target: &str, input: &str, output: &str) -> String {
    let mut s = String::new();
    s.push_str("{\n");
    let _ = writeln!(s, "  \"tool\": {},", js(concat!("nctrans ", env!("CARGO_PKG_VERSION"))));
    let _ = writeln!(s, "  \"target\": {},", js(target));
    let _ = writeln!(s, "  \"input\": {},", js(input));
    let _ = writeln!(s, "  \"output\": {},", js(output));
    let _ = writeln!(s, "  \"jobs\": {},", r.jobs);
    let _ = writeln!(s, "  \"elapsed_s\": {:.3},", r.elapsed.as_secs_f64());
    let _ = writeln!(s, "  \"cancelled\": {},", r.cancelled);
    let _ = writeln!(s, "  \"all_verified\": {},", r.all_verified());
    let _ = writeln!(s, "  \"map_written\": {},", r.map_written);
    let counts: Vec<String> = Status::ALL.iter().map(|st| format!("{}: {}", js(st.as_str()), r.count(*st))).collect();
    let _ = writeln!(s, "  \"counts\": {{{}}},", counts.join(", "));
    s.push_str("  \"files\": [");
    for (i, f) in r.files.iter().enumerate() {
        s.push_str(if i == 0 { "\n" } else { ",\n" });
        let outputs: Vec<String> = f.outputs.iter().map(|o| js(o)).collect();
        let _ = write!(
            s,
            "    {{\"path\": {}, \"outputs\": [{}], \"status\": {}, \"summary\": {}, \"events\": {}, \"not_compared\": {{\"messages\": {}, \"look_ahead\": {}, \"interrupts\": {}}}, \"blocks\": {}, \"time_ms\": {:.3}, \"diagnostics\": [",
            js(&f.path),
            outputs.join(", "),
            js(f.status.as_str()),
            js(&f.summary),
            opt_num(f.events),
            f.excluded.messages,
            f.excluded.modes,
            f.excluded.interrupts,
            f.blocks,
            f.time.as_secs_f64() * 1000.0
        );
        for (j, d) in f.diagnostics.iter().enumerate() {
            if j > 0 {
                s.push_str(", ");
            }
            let _ = write!(
                s,
                "{{\"severity\": {}, \"code\": {}, \"message\": {}, \"file\": {}, \"line\": {}, \"column\": {}}}",
                js(d.severity),
                js(&d.code),
                js(&d.message),
                d.file.as_deref().map_or("null".to_string(), js),
                opt_num(d.line),
                opt_num(d.column)
            );
        }
        s.push_str("]}");
    }
    s.push_str(if r.files.is_empty() { "]\n" } else { "\n  ]\n" });
    s.push_str("}\n");
    s
}

/// A CSV field (RFC 4180 quoting).
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The report as CSV, one row per file. Outputs are separated by `;`; diagnostics by ` | `,
/// each `CODE line:column message`; `not_compared` is what verification knowingly left out
/// (`2 messages kept as comments`), empty for nothing.
pub fn csv(r: &BatchResult) -> String {
    let mut s = String::from("path,outputs,status,events,not_compared,blocks,time_ms,summary,diagnostics\r\n");
    for f in &r.files {
        let diags: Vec<String> = f
            .diagnostics
            .iter()
            .map(|d| match (d.line, d.column) {
                (Some(l), Some(c)) => format!("{} {l}:{c} {}", d.code, d.message),
                _ => format!("{} {}", d.code, d.message).trim().to_string(),
            })
            .collect();
        let row = [
            csv_field(&f.path),
            csv_field(&f.outputs.join(";")),
            f.status.as_str().to_string(),
            opt_num(f.events),
            csv_field(&f.excluded.describe().unwrap_or_default()),
            f.blocks.to_string(),
            format!("{:.3}", f.time.as_secs_f64() * 1000.0),
            csv_field(&f.summary),
            csv_field(&diags.join(" | ")),
        ];
        s.push_str(&row.join(","));
        s.push_str("\r\n");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::batch::{BatchMaps, DiagRecord};
    use std::time::Duration;

    fn result() -> BatchResult {
        let rec = |path: &str, status: Status| FileRecord {
            path: path.into(),
            outputs: if status == Status::Verified { vec![path.replace(".mpf", ".nc")] } else { vec![] },
            status,
            summary: "s, \"q\"".into(),
            diagnostics: vec![],
            events: Some(3),
            excluded: Default::default(),
            blocks: 4,
            time: Duration::from_millis(2),
        };
        let mut bad = rec("b.mpf", Status::Diverged);
        bad.diagnostics.push(DiagRecord {
            severity: "error",
            code: "NC501".into(),
            message: "X differs".into(),
            file: Some("b.mpf".into()),
            line: Some(7),
            column: Some(3),
        });
        let mut good = rec("a.mpf", Status::Verified);
        good.excluded.messages = 2;
        BatchResult {
            files: vec![good, bad, rec("c.mpf", Status::Unsupported)],
            maps: BatchMaps::default(),
            map_written: true,
            cancelled: false,
            elapsed: Duration::from_millis(1500),
            jobs: 2,
        }
    }

    #[test]
    fn summary_counts_and_worst_first() {
        let s = summary(&result(), "fanuc");
        assert!(s.contains("  verified                    1\n"), "{s}");
        assert!(s.contains("  diverged                    1\n"), "{s}");
        let worst = s.split("worst files:\n").nth(1).unwrap();
        let lines: Vec<&str> = worst.lines().collect();
        assert!(lines[0].contains("b.mpf  NC501 line 7: X differs"), "{s}");
        assert!(lines[1].contains("c.mpf"), "{s}");
        assert!(!s.contains("every file verified"));
        assert!(s.contains("  not compared: 2 messages kept as comments (in 1 verified file(s))\n"), "{s}");
    }

    /// A failed file's line names what stopped it: an error before any warning, and a run
    /// stopped without an error diagnostic (the step limit) by its status, not by the
    /// warning it also had (issue 16: NC368 stood where the file failed).
    #[test]
    fn worst_files_name_the_blocking_reason_not_a_warning() {
        let warning = |line| DiagRecord {
            severity: "warning",
            code: "NC368".into(),
            message: "G43 is dropped".into(),
            file: Some("x.nc".into()),
            line: Some(line),
            column: Some(1),
        };
        let mut r = result();
        r.files[1].diagnostics.insert(0, warning(2));
        r.files[2].status = Status::Inconclusive;
        r.files[2].summary = "inconclusive: step limit of 10000000 blocks reached".into();
        r.files[2].diagnostics.push(warning(3));
        let s = summary(&r, "sinumerik");
        let worst: Vec<&str> = s.split("worst files:\n").nth(1).unwrap().lines().collect();
        assert!(worst[0].ends_with("b.mpf  NC501 line 7: X differs"), "{s}");
        assert!(worst[1].ends_with("c.mpf  inconclusive: step limit of 10000000 blocks reached"), "{s}");
        assert!(!s.contains("NC368"), "{s}");
    }

    #[test]
    fn json_and_csv_records() {
        let j = json(&result(), "fanuc", "in", "out");
        assert!(j.contains("\"counts\": {\"verified\": 1, \"translated-unverified\": 0, \"diverged\": 1"), "{j}");
        assert!(j.contains("{\"severity\": \"error\", \"code\": \"NC501\", \"message\": \"X differs\", \"file\": \"b.mpf\", \"line\": 7, \"column\": 3}"), "{j}");
        assert!(j.contains("\"summary\": \"s, \\\"q\\\"\""), "{j}");
        let c = csv(&result());
        let rows: Vec<&str> = c.split("\r\n").collect();
        assert!(
            j.contains("\"events\": 3, \"not_compared\": {\"messages\": 2, \"look_ahead\": 0, \"interrupts\": 0}, \"blocks\": 4"),
            "{j}"
        );
        assert_eq!(rows[0], "path,outputs,status,events,not_compared,blocks,time_ms,summary,diagnostics");
        assert_eq!(rows[1], "a.mpf,a.nc,verified,3,2 messages kept as comments,4,2.000,\"s, \"\"q\"\"\",");
        assert!(rows[2].ends_with(",NC501 7:3 X differs"), "{}", rows[2]);
    }
}
