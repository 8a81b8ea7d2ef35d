O1001 (CT-G140-01 on the twin-turret lathe, channel 2)
CH2
T0001
G142
G00 X0 Z100 A-90 (A is still virtual: nothing physical moves)
G04.1 P1 Q12
G141 A14 (acquire channel 1's A)
G00 A[#5003+10] (from where channel 1 left A: 20 + 10)
G01 A120 F7200 (A turns under channel 2: in place of the tap of steps 12-13)
G00 X0 Z100 A30
G04.1 P2 Q12
G142 (A goes back to channel 1)
M30
