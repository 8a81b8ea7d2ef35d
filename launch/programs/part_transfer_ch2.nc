O1400 (part transfer, lower turret CH2: waits for the left end, takes A from CH1, turns a groove)
CH2
T0202
G04.1 P1 Q12 (wait for the upper turret)
G141 A14 (take A, lent by CH1)
M03 S600
G00 X70 Z-10 A180
G01 X56 F300 (the groove)
G00 X80
G01 A270 F7200
G142 (A goes back to CH1)
G04.1 P2 Q12
M05
M30
