%
O0001 (PRECEDENCE-ARITHMETIC)
(NCTRANS: SINUMERIK precedence-arithmetic.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
(NCTRANS: R3 = #503)
(NCTRANS: R4 = #504)
(NCTRANS: R5 = #505)
(NCTRANS: R6 = #506)
( Precedence of * / DIV MOD over + -, left to right, parentheses override)
#501=2.+3.*4.
#502=10.-6./2.
#503=2.+FIX[6./4.]
#504=100.-10.*2.+5.
#505=[2.+3.]*4.
#506=8./4./2.
M30
%
