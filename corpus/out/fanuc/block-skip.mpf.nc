%
O0001 (BLOCK-SKIP)
(NCTRANS: SINUMERIK block-skip.mpf TO FANUC MACRO B)
( Block skip / and /0../9 at the start of a block)
G00 X0.
/ G01 X10. F100.
/ Y10.
/3 N40 Z-1.
M30
%
