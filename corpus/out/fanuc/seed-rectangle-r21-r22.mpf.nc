%
O0001 (SEED-RECTANGLE-R21-R22)
(NCTRANS: SINUMERIK seed-rectangle-r21-r22.mpf TO FANUC MACRO B)
(NCTRANS: R21 = #521)
(NCTRANS: R22 = #522)
( Seed 000 3.2.2: the 90 x 120 rectangle programmed with R21/R22 [macro version])
#521=90.
#522=120.
N1 G01 G91 X#521 F300.
N2 Y#522
N3 X-#521
N4 Y-#522
M30
%
