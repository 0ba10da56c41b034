%
O0001 (CONTOUR)
(NCTRANS: SINUMERIK subprogram-header.spf TO FANUC MACRO B)
(NCTRANS: LENGTH [parameter, letter A] = #1)
(NCTRANS: WIDTH [parameter, letter B] = #2)
(NCTRANS: DEPTH [parameter, letter C] = #3)
($PATH=/_N_SPF_DIR)
( Punch-tape header names the subprogram  M17 returns)
G91 G01 X#1 F100.
Y#2
Z-#3
G90
M99
%
