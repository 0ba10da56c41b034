%
O0001 (PART_1)
(NCTRANS: SINUMERIK header-mpf.mpf TO FANUC MACRO B)
($PATH=/_N_MPF_DIR)
( Punch-tape header of a main program gives the name PART_1)
G00 X0.
M30
%
