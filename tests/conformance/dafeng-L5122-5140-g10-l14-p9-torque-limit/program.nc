O1000 (spec L5122-5140: friction welding, G10 L14 P9 limits Z to 135 % for the feed and its dwell; Z0 cancels)
T0001
G10 L14 P9 Z0
G00 Z1
G00 X0
G10 L14 P9 Z135
G09 G01 Z-20 F100
G04 X1
G01 Z100 F2000
G10 L14 P9 Z0
M30
