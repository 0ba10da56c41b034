%
O0001 (DEF-SEVERAL-NAMES)
(NCTRANS: SINUMERIK def-several-names.mpf TO FANUC MACRO B)
(NCTRANS: START_X = #100)
(NCTRANS: START_Y = #101)
(NCTRANS: STEP_Y = #102)
(NCTRANS: I_ROW = #103)
(NCTRANS: N_ROWS = #104)
( Several names in one DEF line, with and without initial values)
#100=10.
#101=0.
#102=2.5
#103=0.
#104=4.
G00 X#100 Y#101
M30
%
