O2400 (mill-turn, upper turret CH1: a square and a hexagon on the face by G12.1, the part lent to the lower turret, a slot on the diameter by G07.1)
CH1
M03 S2000 (the driven tool)
G00 X40 Z2 C0
G00 Z-2
G12.1 (polar: X and C as a plane, C a length that reads 0 here)
G01 X16 C0 F2400
C8
X-16
C-8
X16
C0
X40
G16 (format 2: a hexagon by radius and angle, C in degrees from where G12.1 began)
X24 C0
C60
C120
C180
C240
C300
C360
G15
X40 C0
G13.1
G00 Z5
G140 C15 (lend the part's C to the lower turret)
G04.1 P1 Q12
G04.1 P2 Q12 (the lower turret has turned the part and let C go)
G141 C15 (C is CH1's again, where the lower turret left it)
G00 C0
G00 X44 Z-5
G19 (the plane C-Z once C takes Y's place)
G01 X36 F300
G07.1 C20 (cylindrical: C in degrees on a cylinder of radius 20)
G01 C90 F2400
G02 Z-25 C90 R10
G01 C0
G07.1 C0
G18
G00 X44
G00 Z5
M05
M30
