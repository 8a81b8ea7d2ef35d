O1001 (spec L2454-2505: the oscillating axis belongs to the oscillation until G80.1)
G00 X51 Z0
G81.1 Z0 Q100 F2000
G01 X50 F10
G01 W-5
G80.1 Z0
M30
