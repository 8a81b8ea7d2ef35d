(D2-1 straight, the same incremental, D2-2 taper R-5, D2-3 modal repeat X70)
G00 X100 Z5
G90 X80 Z-30 F0.2
G90 U-20 W-35 F0.2
G90 X80 Z-30 R-5 F0.2
G90 X80 Z-30 F0.2
X70
M30
