%
O1004 (param 5300.5 = 1: G51.2 goes on at once, the cut waits for the disc's phase)
N10 M03 S300
N20 G04 P500
N30 G51.2 P1 Q2
N40 G00 Z1.
N50 G01 X4. F600
N60 G50.2
N70 M05
N80 M30
%
