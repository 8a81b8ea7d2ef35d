O2600 (mill cell, the lathe CH1: turns a diameter and waits for the mill)
CH1
M03 S1000
G00 X50 Z2
G01 Z-20 F600
G00 X60
G00 Z10
M05
G04.1 P1 Q12 (the mill has finished too)
M30
