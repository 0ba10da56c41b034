%
O0001 (AXIS-INDIRECT-AX)
(NCTRANS: SINUMERIK axis-indirect-ax.mpf TO FANUC MACRO B)
( Grinder with the infeed axis set up by name: AX[...] moves the axis an AXIS variable names)
G90 G01 X20. Z5. F300.
G91 X-0.5
G90
G52 X0. Y0. Z2.
G01 Z0.
G52 X0. Y0. Z0.
G00 X50.
M30
%
