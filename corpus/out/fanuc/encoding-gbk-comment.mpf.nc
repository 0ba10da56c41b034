%
O0001 (ENCODING-GBK-COMMENT)
(NCTRANS: SINUMERIK encoding-gbk-comment.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
( GBK-encoded comments: 宏程序 R 参数示例)
#501=30. (球半径)
G00 X#501 (快速定位)
M30
%
