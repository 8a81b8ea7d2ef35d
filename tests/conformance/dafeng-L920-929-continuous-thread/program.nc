(three blocks joined: leads 1, 2, 1; the second and third do not wait for the one-rev signal)
G00 X20 Z5
G32 U10 W-20 F1
U0 W-20 F2
U-10 W-20 F1
G00 U10
M30
