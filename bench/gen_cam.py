#!/usr/bin/env python3
"""Generates a CAM-style straight-line program (G1 X.. Y.. Z.. F.. blocks) for the benchmarks.

usage: gen_cam.py {sinumerik|fanuc} BLOCKS OUT
Deterministic (fixed seed), so runs on different days compare the same input.
"""
import random
import sys


def main():
    dialect, blocks, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    rng = random.Random(42)
    x = y = z = 0.0
    with open(out, "w", newline="\n") as f:
        if dialect == "fanuc":
            f.write("%\nO1000 (CAM BENCHMARK)\nG21 G17 G90 G94\nG0 X0. Y0. Z5.\nG1 Z-1. F500.\n")
        else:
            f.write("; CAM benchmark\nG71 G17 G90 G94\nG0 X0 Y0 Z5\nG1 Z-1 F500\n")
        for i in range(blocks):
            x += rng.uniform(-0.5, 0.5)
            y += rng.uniform(-0.5, 0.5)
            z = max(-5.0, min(0.0, z + rng.uniform(-0.05, 0.05)))
            feed = 800 + (i % 7) * 100
            if dialect == "fanuc":
                f.write(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f} F{feed}.\n")
            else:
                f.write(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f} F{feed}\n")
        f.write("M30\n" if dialect == "sinumerik" else "M30\n%\n")


if __name__ == "__main__":
    main()
