%
O0001 (GOTO-DUPLICATE-NUMBERS)
(NCTRANS: SINUMERIK goto-duplicate-numbers.mpf TO FANUC MACRO B)
( Duplicate block numbers are allowed  GOTOF finds the next one forward)
N100 G00 X1.
GOTO 1000
N1000 G00 X5.
M30
%
