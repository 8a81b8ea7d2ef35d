%
O0001 (spec L1240-1252: wait 5 s or until input 2 is on; the forms of I, J, K)
G04 X1
G04 X5 I2
G04 I-3 J2 K0.5
G04 I0
M30
%
