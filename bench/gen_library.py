#!/usr/bin/env python3
"""Generates a Sinumerik program library for the batch benchmark (issue 6).

usage: gen_library.py COUNT OUT_DIR
COUNT programs of 50..2,000 blocks in ten folders: two thirds CAM-style (G1 X.. Y.. Z.. F..
straight lines), one third macro-heavy (R parameters, WHILE/IF/FOR, arithmetic, calls of a
shared PROC subprogram with constant arguments). Deterministic (fixed seed).
"""
import os
import random
import sys


def cam(rng, blocks, i):
    lines = [f"; CAM part {i}", "G71 G17 G90 G94", "G0 X0 Y0 Z5", "G1 Z-1 F500"]
    x = y = z = 0.0
    for k in range(blocks):
        x += rng.uniform(-0.5, 0.5)
        y += rng.uniform(-0.5, 0.5)
        z = max(-5.0, min(0.0, z + rng.uniform(-0.05, 0.05)))
        lines.append(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f} F{800 + (k % 7) * 100}")
    lines.append("M30")
    return lines


def macro(rng, blocks, i):
    lines = [f"; macro part {i}", "G71 G17 G90 G94", "DEF REAL DEPTH, STEP", "DEF INT N",
             f"DEPTH={rng.randint(1, 9)}.5", "STEP=0.25", "R1=0", "R2=0"]
    k = 0
    while len(lines) < blocks:
        k += 1
        kind = k % 4
        if kind == 0:
            lines += [f"R1=0", f"WHILE R1<{rng.randint(3, 12)}",
                      "R2=R1*STEP+SIN(R1*10)", "G1 X=R1*2 Y=R2 F800", "R1=R1+1", "ENDWHILE"]
        elif kind == 1:
            lines += [f"IF R2>{rng.uniform(0, 2):.2f}", "G0 Z5", "ELSE", "G1 Z=-DEPTH F300", "ENDIF"]
        elif kind == 2:
            lines += [f"FOR N=1 TO {rng.randint(2, 6)}", "G1 X=N*1.5 Y=-N F600", "ENDFOR"]
        else:
            lines.append(f"POCKET({rng.randint(5, 40)}.0, {rng.randint(5, 40)}.0, {rng.randint(1, 5)}.0)")
    lines.append("M30")
    return lines


def main():
    count, out = int(sys.argv[1]), sys.argv[2]
    rng = random.Random(6)
    os.makedirs(os.path.join(out, "subs"), exist_ok=True)
    with open(os.path.join(out, "subs", "POCKET.SPF"), "w", newline="\n") as f:
        f.write("PROC POCKET(REAL L, REAL W, REAL D)\nG91 G1 Z=-D F200\nX=L F800\nY=W\nX=-L\nY=-W\nG90\nG0 Z5\nRET\n")
    blocks_total = 0
    for i in range(count):
        blocks = int(50 * (40 ** rng.random()))  # 50..2000, more small programs than large
        lines = macro(rng, blocks, i) if i % 3 == 0 else cam(rng, blocks, i)
        blocks_total += len(lines)
        d = os.path.join(out, f"cell{i % 10}")
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, f"P{i:04d}.MPF"), "w", newline="\n") as f:
            f.write("\n".join(lines) + "\n")
    print(f"{count} programs, {blocks_total} blocks")


if __name__ == "__main__":
    main()
