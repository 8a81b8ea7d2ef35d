O1000 (spec L2578-2591; X52 before the first cut, whose X the example leaves at X50)
G98.1 P-1.5 Q5
T0101
M03 S500
G00 X52
G00 Z0
G90 X50 W-10 F200
X49.5
G98 X49
M30
