O3106 (spec L5251-5252: P99 beside forms 1-3 skips on the input or on the load of param 5511)
G98 G00 X40 Z10
G31 W-20 F100 L13 P99
G31 W-5 F100 P99
G31 U10 W-1 F100 I-7 P99
M30
