%
O0001 (SIGNALS-DOOR-VICE-CHECK)
(NCTRANS: SINUMERIK signals-door-vice-check.mpf TO FANUC MACRO B)
(nctrans: set #1000=1 #1001=0)
( face the part only with the door shut and the vice clamped)
N10 G17 G90 G21 G54
( wait for the door-closed switch [NCK input 1])
N20 WHILE [#1000 EQ 0.] DO1
N30 G04 X0.5
N40 END1
( vice clamped [PLC byte 17]? else stop and tell the operator)
N50 IF [#1001 EQ 1.] GOTO 1000
N60 #3006=1(CLAMP VICE THEN START)
N80
N1000 (CLAMPED:)
N90 S2500 M03
N100 G00 X-5. Y0. Z5.
N110 G01 Z-0.5 F300.
N120 X55.
N130 Y20.
N140 X-5.
N150 G00 Z50.
N160 M05
N170 M30
%
