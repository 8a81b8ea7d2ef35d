O1000 (spec L3894-3904, then an arc: A turns with it; G40.1 holds the angle)
G00 X0 Z0
G41.1
G01 Z10 F300
G01 X10 F300
G03 X30 Z20 R10
G40.1
G01 Z30
M30
