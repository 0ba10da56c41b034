%
O0001 (DEF-ARRAY-1D)
(NCTRANS: SINUMERIK def-array-1d.mpf TO FANUC MACRO B)
(NCTRANS: DEPTHS[…] [4 elements] = #100)
(NCTRANS: I_IDX = #104)
( One-dimensional array with SET initial values and element access)
#100=1.
#101=2.5
#102=4.
#103=6.
#104=2.
G01 Z-#[#104+100.] F100.
#100=0.5
M30
%
