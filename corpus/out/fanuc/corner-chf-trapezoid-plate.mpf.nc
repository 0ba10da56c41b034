%
O0001 (CORNER-CHF-TRAPEZOID-PLATE)
(NCTRANS: SINUMERIK corner-chf-trapezoid-plate.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
( Trapezoid plate 80 x 48, sloping sides 7 in 24 [73.74 deg to the base])
( every edge broken with a 6 mm chamfer, given by its length [CHF])
( T1 10 mm end mill, edge D1)
N10 G17 G40 G90 G21
N20 T1 M06
N30 G43 H1
N40 G54 G00 X-15. Y-15. S3500 M03
N50 Z50. M08
N60 Z2.
#501=-4. ( depth)
N70 G01 Z#501 F250.
( finish pass left of the contour, counter-clockwise)
N80 G41 D1 X-10. Y0. F450.
N90 X80. ,C5.
N100 X66. Y48. ,C3.75
N110 X14. ,C3.75
N120 X0. Y0. ,C5.
N130 X20.
N140 G40 X20. Y-15.
N150 G00 Z50. M09
N160 M05
N170 M30
%
