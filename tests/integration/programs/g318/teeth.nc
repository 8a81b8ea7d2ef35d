O3180 (G31.8: Z passes three teeth of Z1's probe, at Z-10, -12 and -14, and stores each)
G98 G00 X20 Z0
G31.8 W-20 F600 L13 P500 Q5 R1
G00 Z[#500]
G00 Z[#501]
G00 Z[#502]
G00 Z[-#1]
M30
