%
O0001 (PITFALL-FEED-G700-G71)
(NCTRANS: SINUMERIK pitfall-feed-g700-g71.mpf TO FANUC MACRO B)
( G700/G710 set lengths and feeds  G70/G71 set lengths and read F in the basic system [mm/min])
G20
G01 X1. Y1. F20.
G21
G01 X10. F500.
G20 G01 X1. F[10./25.4]
G21
G01 X2. F100.
G20
G01 X1. F[254./25.4]
G20
G21 G01 X5. F2.
M30
%
