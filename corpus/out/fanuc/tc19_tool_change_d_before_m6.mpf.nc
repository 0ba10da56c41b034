%
O0001 (TC19_TOOL_CHANGE_D_BEFORE_M6)
(NCTRANS: SINUMERIK tc19_tool_change_d_before_m6.mpf TO FANUC MACRO B)
( Face and drill with the 840D tool change order: the next tool and its edge are)
( preselected while the old one still cuts, M6 changes at the safe level.)
( Translated with the profile's MD20270 = 1 [corpus/profiles/sinumerik-factory-d1.toml]:)
( the tool change selects D1 of the new tool, the D before it is the old tool's.)
N10 G17 G90 G54 G21 G40
N20 T1
N30 M06
G43 H1
N40 S2400 M03 M08
N50 G00 X-35. Y0.
N60 Z5.
N70 G01 Z0. F600.
N80 X85.
N90 G00 Z50.
N100 T2
N110 M05 M09
N120 M06
G43 H2
N130 S1800 M03 M08
N140 G00 X20. Y10.
N150 Z5.
N160 G01 Z-15. F180.
N170 G00 Z5.
N180 X60.
N190 G01 Z-15.
N200 G00 Z50. M09
N210 M05
N220 M30
%
