O3102 (spec L5233: G31 P1-P8 skips on the PLC's signal G0014.0-7; without the runtime the signal comes at the end point)
G98 G00 X40 Z10
G31 W-50 F200 P2 R100
G00 X[#5061+#100*2]
M30
