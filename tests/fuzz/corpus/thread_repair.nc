2O1000 (gsk thread repair: G92 P1 and its modal blocks, G92.1 P1 with two starts, P2, a face thread)
G00 X30 Z5
G92 X19.2 Z-20 F2 P1
X18.6
G92 X18.4 Z-20 F2 P0
M14
G92.1 X19 Z-20 F1.5 L2 S300 P1
G92 X18 Z-5 F2 P1
G92 X18 Z-20 F2 P2
G00 X100 Z5
G92 X20 Z2 F2 P1
M30
