O3110 (G10 L14 P10-P12: the tailstock B1 pushed into the centre at B-150 in torque mode with 50 % of its rated torque at 30 rpm, 5 mm/s; X cuts while it holds; P12 takes it back to position mode where it stands, and it retracts from there)
G98 G00 X20 Z0
G00 B-148
G10 L14 P10 B-50
G04 X1.5
G01 X10 F300
G10 L14 P12 B-1
G00 B-140
M30
