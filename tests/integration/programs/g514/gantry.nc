(Spec dafeng 3.2 example 1: X1 follows X from power-on; realigned with G50.4 and G51.4 Q4)
G00 X50
G50.4 Q4
G00 X60
G51.4 Q4
G00 X80
G01 B5 F100
M30
