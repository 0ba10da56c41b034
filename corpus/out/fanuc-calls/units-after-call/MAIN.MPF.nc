%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
( The subprogram leaves the lengths in inch [G70]: the feeds stay metric here)
G21 G90 G00 X0. Y0.
G65 P9000
G01 X5. F[100./25.4]
G21
G01 X20. F300.
M30
O9000 (TO_INCH)
G20
G01 X1. F[25./25.4]
M99
%
