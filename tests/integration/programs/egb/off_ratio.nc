O4 (T1 L1: C would have to turn as fast as S1, which starts at twice C's acceleration)
G00 X30 Z5 C0
G81.4 T1 L1 R0
M03 S300
G04 X2
G01 X20 F300
M30
