%
O0001 (IF-GOTO)
(NCTRANS: SINUMERIK if-goto.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
( IF condition GOTOF target in one block [no ENDIF])
#501=5.
IF [#501 GT 3.] GOTO 1000
G00 X1.
N1000 G00 X2. (BIG:)
M30
%
