%
O0001 (PITFALL-ROUND-IN-ADDRESS)
(NCTRANS: SINUMERIK pitfall-round-in-address.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: TEMPORARIES #1 #2)
( Pitfall 3: ROUND in a FANUC address rounds to the increment, not to an integer)
#501=2.6
#1=ROUND[#501]
#2=ROUND[#501]
G01 X#1 Y[#2+0.25] F100.
M30
%
