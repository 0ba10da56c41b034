%
O0001 (OPERATORS-ARITHMETIC)
(NCTRANS: SINUMERIK operators-arithmetic.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
(NCTRANS: R3 = #503)
(NCTRANS: R4 = #504)
(NCTRANS: R5 = #505)
( Arithmetic operators + - * / DIV MOD)
#501=7.+3.-2.
#502=7.*3./2.
#503=FIX[7./2.]
#504=7.-FIX[7./4.]*4.
#505=2.*[-3.]
M30
%
