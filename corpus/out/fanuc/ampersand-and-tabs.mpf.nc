%
O0001 (AMPERSAND-AND-TABS)
(NCTRANS: SINUMERIK ampersand-and-tabs.mpf TO FANUC MACRO B)
( & is a blank, tabs separate words)
G00 X0. Y0.
G01 X10. F100.
M30
%
