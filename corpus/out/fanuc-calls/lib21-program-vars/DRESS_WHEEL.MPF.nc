%
O0001 (DRESS_WHEEL)
(NCTRANS: SINUMERIK DRESS_WHEEL.MPF TO FANUC MACRO B)
(NCTRANS: R10 = #510)
(NCTRANS: SHAPE [global user data] = #600)
( Wheel dressing: the profile is chosen from the wheel type, then dressed)
#510=2. ( wheel type: 1 triangle, 2 trapezoid, other none)
G17 G90 G54
T1 M06
G43 H1
G65 P9001
G00 X0. Y0. Z10.
G65 P9000
G00 Z50.
M30
O9000 (DRESS_SHAPE)
IF [#600 NE 0.] GOTO 1000
G00 Z20. ( no profile: stay clear)
M99
N1000
G01 Z0. F100.
G65 P#600 ( run the profile program SHAPE names)
IF [#600 EQ 9003.] GOTO 1001
G01 X0. F300. ( back along the flank)
N1001
G00 Z10.
M99
O9001 (PAR_INIT)
( the profile program of the wheel type)
IF [ABS[#510-1.] GT [ABS[#510]+1.+ABS[ABS[#510]-1.]]*0.0000005*0.000001] GOTO 1000
#600=9003.
GOTO 1003
N1000
IF [ABS[#510-2.] GT [ABS[#510]+2.+ABS[ABS[#510]-2.]]*0.0000005*0.000001] GOTO 1001
#600=9002.
GOTO 1002
N1001
#600=0.
N1002
N1003
M99
O9002 (PROFILE_TRAP)
G01 X3. Y2. F200.
G01 X7. Y2.
G01 X10. Y0.
M99
O9003 (PROFILE_TRI)
G01 X5. Y2. F200.
G01 X10. Y0.
M99
%
