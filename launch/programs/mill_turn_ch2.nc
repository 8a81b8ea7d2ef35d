O2401 (mill-turn, lower turret CH2: takes the part's C from the upper turret, turns it and lets it go)
CH2
G00 X60 Z10
G04.1 P1 Q12 (the upper turret has lent C)
G141 C15
G00 C90 (from where the upper turret left C)
G00 C135
G140 C15
G04.1 P2 Q12
M30
