O1000 (gsk D2-35: thread repair on and no recorded position: alarm, rule 3)
G00 X30 Z5
G92 X19.2 Z-20 F2 P1
G00 X40 Z50
M30
