%
O0001 (PITFALL-INCH-G70)
(NCTRANS: SINUMERIK pitfall-inch-g70.mpf TO FANUC MACRO B)
( Pitfall 30: G70 changes lengths to inch but not feeds  FANUC G20 changes both)
G20
G01 X1. F[254./25.4]
G21
G01 X10.
M30
%
