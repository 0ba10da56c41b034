%
O0001 (OPERATORS-CONCAT)
(NCTRANS: SINUMERIK operators-concat.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
( String concatenation << in a message)
#501=3.
(MSG: "Layer "<<R1<<" done")
M30
%
