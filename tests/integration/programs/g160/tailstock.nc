O3160 (G160: the tailstock B1 presses against a centre at B-150 with half its rated torque)
G98 G00 X20 Z0
G00 B-140
G160 B-200 Q2 P50 F600
#101=#5063
G01 X10 F300
G01 Z-5 F300
G160 B0 Q2 P50 F1200
G00 B[#101+10]
M30
