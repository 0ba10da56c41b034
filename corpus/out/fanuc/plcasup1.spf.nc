%
O0001 (PLCASUP1)
(NCTRANS: SINUMERIK plcasup1.spf TO FANUC MACRO B)
( initial angle of the headstock)
G00 X5.
M99
%
