%
O0001 (MULTIPLE-ASSIGN-ONE-BLOCK)
(NCTRANS: SINUMERIK multiple-assign-one-block.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
(NCTRANS: R3 = #503)
(NCTRANS: R4 = #504)
(NCTRANS: TEMPORARIES #1)
( Several assignments and words in one block)
#501=0.
#504=1.
#1=#501
#502=5.
G01 X#1 F100.
#503=#502
Y#503
M30
%
