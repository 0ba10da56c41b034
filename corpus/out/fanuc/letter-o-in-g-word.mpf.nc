%
O0001 (LETTER-O-IN-G-WORD)
(NCTRANS: SINUMERIK letter-o-in-g-word.mpf TO FANUC MACRO B)
( Letter O typed for zero in a G word is read as 0 with a warning [NC111])
G00 X10. Y10.
G01 X0. F100.
M30
%
