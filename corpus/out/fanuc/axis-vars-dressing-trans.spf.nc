%
O0001 (D_TRIANGLE_SHIFT)
(NCTRANS: SINUMERIK axis-vars-dressing-trans.spf TO FANUC MACRO B)
(NCTRANS: WB = #1)
(NCTRANS: VB = #2)
(a dressing shape as grinding libraries write it: the roller's axes named once, then moved by name)
(horizontal and vertical axis)
(horizontal)
(vertical)
G18 G90
#1=4.5
#2=1.2
G52 X#2 Y0. Z#1
G01 Z0. X3. F300.
G03 Z2. X1. R2.
G01 Z6.
G52 X0. Y0. Z0.
M99
%
