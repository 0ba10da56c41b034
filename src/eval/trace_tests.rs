//! Unit tests of `eval::trace` (the text and jsonl forms of events).

use super::*;

#[test]
fn json_of_a_move_follows_the_spec() {
    let mut to = [None; 9];
    to[0] = Some(10.0);
    to[2] = Some(-0.5);
    let ev = Event::Move { rapid: false, to, f: Some(300.0), probe: false };
    assert_eq!(json_line(&ev, Some(3)), r#"{"ev":"move","mode":"linear","to":{"X":10,"Z":-0.5},"f":300,"line":3}"#);
    assert_eq!(text_line(&ev), "move linear X=10 Z=-0.5 f=300");
}

#[test]
fn line_numbers_counted_up_are_written_as_put_int_writes_them() {
    let mut last = (0, *b"000000000000000000000000", 1);
    let mut seq: Vec<usize> = (0..12_000).collect();
    seq.extend([99, 100, 100, 101, 999_999, 1_000_000, 5, 4, 3, 0, 0, 1, 9, 10, usize::MAX - 1, usize::MAX, 0]);
    let mut x = 7usize;
    for _ in 0..2000 {
        x = x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
        let l = x >> (x % 60);
        seq.extend([l, l.wrapping_add(1), l.wrapping_add(2)]);
    }
    let mut b = [0u8; 64];
    for l in seq {
        let end = put_line(&mut b, 3, l, &mut last);
        let mut want = Vec::new();
        super::super::numfmt::put_int(&mut want, l as i64);
        if l > i64::MAX as usize {
            want = l.to_string().into_bytes();
        }
        assert_eq!(&b[3..end], &want[..], "line {l}");
    }
}

#[test]
fn json_escapes_messages() {
    let ev = Event::Stop { optional: false, message: Some("a\"b".into()) };
    assert_eq!(json_line(&ev, None), r#"{"ev":"stop","optional":false,"message":"a\"b"}"#);
}
