%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
(dressing before grinding: the axes come from the set-up's global user data)
G90 G00 X50. Z10.
G65 P9000 A0.02 B3.
G01 X20. F500.
M30
O9000 (D_DRESS)
(NCTRANS: DEPTH [parameter, letter A] = #1)
(NCTRANS: PASSES [parameter, letter B] = #2)
(NCTRANS: PASS = #3)
(dress the wheel: the roller in the set-up's horizontal and vertical axes)
(horizontal and vertical axis)
(horizontal)
(vertical)
G90 G00 X5. Z-2.
#3=0.
WHILE [#3 LT #2] DO1
#3=#3+1.
G01 X[-#3*#1] F200.
G01 Z40. F800.
G00 X5.
G00 Z-2.
END1
M99
%
