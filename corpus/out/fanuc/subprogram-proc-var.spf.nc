%
O0001 (POCKET)
(NCTRANS: SINUMERIK subprogram-proc-var.spf TO FANUC MACRO B)
(NCTRANS: LENGTH [parameter, letter A] = #1)
(NCTRANS: DEPTH_DONE [VAR parameter, letter B: the number of the caller's variable] = #2)
(NCTRANS: PASSES [parameter, letter C] = #3)
(NCTRANS: SIZES [VAR parameter, letter D: the number of the caller's variable] = #7)
(NCTRANS: TEMPORARIES #4 #5)
#4=#4001
#5=#4003
( PROC with value, reference [VAR] and array parameters, SAVE attribute)
G91 G01 X#1 F100.
#[#2]=#3*#[#7]
G90
G#4 G#5
M99
%
