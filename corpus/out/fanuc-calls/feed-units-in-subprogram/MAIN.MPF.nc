%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
( A subprogram that sets its lengths with G71/G70 only: its feeds stay in the unit of)
( whichever program calls it [metric here, inch after G700].)
G21 G90 G17 G00 X0. Y0. Z5.
G65 P9000
G20
G65 P9000
G21
G01 X5. F100.
M30
O9000 (SLOT_MM)
(NCTRANS: TEMPORARIES #1)
#1=[21.-#4006]*24.4+1.
( Lengths in mm from here on  F is still in the caller's feed unit)
G21 G01 X10. F[500.*#1]
Y20.
G20 G01 X1. F[20./[25.4/#1]]
M99
%
