%
O0001 (GOTO-BACKWARD-NUMBER)
(NCTRANS: SINUMERIK goto-backward-number.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
( GOTOB to a block number, counted loop)
#501=0.
N10 G91 G01 X1. F100.
#501=#501+1.
IF [#501 LT 3.] GOTO 10
G90
M30
%
