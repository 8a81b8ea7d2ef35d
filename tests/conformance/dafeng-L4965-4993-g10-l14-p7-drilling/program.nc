O1000 (spec L4965-4993: Z watched at 100 % in each G83 hole's feed with 5100.2 = 1, .3 = 0, .4 = 1: on an overload back to R1, then the alarm; G10 L14 P7 alone cancels)
T0101
G00 X0 Z10
M03 S1000
G10 L14 P7 Z100
G98 G83 X0 R1 Z-10 F100
X50
X100
G80
G10 L14 P7
M30
