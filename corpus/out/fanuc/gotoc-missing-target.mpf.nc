%
O0001 (GOTOC-MISSING-TARGET)
(NCTRANS: SINUMERIK gotoc-missing-target.mpf TO FANUC MACRO B)
( GOTOC to a label that does not exist continues with the next block)
G00 X0.
G00 X1.
M30
%
