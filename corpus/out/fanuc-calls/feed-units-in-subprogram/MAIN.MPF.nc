%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
( A subprogram that sets its units with G71/G70 only: its F words are in the basic)
( system [mm/min], whether the caller runs in G710 or G700.)
G21 G90 G17 G00 X0. Y0. Z5.
G65 P9000
G20
G65 P9000
G21
G01 X5. F100.
M30
O9000 (SLOT_MM)
( Lengths in mm from here on  F in mm/min [the basic system] whatever the caller's unit)
G21 G01 X10. F500.
Y20.
G20 G01 X1. F[20./25.4]
M99
%
