%
O0001 (MAIN)
(NCTRANS: SINUMERIK MAIN.MPF TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R10 = #510)
(NCTRANS: IX = #100)
(NCTRANS: DEPTHS[…] [3 elements] = #101)
(NCTRANS: TOTAL = #104)
(NCTRANS: PASSES = #105)
( Depth passes counted and summed through VAR [by-reference] parameters)
#100=0.
#101=0.
#102=0.
#103=0.
G21 G90 G17 G00 X0. Y0. Z5.
#104=0.
#105=0.
#510=1.5
( the subprogram adds to the caller's counter and sum)
G65 P9000 A104. B2.5 C105.
G65 P9000 A104. B#510 C105.
G01 X#104 Y#105 F200.
( passed on to a nested call [VAR to VAR], twice)
G65 P9003 A104. B105.
G01 X#104 Y#105
( an array element with a computed index, and a whole array)
#100=0.
WHILE [#100 LE 2.] DO1
G65 P9000 A[#100+101.] B[0.5*[#100+1.]] C105.
#100=#100+1.
END1
G65 P9002 A101. B104.
G01 X#104 Y#103 Z#105
G01 X#102 Y#101
( the same R parameter for two VAR parameters, which the callee also reads directly)
#501=3.
G65 P9001 A501. B501.
G00 X#501 Z5.
M30
O9000 (ADD_PASS)
(NCTRANS: SUM [VAR parameter, letter A: the number of the caller's variable] = #1)
(NCTRANS: STEP [parameter, letter B] = #2)
(NCTRANS: COUNT [VAR parameter, letter C: the number of the caller's variable] = #3)
( one pass deeper: read and written several times)
#[#1]=#[#1]+#2
#[#3]=#[#3]+1.
G01 Z-#[#1] F100.
IF [#[#1]-3. GT [ABS[#[#1]]+3.+ABS[ABS[#[#1]]-3.]]*0.0000005*0.000001] THEN #[#1]=#[#1]-0.25
G00 Z[5.-#[#3]]
M99
O9001 (ALIASED)
(NCTRANS: FIRST [VAR parameter, letter A: the number of the caller's variable] = #1)
(NCTRANS: SECOND [VAR parameter, letter B: the number of the caller's variable] = #2)
( FIRST and SECOND are both R1: a write through one is read through the other)
#[#1]=#[#1]+1.
#[#2]=#[#2]*2.
G01 X#[#1] Y#[#2] Z#501 F150.
#501=#501-1.
G01 X#[#1]
M99
O9002 (SUM3)
(NCTRANS: VALS [VAR parameter, letter A: the number of the caller's variable] = #1)
(NCTRANS: RESULT [VAR parameter, letter B: the number of the caller's variable] = #2)
#[#2]=#[#1]+#[#1+1.]+#[#1+2.]
#[#1+1.]=#[#1+1.]*10.
M99
O9003 (TWO_PASSES)
(NCTRANS: SUM [VAR parameter, letter A: the number of the caller's variable] = #1)
(NCTRANS: COUNT [VAR parameter, letter B: the number of the caller's variable] = #2)
G65 P9000 A#1 B1. C#2
G65 P9000 A#1 B[#[#2]*0.1] C#2
G01 X[#[#1]*2.] F300.
M99
%
