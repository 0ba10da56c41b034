%
o1059
(LOWER-CASE INPUT IS READ AS UPPER CASE; COMMENT TEXT KEEPS ITS CASE: MixedCase)
g90 g0 x1. y2.
#1=sin[30.]
if[#1 gt 0.4]goto10
#2=1
n10 while[#1 lt 2.]do1
#1=#1+1.
end1
m30
%
