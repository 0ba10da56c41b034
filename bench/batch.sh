#!/usr/bin/env bash
# Batch benchmark (issue 6): translate and verify a generated library of 2,000 Sinumerik
# programs (50..2,000 blocks, CAM-style and macro-heavy) to FANUC with -j 1 and -j 2.
# Prints files/s, blocks/s and peak memory (max RSS from /usr/bin/time). Release build.
# usage: bench/batch.sh [COUNT]   (default 2000)
set -euo pipefail
cd "$(dirname "$0")/.."
count="${1:-2000}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cargo build --release --quiet
summary="$(python3 bench/gen_library.py "$count" "$work/lib")"
echo "library: $summary"
blocks="$(echo "$summary" | awk '{print $3}')"
for j in 1 2; do
    out="$work/out$j"
    /usr/bin/time -f "%e %M" -o "$work/time$j" ./target/release/nctrans --to fanuc -j "$j" -o "$out" "$work/lib" \
        >"$work/summary$j" 2>/dev/null || true
    read -r secs kb <"$work/time$j"
    files="$(grep -ci '\.nc$' <(cd "$out" && find . -type f) || true)"
    echo "-j $j: ${secs} s, $(python3 -c "print(f'{$count/$secs:.0f} files/s, {$blocks/$secs:,.0f} blocks/s, peak RSS {$kb/1024:.0f} MiB')"), $files outputs"
    grep -E "verified|diverged|inconclusive|unsupported" "$work/summary$j" | tr -s ' ' | paste -sd';' -
done
cmp <(cd "$work/out1" && find . -type f -exec md5sum {} + | sort -k2) <(cd "$work/out2" && find . -type f -exec md5sum {} + | sort -k2) \
    && echo "outputs of -j 1 and -j 2: byte-identical"
