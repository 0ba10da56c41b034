%
O0001 (ALARM-SETAL)
(NCTRANS: SINUMERIK alarm-setal.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
( SETAL raises a user alarm when a check fails)
#501=-1.
IF [#501 GE 0.] GOTO 1000
#3000=0(SETAL 65000)
N1000 M30 (OK:)
%
