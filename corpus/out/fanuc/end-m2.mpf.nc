%
O0001 (END-M2)
(NCTRANS: SINUMERIK end-m2.mpf TO FANUC MACRO B)
( M2 and M02 end the program like M30)
G00 X0.
M02
%
