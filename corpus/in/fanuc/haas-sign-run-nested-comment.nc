%
O1202 (FACE (SHABLON 2) TEMPLATE)
#4=40.
G00 X [ + - 0. / 2 ] Y [ - + #4 / 2 ] (START (LEFT))
G01 X [ - - 5. ] F300.
M30
%
