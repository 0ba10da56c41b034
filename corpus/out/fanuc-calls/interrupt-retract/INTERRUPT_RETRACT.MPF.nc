%
O0001 (INTERRUPT_RETRACT)
(NCTRANS: SINUMERIK INTERRUPT_RETRACT.MPF TO FANUC MACRO B)
( Face a plate in two passes  a tool-breakage sensor on fast input 1)
( retracts the spindle and stops for the operator.)
( nctrans: interrupt 1@3)
G21 G90 G17
T1
M06
G43 H1
S2400 M03
G00 X-5. Y0. Z5.
M96 P9000
G01 Z-0.5 F300.
G01 X105. F800.
G00 Z5.
( The sensor is not watched while the tool is out of the part.)
M97
G00 X-5. Y20.
M96 P9000
G01 Z-0.5 F300.
G01 X105. F800.
M97
G00 Z50.
M05
M30
O9000 (RETRACT_Z)
( Interrupt routine: lift clear and wait for the operator.)
G00 Z50.
M05
#3006=1(TOOL BROKEN - CHECK T1)
M99
%
