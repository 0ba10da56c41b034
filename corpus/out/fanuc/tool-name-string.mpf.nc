%
O0001 (TOOL-NAME-STRING)
(NCTRANS: SINUMERIK tool-name-string.mpf TO FANUC MACRO B)
( Tool selected by name: the string keeps its case)
T1 M06
T2
M06
M30
%
