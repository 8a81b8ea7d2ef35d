(gsk B.1 L18-20: G43 adds the length of H, G44 subtracts it, G49 cancels; no move without Z)
G90 G00 X0 Y0 Z0
G43 H1 Z10
G44 H2 Z10
H1
Z5
X5
G49 Z10
M30
