%
O0001 (REPEAT-SECTION-ENDLABEL)
(NCTRANS: SINUMERIK repeat-section-endlabel.mpf TO FANUC MACRO B)
(NCTRANS: NSTROKE = #100)
(NCTRANS: TEMPORARIES #1)
( DRESSING STROKES: AN INFEED AND A STROKE, REPEATED UP TO ENDLABEL  THE DWELL AFTER)
( ENDLABEL IS NOT PART OF THE SECTION)
G18 G90 G54 G21
T5 M06
G43 H5
#100=2.
G00 X20. Z5.
( infeed)
G91 G01 X-0.02 F50. (STROKE:)
G90 G01 Z-30. F300. ( dressing stroke)
( back to the start of the stroke)
G00 Z5. (ENDLABEL:)
G04 X0.5 ( let the coolant settle on the wheel, once)
(REPEAT SECTION FROM STROKE, P=NSTROKE TIMES: NSTROKE more strokes, each to ENDLABEL)
#1=ROUND[#100]
WHILE [#1 GT 0.] DO1
G91 G01 X-0.02 F50.
G90 G01 Z-30. F300. ( dressing stroke)
( back to the start of the stroke)
G00 Z5.
#1=#1-1.
END1
( spark-out stroke)
G01 Z-30. F150. (SPARK:)
G00 Z5. (ENDLABEL:)
(REPEAT SECTION FROM SPARK, ONCE: one more spark-out stroke)
G01 Z-30. F150.
G00 Z5.
G00 X50. Z50.
M30
%
