%
O0001 (COMP-G41-G42-CONTOUR)
(NCTRANS: SINUMERIK comp-g41-g42-contour.mpf TO FANUC MACRO B)
( Outside contour with cutter radius compensation, left then right)
( T3 12 mm end mill, edge D1 [length and radius])
G17 G40 G90 G21
T3 M06
G43 H3
G54 G00 X-20. Y-20. S3000 M03
Z50. M08
Z2.
G01 Z-5. F300.
( climb: left of the contour, approach on a line)
G41 D3 X0. Y-10. F400.
Y40.
G02 X10. Y50. R10.
G01 X60.
G02 X70. Y40. R10.
G01 Y0.
G03 X60. Y-10. R10.
G01 X-10.
G40 X-20. Y-20.
G00 Z2.
( conventional: right of the contour, the other way round)
G01 Z-5. F300.
G42 D3 X-10. Y0. F400.
X60.
G02 X70. Y-10. R10.
G01 Y40.
X10.
G03 X0. Y30. R10.
G01 Y-20.
G40 X-20. Y-20.
G00 Z50. M09
M05
M30
%
