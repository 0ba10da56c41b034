%
O0001 (LINE-ENDINGS-CRLF)
(NCTRANS: SINUMERIK line-endings-crlf.mpf TO FANUC MACRO B)
( CRLF line ends)
G00 X0.
G01 X10. F100.
M30
%
