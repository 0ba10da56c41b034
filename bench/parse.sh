#!/usr/bin/env bash
# Parse benchmark (issue 2): a 1,000,000-block CAM program in each dialect through
# `nctrans parse --summary` on one core; prints blocks/s and peak RSS, and times LinuxCNC's
# rs274 on the same motion as a peer when it is installed. Results go in bench/README.md.
set -euo pipefail
cd "$(dirname "$0")/.."
BLOCKS=${BLOCKS:-1000000}
OUT=bench/out
mkdir -p "$OUT"
cargo build --release --quiet
BIN=target/release/nctrans
for d in sinumerik fanuc; do
  ext=$([ "$d" = fanuc ] && echo nc || echo mpf)
  f="$OUT/cam-$BLOCKS.$ext"
  [ -f "$f" ] || python3 bench/gen_cam.py "$d" "$BLOCKS" "$f"
  # One core: taskset keeps the measurement comparable between machines with more cores.
  /usr/bin/time -f "%e %M" -o "$OUT/time.txt" taskset -c 0 "$BIN" parse --summary "$f" > /dev/null
  read -r secs kb < "$OUT/time.txt"
  python3 - "$d" "$BLOCKS" "$secs" "$kb" <<'PY'
import sys
d, n, s, kb = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
print(f"{d:10s} parse: {n} blocks in {s:.2f} s = {n / max(s, 1e-9):,.0f} blocks/s, peak RSS {kb / 1024:.0f} MiB")
PY
done
if command -v rs274 >/dev/null 2>&1; then
  f="$OUT/cam-$BLOCKS.ngc"
  [ -f "$f" ] || { sed -e '/^%/d' -e '/^O1000/d' -e 's/\.$//' "$OUT/cam-$BLOCKS.nc" > "$f"; }
  /usr/bin/time -f "%e %M" -o "$OUT/time.txt" taskset -c 0 rs274 -g "$f" > /dev/null 2>&1 || true
  read -r secs kb < "$OUT/time.txt"
  echo "rs274 (peer): $secs s, peak RSS $((kb / 1024)) MiB"
else
  echo "rs274 not installed (Debian package linuxcnc-uspace): no peer measurement"
fi
