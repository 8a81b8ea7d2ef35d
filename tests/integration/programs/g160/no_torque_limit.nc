O3161 (G160 of Z1, whose drive takes no torque limit: refused before anything moves)
G98 G00 X20 Z0
G01 X10 F300
G160 W-50 P50 F600
M30
