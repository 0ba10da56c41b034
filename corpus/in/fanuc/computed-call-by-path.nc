%
O0180 (COMPUTED CALL BY PATH)
(The program number depends on the path: O0181 for a face pass, O0182 for a contour.)
#11=181
IF [#5041 GT 0] THEN #11=182
G90 G0 X0 Y0
M98 P#11
(A macro chosen the same way, with its argument.)
#12=9183
IF [#5042 GT 0] THEN #12=9184
G65 P#12 A6.
G0 X0 Y0
M30
O0181
G1 X20. F300.
M99
O0182
G1 Y20. F300.
M99
O9183
G1 X#1 F300.
M99
O9184
G1 Y#1 F300.
M99
%
