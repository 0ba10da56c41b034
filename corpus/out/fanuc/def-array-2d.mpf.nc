%
O0001 (DEF-ARRAY-2D)
(NCTRANS: SINUMERIK def-array-2d.mpf TO FANUC MACRO B)
(NCTRANS: TAB_A[…] [30 elements] = #100)
(NCTRANS: TAB_B[…] [6 elements] = #130)
(NCTRANS: TAB_C[…] [4 elements] = #136)
( Two-dimensional arrays: SET with omitted entries, REP fill, element assignment)
#100=0.
#101=0.
#102=0.
#103=9.
#104=0.
#105=0.
#106=0.
#107=0.
#108=0.
#109=0.
#110=0.
#111=0.
#112=0.
#113=0.
#114=0.
#115=0.
#116=0.
#117=0.
#118=0.
#119=0.
#120=0.
#121=0.
#122=0.
#123=0.
#124=0.
#125=0.
#126=0.
#127=0.
#128=0.
#129=0.
#130=1.
#131=1.
#132=1.
#133=1.
#134=1.
#135=1.
#136=7.
#137=7.
#138=7.
#139=7.
#105=#100+#135
G01 X#105 F100.
M30
%
