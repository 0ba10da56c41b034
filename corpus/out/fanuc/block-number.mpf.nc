%
O0001 (BLOCK-NUMBER)
(NCTRANS: SINUMERIK block-number.mpf TO FANUC MACRO B)
( Block numbers N10, N20 in front of the words)
N10 G00 X0. Y0.
N20 G01 X10. F100.
N30 M30
%
