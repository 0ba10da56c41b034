#!/usr/bin/env bash
# Streaming benchmark (issue 7): generated CAM programs of 1 M and 10 M blocks (about 40 and
# 400 MB) in each dialect and a macro-heavy program of 1 M blocks per dialect, each through
# `parse --summary`, `run` (text trace to /dev/null) and translation with verification, on
# one core (taskset -c 0), release build; blocks/s and peak RSS from /usr/bin/time. The CAM
# programs are also run and translated with a small macro part (segmented streaming).
# LinuxCNC rs274 on the same motion is the peer when installed. Also runs the
# million-block differential fast-path test in release. Results go in bench/README.md.
#
#   SIZES="1000000 10000000" bench/stream.sh      (default; 10 M files are deleted after)
#   SIZES= SKIP_DIFF=1 bench/stream.sh             (the macro-heavy programs only)
set -euo pipefail
cd "$(dirname "$0")/.."
SIZES=${SIZES-"1000000 10000000"}
OUT=bench/out
mkdir -p "$OUT"
cargo build --release --quiet
BIN=target/release/nctrans
STEPS=1000000000

# measure LABEL BLOCKS CMD… : one row (seconds, blocks/s, peak RSS, exit status).
measure() {
  local label=$1 blocks=$2
  shift 2
  local status=0
  /usr/bin/time -f "%e %M" -o "$OUT/time.txt" taskset -c 0 "$@" > /dev/null 2> "$OUT/err.txt" || status=$?
  read -r secs kb < <(tail -1 "$OUT/time.txt")
  python3 - "$label" "$blocks" "$secs" "$kb" "$status" "$(grep -E 'equivalent|diverged|inconclusive|not verified' "$OUT/err.txt" | tail -1)" <<'PY'
import sys
label, n, s, kb, st, verdict = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), sys.argv[5], sys.argv[6]
print(f"{label:44s} {s:8.2f} s {n / max(s, 1e-9):12,.0f} blocks/s {kb / 1024:8.1f} MiB  exit {st} {verdict}")
PY
}

if [ -z "${SKIP_DIFF:-}" ]; then
  echo "== differential fast-path test, 1 M generated blocks per dialect (release)"
  cargo test --release --quiet --test fast_path_diff -- --ignored 2>&1 | grep -E "test result|panicked" || true
  echo "== differential streamed-translation test, 1 M generated blocks (release)"
  cargo test --release --quiet --test stream_translate_fast -- --ignored 2>&1 | grep -E "test result|panicked" || true
fi

for n in $SIZES; do
  for d in sinumerik fanuc; do
    ext=$([ "$d" = fanuc ] && echo nc || echo mpf)
    f="$OUT/cam-$n.$ext"
    [ -f "$f" ] || python3 bench/gen_cam.py "$d" "$n" "$f"
    echo "== $d CAM, $n blocks ($(du -m "$f" | cut -f1) MB)"
    measure "parse --summary" "$n" "$BIN" parse --summary "$f"
    measure "run (text trace to /dev/null)" "$n" "$BIN" run --max-steps $STEPS "$f"
    measure "run --quiet (no trace)" "$n" "$BIN" run --quiet --max-steps $STEPS "$f"
    if [ "$d" = sinumerik ]; then
      measure "--to fanuc -o (verified)" "$n" "$BIN" --to fanuc "$f" -o "$OUT/cam-$n.out.nc" --max-steps $STEPS
      measure "--to fanuc -o --no-verify" "$n" "$BIN" --to fanuc "$f" -o "$OUT/cam-$n.out.nc" --no-verify
      rm -f "$OUT/cam-$n.out.nc"
    else
      measure "--to sinumerik -o (verified)" "$n" "$BIN" --to sinumerik "$f" -o "$OUT/cam-$n.out.mpf" --max-steps $STEPS
      measure "--to sinumerik -o --no-verify" "$n" "$BIN" --to sinumerik "$f" -o "$OUT/cam-$n.out.mpf" --no-verify
      rm -f "$OUT/cam-$n.out.mpf"
    fi
  done
  if command -v rs274 > /dev/null 2>&1; then
    g="$OUT/cam-$n.ngc"
    [ -f "$g" ] || sed -e '/^%/d' -e '/^O1000/d' -e 's/\.$//' "$OUT/cam-$n.nc" > "$g"
    measure "rs274 (peer) on the same motion" "$n" rs274 -g "$g"
    [ "$n" -gt 1000000 ] && rm -f "$g"
  fi
  if [ "$n" -gt 1000000 ]; then
    rm -f "$OUT/cam-$n.mpf" "$OUT/cam-$n.nc"
  fi
  # The same motion cut into three runs by a small macro part (gen_cam.py --macro): it
  # streams segmented. Capped at 4 GiB of address space, so that a build whose segmented
  # route declined (and read the file whole) fails here instead of filling the machine.
  for d in sinumerik fanuc; do
    ext=$([ "$d" = fanuc ] && echo nc || echo mpf)
    to=$([ "$d" = fanuc ] && echo sinumerik || echo fanuc)
    oext=$([ "$d" = fanuc ] && echo mpf || echo nc)
    f="$OUT/cam-macro-$n.$ext"
    [ -f "$f" ] || python3 bench/gen_cam.py "$d" "$n" "$f" --macro
    echo "== $d CAM with a macro part, $n blocks ($(du -m "$f" | cut -f1) MB)"
    (
      ulimit -v 4194304
      measure "run (text trace to /dev/null)" "$n" "$BIN" run --max-steps $STEPS "$f"
      measure "--to $to -o (verified, segmented)" "$n" "$BIN" --to $to "$f" -o "$OUT/cam-macro-$n.out.$oext" --max-steps $STEPS
    )
    rm -f "$OUT/cam-macro-$n.out.$oext"
    [ "$n" -gt 1000000 ] && rm -f "$f"
  done
done

for d in sinumerik fanuc; do
  ext=$([ "$d" = fanuc ] && echo nc || echo mpf)
  f="$OUT/macro-1000000.$ext"
  [ -f "$f" ] || python3 bench/gen_macro.py "$d" 1000000 "$f"
  blocks=$(grep -c . "$f")
  echo "== $d macro-heavy, $blocks lines ($(du -m "$f" | cut -f1) MB)"
  measure "parse --summary" "$blocks" "$BIN" parse --summary "$f"
  measure "run (text trace to /dev/null)" "$blocks" "$BIN" run --max-steps $STEPS "$f"
  if [ "$d" = sinumerik ]; then
    # A macro program is translated whole (not straight-line). At 1 M lines it has some
    # 200,000 jump targets, more than FANUC's 99,999 N numbers (NC306), so the translation
    # is measured on 100,000 lines.
    g="$OUT/macro-100000.mpf"
    [ -f "$g" ] || python3 bench/gen_macro.py sinumerik 100000 "$g"
    measure "--to fanuc -o (verified, whole; $(grep -c . "$g") lines)" "$(grep -c . "$g")" "$BIN" --to fanuc "$g" -o "$OUT/macro.out.nc" --max-steps $STEPS
    rm -f "$OUT/macro.out.nc"
  fi
done
