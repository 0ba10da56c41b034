%
O0001 (CONSTANT-HEX-BIN-BOOL)
(NCTRANS: SINUMERIK constant-hex-bin-bool.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
(NCTRANS: R3 = #503)
(NCTRANS: R4 = #504)
( Hex and binary constants, TRUE and FALSE)
#501=31.
#502=5.
#503=1.
#504=0.
M30
%
