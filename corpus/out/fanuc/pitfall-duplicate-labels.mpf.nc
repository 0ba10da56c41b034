%
O0001 (PITFALL-DUPLICATE-LABELS)
(NCTRANS: SINUMERIK pitfall-duplicate-labels.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
( Pitfall 14: duplicate N numbers  GOTOB finds the one above, GOTOF the one below)
#501=0.
N1000 #501=#501+1.
G01 X#501 F100.
IF [#501 LT 2.] GOTO 1000
GOTO 1001
G01 Y99.
N1001 G01 Y#501
M30
%
