O3181 (G31.8 Q2: the second tooth, at Z-12, ends the move)
G98 G00 X20 Z0
G31.8 W-20 F600 L13 P510 Q2 R1
#102=#511
G00 W1
G00 Z[#102-#1]
M30
