O3107 (spec L5246-5247: G31 P98 on an axis without a load ratio of G10 L14 P6 or param 5511 is an alarm)
G98 G00 X40 Z10
G31 W-20 F100 P98
M30
