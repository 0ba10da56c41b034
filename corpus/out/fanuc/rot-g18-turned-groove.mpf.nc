%
O0001 (ROT-G18-TURNED-GROOVE)
(NCTRANS: SINUMERIK rot-g18-turned-groove.mpf TO FANUC MACRO B)
( A groove in the ZX plane [G18] turned by 30 degrees about Z10 X20:)
( the frame sequence the FANUC translation writes for G68 Z10 X20 R30)
G18 G90 G54 G00 X0. Y0. Z0.
G68 Z10. X20. R30.
G00 X40. Z10.
G01 X30. F100.
Z30.
G02 X20. Z40. R10.
G01 X40.
G69
G00 X60. Z0.
M30
%
