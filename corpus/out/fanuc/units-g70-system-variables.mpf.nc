%
O0001 (UNITS-G70-SYSTEM-VARIABLES)
(NCTRANS: SINUMERIK units-g70-system-variables.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
( Inch dimensions in a metric program: under G70 the position variables read mm [the)
( basic system], under G700 inch [828D FM G2, 7.3].)
N10 G17 G90 G21 G00 X10. Y20. Z5.
N20 G20 G01 X1. F[200./25.4]
N30
N40 #501=#5041*25.4
N50 G00 Y[#501/25.4]
N60 G20 G01 X2. F10.
N70
N80 #502=#5041
N90 G00 Y#502
N100 G20
N110 #5221=5./25.4
N120 G54 G00 X0.
N130 G21 G00 Y#501
N140 M30
%
