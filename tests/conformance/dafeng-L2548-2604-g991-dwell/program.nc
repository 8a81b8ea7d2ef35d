O1000 (G99.1: 0.2 mm/rev, a break of 2 revolutions every 10; the count goes on over the moves)
G99.1 P2 Q10
M03 S100
G00 X50 Z0
G01 W-3 F0.2
G01 U4 W-1
G02 U0 W-4 R3
G00 X60
M30
