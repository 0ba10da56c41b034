%
O0001 (CORNER-SLOWDOWN-FEED-SAVE)
(NCTRANS: SINUMERIK corner-slowdown-feed-save.mpf TO FANUC MACRO B)
(NCTRANS: R10 = #510)
(NCTRANS: R11 = #511)
(NCTRANS: TEMPORARIES #1)
( Contour finishing of a pocket wall: the feed and speed in force are saved)
( [$P_F, $P_S], the feed is halved into each inside corner and the speed)
( dropped for the last spring pass, then both are restored from the saved values.)
G90 G21 G17 G54 G94
T4 M06
G43 H4
G00 X5. Y5. S3200 M03
G00 Z2.
G01 Z-6. F250.
G01 X60. F900.
#510=#4109 ( 900 mm/min as programmed)
#511=#4119 ( 3200 rpm)
G01 X70. F[#510*0.5] ( slow into the corner)
G01 Y45. F#510
G01 Y55. F[#510*0.5]
G01 X5. F#510
#1=#4109
IF [ABS[#1-#510] GT [ABS[#1]+ABS[#510]+ABS[ABS[#1]-ABS[#510]]]*0.0000005*0.000001] GOTO 1000
( spring pass at 80 percent speed, then the saved speed again)
S[#511*0.8]
G01 Y5.
S#511
G00 Z50.
M05
M30
N1000 (FEED_LOST:)
#3006=1(FEED NOT RESTORED)
M30
%
