%
O0002 (the main spindle turns, reverses and stops while the slides move)
N10 M03 S600
N20 G00 X40. Z5.
N30 G04 P500
N40 M04 S300
N50 G01 Z-5. F600
N60 M05
N70 G04 P300
N80 M30
%
