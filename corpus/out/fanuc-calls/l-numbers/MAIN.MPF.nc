%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
(NCTRANS: R1 = #501)
( Two DIN subprograms called by a name built at run time: L10, then L20.)
#501=10.
G00 X0. Y0.
G65 P#501
#501=#501+10.
G65 P#501
G00 X0. Y0.
M30
O0010 (L10)
( Side A: a move in X.)
G01 X40. F500.
M99
O0020 (L20)
(NCTRANS: TEMPORARIES #1)
( Side B: a move in Y, relative to where side A ended.)
#1=#4003
G91 G01 Y25. F500.
G#1
M99
%
