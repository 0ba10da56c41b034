#!/usr/bin/env bash
# Evaluator benchmark (issue 3): a loop of ITER iterations (default 1,000,000) doing
# arithmetic and one G1 per iteration, in FANUC (WHILE[..]DO1) and Siemens (WHILE), run
# by `nctrans run` with the trace discarded (--quiet) and with jsonl written to a file.
# Prints blocks/s and peak RSS; run it with ITER=100000 too to see that memory does not
# grow with the iteration count. Times LinuxCNC's rs274 on the equivalent `o100 while`
# program as a peer when it is installed. Results go in bench/README.md.
set -euo pipefail
cd "$(dirname "$0")/.."
ITER=${ITER:-1000000}
OUT=bench/out
mkdir -p "$OUT"
cargo build --release --quiet
BIN=target/release/nctrans

cat > "$OUT/loop-$ITER.nc" <<NC
%
O1000
#1=0
#2=0
G90 G1 X0 F1000.
WHILE[#1 LT $ITER]DO1
#1=#1+1
#2=#1*0.001+[#1 MOD 7]
G1 X#2
END1
M30
%
NC
cat > "$OUT/loop-$ITER.mpf" <<MPF
R1=0
R2=0
G90 G1 X0 F1000
WHILE R1<$ITER
R1=R1+1
R2=R1*0.001+(R1 MOD 7)
G1 X=R2
ENDWHILE
M30
MPF
cat > "$OUT/loop-$ITER.ngc" <<NGC
#1 = 0
#2 = 0
G90 G1 X0 F1000
o100 while [#1 LT $ITER]
#1 = [#1 + 1]
#2 = [#1 * 0.001 + [#1 MOD 7]]
G1 X#2
o100 endwhile
M2
NGC

measure() { # label, then the command; prints seconds and peak RSS
  local label=$1; shift
  /usr/bin/time -f "%e %M" -o "$OUT/time.txt" taskset -c 0 "$@" || true
  read -r secs kb < "$OUT/time.txt"
  LAST_SECS=$secs
  python3 - "$label" "$ITER" "$secs" "$kb" <<'PY'
import sys
label, n, s, kb = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
blocks = 5 * n + 5  # WHILE head, two assignments, G1, END per iteration
print(f"{label:28s} {n} iterations ({blocks} blocks) in {s:.2f} s = {blocks / max(s, 1e-9):,.0f} blocks/s, peak RSS {kb / 1024:.1f} MiB")
PY
}

for ext in nc mpf; do
  f="$OUT/loop-$ITER.$ext"
  measure "$ext trace discarded" "$BIN" run --quiet "$f"
  measure "$ext jsonl to a file" sh -c "\"$BIN\" run --format jsonl \"$f\" > \"$OUT/loop-$ITER.$ext.jsonl\""
  NCTRANS_SECS=$LAST_SECS
done
ls -l "$OUT"/loop-"$ITER".*.jsonl | awk '{print "jsonl size:", $5, $9}'
if command -v rs274 >/dev/null 2>&1; then
  measure "rs274 (peer)" sh -c "rs274 -g \"$OUT/loop-$ITER.ngc\" > /dev/null 2>&1"
  python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); print(f'ratio: rs274 takes {a / max(b, 1e-9):.1f}x the time of nctrans run (Siemens, jsonl)')" "$LAST_SECS" "$NCTRANS_SECS"
else
  echo "rs274 not installed (Debian package linuxcnc-uspace): no peer measurement"
fi
