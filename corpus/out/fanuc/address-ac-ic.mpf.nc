%
O0001 (ADDRESS-AC-IC)
(NCTRANS: SINUMERIK address-ac-ic.mpf TO FANUC MACRO B)
( Absolute and incremental values for one word: AC[..] and IC[..])
G90 G00 X0. Y0.
G01 X[#5001+5.] Y10. F100.
G90 X0.
G91
M30
%
