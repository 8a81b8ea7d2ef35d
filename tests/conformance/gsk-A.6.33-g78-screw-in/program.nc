O1000 (gsk A.6.33: the screw-in E0.5, each pass entering its depth at 45 degrees on the thread)
G00 X32 Z3
G78 P010060 Q100 R0.1 E0.5
G78 X27.6 Z-30 P1200 Q400 F2
M30
