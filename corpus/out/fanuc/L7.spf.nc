%
O0001 (L7)
(NCTRANS: SINUMERIK L7.spf TO FANUC MACRO B)
( L7 without a PROC line: found by its file name)
G01 X7. F300.
M99
%
