%
O0001 (R-PARAM-INDIRECT)
(NCTRANS: SINUMERIK r-param-indirect.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R[i] [all R, #500+i] = #500)
( Indirect R parameters R[expr])
#501=5.
#[#501+1.+500.]=12.
#[2.*3.+1.+500.]=#[6.+500.]/2.
G01 X#[7.+500.] F100.
M30
%
