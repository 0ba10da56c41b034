%
O0001 (PITFALL-MSG-M0-SETAL)
(NCTRANS: SINUMERIK pitfall-msg-m0-setal.mpf TO FANUC MACRO B)
( Pitfall 24: MSG followed by M0 is a stop with a message [#3006]  SETAL is a user alarm [#3000])
G01 X1. F100.
#3006=1(CHECK PART)
G01 X2.
#3000=10(SETAL 65010)
M30
%
