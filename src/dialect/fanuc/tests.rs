//! Unit tests of the FANUC reader's two block paths: the byte-level fast path must give
//! exactly the parts the grammar gives, on many generated plain blocks.

use super::fast::parse_fast_for_test;
use super::parse::parse_grammar_for_test;

use crate::test_rng::Rng;

fn number(r: &mut Rng) -> String {
    let int = r.below(100_000);
    match r.below(6) {
        0 => format!("{int}"),
        1 => format!("{int}."),
        2 => format!("{int}.{}", r.below(1000)),
        3 => format!(".{}", r.below(1000) + 1),
        4 => format!("{:05}", r.below(100)),
        _ => format!("{}.{:03}", r.below(10), r.below(1000)),
    }
}

fn block(r: &mut Rng) -> String {
    let mut s = String::new();
    let sep = |r: &mut Rng| match r.below(4) {
        0 => "",
        1 | 2 => " ",
        _ => "\t ",
    };
    if r.below(5) == 0 {
        s.push('/');
        if r.below(2) == 0 {
            s.push_str(&r.below(10).to_string());
        }
        s.push(' ');
    }
    if r.below(2) == 0 {
        s.push_str(&format!("N{}", r.below(99_999) + 1));
        s.push_str(sep(r));
    }
    let letters = b"GXYZFIJKRSMTHDPQUVWABCE";
    for _ in 0..(1 + r.below(6)) {
        let l = letters[r.below(letters.len() as u64) as usize] as char;
        let l = if r.below(8) == 0 { l.to_ascii_lowercase() } else { l };
        s.push(l);
        if r.below(8) == 0 {
            s.push(' ');
        }
        match r.below(5) {
            0 => s.push('-'),
            1 if r.below(3) == 0 => s.push('+'),
            _ => {}
        }
        s.push_str(&number(r));
        s.push_str(sep(r));
    }
    s.trim().to_string()
}

#[test]
fn fast_path_equals_grammar_on_generated_blocks() {
    let mut r = Rng(0x9E37_79B9_7F4A_7C15);
    let mut fast_taken = 0;
    for _ in 0..20_000 {
        let b = block(&mut r);
        let slow = parse_grammar_for_test(&b);
        match parse_fast_for_test(&b) {
            Some(fast) => {
                fast_taken += 1;
                assert_eq!(Ok(fast), slow, "block `{b}`");
            }
            None => panic!("fast path declined the plain block `{b}`"),
        }
    }
    assert_eq!(fast_taken, 20_000);
}

#[test]
fn fast_path_declines_what_it_does_not_know() {
    for b in [
        "G1 X#1",
        "X[1+2]",
        "#1=2",
        "GOTO10",
        "DO1",
        "END1",
        "IF[#1EQ1]GOTO5",
        "G1 X1 (C)",
        "X1.2.3",
        "X.",
        "X",
        "X--1",
        "//1",
        "WHILE[1LT2]DO1",
    ] {
        assert_eq!(parse_fast_for_test(b), None, "`{b}`");
    }
}
