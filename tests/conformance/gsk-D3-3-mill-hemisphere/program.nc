(gsk B.5.4 / D3-3: the hemisphere, as written, with G43 H1)
G90 G0 G54 X-10. Y0 M3 S4500
G43 Z50. H1 M8
#1=0.5
WHILE [#1 LE 50.] DO1
#2=50.-#1
#3=SQRT[2500.-[#2*#2]]
G1 Z-#1 F20
X-#3 F500
G2 I#3
#1=#1+0.5
END1
G0 Z50. M5
M30
