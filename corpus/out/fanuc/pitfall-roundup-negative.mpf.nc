%
O0001 (PITFALL-ROUNDUP-NEGATIVE)
(NCTRANS: SINUMERIK pitfall-roundup-negative.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
(NCTRANS: TEMPORARIES #1 #2)
( Pitfall 1: ROUNDUP is a ceiling  FANUC FUP rounds away from zero [FUP[-1.2] = -2])
#501=-1.2
#502=3.1
#1=FIX[#501]
IF [#501 GT #1] THEN #1=#1+1.
#2=FIX[#502]
IF [#502 GT #2] THEN #2=#2+1.
G01 X#1 Y#2 Z[FIX[-3.7]] F100.
M30
%
