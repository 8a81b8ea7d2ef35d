O2000 (CT-G144-01, channel 2; T0001 of the spec left out until the PLC node runs T codes)
CH2
G00 X10
G01 Z-5 F600
G145 (release channel 1)
G00 X20
M99
