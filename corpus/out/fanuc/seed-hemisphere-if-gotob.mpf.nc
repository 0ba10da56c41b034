%
O0001 (SEED-HEMISPHERE-IF-GOTOB)
(NCTRANS: SINUMERIK seed-hemisphere-if-gotob.mpf TO FANUC MACRO B)
(NCTRANS: R0 = #500)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
( Seed 000 6.1: hemisphere R30 milled with a ball nose D8, loop by IF ... GOTOB)
T1 (直径 8 毫米球头立铣刀)
M06
S5000 M03
#500=0.
#501=30. (球半径)
#502=4. (球刀半径)
G54 G90 G94 G17 G00 Z100.
X[#501+#502+5.] Y0.
N11 G01 Z[[#501+#502]*SIN[#500]-#502-#501] F4000.
G01 X[[#501+#502]*COS[#500]] F2000.
G03 I[-[#501+#502]*COS[#500]]
#500=#500+1.
IF [#500 LT 90.] GOTO 11
G00 Z30.
M30
%
