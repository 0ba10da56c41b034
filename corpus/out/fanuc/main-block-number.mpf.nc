%
O0001 (MAIN-BLOCK-NUMBER)
(NCTRANS: SINUMERIK main-block-number.mpf TO FANUC MACRO B)
( Main block number :10 marks a main block)
N10 G00 X0. Y0.
N20 G01 X5. F100.
N30 M30
%
