O1000 (gsk D2-35: the recorded Z-30 outside the block's Z5..Z-20: alarm, rule 5)
G00 X30 Z5
G92 X19.2 Z-20 F2 P1
G00 X40 Z50
M30
