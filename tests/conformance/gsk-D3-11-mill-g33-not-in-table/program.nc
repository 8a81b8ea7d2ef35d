(gsk D3-11: G33 is not in the table of B.1: alarm, nothing moves)
G00 X10
G33 Z-10 F1
M30
