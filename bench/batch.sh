#!/usr/bin/env bash
# Batch benchmark (issue 6): translate and verify a generated library of 2,000 programs
# (50..2,000 blocks, CAM-style and macro-heavy) with -j 1 and -j 2.
# To FANUC: the generated Sinumerik library. To Sinumerik: that library translated to FANUC
# first (unverified, not timed), then the FANUC library is the input.
# Prints files/s, blocks/s (blocks read, from the report) and peak memory (max RSS from
# /usr/bin/time). Release build.
# usage: bench/batch.sh [COUNT] [fanuc|sinumerik]   (default 2000 fanuc)
set -euo pipefail
cd "$(dirname "$0")/.."
count="${1:-2000}"
to="${2:-fanuc}"
case "$to" in
    fanuc) ext='\.nc$' ;;
    sinumerik|siemens) to=sinumerik; ext='\.[ms]pf$' ;;
    *) echo "usage: bench/batch.sh [COUNT] [fanuc|sinumerik]" >&2; exit 2 ;;
esac
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cargo build --release --quiet
summary="$(python3 bench/gen_library.py "$count" "$work/lib")"
echo "library: $summary"
lib="$work/lib"
if [ "$to" = sinumerik ]; then
    ./target/release/nctrans --to fanuc --no-verify -j 2 -o "$work/flib" "$work/lib" >/dev/null 2>&1 || true
    rm -f "$work/flib/nctrans-map.toml"
    lib="$work/flib"
    echo "FANUC library: $(find "$lib" -type f | wc -l) files"
fi
for j in 1 2; do
    out="$work/out$j"
    /usr/bin/time -f "%e %M" -o "$work/time$j" ./target/release/nctrans --to "$to" -j "$j" \
        --report "$work/report$j.json" -o "$out" "$lib" >"$work/summary$j" 2>/dev/null || true
    read -r secs kb <"$work/time$j"
    files="$(grep -ciE "$ext" <(cd "$out" && find . -type f) || true)"
    inputs="$(grep -c '"path": ' "$work/report$j.json")"
    blocks="$(grep -o '"blocks": [0-9]*' "$work/report$j.json" | awk '{s += $2} END {print s}')"
    echo "-j $j: ${secs} s, $(python3 -c "print(f'{$inputs/$secs:.0f} files/s, {$blocks/$secs:,.0f} blocks/s, peak RSS {$kb/1024:.0f} MiB')"), $inputs inputs, $blocks blocks, $files outputs"
    grep -E "verified|diverged|inconclusive|unsupported" "$work/summary$j" | tr -s ' ' | paste -sd';' -
done
cmp <(cd "$work/out1" && find . -type f -exec md5sum {} + | sort -k2) <(cd "$work/out2" && find . -type f -exec md5sum {} + | sort -k2) \
    && echo "outputs of -j 1 and -j 2: byte-identical"
