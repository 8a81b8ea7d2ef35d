O9020 (CT-CHN-01: one subprogram, each channel its own axis; the spec's Y axis is Z here)
G4I0 (read-ahead barrier)
IF[CHN==1] G53 X0
IF[CHN==2] G53 Z0
IF[CHN==3] G53 X10 Z10
M99
