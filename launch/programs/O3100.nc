O3100 (twin turret, gantry loader CH3: a blank into the main chuck)
CH3
G00 X200 Z80
G01 Z10 F3000 (down to the chuck)
G145 (the blank is in: the upper turret may start)
G00 Z80
G00 X0
M99
