%
O0001 (SEED-RECTANGLE-FULL-WIDTH)
(NCTRANS: SINUMERIK seed-rectangle-full-width.mpf TO FANUC MACRO B)
( Seed 000 3.2.2: the same rectangle as an ordinary program, typed in full-width characters [NC110])
N1 G01 G91 X90. F300.
N2 Y120.
N3 X-90.
N4 Y-120.
M30
%
