O3199 (G31 P99: Z1's touch probe on input 13 or B1's load of param 5511, whichever comes first)
G98 G00 X20 Z0
G00 B-140
G31 W-2 B-160 F300 L13 P99
#101=#5063
G00 B[#101+10]
G31 W-20 B-146 F300 L13 P99
#102=#5062
G00 Z[#102+2]
M30
