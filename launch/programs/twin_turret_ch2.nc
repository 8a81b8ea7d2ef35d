O1200 (twin turret, lower turret CH2: waits for the left end, then turns a groove)
CH2
T0202
G04.1 P1 Q12 (wait for the upper turret)
M03 S600
G00 X70 Z-10
G01 X56 F300
G00 X80
G04.1 P2 Q12
M05
M30
