O1000 (gsk A.6.33: G78 with constant-distance infeed, left-flank entry, 2 finishing passes, run-out J0.5 K2)
G00 X32 Z3
G78 P000160 Q100 R0.1 J0.5 K2 D2
G78 X27.6 Z-30 P1200 Q400 F2
M30
