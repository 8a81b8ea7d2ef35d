O1000 (CT-G140-01 on the twin-turret lathe, channel 1: spec dafeng 3.3, L5653-5699)
CH1
T0001
G142 (restore: nothing exchanged yet)
G00 X0 Z100 A0
G00 Z5
G01 A360 F7200 (A turns under channel 1: in place of the rigid tap of steps 6-7)
G00 X0 Z100 A20 (A left at 20 degrees)
G140 A14 (release A to channel 2)
G04.1 P1 Q12
G04.1 P2 Q12
G142 (A comes back from channel 2)
G00 A[#5003+15] (from where channel 2 left A: 30 + 15)
M30
