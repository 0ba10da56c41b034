%
O0001 (MESSAGE-MSG)
(NCTRANS: SINUMERIK message-msg.mpf TO FANUC MACRO B)
( MSG shows a text, MSG[] clears it)
#3006=1(Change tool to T2)
M30
%
