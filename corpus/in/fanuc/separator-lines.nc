%
O1203 (TEMPLATE WITH SEPARATORS)
* * * * * * * * * * * *
G00 X0 Y0
=========================
G01 X10. F200.
M30
%
