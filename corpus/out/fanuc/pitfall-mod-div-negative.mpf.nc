%
O0001 (PITFALL-MOD-DIV-NEGATIVE)
(NCTRANS: SINUMERIK pitfall-mod-div-negative.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
(NCTRANS: R3 = #503)
(NCTRANS: R4 = #504)
(NCTRANS: R5 = #505)
(NCTRANS: R6 = #506)
(NCTRANS: TEMPORARIES #1 #2 #3)
( MOD keeps the sign of the dividend, DIV truncates toward zero  POT squares)
#501=-7.-FIX[-7./3.]*3.
#502=FIX[-7./2.]
#503=-3.*[-3.]
G01 X#501 Y#502 Z#503 F100.
#1=#501
IF [#502 LT #1] THEN #1=#502
#504=#1
#2=#501
IF [#502 GT #2] THEN #2=#502
#505=#2
#3=#503
IF [#3 LT 0.] THEN #3=0.
IF [#3 GT 5.] THEN #3=5.
#506=#3
G01 X#504 Y#505 Z#506
M30
%
