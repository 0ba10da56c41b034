%
O0001 (LABEL-DEFINITION)
(NCTRANS: SINUMERIK label-definition.mpf TO FANUC MACRO B)
( Jump labels NAME: at the start of a block, also after a block number)
G00 X0. (START:)
N20 G01 X20. F100. (MARKE1:)
Y5. (TR_789:)
M30
%
