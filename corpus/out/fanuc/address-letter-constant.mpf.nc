%
O0001 (ADDRESS-LETTER-CONSTANT)
(NCTRANS: SINUMERIK address-letter-constant.mpf TO FANUC MACRO B)
( Single-letter addresses with constants, also packed and lower case)
G00 X10. Y-2.5 Z0.5
G01 X10. Y20. F100.
X100. Y-1.
M30
%
