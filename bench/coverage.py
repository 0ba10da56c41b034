#!/usr/bin/env python3
"""Coverage of a program library: how many files nctrans reads, translates and verifies.

Usage: bench/coverage.py [--nctrans BIN] [--to fanuc|sinumerik|both] [--top N] FOLDER...

For each FOLDER it runs the batch job (`nctrans --to T -o TMP/ FOLDER --report r.json`, with
verification) once per target, so every program is judged in the direction that translates it
away from its own dialect (files already in the target dialect are skipped by the batch and
counted in the other direction). "Read" is judged per file by `nctrans parse --summary`, so a
file is not counted unread because a program it calls does not read. Prints per folder and in
all: files, empty (no program at all, NC145), read, translated (the batch wrote an output),
verified (equivalent), as counts and as shares of the files that hold a program, and the most
frequent diagnostic codes among the errors that stopped files, with one example message each.
Nothing is written outside a temporary folder; the programs are only read.
"""

import argparse
import collections
import json
import os
import subprocess
import sys
import tempfile

SUFFIXES = {".mpf", ".spf", ".nc", ".tap", ".def"}


def programs(folder):
    for root, dirs, files in os.walk(folder):
        dirs.sort()
        for name in sorted(files):
            if os.path.splitext(name)[1].lower() in SUFFIXES:
                yield os.path.join(root, name)


def reads(nctrans, path):
    """"read" when `parse --summary` reports no error (exit 0), "empty" when the file holds
    no program at all (NC145: blank, or only a header and comments), else "unread"."""
    r = subprocess.run([nctrans, "parse", "--summary", path], capture_output=True, timeout=120)
    if r.returncode == 0:
        return "read"
    return "empty" if b"NC145" in r.stderr else "unread"


def batch(nctrans, folder, target, tmp):
    out = os.path.join(tmp, "out-" + target)
    report = os.path.join(tmp, target + ".json")
    cmd = [nctrans, "--to", target, "-o", out, folder, "--report", report, "--force"]
    r = subprocess.run(cmd, capture_output=True, timeout=3600)
    if not os.path.exists(report):
        # A folder with no program in the source dialect is judged in the other direction.
        if b"NC612" in r.stderr:
            return {"files": []}
        sys.exit(f"coverage: {' '.join(cmd)} wrote no report")
    with open(report, encoding="utf-8") as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="+")
    ap.add_argument("--nctrans", default=os.environ.get("NCTRANS", "target/release/nctrans"))
    ap.add_argument("--to", default="both", choices=["fanuc", "sinumerik", "both"])
    ap.add_argument("--top", type=int, default=10)
    args = ap.parse_args()
    targets = ["fanuc", "sinumerik"] if args.to == "both" else [args.to]

    total = collections.Counter()
    codes = collections.Counter()
    examples = {}
    rows = []
    for folder in args.folders:
        folder = os.path.abspath(folder)
        files = [os.path.relpath(p, folder) for p in programs(folder)]
        verdicts = [reads(args.nctrans, os.path.join(folder, p)) for p in files]
        read = verdicts.count("read")
        empty = verdicts.count("empty")
        judged = {}
        with tempfile.TemporaryDirectory() as tmp:
            for t in targets:
                rep = batch(args.nctrans, folder, t, tmp)
                for entry in rep.get("files", []):
                    if entry["status"] != "skipped":
                        judged[entry["path"]] = entry
        translated = sum(1 for e in judged.values() if e.get("outputs"))
        verified = sum(1 for e in judged.values() if e["status"] == "verified")
        for e in judged.values():
            if e["status"] == "verified":
                continue
            # The blocking diagnostic: the first error, else the first warning.
            diags = e.get("diagnostics") or []
            first = next((d for d in diags if d["severity"] == "error"), diags[0] if diags else None)
            code = first["code"] if first else e["status"]
            codes[code] += 1
            examples.setdefault(code, f"{first['message']} ({e['path']})" if first else e.get("summary", ""))
        row = (os.path.basename(folder.rstrip("/")), len(files), empty, read, translated, verified)
        rows.append(row)
        for k, v in zip(["files", "empty", "read", "translated", "verified"], row[1:]):
            total[k] += v

    def pct(n, d):
        return f"{100.0 * n / d:5.1f} %" if d else "    -"

    # Percentages are of the files that hold a program: an empty file (NC145) has nothing
    # to read, run or translate, and is counted apart.
    print(f"{'library':<28} {'files':>6} {'empty':>6} {'read':>14} {'translated':>14} {'verified':>14}")
    all_row = ("all", total["files"], total["empty"], total["read"], total["translated"], total["verified"])
    for name, n, e, r, t, v in rows + [all_row]:
        m = n - e
        print(f"{name:<28} {n:>6} {e:>6} {r:>6} {pct(r, m)} {t:>6} {pct(t, m)} {v:>6} {pct(v, m)}")
    print(f"\nmost frequent blocking diagnostics (files not verified):")
    for code, n in codes.most_common(args.top):
        print(f"  {code:<8} {n:>5}  e.g. {examples[code]}")


if __name__ == "__main__":
    main()
