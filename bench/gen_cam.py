#!/usr/bin/env python3
"""Generates a CAM-style straight-line program (G1 X.. Y.. Z.. F.. blocks) for the benchmarks.

usage: gen_cam.py {sinumerik|fanuc} BLOCKS OUT [--macro]
Deterministic (fixed seed), so runs on different days compare the same input. With --macro the
same motion is cut into three runs by a small macro part, as CAM output with a safety-plane
parameter, a skipped section and a repeated pass has: R parameters / # variables, a forward
jump to a label or N number, a WHILE loop. Such a program streams only segmented (the macro
part kept, the runs streamed).
"""
import random
import sys

# Sinumerik, FANUC text put before run k (k = 0, 1, 2) and after the last run.
MACRO = {
    "sinumerik": [
        "; CAM benchmark with a macro part\nR1=5\nR2=0\nG71 G17 G90 G94\nG0 X0 Y0 Z=R1\nG1 Z-1 F500\n",
        "IF R2>0 GOTOF SKIP\n",
        "SKIP:\nG0 Z=R1\nWHILE R2<2\nR2=R2+1\nG1 X0 Y0 Z-1 F500\nENDWHILE\n",
        "G0 Z=R1\nM30\n",
    ],
    "fanuc": [
        "%\nO1000 (CAM BENCHMARK WITH A MACRO PART)\n#100=5.\n#101=0\nG21 G17 G90 G94\n"
        "G0 X0. Y0. Z#100\nG1 Z-1. F500.\n",
        "IF[#101GT0]GOTO100\n",
        "N100 G0 Z#100\nWHILE[#101LT2]DO1\n#101=#101+1\nG1 X0. Y0. Z-1. F500.\nEND1\n",
        "G0 Z#100\nM30\n%\n",
    ],
}


def main():
    dialect, blocks, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    macro = sys.argv[4:] == ["--macro"]
    rng = random.Random(42)
    x = y = z = 0.0
    # Where the macro part's pieces go: before block 0, blocks/2 and 3*blocks/4.
    cuts = {0: 0, blocks // 2: 1, 3 * blocks // 4: 2} if macro else {}
    with open(out, "w", newline="\n") as f:
        if macro:
            pass
        elif dialect == "fanuc":
            f.write("%\nO1000 (CAM BENCHMARK)\nG21 G17 G90 G94\nG0 X0. Y0. Z5.\nG1 Z-1. F500.\n")
        else:
            f.write("; CAM benchmark\nG71 G17 G90 G94\nG0 X0 Y0 Z5\nG1 Z-1 F500\n")
        for i in range(blocks):
            if i in cuts:
                f.write(MACRO[dialect][cuts[i]])
            x += rng.uniform(-0.5, 0.5)
            y += rng.uniform(-0.5, 0.5)
            z = max(-5.0, min(0.0, z + rng.uniform(-0.05, 0.05)))
            feed = 800 + (i % 7) * 100
            if dialect == "fanuc":
                f.write(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f} F{feed}.\n")
            else:
                f.write(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f} F{feed}\n")
        if macro:
            f.write(MACRO[dialect][3])
        else:
            f.write("M30\n" if dialect == "sinumerik" else "M30\n%\n")


if __name__ == "__main__":
    main()
