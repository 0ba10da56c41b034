%
O0001 (OPERATORS-COMPARE)
(NCTRANS: SINUMERIK operators-compare.mpf TO FANUC MACRO B)
(NCTRANS: R1 = #501)
(NCTRANS: R2 = #502)
(NCTRANS: R3 = #503)
(NCTRANS: R4 = #504)
(NCTRANS: R5 = #505)
(NCTRANS: R6 = #506)
(NCTRANS: R7 = #507)
(NCTRANS: TEMPORARIES #1 #2 #3 #4 #5 #6)
( Comparison operators == <> > >= < <= [results are values])
#501=5.
#1=0.
IF [#501 EQ 5.] THEN #1=1.
#502=#1
#2=0.
IF [#501 NE 5.] THEN #2=1.
#503=#2
#3=0.
IF [#501 GT 4.] THEN #3=1.
#504=#3
#4=0.
IF [#501 GE 5.] THEN #4=1.
#505=#4
#5=0.
IF [#501 LT 6.] THEN #5=1.
#506=#5
#6=0.
IF [#501 LE 5.] THEN #6=1.
#507=#6
M30
%
