%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
(NCTRANS: SIDE = #100)
( Edge finishing: the operation is chosen once at the top by its program name)
#100=40.
G17 G90 G54
T1 M06
G43 H1
S3000 M03
G00 X[-#100/2.-5.] Y[-#100/2.] Z5.
G01 Z-1. F300.
G65 P9000
G00 Z5.
G65 P9000
G00 Z50. M05
M30
O9000 (DEBUR_EDGE)
( One lap round the square at the depth the caller left)
G91 G01 X45. F600.
Y40.
X-45.
Y-40.
G90
M99
%
