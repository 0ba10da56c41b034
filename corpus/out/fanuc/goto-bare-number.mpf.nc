%
O0001 (GOTO-BARE-NUMBER)
(NCTRANS: SINUMERIK goto-bare-number.mpf TO FANUC MACRO B)
( GOTOF with a bare number: block number 90)
N70 GOTO 90
N80 X999.
N90 G00 X0.
M30
%
