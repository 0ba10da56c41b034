%
O0001 (CASE-INSENSITIVE)
(NCTRANS: SINUMERIK case-insensitive.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: DEPTH = #100)
( Keywords and names in lower case are the same as upper case)
#100=1.
#501=0.
WHILE [#501 LT 2.] DO1
G01 X[#501*#100] F100.
#501=#501+1.
END1
IF [#100 GT 0.] GOTO 1000
N1000 M30 (DONE:)
%
