O1000 (spec L2491-2501: Z oscillates between 0 and 100 at 2000 mm/min while X feeds)
T0001
G00 X51 Z0
G81.1 Z0 Q100 F2000
G01 X50 F10
G00 X100
G80.1 Z0
M30
