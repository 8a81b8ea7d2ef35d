O1001 (CT-G1141-01 on the twin-turret lathe, channel 2)
CH2
T0002
G04.1 P1 Q12 (wait for channel 1)
G00 X0 Z0 (spindle 2 moves to the part)
M11 (chuck 2 opens)
G01 Z-5 F100 (move in to receive the part)
M10 (chuck 2 clamps: before P2, as channel 1's comment on P2 says)
G04.1 P2 Q12
G04.1 P3 Q12
T0001
G04.1 P4 Q12 (waits for the end of the synchronisation)
M03 S1000 (spindle 2 on its own)
G00 X100 Z0
M30
