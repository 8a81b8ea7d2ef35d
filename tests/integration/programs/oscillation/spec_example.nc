O1000 (G81.1 / G80.1, spec L2491-2501 with Q20 and no T: Z strokes between 0 and 20 while X feeds)
G00 X51 Z0
G81.1 Z0 Q20 F2000
G01 X50 F10
G00 X100
G80.1 Z0
G00 X60
M30
