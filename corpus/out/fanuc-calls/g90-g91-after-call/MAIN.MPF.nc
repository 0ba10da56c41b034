%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
( The subprogram returns in G91 [no SAVE]: AC[] after the call must switch back to G91)
G90 G00 X0. Y0.
G65 P9000
G90 X10.
G91
X2.
G91 X3.
G90
M30
O9000 (STEP_INC)
G91 G01 X1. F100.
M99
%
