O1100 (twin turret, upper turret CH1: the loader brings the blank, CH1 turns the left end)
CH1
M11 (open the main chuck: the PLC waits until it is open)
G144 N3 P3100 H1 (the loader puts a blank in the main chuck; its G145 lets CH1 go on)
M10 (clamp the blank)
T0101
M03 S800 (the PLC allows it: the chuck is closed)
M08
G00 X60 Z2
G01 Z-30 F600
G01 X64
G00 Z2
G04.1 P1 Q12 (the left end is done: the lower turret may start)
G00 X100 Z50
G04.1 P2 Q12 (both turrets clear)
M09
M05
M30
