O1000 (CT-G144-01, channel 1: spec dafeng 3.4 example 1)
CH1
G00 X0 Z0
M03 S200
G144 N2 P2000 H1 (start O2000 in channel 2 and wait)
G01 Z-10 F600
M30
