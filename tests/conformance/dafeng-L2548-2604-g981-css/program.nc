O1002 (G98.1 under G96: the breaks follow the speed at each radius; G50 S limits it)
G50 S2000
G98.1 P-0.5 Q20
G96 S60 M03
G00 X40 Z1
G01 Z-3 F120
G01 X4
G00 Z5
G98 X40
M30
