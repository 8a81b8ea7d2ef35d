O1000 (CT-G1141-01 on the twin-turret lathe, channel 1: spec dafeng 3.7, L3476-3520)
CH1
T0001
G00 X100 Z0
M03 S500 (spindle 1 turns)
G01 X90 F300 (machining)
G00 X100
G114.1 (spindle 2 follows spindle 1: P1 Q1 K1 R0)
T0002
G00 X100 Z50 (clear of the transfer)
G04.1 P1 Q12 (tell channel 2 to prepare the transfer)
G04.1 P2 Q12 (wait for the channel-2 chuck to clamp)
M11 (chuck 1 opens: the spindles turn in phase)
G04.1 P3 Q12
G113 (spindle 2 leaves spindle 1)
G00 X100 Z0
G04.1 P4 Q12 (tell channel 2 the synchronisation is cancelled)
M30
