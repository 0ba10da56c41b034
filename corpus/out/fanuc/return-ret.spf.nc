%
O0001 (SHIFT)
(NCTRANS: SINUMERIK return-ret.spf TO FANUC MACRO B)
( RET returns from a subprogram)
G91 G00 X5.
G90
M99
%
