%
O0001 (ROTARY-4TH-AXIS-WRAP)
(NCTRANS: SINUMERIK rotary-4th-axis-wrap.mpf TO FANUC MACRO B)
( Wrap milling on a 4th axis: a spiral groove on a 50 mm roller)
( The path feed runs along X and A [FGROUP]: the programmed F is the speed along)
( the combined path, a degree counted as a millimetre [FGREF default])
N10 G90 G94 G17 G21
N20 T4 M06
G43 H4
N30 S3500 M03
N40 G54 G00 X0. Y0. A0.
N50 Z30.
N60 Z26.
N70 G01 Z24.5 F100.
N80
N90 G01 X40. A360. F300. ( one turn of the spiral)
N100 A450. ( run-out on A alone, degrees/min)
N110 G01 X0. A0. F600.
N120
N130 G01 Z26. F800. ( the default group again: X, Y, Z only)
N140 G00 Z30.
N150 M05
N160 M30
%
