O3109 (G10 L14 P9: the tailstock B1 presses against the centre at B-150 with at most 30 % of its rated torque, then with all of it)
G98 G00 X20 Z0
G00 B-149
G10 L14 P9 B30
G01 B-150.0004 F300
G04 X0.5
G10 L14 P9 B0
G04 X0.5
G00 B-140
M30
