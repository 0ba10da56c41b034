%
O0001 (ADDRESS-AC-IC-OWN-MODE)
(NCTRANS: SINUMERIK address-ac-ic-own-mode.mpf TO FANUC MACRO B)
( AC[]/IC[] in a block with its own G90/G91: the block runs in the word's mode)
G00 X0. Y0.
N10 G91 X2. ( incremental though the block says G90)
G90
G90 X5.
G91
G91 G01 X2. Y1. F100.
G90
G91 X2.
G90 X1. Y3.
M30
%
