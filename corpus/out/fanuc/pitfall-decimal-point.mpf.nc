%
O0001 (PITFALL-DECIMAL-POINT)
(NCTRANS: SINUMERIK pitfall-decimal-point.mpf TO FANUC MACRO B)
( Pitfall 10 and 11: Siemens X1 is 1 mm [FANUC X1 would be 0.001 mm]  M/S stay integers)
S1200 M03
G01 X1. Y2. Z-3. F250.
G04 X1.5
M05
M30
%
