%
O0001 (UNITS-G70-AFTER-G700-FEED)
(NCTRANS: SINUMERIK units-g70-after-g700-feed.mpf TO FANUC MACRO B)
( Inch drawing feature in a metric shop program [basic system metric, MD10240=1].)
( G700 reads F in inch/min  G70/G71 read F in the basic system [mm/min] again, and the)
( feed already in force stays physically the same across each switch.)
N10 G17 G90 G21 G00 X0. Y0. Z5.
N20 G20 G01 Z-0.05 F20.
N30 G01 X1.5
N40 G20 G01 Y1. F[300./25.4]
N50 X0.
N60 G20 G01 Y0. F15.
N70 G21 G01 X10.
N80 G01 Y10. F250.
N90 G00 Z5.
N100 M30
%
