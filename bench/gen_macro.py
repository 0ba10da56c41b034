#!/usr/bin/env python3
"""Generates a macro-heavy program of about BLOCKS blocks for the streaming benchmark:
R parameters / # variables, IF/ELSE, WHILE (Siemens) or WHILE-DO (FANUC) loops with a few
iterations, labels with forward jumps, and motion computed from variables, in sections of
about 25 blocks. Every section runs once, so the run executes about as many blocks as the
file holds (plus the loop repetitions).

usage: gen_macro.py {sinumerik|fanuc} BLOCKS OUT      (deterministic: fixed seed)
"""
import random
import sys


def sinumerik(f, sections, rng):
    f.write("; macro-heavy benchmark\nDEF INT CNT\nDEF REAL DEPTH\nG71 G17 G90 G94\nF800\nR1=0\n")
    for s in range(sections):
        a = rng.randint(1, 9)
        f.write(f"R2={a}*0.5\nR3=R2*R2+{s % 7}\nDEPTH=-R2/10\n")
        f.write(f"IF R3>{a}\nG1 X=R3 Y=R2 Z=DEPTH\nELSE\nG1 X=-R3 Y=R2 Z=DEPTH\nENDIF\n")
        f.write("CNT=0\nWHILE CNT<3\nG1 X=R2+CNT Y=R3-CNT\nCNT=CNT+1\nENDWHILE\n")
        f.write(f"GOTOF LA{s}\nG0 Z100\nLA{s}:\nR1=R1+1\n")
        f.write("G1 X=SIN(R1)*10 Y=COS(R1)*10\nG1 Z=DEPTH-0.1\n")
        f.write("IF R1>0 GOTOF LB" + str(s) + "\nG0 Z50\nLB" + str(s) + ":\nG0 Z5\n")
    f.write("M30\n")


def fanuc(f, sections, rng):
    f.write("%\nO2000 (MACRO BENCHMARK)\nG21 G17 G90 G94\nF800.\n#1=0\n")
    n = 10
    for s in range(sections):
        a = rng.randint(1, 9)
        f.write(f"#2={a}*0.5\n#3=#2*#2+{s % 7}\n#4=-#2/10\n")
        f.write(f"IF[#3 GT {a}]GOTO{n}\nG1 X-#3 Y#2 Z#4\nGOTO{n + 1}\nN{n} G1 X#3 Y#2 Z#4\nN{n + 1}\n")
        f.write("#5=0\nWHILE[#5 LT 3]DO1\nG1 X[#2+#5] Y[#3-#5]\n#5=#5+1\nEND1\n")
        f.write(f"GOTO{n + 2}\nG0 Z100.\nN{n + 2} #1=#1+1\n")
        f.write("G1 X[SIN[#1]*10] Y[COS[#1]*10]\nG1 Z[#4-0.1]\n")
        n += 3
    f.write("M30\n%\n")


def main():
    dialect, blocks, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    rng = random.Random(7)
    per = 25 if dialect == "sinumerik" else 20
    with open(out, "w", newline="\n") as f:
        (sinumerik if dialect == "sinumerik" else fanuc)(f, blocks // per, rng)


if __name__ == "__main__":
    main()
