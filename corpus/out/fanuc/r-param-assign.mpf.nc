%
O0001 (R-PARAM-ASSIGN)
(NCTRANS: SINUMERIK r-param-assign.mpf TO FANUC MACRO B)
(NCTRANS: R0 = #500)
(NCTRANS: R10 = #510)
(NCTRANS: R299 = #799)
( R parameters R0..R299: assignment and use)
#500=1.5
#799=-2.
#510=#500*#799
G01 X#510 F100.
M30
%
