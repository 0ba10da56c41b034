%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
( Two pockets on one fixture plate, each under its own TRANS. The step-over passes are)
( incremental, in the subprogram, after it has positioned every axis absolutely in the)
( new frame [an incremental move right after the TRANS would also travel the shift on)
( the Sinumerik, MD42440, and not on the FANUC])
G17 G90 G54 G21
T1 M06
G43 H1
S3000 M03
G00 X0. Y0. Z100.
G52 X40. Y30. Z0.
G65 P9000 A4. B3.5
G52 X120. Y30. Z0.
G65 P9000 A4. B3.5
G52 X0. Y0. Z0.
G00 Z100.
G00 X0. Y0.
M30
O9000 (POCKET_STEPS)
(NCTRANS: PASSES [parameter, letter A] = #1)
(NCTRANS: STEP [parameter, letter B] = #2)
(NCTRANS: PASS = #3)
#3=0.
( the pocket corner is the frame zero: position absolute first, then step over)
G90 G00 X0. Y0. Z5.
G01 Z-3. F150.
#3=1.
WHILE [#3 LE #1] DO1
G91 G01 X30. F500.
G01 Y#2
G01 X-30.
G01 Y#2
#3=#3+1.
END1
G90 G00 Z5.
M99
%
