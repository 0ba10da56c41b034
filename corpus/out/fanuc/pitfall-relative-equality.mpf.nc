%
O0001 (PITFALL-RELATIVE-EQUALITY)
(NCTRANS: SINUMERIK pitfall-relative-equality.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
( Pitfall 7: Siemens compares with a 1e-12 relative tolerance  ten times 0.1 equals 1)
#501=0.
#502=0.
WHILE [ABS[#501-1.] GT [ABS[#501]+1.+ABS[ABS[#501]-1.]]*0.0000005*0.000001] DO1
#501=#501+0.1
#502=#502+1.
IF [#502 GT 20.] GOTO 1000
END1
N1000 G01 X#502 F100. (OUT:)
M30
%
