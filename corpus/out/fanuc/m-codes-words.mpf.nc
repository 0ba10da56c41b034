%
O0001 (M-CODES-WORDS)
(NCTRANS: SINUMERIK m-codes-words.mpf TO FANUC MACRO B)
( M codes other than M2/M17/M30 stay address words)
S1000 M03
M08
M05 M09
M30
%
