(CT-G514-01, spec dafeng 3.2 example 2: Y and Z follow X, then are released one by one)
T0001
G00 X0 Y0 Z0
G51.4 P1 Q2
G51.4 P1 Q3
G01 U10 F100
G50.4 P1 Q3
G01 U10 F100
G50.4 P1 Q2
G01 U10 F100
M30
