(gsk B.1 L37, L45: G76 fine boring and G87 back boring; Q the shift off the wall along +X)
(P is modal: G87 dwells 0.3 s too)
G90 G00 X0 Y0 Z50 S800 M03
G76 X10 Y10 Z-20 R2 Q0.5 P300 F80
G87 X30 Y10 Z-5 R-25 Q500 F80
G80
M30
