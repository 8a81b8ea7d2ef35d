O1000 (spec L5396-5404: G160 as a probe; without the runtime the skip comes at the end point)
T0101
G98 G00 X50 Z100
G160 X40 P80 F20
#100=#5061
G160 X50 P80 F500
G00 X[#100]
M30
