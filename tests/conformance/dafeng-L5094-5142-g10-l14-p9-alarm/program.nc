O1001 (spec L5098-5100: G10 L14 P9 takes the limits by absolute addresses; W is alarm 1121, nothing moves)
G98 G00 X20 Z10
G10 L14 P9 W135
G01 W-20 F100
M30
