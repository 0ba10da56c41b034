%
O0001 (MSG-PROGRESS-MESSAGES)
(NCTRANS: SINUMERIK msg-progress-messages.mpf TO FANUC MACRO B)
(NCTRANS: PASS = #100)
( Operator messages while the part runs: shown without stopping, except the inspection stop)
#100=0.
G21 G90 G17 G00 X0. Y0. Z5.
(MSG: ROUGHING)
#100=1.
WHILE [#100 LE 3.] DO1
(MSG: ROUGHING PASS)
G01 Z-#100 F150.
X40.
G00 Z5.
X0.
#100=#100+1.
END1
#3006=1(CHECK THE PART)
(MSG: FINISHING)
G01 Z-3.5 F80.
X40.
G00 Z5.
M30
%
