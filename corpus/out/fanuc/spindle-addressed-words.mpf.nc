%
O0001 (SPINDLE-ADDRESSED-WORDS)
(NCTRANS: SINUMERIK spindle-addressed-words.mpf TO FANUC MACRO B)
( Grinding wheel on the master spindle, addressed by its number as grinding cycles write it)
G00 X50. Z5.
M03 S1800
G01 X40. F300.
G01 Z-20. F150.
M05
G00 X60.
M30
%
