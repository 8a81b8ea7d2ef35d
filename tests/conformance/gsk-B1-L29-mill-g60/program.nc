(gsk B.1 L29: G60 single-direction positioning: the last move into each named axis's point)
(comes from the side its approach gives)
G90 G00 X0 Y0 Z10
G60 X20 Y30
G60 Z5
G00 X10
M30
