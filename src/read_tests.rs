//! Unit tests of `read` (decoding, lines, block normalisation).

use super::*;

fn raw(s: &str) -> RawBlock<'_> {
    RawBlock { text: s, start: 10, line: 1 }
}

#[test]
fn splits_every_line_end() {
    let v: Vec<_> = blocks("a\r\nb\rc\n\nd").map(|b| (b.text, b.start, b.line)).collect();
    assert_eq!(v, vec![("a", 0, 1), ("b", 3, 2), ("c", 5, 3), ("", 7, 4), ("d", 8, 5)]);
}

#[test]
fn full_width_is_normalised_with_spans_into_the_original() {
    let n = normalise(&raw("Ｎ１ Ｇ０１ Ｘ９０．０"), CommentStyle::Semicolon);
    assert_eq!(n.text, "N1 G01 X90.0");
    assert_eq!(n.span(3, 6), Span::new(10 + 7, 10 + 16));
    assert_eq!(n.full_width.len(), 3);
}

#[test]
fn comments_keep_full_width_text() {
    let n = normalise(&raw("G1 X1 ；注释，（一）"), CommentStyle::Semicolon);
    assert_eq!(n.text, "G1 X1 ;注释，（一）");
    let n = normalise(&raw("G1（注释，Ａ）X1"), CommentStyle::Parens);
    assert_eq!(n.text, "G1(注释，Ａ)X1");
}

#[test]
fn letter_o_in_g_word() {
    let n = normalise(&raw("GO X[#1+#2]"), CommentStyle::Parens);
    assert_eq!(n.text, "G0 X[#1+#2]");
    assert_eq!(n.letter_o, vec![Span::new(11, 12)]);
    let n = normalise(&raw("GOTO10 (GO HOME)"), CommentStyle::Parens);
    assert_eq!(n.text, "GOTO10 (GO HOME)");
    assert!(n.letter_o.is_empty());
}

#[test]
fn word_at_a_time_searches_match_byte_by_byte() {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let alphabet = b"G1X.5;(o)O\n\r\t\x0c\x1a\x7f\x00\x1b\xc3\xa9 ~";
    for len in 0..200 {
        for _ in 0..20 {
            let b: Vec<u8> = (0..len)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    alphabet[(state % alphabet.len() as u64) as usize]
                })
                .collect();
            let end = b.iter().position(|&c| c == b'\n' || c == b'\r').unwrap_or(b.len());
            let plain = b[..end].iter().all(|&c| matches!(c, b'\t' | 0x0c | 0x1a | 0x20..=0x7e));
            assert_eq!(line_end(&b), (end, plain), "{b:?}");
            assert_eq!(find2(&b, b';', b'('), b.iter().position(|&c| c == b';' || c == b'('), "{b:?}");
            assert_eq!(has_letter_o(&b), b.iter().any(|&c| c == b'o' || c == b'O'), "{b:?}");
        }
    }
}

#[test]
fn ascii_trims_are_the_unicode_trims() {
    let pieces = [" ", "\t", "\x0b", "\x0c", "\u{3000}", "\u{85}", "\u{a0}", "a", "é", "\u{2003}", "G1", "\r"];
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    for _ in 0..20_000 {
        let mut s = String::new();
        for _ in 0..(state % 7) {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            s.push_str(pieces[(state % pieces.len() as u64) as usize]);
        }
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        assert_eq!(trim_start(&s), s.trim_start(), "{s:?}");
        assert_eq!(trim_end(&s), s.trim_end(), "{s:?}");
        assert_eq!(trim(&s), s.trim(), "{s:?}");
    }
}

#[test]
fn legacy_encodings_round_trip() {
    let (gbk, _, _) = encoding_rs::GBK.encode("N10 G1 X1 ;加工中心程序");
    let d = decode(&gbk, None);
    assert!(d.text.contains("加工"), "{}", d.text);
    assert_eq!(encode(&d.text, d.encoding, d.bom), gbk.as_ref());
    let latin = b"N10 X1 ; \xe9t\xe9 \x81\x8d";
    let d = decode(latin, None);
    assert_eq!(encode(&d.text, d.encoding, d.bom), latin);
}

#[test]
fn line_ends_of_plain_lines_at_every_place_in_a_word() {
    // CAM lines: plain text, the line end anywhere in an eight-byte word, sometimes a
    // tab, form feed, control or non-ASCII byte before it in the same word or earlier.
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for len in 0..80 {
        for _ in 0..40 {
            let mut b: Vec<u8> = (0..len).map(|_| b"G1 X0.5Y-2;("[(next() % 12) as usize]).collect();
            if len > 0 && next() % 3 == 0 {
                let at = (next() % len as u64) as usize;
                b[at] = [b'\t', 0x0c, 0x1a, 0x7f, 0x01, 0xc3][(next() % 6) as usize];
            }
            b.extend_from_slice([&b"\n"[..], b"\r\n", b"\r", b"", b"\nG1"][(next() % 5) as usize]);
            let end = b.iter().position(|&c| c == b'\n' || c == b'\r').unwrap_or(b.len());
            let plain = b[..end].iter().all(|&c| matches!(c, b'\t' | 0x0c | 0x1a | 0x20..=0x7e));
            assert_eq!(line_end(&b), (end, plain), "{b:?}");
        }
    }
}

#[test]
fn exact_values_are_the_parsed_literals() {
    // Every digit count and place of the point, and the largest whole numbers below 2^53.
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    for _ in 0..200_000 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let digits = 1 + (state % 15) as u32;
        let mant = (state >> 8) % 10u64.pow(digits);
        let k = ((state >> 4) % u64::from(digits + 1)) as usize;
        let text = format!("{mant:0width$}", width = digits as usize);
        let literal = format!("{}.{}", &text[..text.len() - k], &text[text.len() - k..]);
        let want: f64 = literal.parse().expect("a literal");
        assert_eq!(exact(mant, k).map(f64::to_bits), Some(want.to_bits()), "{literal}");
        assert_eq!(exact(mant, k), scaled(mant, k), "{literal}");
        if k < 8 {
            assert_eq!(exact_short(mant, k).to_bits(), want.to_bits(), "{literal}");
        }
    }
    for mant in [0, 1, (1 << 53) - 1] {
        assert_eq!(exact(mant, 0), Some(mant as f64));
    }
    assert_eq!(exact(1 << 53, 0), None);
    assert_eq!(exact(1, 23), None);
}
