O3104 (spec L5344: G31.8 without P is an alarm)
G98
G31.8 W-10 F100 I1 Q5 R1
M30
