//! The trace's JSON Lines form (`--format jsonl`): one object per event, fields as
//! docs/trace-format.md names them.

use super::*;

fn axes_json(out: &mut TextBuf, to: &Axes) {
    out.push('{');
    let mut first = true;
    for (i, v) in to.iter().enumerate() {
        if let Some(x) = v {
            if !first {
                out.push(',');
            }
            first = false;
            out.push('"');
            out.push(AXES[i]);
            out.push_str("\":");
            push_num_b(out, *x);
        }
    }
    out.push('}');
}

/// One event as a JSON object (no newline); `line` is added when known.
pub fn json_line(ev: &Event, line: Option<usize>) -> String {
    let mut s = String::new();
    write_json(&mut s, ev, line);
    s
}

/// Appends the JSON object of `ev` to `s`.
pub fn write_json(s: &mut String, ev: &Event, line: Option<usize>) {
    to_string_buf(s, |b| json_form(b, ev, line));
}

/// Appends the JSON object of `ev` to `v` (UTF-8).
pub fn write_json_bytes(v: &mut Vec<u8>, ev: &Event, line: Option<usize>) {
    json_form(&mut TextBuf(v), ev, line);
}

fn json_form(s: &mut TextBuf, ev: &Event, line: Option<usize>) {
    s.push_str("{\"ev\":\"");
    s.push_str(ev.kind());
    s.push('"');
    match ev {
        Event::Move { rapid, to, f, probe } => {
            s.push_str(if *rapid { ",\"mode\":\"rapid\",\"to\":" } else { ",\"mode\":\"linear\",\"to\":" });
            axes_json(s, to);
            s.push_str(",\"f\":");
            push_opt(s, *f, "null");
            if *probe {
                s.push_str(",\"probe\":true");
            }
        }
        Event::Arc { cw, plane, to, center, f } => {
            s.push_str(if *cw { ",\"dir\":\"cw\",\"plane\":\"" } else { ",\"dir\":\"ccw\",\"plane\":\"" });
            s.push_str(plane.name());
            s.push_str("\",\"to\":");
            axes_json(s, to);
            s.push_str(",\"center\":{\"");
            s.push(AXES[center[0].0]);
            s.push_str("\":");
            push_num_b(s, center[0].1);
            s.push_str(",\"");
            s.push(AXES[center[1].0]);
            s.push_str("\":");
            push_num_b(s, center[1].1);
            s.push_str("},\"f\":");
            push_opt(s, *f, "null");
        }
        Event::Dwell { seconds } => {
            s.push_str(",\"seconds\":");
            push_num_b(s, *seconds);
        }
        Event::Tool { tool } => {
            s.push_str(",\"tool\":");
            match tool {
                ToolId::Number(n) => push_num_b(s, *n),
                ToolId::Name(n) => push_quoted(s, n),
            }
        }
        Event::Spindle { rpm, dir } => {
            s.push_str(",\"rpm\":");
            push_num_b(s, *rpm);
            s.push_str(",\"dir\":\"");
            s.push_str(dir.name());
            s.push('"');
        }
        Event::Coolant { on } => s.push_str(if *on { ",\"on\":true" } else { ",\"on\":false" }),
        Event::Stop { optional, message } => {
            s.push_str(if *optional { ",\"optional\":true,\"message\":" } else { ",\"optional\":false,\"message\":" });
            match message {
                Some(m) => push_quoted(s, m),
                None => s.push_str("null"),
            }
        }
        Event::Message { text } | Event::Print { text } => {
            s.push_str(",\"text\":");
            push_quoted(s, text);
        }
        Event::Alarm { number, message } => {
            s.push_str(&format!(",\"number\":{number},\"message\":"));
            push_quoted(s, message);
        }
        Event::End { code, steps } => s.push_str(&format!(",\"code\":\"{code}\",\"steps\":{steps}")),
        Event::Limit { steps } => s.push_str(&format!(",\"steps\":{steps}")),
        Event::Cycle(h) => s.push_str(&crate::eval::cycles::json_fields(h)),
        Event::WorkOffset { n } => s.push_str(&format!(",\"n\":{n}")),
        Event::Home(h) => {
            s.push_str(",\"axes\":[");
            for (k, &i) in h.axes.iter().enumerate() {
                if k > 0 {
                    s.push(',');
                }
                s.push('"');
                s.push(AXES[usize::from(i)]);
                s.push('"');
            }
            s.push_str("],\"via\":");
            axes_json(s, &h.via);
            s.push_str(&format!(",\"point\":{}", h.point));
        }
        Event::Comp(c) => {
            s.push_str(",\"length\":");
            match &c.length {
                Some(r) => {
                    s.push_str("{\"register\":");
                    reg_text(s, r);
                    s.push('}');
                }
                None => s.push_str("null"),
            }
            s.push_str(",\"radius\":");
            match &c.radius {
                Some((side, r)) => {
                    s.push_str("{\"side\":\"");
                    s.push_str(side.name());
                    s.push_str("\",\"register\":");
                    reg_text(s, r);
                    s.push('}');
                }
                None => s.push_str("null"),
            }
        }
        Event::ToolData(t) => {
            s.push_str(",\"register\":");
            reg_text(s, &t.register);
            s.push_str(",\"field\":\"");
            s.push_str(t.field.name());
            s.push_str("\",\"value\":");
            push_num_b(s, t.value);
        }
    }
    if let Some(l) = line {
        s.push_str(",\"line\":");
        crate::eval::numfmt::put_int(s.0, l as i64);
    }
    s.push('}');
}
