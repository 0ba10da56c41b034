%
O0001 (PITFALL-BLOCK-ORDER)
(NCTRANS: SINUMERIK pitfall-block-order.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
(NCTRANS: TEMPORARIES #1)
( Pitfall 26: several statements in one block: each value is taken at its place in the text, the motion runs last)
#501=1.
#1=#501
#501=5.
#502=#501*2.
G01 X#1 F100.
G01 Y#502
M30
%
