%
O1002 (G50.2 while the spindle turns: the disc slows down and stands before the program goes on)
N10 M03 S300
N20 G51.2 P2 Q-3 R45.
N30 G04 P500
N40 G50.2
N50 G04 P200
N60 G51.2 P1 Q1
N70 G50.2 P0
N80 G01 X20. F3000
N90 M05
N100 M30
%
