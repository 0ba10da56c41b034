%
O0001 (SEED-GOTO-NUMBERS)
(NCTRANS: SINUMERIK seed-goto-numbers.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
( Seed 000 5.1: unconditional jumps GOTOF N10 and GOTOB N1 between block numbers)
#501=0.
N1 G00 X#501
#501=#501+10.
IF [#501 GE 30.] GOTO 10
GOTO 1
N10 G00 Z50.
M30
%
