%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
( Pair of pockets 30 x 20, the left one mirrored about X0)
( T2 8 mm end mill, edge D1)
( POCKET cuts the right pocket about X35 Y0, MIRROR X0 mirrors it to the left:)
( CHR and RND follow the mirrored contour, the roundings turn the other way)
N10 G17 G40 G90 G21
N20 T2 M06
N30 G43 H2
N40 G54 G00 X35. Y0. S4000 M03
N50 Z50. M08
N60 G65 P9000
N70 G50.1 X0. Y0. Z0.
G52 X0. Y0. Z0.
G51.1 X0.
N80 G65 P9000
G50.1 X0. Y0. Z0.
N90 G52 X0. Y0. Z0.
N100 G00 Z50. M09
N110 M05
N120 M30
O9000 (POCKET)
( Finish pass, the tool centre 4 mm inside the walls: CHR = leg from the corner, RND = radius)
G00 X35. Y0.
Z2.
G01 Z-3. F200.
Y-6. F500.
X46. ,C2.
Y6. ,R3.
X24. ,C2.
Y-6. ,R3.
X35.
G00 Z2.
M99
%
