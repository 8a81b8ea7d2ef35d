O3103 (spec L5346-5354: tooth measuring; without the runtime Q signals evenly along the move)
G98
G31.8 UA360 F100 I1 P500 Q5 R1
IF[#1 < 5] #3000=1(TOOTH COUNT)
G00 A#502
G00 A#504
M30
