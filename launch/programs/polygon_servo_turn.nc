%
O1003 (polygon turning with a servo disc: C turns twice the spindle, then is positioned)
N10 M03 S300
N20 G00 X50. Z2.
N30 G51.2 P1 Q2
N40 G01 X45. F100
N50 G01 W-5. F200
N60 G00 U10.
N70 G50.2
N80 G00 H90.
N90 M05
N100 M30
%
