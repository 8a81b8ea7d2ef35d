O1000 (G16: a hexagon in the polar plane by radius and angle, polar interpolation format 2)
G00 X60 Z0 C0
G01 F400
G16
G12.1
G01 X40 C0
C60
C120
C180
C240
C300
H60
X60
G13.1
G15
M30
