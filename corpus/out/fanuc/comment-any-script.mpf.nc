%
O0001 (COMMENT-ANY-SCRIPT)
(NCTRANS: SINUMERIK comment-any-script.mpf TO FANUC MACRO B)
( Comments keep their text exactly: 中文注释, Кириллица, äöü ß, 日本語)
G00 X0. ( 快速定位 to X0)
G01 X1. F100. (   double   inside)
M30 (   trailing blanks kept   )
%
