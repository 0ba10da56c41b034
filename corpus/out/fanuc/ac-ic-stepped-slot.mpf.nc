%
O0001 (AC-IC-STEPPED-SLOT)
(NCTRANS: SINUMERIK ac-ic-stepped-slot.mpf TO FANUC MACRO B)
( Stepped slot: each pass goes down incrementally while X is given absolute [AC/IC in one block])
G17 G90 G54 G21
S3000 M03
G00 X0. Y0. Z5.
G91 G01 Z-7. F150. ( to the top of the slot)
G90
G01 X40. Z[#5003-2.] F300. ( first step, ramping down)
X0. Z[#5003-2.] ( second step, back)
G91 X40. Y-#5002 ( finishing pass, the incremental block holds Y on the slot line)
G90 G00 Z5.
M05
M30
%
