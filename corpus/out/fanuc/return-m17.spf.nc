%
O0001 (LIFT)
(NCTRANS: SINUMERIK return-m17.spf TO FANUC MACRO B)
( M17 returns from a subprogram)
G00 Z50.
M99
%
