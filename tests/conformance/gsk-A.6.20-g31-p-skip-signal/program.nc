O3103 (gsk A.6.20: G31 P1-P4 skips on the signal of param 148-151 and stores the position in #995-#999; without the runtime the signal comes at the end point)
G98 G00 X40 Z10
G31 W-50 F200 P2
G00 X[#995+2] Z[#996+1]
M30
