O1300 (part transfer, upper turret CH1: the loader brings a blank, CH1 turns the left end, lends A to the lower turret and takes it back)
CH1
M11 (open the main chuck: the PLC waits until it is open)
G144 N3 P3100 H1 (the gantry loader puts a blank in the main chuck; its G145 lets CH1 go on)
M10 (clamp the blank)
T0101
M03 S800
G00 X60 Z2 A0
G01 Z-30 F600 (turn the left end)
G01 X64
G00 Z2
G01 A90 F7200 (A indexes under CH1)
G00 X100 Z50
G140 A14 (lend A to the lower turret)
G04.1 P1 Q12 (the left end is done: the lower turret may start)
G04.1 P2 Q12 (the lower turret is done and has given A back)
G142 (A is CH1's again)
G01 A0 F7200
M05
M30
