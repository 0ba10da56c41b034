%
O0001 (REPEAT-SECTION-GROOVE-P3)
(NCTRANS: SINUMERIK repeat-section-groove-p3.mpf TO FANUC MACRO B)
(NCTRANS: TEMPORARIES #1)
( FOUR GROOVES 8 MM APART ON A SHAFT: THE FIRST ONE IS PROGRAMMED, REPEAT CUTS THREE MORE)
G18 G90 G54 G21
T3 M06
G43 H3
G00 X42. Z2. S800 M03
G00 Z-10.
( plunge to the groove floor)
G01 X30. F30. (GROOVE:)
G04 X0.5 ( dwell to clean the floor)
G00 X42.
G91 G00 Z-8. ( next groove position)
G90
(REPEAT SECTION FROM GROOVE, 3 TIMES: three more grooves)
#1=1.
WHILE [#1 LE 3.] DO1
G01 X30. F30.
G04 X0.5 ( dwell to clean the floor)
G00 X42.
G91 G00 Z-8. ( next groove position)
G90
#1=#1+1.
END1
G00 X100. Z50. M05
M30
%
