O1000 (gsk D2-35: with №174.4 = 0 G92 P1 ignores P1, a normal thread, rule 1)
G00 X30 Z5
G92 X19.2 Z-20 F2 P1
G00 X40 Z50
M30
