%
O1000 (polygon turning, spec dafeng L2953-2969: a square with two cutters on the disc)
N10 M03 S500
N20 G00 X50. Z2.
N30 G51.2 P1 Q2
N40 G01 X45. F100
N50 G01 W-15. F200
N60 G00 U10.
N70 G00 Z100.
N80 M05
N90 G50.2
N100 M30
%
