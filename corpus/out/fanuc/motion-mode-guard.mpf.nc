%
O0001 (MOTION-MODE-GUARD)
(NCTRANS: SINUMERIK motion-mode-guard.mpf TO FANUC MACRO B)
(NCTRANS: R20 = #520)
( A finishing pass that checks the motion mode it relies on before it cuts:)
( the active G function of group 1 [$P_GG[1]: G0..G3 are 1..4] must be G1.)
G90 G21 G17 G54
T3 M06
G43 H3
G00 X-5. Y0. S2400 M03
G00 Z2.
G01 Z-1.5 F300.
#520=2. ( 2 after the G1 plunge)
IF [ABS[#520-2.] GT [ABS[#520]+2.+ABS[ABS[#520]-2.]]*0.0000005*0.000001] GOTO 1000
G01 X40. F600.
G01 Y25.
G01 X-5.
G00 Z50.
M05
M30
N1000 (NOT_LINEAR:)
#3006=1(MOTION MODE IS NOT G1)
M30
%
